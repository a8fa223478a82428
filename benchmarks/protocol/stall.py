"""Why a tree search stalls: where it commits and why its new actions fail there.

The v1 protocol found VOOT's kitchen searches stalling: the best plan stops improving
early and every later simulation executes about one failing step. :func:`trace_search`
re-runs one search (the same run as the store's row: same planner settings, same search
seed) with every new action traced, and :func:`stall_report` summarises, per seed:

* where the search last committed its root (simulation, depth, operator, objects left);
* the outcome of every draw made at that root afterwards: rejected by the kinematic
  pre-check (per cause: collision, region, IK ...) or executed and failed (per cause:
  forbidden room, no base path ...), or feasible;
* VOO's exploitation radius at that root over time: half the distance from its best
  point :math:`x^*` to the nearest other Voronoi site (every point of the best cell within
  that distance of :math:`x^*` is certainly in the cell, so it bounds how local the
  exploitation draws are), in the planner's normalised action units.

Nothing here changes a planner: the traced search is the plain :class:`voot.tree.MCTS`
with a recording hook on :meth:`~voot.tree.MCTS.new_action`, and its curve is checked to
equal the untraced run's.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from voot.bench.sweep.plan import PlanSpec
from voot.bench.sweep.search import search_seed
from voot.tree.mcts import MCTS
from voot.tree.node import Node
from voot.tree.step_info import StepInfo


@dataclass
class Draw:
    """One proposal at a node: its stage and cause."""

    simulation: int
    node: int
    stage: str  # "precheck" (rejected), "execution" (executed, failed) or "feasible"
    cause: str
    distance_to_best: float  # to the node's best point (nan without a VOO sampler)


@dataclass
class Trace:
    """Everything recorded during one traced search."""

    draws: list[Draw] = field(default_factory=list)
    #: (simulation, root id, root depth, visits of the root it left) at every change of
    #: the current root.
    roots: list[tuple[int, int, int, int]] = field(default_factory=list)
    #: (simulation, node id, exploitation radius) at every new action of a VOO node.
    radius: list[tuple[int, int, float]] = field(default_factory=list)
    curve: list[float] = field(default_factory=list)
    #: New actions drawn at a VOO node that has a feasible action (where VOO may exploit
    #: its best point), and how many of them found the best value tied between several
    #: points (where the authors' random tie-break and voot's first argmax could differ).
    exploiting_draws: int = 0
    tied_best_draws: int = 0


#: ``record(stage, cause, action)``: what :class:`_TracedProblem` reports of every draw.
Recorder = Callable[[str, str, Any], None]


class _TracedProblem:
    """The planning problem with its pre-checks and steps recorded (answers unchanged)."""

    def __init__(self, problem: Any, record: Recorder) -> None:
        self._p = problem
        self._record = record
        check = getattr(problem, "is_feasible", None)
        self.is_feasible = self._is_feasible if callable(check) else None

    def __getattr__(self, name: str) -> Any:
        return getattr(self._p, name)

    def snapshot(self) -> Any:
        return self._p.snapshot()

    def restore(self, state: Any) -> None:
        self._p.restore(state)

    def action_bounds(self) -> Any:
        return self._p.action_bounds()

    def _is_feasible(self, action: Any) -> bool:
        ok = bool(self._p.is_feasible(action))
        if not ok:
            self._record("precheck", StepInfo.of(self._p.last_check.info).reason_code, action)
        return ok

    def step(self, action: Any) -> Any:
        res = self._p.step(action)
        if res.feasible:
            self._record("feasible", "", action)
        else:
            self._record("execution", StepInfo.of(res.info).reason_code, action)
        return res


class _TracedMCTS(MCTS):
    """MCTS that notes the node of every new action (behaviour unchanged)."""

    def __init__(self, problem: Any, config: Any, seed: Any) -> None:
        self.trace = Trace()
        self._node: Node | None = None
        super().__init__(_TracedProblem(problem, self.record), config, seed=seed)

    def new_action(self, node: Node) -> int:
        self._node = node
        return super().new_action(node)

    def record(self, stage: str, cause: str, action: Any) -> None:
        node = self._node
        if node is None:  # pragma: no cover - steps only happen inside new_action
            return
        distance = float("nan")
        opt = getattr(node.sampler, "optimizer", None)
        if opt is not None and opt.n_told > 0:
            best = opt.xs[opt.best_index]
            distance = float(np.linalg.norm(np.asarray(action) - best))
        self.trace.draws.append(Draw(self.n_simulations, node.id, stage, cause, distance))
        # before the node has a feasible action, VOO draws uniformly (both codes)
        if stage != "precheck" and opt is not None and opt.n_told >= 2 and node.n_feasible:
            values = opt.values
            self.trace.exploiting_draws += 1
            self.trace.tied_best_draws += int(np.sum(values == values[opt.best_index]) > 1)
            xs = opt.xs
            d = np.linalg.norm(xs - xs[opt.best_index], axis=1)
            d[opt.best_index] = np.inf
            self.trace.radius.append((self.n_simulations, node.id, float(d.min()) / 2))


def trace_search(spec: PlanSpec) -> tuple[Trace, MCTS]:
    """Re-run the tree search of ``spec`` with every new action traced."""
    from voot.bench.protocol import problems as P

    config = spec.run_config()
    problem = P.make_instance(spec.problem, spec.dim, spec.env_kwargs_dict, spec.seed).problem
    mcts = _TracedMCTS(problem, config, search_seed(spec))
    last_root = None

    def watch(m: MCTS, i: int) -> None:
        nonlocal last_root
        root = m.current_root
        if root is not last_root:
            left = 0 if last_root is None else last_root.visits
            mcts.trace.roots.append((i, root.id, root.depth, left))
            last_root = root

    mcts.search(spec.simulations, callback=watch, record_info=P.OBJECTS_KEY)
    mcts.trace.curve = list(mcts.best_return_curve)
    return mcts.trace, mcts


@dataclass(frozen=True)
class StallSummary:
    """Where one search last committed and what happened at that root afterwards."""

    seed: int
    last_improvement: int
    committed_at: int
    root_depth: int
    root_operator: str
    objects_left_at_root: int | None
    parent_visits: int
    parent_counted: int
    tied_children: int
    draws: int
    precheck: Mapping[str, int]
    execution: Mapping[str, int]
    feasible: int
    radius_first: float
    radius_last: float
    voo: bool = True


def summarize(seed: int, trace: Trace, mcts: MCTS) -> StallSummary:
    """The :class:`StallSummary` of a traced search."""
    curve = np.asarray(trace.curve)
    changes = np.flatnonzero(np.diff(curve) != 0)
    last = int(changes[-1]) + 2 if changes.size else 1
    sim, root_id, depth, parent_visits = trace.roots[-1]
    root = mcts.nodes[root_id]
    parent = root.parent
    tied = 0
    if parent is not None:
        chosen = parent.q[root.edge]
        tied = sum(
            1
            for i, c in enumerate(parent.children)
            if parent.feasible[i] and c.expandable and parent.q[i] == chosen
        )
    at_root = [d for d in trace.draws if d.node == root_id and d.simulation >= sim]
    pre = Counter(d.cause for d in at_root if d.stage == "precheck")
    exe = Counter(d.cause for d in at_root if d.stage == "execution")
    radius = [r for s, n, r in trace.radius if n == root_id and s >= sim]
    info = StepInfo.of(root.info) if root.info else None
    operator = info.next_operator if info is not None and info.next_operator else "pick"
    return StallSummary(
        seed=seed,
        last_improvement=last,
        committed_at=sim + 1,
        root_depth=depth,
        root_operator=str(operator),
        objects_left_at_root=None if info is None else info.objects_left,
        parent_visits=parent_visits,
        parent_counted=0 if parent is None else parent.n_commit_actions,
        tied_children=tied,
        draws=len(at_root),
        precheck=dict(pre.most_common()),
        execution=dict(exe.most_common()),
        feasible=sum(d.stage == "feasible" for d in at_root),
        radius_first=radius[0] if radius else float("nan"),
        radius_last=radius[-1] if radius else float("nan"),
        voo=hasattr(root.sampler, "optimizer"),
    )


@dataclass(frozen=True)
class Commitment:
    """One move of the root to a child (a return to the original root is not one)."""

    simulation: int
    depth: int
    parent_visits: int
    tied_children: int
    feasible_children: int
    dead_end: bool  # the new root never had a feasible action


def commitments(trace: Trace, mcts: MCTS) -> list[Commitment]:
    """Every commitment of a traced search, with the evidence it was made on."""
    out = []
    for sim, root_id, depth, parent_visits in trace.roots:
        root = mcts.nodes[root_id]
        parent = root.parent
        if parent is None or depth == 0:
            continue
        chosen = parent.q[root.edge]
        live = [i for i, c in enumerate(parent.children) if parent.feasible[i] and c.expandable]
        tied = sum(1 for i in live if parent.q[i] == chosen)
        out.append(Commitment(sim + 1, depth, parent_visits, tied, len(live), root.n_feasible == 0))
    return out


def _share(counts: Mapping[str, int], total: int) -> str:
    if not total:
        return "-"
    return ", ".join(f"{k} {100 * v / total:.0f}%" for k, v in counts.items())


def _parent(s: StallSummary) -> str:
    if s.root_depth == 0:
        return "(back at the original root after a goal)"
    return f"{s.parent_visits}, {s.parent_counted}, {s.tied_children}"


def _radius(s: StallSummary) -> str:
    if not s.voo:
        return "- (no VOO)"
    if np.isnan(s.radius_first):
        return "no exploitation (no feasible action)"
    return f"{s.radius_first:.3g}, {s.radius_last:.3g}"


def stall_table(summaries: Sequence[StallSummary]) -> str:
    """A markdown table of :class:`StallSummary` rows, and the totals."""
    lines = [
        "| seed | last improvement | last commitment (simulation, depth, operator, objects left) | parent at commitment (visits, counted actions, children tied at the chosen Q) | draws at the root since | pre-check rejections | execution failures | feasible | VOO radius (first, last) |",
        "| ---: | ---: | --- | --- | ---: | --- | --- | ---: | --- |",
    ]
    pre_all: Counter[str] = Counter()
    exe_all: Counter[str] = Counter()
    draws = feasible = 0
    for s in summaries:
        n_pre, n_exe = sum(s.precheck.values()), sum(s.execution.values())
        pre_all.update(s.precheck)
        exe_all.update(s.execution)
        draws += s.draws
        feasible += s.feasible
        lines.append(
            f"| {s.seed} | {s.last_improvement} | {s.committed_at}, {s.root_depth},"
            f" {s.root_operator}, {s.objects_left_at_root} | {_parent(s)} | {s.draws} |"
            f" {n_pre} ({_share(s.precheck, n_pre)}) | {n_exe} ({_share(s.execution, n_exe)}) |"
            f" {s.feasible} | {_radius(s)} |"
        )
    n_pre, n_exe = sum(pre_all.values()), sum(exe_all.values())
    lines.append(
        f"| all | | | | {draws} | {n_pre} ({_share(dict(pre_all.most_common()), n_pre)}) |"
        f" {n_exe} ({_share(dict(exe_all.most_common()), n_exe)}) | {feasible} | |"
    )
    return "\n".join(lines)
