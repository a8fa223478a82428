r"""Root-parallel tree search: K independent trees on K workers, merged at the root.

Root parallelisation (Chaslot, Winands and van den Herik, 2008) runs :math:`K` searches
of the same root state with different seeds, with no communication between them, and
combines them only at the end, at the root. It needs no locks and no shared tree, so the
trees can run in separate processes (or on separate machines: the executor is a plug-in),
and the result of :math:`K` trees is a deterministic function of the base seed.

**Seeds.** Tree :math:`k` is seeded with ``np.random.SeedSequence(seed).spawn(K)[k]``,
whose spawn key is ``(k,)`` whatever :math:`K` is: tree :math:`k` is the same tree in a
run of 2 trees as in a run of 4, so adding trees only adds trees (:func:`tree_seeds`).

**Merging the root.** Every tree reports its root's edges (actions, :math:`\hat Q`, visit
counts, feasibility). Candidates are the feasible root edges of all trees (all edges if
none is feasible, as :meth:`voot.tree.Node.best_edge` does); the merged root action is a
candidate's own action, so it has been executed and its child is known. Rules
(:class:`MergeRule`):

``max_q``
    The candidate with the highest :math:`\hat Q` (ties: the lowest tree, then edge).
``most_visited``
    The candidate with the most visits (ties: higher :math:`\hat Q`, then lowest tree and
    edge). Both rules equal the single tree's ``final_action`` when :math:`K = 1`.
``vote``
    Actions of different trees never coincide in a continuous space, so "the same
    action" is replaced by "a nearby action": with :math:`z = (u - l) / (h - l)` the
    action in the root's box :math:`[l, h]` normalised to :math:`[0, 1]^d`, and
    :math:`\delta(u, u') = \lVert z - z' \rVert_2 / \sqrt d` (the root-mean-square
    coordinate difference in box widths, in :math:`[0, 1]` whatever :math:`d`), each
    candidate :math:`c` scores the visits of all candidates within ``vote_radius``
    :math:`r` of it (itself and the other trees' actions included):

    .. math:: V(c) = \sum_{c' :\ \delta(c, c') \le r} n(c').

    The candidate with the largest :math:`V` wins (ties: higher own :math:`\hat Q`, then
    lowest tree and edge). It is a kernel vote: a region that several trees explored
    heavily beats a single lucky action. Visits are summed, not values: :math:`\hat Q` can
    be negative (the infeasible penalty, distance costs), and a sum of values would count
    how many actions were tried near :math:`c` rather than how good they are; the
    decision reports the neighbourhood's best and visit-weighted mean :math:`\hat Q`.
    ``vote_radius = 0`` reduces the vote to ``most_visited`` summed over exact duplicates.

**The merged plan and curve.** The best plan is the best tree's (highest best return;
ties: lowest tree). The merged best-return curve is the maximum over trees at each
simulation index :math:`i`,

.. math:: B_K(i) = \max_{k < K} B^{(k)}(i), \qquad i = 1, \dots, N,

the best return known after every tree has run :math:`i` simulations: after :math:`i`
rounds of wall-clock time when the :math:`K` trees run in parallel. Plotted against the
*total* number of simulations :math:`K i`
(:meth:`RootParallelResult.curve_by_total_simulations`) it compares with one tree of
:math:`K N` simulations at equal computation; plotted against :math:`i` it compares at
(ideally) equal wall time.

**Workers.** An executor is anything with ``map(fn, items)`` (results may come back in
any order, as from a pool; each carries its tree index and the merge sorts them): a
:class:`SerialExecutor` (in-process, for tests and for a sweep that is already parallel),
a :class:`LocalProcessExecutor` (a :class:`~concurrent.futures.ProcessPoolExecutor`, the
default), a :class:`concurrent.futures.Executor` of your own, or an object with only
``map_unordered(fn, items)`` (a ``voot.bench`` backend, e.g. its Ray backend). The work
item (:class:`TreeTask`) and the worker function (:func:`run_tree`) pickle, so they go to
another process or machine as they are. MuJoCo problems may not pickle (or not cheaply):
pass a zero-argument *factory* instead of the problem; each worker process builds the
problem once per factory and keeps it (:func:`clear_problem_cache`), restoring its
initial snapshot before every tree.
"""

from __future__ import annotations

import contextlib
import math
import multiprocessing
import os
import pickle
import time
from collections import OrderedDict
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_EXCEPTION, Future, ProcessPoolExecutor, wait
from dataclasses import dataclass, field, fields, replace
from enum import StrEnum
from typing import Any, Protocol, TypeVar, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from voot._workers import single_threaded_children
from voot.optim.base import FloatArray
from voot.tree.config import MCTSConfig, planner_config
from voot.tree.mcts import MCTS, PlanResult, check_n_simulations, problem_bounds
from voot.tree.node import Node
from voot.tree.problem import PlanningProblem

T = TypeVar("T")
R = TypeVar("R")

#: A zero-argument callable that builds the planning problem (in its initial state).
ProblemFactory = Callable[[], PlanningProblem]

#: Problems each process keeps built from factories (least recently used dropped).
PROBLEM_CACHE_SIZE = 4


def _same(a: object, b: object) -> bool:
    """Equality through arrays, mappings and sequences (NaN equals NaN)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if not (isinstance(a, np.ndarray) and isinstance(b, np.ndarray)) or a.shape != b.shape:
            return False
        return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc" and b.dtype.kind in "fc"))
    if isinstance(a, Mapping) or isinstance(b, Mapping):
        return (
            isinstance(a, Mapping)
            and isinstance(b, Mapping)
            and list(a) == list(b)
            and all(_same(a[k], b[k]) for k in a)
        )
    if isinstance(a, list | tuple) or isinstance(b, list | tuple):
        return (
            type(a) is type(b)
            and len(a) == len(b)  # type: ignore[arg-type]
            and all(_same(x, y) for x, y in zip(a, b, strict=True))  # type: ignore[call-overload]
        )
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


def _same_fields(a: Any, b: Any) -> bool:
    """Dataclasses ``a`` and ``b`` agree on every field compared by ``==``."""
    return type(a) is type(b) and all(
        _same(getattr(a, f.name), getattr(b, f.name)) for f in fields(a) if f.compare
    )


#: The fields of a :class:`PlanResult` that a seed determines (not timings, not the tree).
_PLAN_FIELDS = tuple(f.name for f in fields(PlanResult) if f.name not in ("wall_time", "mcts"))


class MergeRule(StrEnum):
    """How the root statistics of the trees choose the merged root action.

    See the module docstring for the exact rules and their tie-breaking.
    """

    MAX_Q = "max_q"
    MOST_VISITED = "most_visited"
    VOTE = "vote"


@dataclass(frozen=True)
class RootParallelConfig:
    """Options of root-parallel search (not paper constants: the paper runs one tree).

    Attributes:
        n_trees: :math:`K \\ge 1`, the number of independent trees.
        merge: the root merge rule, see :class:`MergeRule`.
        vote_radius: :math:`r \\in [0, 1]`, the neighbourhood radius of the ``vote`` rule
            in root-mean-square box widths (0.1: actions within a tenth of the box of each
            other, coordinate-wise on average, vote together). Ignored by other rules.
    """

    n_trees: int = 2
    merge: MergeRule | str = MergeRule.MAX_Q
    vote_radius: float = 0.1

    def __post_init__(self) -> None:
        k = self.n_trees
        if isinstance(k, bool) or not isinstance(k, int | np.integer) or k < 1:
            raise ValueError(f"n_trees must be an integer >= 1, got {k!r}")
        object.__setattr__(self, "n_trees", int(k))
        object.__setattr__(self, "merge", merge_rule(self.merge))
        r = self.vote_radius
        if (
            isinstance(r, bool)
            or not isinstance(r, int | float | np.floating)
            or not math.isfinite(r)
            or not 0.0 <= float(r) <= 1.0
        ):
            raise ValueError(f"vote_radius must be a number in [0, 1], got {r!r}")
        object.__setattr__(self, "vote_radius", float(r))

    def to_dict(self) -> dict[str, Any]:
        """Plain values (the rule as a string), e.g. for a results row."""
        return {
            "n_trees": self.n_trees,
            "merge": MergeRule(self.merge).value,
            "vote_radius": self.vote_radius,
        }


def merge_rule(value: object) -> MergeRule:
    """``value`` as a :class:`MergeRule`, or a ValueError listing the valid rules."""
    try:
        return MergeRule(str(value).strip().lower().replace("-", "_"))
    except ValueError:
        valid = ", ".join(r.value for r in MergeRule)
        raise ValueError(f"unknown merge rule {value!r}; valid merge rules are: {valid}") from None


def tree_seeds(
    seed: int | Sequence[int] | np.random.SeedSequence | None, n_trees: int
) -> list[np.random.SeedSequence]:
    """The seeds of ``n_trees`` trees: ``SeedSequence(seed).spawn(n_trees)``.

    A :class:`~numpy.random.SeedSequence` passed as ``seed`` is not advanced (a copy with
    its entropy and spawn key is spawned from), so the same call always gives the same
    seeds. Tree ``k``'s seed does not depend on ``n_trees``.
    """
    if isinstance(n_trees, bool) or not isinstance(n_trees, int | np.integer) or n_trees < 1:
        raise ValueError(f"n_trees must be an integer >= 1, got {n_trees!r}")
    if isinstance(seed, np.random.SeedSequence):
        base = np.random.SeedSequence(
            seed.entropy, spawn_key=seed.spawn_key, pool_size=seed.pool_size
        )
    else:
        base = np.random.SeedSequence(seed)
    return base.spawn(int(n_trees))


# ----- root statistics and the merge ---------------------------------------------------------
@dataclass(frozen=True)
class RootStats:
    """A tree's root edges, as the merge needs them.

    Attributes:
        actions: ``(m, d)`` tried root actions, in the order they were tried.
        q: :math:`\\hat Q` of each (``m``).
        n: visit count of each (``m``).
        feasible: whether each was feasible (``m``).
        lower, upper: the root's action box (``d`` each), for the ``vote`` distance.
    """

    actions: FloatArray
    q: FloatArray
    n: np.ndarray[Any, np.dtype[np.int64]]
    feasible: np.ndarray[Any, np.dtype[np.bool_]]
    lower: FloatArray
    upper: FloatArray

    def __post_init__(self) -> None:
        lo = np.array(self.lower, dtype=np.float64).reshape(-1)
        hi = np.array(self.upper, dtype=np.float64).reshape(-1)
        if lo.shape != hi.shape or lo.size == 0 or not np.all(hi > lo):
            raise ValueError(
                f"root box must have lower < upper in every dimension, got {lo} and {hi}"
            )
        d = lo.size
        acts = np.array(self.actions, dtype=np.float64)
        if acts.size == 0:
            acts = acts.reshape(0, d)
        if acts.ndim != 2 or acts.shape[1] != d:
            raise ValueError(f"root actions must be an (m, {d}) array, got shape {acts.shape}")
        m = acts.shape[0]
        q = np.array(self.q, dtype=np.float64).reshape(-1)
        n = np.array(self.n, dtype=np.int64).reshape(-1)
        feasible = np.array(self.feasible, dtype=bool).reshape(-1)
        for name, arr in (("q", q), ("n", n), ("feasible", feasible)):
            if arr.shape != (m,):
                raise ValueError(
                    f"root {name} must have {m} entries (one per action), got {arr.shape}"
                )
        for name, arr in (("actions", acts), ("q", q), ("n", n), ("feasible", feasible)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        lo.setflags(write=False)
        hi.setflags(write=False)
        object.__setattr__(self, "lower", lo)
        object.__setattr__(self, "upper", hi)

    @classmethod
    def from_node(cls, node: Node, lower: ArrayLike, upper: ArrayLike) -> RootStats:
        """The statistics of a tree node (the root) whose action box is ``[lower, upper]``."""
        d = np.asarray(lower).size
        return cls(
            actions=np.array(node.actions, dtype=np.float64).reshape(-1, d),
            q=np.array(node.q, dtype=np.float64),
            n=np.array(node.n, dtype=np.int64),
            feasible=np.array(node.feasible, dtype=bool),
            lower=np.asarray(lower, dtype=np.float64),
            upper=np.asarray(upper, dtype=np.float64),
        )

    @property
    def n_actions(self) -> int:
        return int(self.q.size)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RootStats):
            return NotImplemented
        return _same_fields(self, other)

    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True)
class MergeDecision:
    """The merged root action and why it was chosen.

    Attributes:
        rule: the merge rule.
        tree: the tree whose root edge was chosen.
        edge: the edge's index at that tree's root.
        action: the chosen root action.
        q: its :math:`\\hat Q`.
        visits: its visit count.
        score: what the rule maximised: :math:`\\hat Q` (``max_q``), visits
            (``most_visited``) or the neighbourhood's summed visits :math:`V` (``vote``).
        members: ``(tree, edge)`` of the candidates that voted for it (``vote``; the
            chosen edge alone otherwise).
        members_best_q: the best :math:`\\hat Q` among the members.
        members_mean_q: the members' visit-weighted mean :math:`\\hat Q`.
        n_candidates: the number of root edges the rule chose among.
    """

    rule: MergeRule
    tree: int
    edge: int
    action: FloatArray
    q: float
    visits: int
    score: float
    members: tuple[tuple[int, int], ...]
    members_best_q: float
    members_mean_q: float
    n_candidates: int

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, MergeDecision):
            return NotImplemented
        return _same_fields(self, other)

    __hash__ = None  # type: ignore[assignment]

    def to_dict(self) -> dict[str, Any]:
        """Plain values for a results row."""
        return {
            "rule": self.rule.value,
            "tree": self.tree,
            "edge": self.edge,
            "action": self.action.tolist(),
            "q": self.q,
            "visits": self.visits,
            "score": self.score,
            "members": [list(m) for m in self.members],
            "members_best_q": self.members_best_q,
            "members_mean_q": self.members_mean_q,
            "n_candidates": self.n_candidates,
        }


def normalized_distances(
    x: FloatArray, y: FloatArray, lower: FloatArray, upper: FloatArray
) -> FloatArray:
    """:math:`\\delta` between the rows of ``x`` and ``y`` (an ``(len(x), len(y))`` array):
    root-mean-square coordinate difference in units of the box's widths."""
    width = np.asarray(upper, dtype=np.float64) - np.asarray(lower, dtype=np.float64)
    zx = np.asarray(x, dtype=np.float64) / width
    zy = np.asarray(y, dtype=np.float64) / width
    diff = zx[:, None, :] - zy[None, :, :]
    out: FloatArray = np.sqrt(np.mean(diff * diff, axis=2))
    return out


#: Rows of the vote's pairwise distances computed at once (bounds its memory).
_VOTE_BLOCK = 512


def merge_roots(
    roots: Sequence[RootStats],
    rule: MergeRule | str = MergeRule.MAX_Q,
    vote_radius: float = 0.1,
) -> MergeDecision | None:
    """The merged root action of ``roots`` (one per tree, in tree order); None if no
    tree's root has an action. See the module docstring for the rules.

    Raises:
        ValueError: unknown rule, bad radius, or roots with different action boxes (the
            trees did not search the same root state).
    """
    rule = merge_rule(rule)
    RootParallelConfig(n_trees=max(1, len(roots)), merge=rule, vote_radius=vote_radius)
    if not roots:
        return None
    first = roots[0]
    for k, r in enumerate(roots):
        if not (np.array_equal(r.lower, first.lower) and np.array_equal(r.upper, first.upper)):
            raise ValueError(
                f"tree {k}'s root box [{r.lower}, {r.upper}] differs from tree 0's"
                f" [{first.lower}, {first.upper}]: the trees must search the same root state"
                " (does the problem factory always build the same initial state?)"
            )
    tree_idx = np.concatenate(
        [np.full(r.n_actions, k, dtype=np.int64) for k, r in enumerate(roots)]
    )
    edge_idx = np.concatenate([np.arange(r.n_actions, dtype=np.int64) for r in roots])
    if tree_idx.size == 0:
        return None
    actions = np.concatenate([r.actions for r in roots], axis=0)
    q = np.concatenate([r.q for r in roots])
    n = np.concatenate([r.n for r in roots])
    feasible = np.concatenate([r.feasible for r in roots])
    keep = np.flatnonzero(feasible) if feasible.any() else np.arange(q.size)
    tree_idx, edge_idx = tree_idx[keep], edge_idx[keep]
    actions, q, n = actions[keep], q[keep], n[keep]
    m = q.size
    if rule is MergeRule.VOTE:
        neighbours = np.zeros((m, m), dtype=bool)
        limit = float(vote_radius)
        for s in range(0, m, _VOTE_BLOCK):
            block = normalized_distances(
                actions[s : s + _VOTE_BLOCK], actions, first.lower, first.upper
            )
            neighbours[s : s + _VOTE_BLOCK] = block <= limit
        np.fill_diagonal(neighbours, True)
        score = neighbours.astype(np.int64) @ n
        primary, secondary = score.astype(np.float64), q
    elif rule is MergeRule.MOST_VISITED:
        primary, secondary = n.astype(np.float64), q
    else:
        primary, secondary = q, np.zeros(m)
    # Lexicographic maximum of (primary, secondary), the lowest (tree, edge) on ties:
    # candidates are in (tree, edge) order, so np.lexsort's stable order gives the first.
    order = np.lexsort((-secondary, -primary))
    best = int(order[0])
    if rule is MergeRule.VOTE:
        members = np.flatnonzero(neighbours[best])
    else:
        members = np.array([best])
    w = n[members].astype(np.float64)
    mq = q[members]
    finite = np.isfinite(mq)
    if finite.any() and w[finite].sum() > 0:
        mean_q = float(np.sum(w[finite] * mq[finite]) / np.sum(w[finite]))
    else:
        mean_q = float(np.max(mq))
    return MergeDecision(
        rule=rule,
        tree=int(tree_idx[best]),
        edge=int(edge_idx[best]),
        action=actions[best].copy(),
        q=float(q[best]),
        visits=int(n[best]),
        score=float(primary[best]),
        members=tuple((int(tree_idx[j]), int(edge_idx[j])) for j in members),
        members_best_q=float(np.max(mq)),
        members_mean_q=mean_q,
        n_candidates=int(m),
    )


# ----- one tree (runs in a worker) --------------------------------------------------------------
@dataclass(frozen=True)
class TreeTask:
    """One tree's work, sent to a worker (it pickles if the problem source does).

    Attributes:
        index: the tree's index :math:`k`.
        source: the problem, or a zero-argument factory that builds it.
        is_factory: whether ``source`` is a factory.
        root_snapshot: the root state to restore first (problems passed as objects).
        config: the search's configuration.
        n_simulations: simulations of this tree.
        seed: the tree's seed (see :func:`tree_seeds`).
        record_info: a step-info key to record at the best leaf (see :meth:`MCTS.search`).
        keep_tree: return the search object in ``plan.mcts`` (in-process executors only).
        time_limit: stop after this many seconds of search even before ``n_simulations``.
    """

    index: int
    source: Any
    is_factory: bool
    root_snapshot: Any
    config: MCTSConfig
    n_simulations: int
    seed: np.random.SeedSequence
    record_info: str | None = None
    keep_tree: bool = False
    time_limit: float | None = None


@dataclass(frozen=True)
class TreeResult:
    """What one tree found.

    Attributes:
        index: the tree's index :math:`k`.
        seed: its seed.
        plan: its :class:`~voot.tree.PlanResult` (``mcts`` is None unless the tree was
            kept by an in-process executor).
        root: its root statistics (what the merge sees).
        started: ``time.time()`` when its search started (for wall-time alignment).
        elapsed: seconds since its search started, after every simulation.
        pid: the process that ran it.
        cpu_time: CPU seconds its process spent in the search (wall time minus waiting
            for a core, on a shared machine).
    """

    index: int
    seed: np.random.SeedSequence = field(compare=False)
    plan: PlanResult = field(compare=False)
    root: RootStats
    started: float = field(compare=False)
    elapsed: FloatArray = field(compare=False, repr=False)
    pid: int = field(compare=False)
    cpu_time: float = field(default=math.nan, compare=False)

    def __eq__(self, other: object) -> bool:
        """Equal if the seed determines the same tree: timings, process and tree ignored."""
        if not isinstance(other, TreeResult):
            return NotImplemented
        return (
            _same_fields(self, other)
            and _same(self.seed.entropy, other.seed.entropy)
            and self.seed.spawn_key == other.seed.spawn_key
            and all(_same(getattr(self.plan, f), getattr(other.plan, f)) for f in _PLAN_FIELDS)
        )

    __hash__ = None  # type: ignore[assignment]


_PROBLEM_CACHE: OrderedDict[bytes, tuple[PlanningProblem, Any]] = OrderedDict()


def clear_problem_cache() -> None:
    """Forget the problems this process built from factories."""
    _PROBLEM_CACHE.clear()


def _problem_of(task: TreeTask) -> tuple[PlanningProblem, Any]:
    """The task's problem and its root snapshot (a factory's problem is kept per process)."""
    if not task.is_factory:
        return task.source, task.root_snapshot
    try:
        key: bytes | None = pickle.dumps(task.source)
    except Exception:  # a lambda, a closure: built afresh every time
        key = None
    if key is not None and key in _PROBLEM_CACHE:
        _PROBLEM_CACHE.move_to_end(key)
        return _PROBLEM_CACHE[key]
    problem = task.source()
    entry = (problem, problem.snapshot())
    if key is not None:
        _PROBLEM_CACHE[key] = entry
        while len(_PROBLEM_CACHE) > PROBLEM_CACHE_SIZE:
            _PROBLEM_CACHE.popitem(last=False)
    return entry


def prebuild_problem(factory: ProblemFactory) -> None:
    """Build ``factory``'s problem into this process's cache now (a worker initializer)."""
    _problem_of(TreeTask(0, factory, True, None, MCTSConfig(), 1, np.random.SeedSequence(0)))


def run_tree(task: TreeTask) -> TreeResult:
    """Run one tree (the worker function; module-level so that it pickles)."""
    problem, snapshot = _problem_of(task)
    problem.restore(snapshot)
    mcts = MCTS(problem, task.config, seed=task.seed)
    elapsed: list[float] = []
    clock = time.perf_counter
    started = time.time()
    c0 = time.process_time()
    t0 = clock()

    limit = math.inf if task.time_limit is None else task.time_limit

    def tick(_: MCTS, __: int) -> bool:
        t = clock() - t0
        elapsed.append(t)
        return t >= limit

    res = mcts.search(task.n_simulations, callback=tick, record_info=task.record_info)
    cpu = time.process_time() - c0
    bounds = mcts.root.bounds if mcts.root.bounds is not None else problem_bounds(problem)
    root = RootStats.from_node(mcts.root, bounds.lower, bounds.upper)
    problem.restore(snapshot)
    return TreeResult(
        index=task.index,
        seed=task.seed,
        plan=res if task.keep_tree else replace(res, mcts=None),
        root=root,
        started=started,
        elapsed=np.array(elapsed, dtype=np.float64),
        pid=os.getpid(),
        cpu_time=cpu,
    )


# ----- executors -----------------------------------------------------------------------------
@runtime_checkable
class TreeExecutor(Protocol):
    """Runs ``fn`` on every item; results may come back in any order (the plug-in point
    for other backends, e.g. Ray: ``ray.get([remote(fn).remote(i) for i in items])``)."""

    def map(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterable[R]: ...


class SerialExecutor:
    """Runs the trees one after the other in this process (tests; already-parallel sweeps)."""

    in_process = True

    def map(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        for item in items:
            yield fn(item)


class LocalProcessExecutor:
    """A :class:`~concurrent.futures.ProcessPoolExecutor` kept between searches.

    Args:
        max_workers: worker processes (default ``os.cpu_count()``).
        start_method: ``"spawn"`` (default: a fresh interpreter per worker, nothing of
            the parent's state leaks in; slower to start), ``"forkserver"`` or ``"fork"``.
        initializer: run as ``initializer(*initargs)`` in every worker when it starts,
            e.g. ``initializer=prebuild_problem, initargs=(factory,)`` to build a MuJoCo
            problem in every worker before the first (timed) search.
        initargs: the initializer's arguments.

    The pool starts at the first :meth:`map` and lives until :meth:`close` (or the end of
    a ``with`` block), so problems built from factories stay built in its workers: keep
    one executor for many searches (an execution loop, a benchmark) to pay the start-up
    and the problem construction once.
    """

    in_process = False

    def __init__(
        self,
        max_workers: int | None = None,
        start_method: str = "spawn",
        initializer: Callable[..., object] | None = None,
        initargs: tuple[Any, ...] = (),
    ) -> None:
        n = (os.cpu_count() or 1) if max_workers is None else max_workers
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise ValueError(f"max_workers must be an integer >= 1, got {max_workers!r}")
        valid = multiprocessing.get_all_start_methods()
        if start_method not in valid:
            raise ValueError(
                f"unknown start method {start_method!r}; valid start methods are: {', '.join(valid)}"
            )
        self.max_workers = n
        self.start_method = start_method
        self.initializer = initializer
        self.initargs = tuple(initargs)
        self._pool: ProcessPoolExecutor | None = None

    def map(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """Submit every item, yield results as they complete (the first error is raised)."""
        items = list(items)
        with single_threaded_children():
            if self._pool is None:
                ctx = multiprocessing.get_context(self.start_method)
                self._pool = ProcessPoolExecutor(
                    max_workers=self.max_workers,
                    mp_context=ctx,
                    initializer=self.initializer,
                    initargs=self.initargs,
                )
            futures: list[Future[R]] = [self._pool.submit(fn, item) for item in items]
        pending = set(futures)
        try:
            while pending:
                done, pending = wait(pending, return_when=FIRST_EXCEPTION)
                for fut in done:
                    yield fut.result()
        finally:
            for fut in pending:
                fut.cancel()

    def warm_up(self) -> None:
        """Start every worker process now (so that a timed search does not pay for it)."""
        list(self.map(_pid, [None] * (2 * self.max_workers)))

    def close(self, *, kill: bool = False) -> None:
        """Shut the pool down (its workers and their problems go).

        Args:
            kill: terminate the workers instead of letting running trees finish (after
                an error or an interrupt, so that no orphan keeps computing).
        """
        pool, self._pool = self._pool, None
        if pool is None:
            return
        if kill:
            terminate = getattr(pool, "terminate_workers", None)  # Python >= 3.14
            if callable(terminate):
                terminate()
            else:
                for process in list((getattr(pool, "_processes", None) or {}).values()):
                    with contextlib.suppress(Exception):
                        process.terminate()
        pool.shutdown(wait=True, cancel_futures=True)

    def __enter__(self) -> LocalProcessExecutor:
        return self

    def __exit__(self, exc_type: object, *exc: object) -> None:
        self.close(kill=exc_type is not None)


def _pid(_: object) -> int:
    time.sleep(0.05)  # keep this worker busy so that the next item starts another one
    return os.getpid()


#: Executor names accepted by :func:`plan_root_parallel`.
EXECUTORS = ("process", "serial")


def _map(executor: Any, fn: Callable[[T], R], items: Sequence[T]) -> Iterable[R]:
    mapper = getattr(executor, "map", None)
    if not callable(mapper):
        mapper = getattr(executor, "map_unordered", None)
    if not callable(mapper):
        raise ValueError(
            f"executor must be one of {', '.join(EXECUTORS)} or an object with"
            f" map(fn, items) (or map_unordered(fn, items)); got {type(executor).__name__}"
        )
    return mapper(fn, items)  # type: ignore[no-any-return]


# ----- the merged result ---------------------------------------------------------------------
@dataclass(frozen=True)
class RootParallelResult:
    """The outcome of a root-parallel search.

    Attributes:
        parallel: the root-parallel options.
        trees: every tree's result, in tree order.
        decision: the merge decision (None if no root has an action).
        best_action: the merged root action (None if no root has an action).
        best_tree: the tree holding the best plan (highest best return; lowest on ties).
        actions, rewards, bonuses, feasible, best_return, best_leaf_info: the best plan
            (the best tree's), as in :class:`~voot.tree.PlanResult`.
        best_return_curve: :math:`B_K(i) = \\max_k B^{(k)}(i)`, ``i = 1 .. N``.
        info_curve: at each index, ``info[record_info]`` of the tree best at that index
            (lowest on ties), if asked.
        n_simulations: simulations per tree (:math:`N`; the longest tree's).
        total_simulations: simulations of all trees.
        n_nodes, n_steps, n_feasibility_checks, n_node_visits: sums over trees.
        started: ``time.time()`` at the start of the call.
        wall_time: seconds of the whole call (workers, transfer and merge included).
        search_time: the trees' search seconds summed (compute, not wall time).
        cpu_time: the trees' CPU seconds summed.
    """

    parallel: RootParallelConfig
    trees: tuple[TreeResult, ...]
    decision: MergeDecision | None
    best_action: FloatArray | None
    best_tree: int
    actions: tuple[FloatArray, ...]
    rewards: FloatArray
    bonuses: FloatArray
    feasible: tuple[bool, ...]
    best_return: float
    best_leaf_info: Mapping[str, Any]
    best_return_curve: FloatArray
    info_curve: tuple[Any, ...] | None
    n_simulations: int
    total_simulations: int
    n_nodes: int
    n_steps: int
    n_feasibility_checks: int
    n_node_visits: int
    started: float = field(compare=False)
    wall_time: float = field(compare=False)
    search_time: float = field(compare=False)
    cpu_time: float = field(default=math.nan, compare=False)

    def __eq__(self, other: object) -> bool:
        """Equal if everything a seed determines is equal (timings are ignored)."""
        if not isinstance(other, RootParallelResult):
            return NotImplemented
        return _same_fields(self, other)

    __hash__ = None  # type: ignore[assignment]

    @property
    def n_trees(self) -> int:
        return len(self.trees)

    @property
    def plan(self) -> PlanResult:
        """The best tree's :class:`~voot.tree.PlanResult`."""
        return self.trees[self.best_tree].plan

    @property
    def tree_best_returns(self) -> FloatArray:
        """Each tree's best return."""
        return np.array([t.plan.best_return for t in self.trees], dtype=np.float64)

    def curve_by_total_simulations(self) -> tuple[np.ndarray[Any, np.dtype[np.int64]], FloatArray]:
        """``(K i, B_K(i))``: the merged curve against the simulations of all trees."""
        x = self.n_trees * np.arange(1, self.best_return_curve.size + 1, dtype=np.int64)
        return x, self.best_return_curve

    def best_return_at(self, seconds: ArrayLike) -> FloatArray:
        """The best return known ``seconds`` after the call started (wall clock).

        Tree :math:`k`'s simulation :math:`i` counts once its worker finished it, at
        ``trees[k].started - started + trees[k].elapsed[i]``; the result is the maximum
        over trees of their best return by then (:math:`-\\infty` before any). Workers'
        clocks must agree (one machine, or synchronised hosts).
        """
        t = np.asarray(seconds, dtype=np.float64)
        out = np.full(t.shape, -math.inf)
        for tree in self.trees:
            done = (tree.started - self.started) + tree.elapsed
            curve = tree.plan.best_return_curve
            count = np.searchsorted(done, t, side="right")
            value = np.where(count > 0, curve[np.maximum(count - 1, 0)], -math.inf)
            out = np.maximum(out, value)
        return out

    def summary(self) -> dict[str, Any]:
        """Plain values for a results row (curves as lists)."""
        return {
            **self.parallel.to_dict(),
            "best_return": self.best_return,
            "best_tree": self.best_tree,
            "plan_length": len(self.actions),
            "best_action": None if self.best_action is None else self.best_action.tolist(),
            "decision": None if self.decision is None else self.decision.to_dict(),
            "tree_best_returns": self.tree_best_returns.tolist(),
            "n_simulations": self.n_simulations,
            "total_simulations": self.total_simulations,
            "n_nodes": self.n_nodes,
            "n_steps": self.n_steps,
            "n_feasibility_checks": self.n_feasibility_checks,
            "n_node_visits": self.n_node_visits,
            "wall_time": self.wall_time,
            "search_time": self.search_time,
            "cpu_time": self.cpu_time,
            "best_return_curve": self.best_return_curve.tolist(),
        }


def merge_trees(
    trees: Sequence[TreeResult], parallel: RootParallelConfig, started: float, wall_time: float
) -> RootParallelResult:
    """Combine the trees' results (in any order) into a :class:`RootParallelResult`.

    Raises:
        RuntimeError: the results are not exactly one per tree ``0 .. K-1``.
    """
    ordered = sorted(trees, key=lambda t: t.index)
    if [t.index for t in ordered] != list(range(parallel.n_trees)):
        raise RuntimeError(
            f"expected one result for each of trees 0..{parallel.n_trees - 1}, got indices"
            f" {[t.index for t in ordered]}"
        )
    decision = merge_roots([t.root for t in ordered], parallel.merge, parallel.vote_radius)
    returns = [t.plan.best_return for t in ordered]
    best_tree = int(np.argmax(returns))  # first on ties
    best = ordered[best_tree].plan
    length = max(t.plan.best_return_curve.size for t in ordered)
    curves = np.full((len(ordered), length), -math.inf)
    for k, t in enumerate(ordered):
        c = t.plan.best_return_curve
        if c.size:
            curves[k, : c.size] = c
            curves[k, c.size :] = c[-1]  # a tree that stopped early keeps its best
    curve = curves.max(axis=0) if length else np.empty(0)
    info_curve: tuple[Any, ...] | None = None
    if all(t.plan.info_curve is not None for t in ordered) and length:
        leaders = np.argmax(curves, axis=0)
        infos = [t.plan.info_curve or () for t in ordered]
        info_curve = tuple(
            infos[k][min(i, len(infos[k]) - 1)] if infos[k] else None
            for i, k in enumerate(leaders.tolist())
        )
    return RootParallelResult(
        parallel=parallel,
        trees=tuple(ordered),
        decision=decision,
        best_action=None if decision is None else decision.action.copy(),
        best_tree=best_tree,
        actions=best.actions,
        rewards=best.rewards,
        bonuses=best.bonuses,
        feasible=best.feasible,
        best_return=float(best.best_return),
        best_leaf_info=best.best_leaf_info,
        best_return_curve=curve,
        info_curve=info_curve,
        n_simulations=length,
        total_simulations=sum(t.plan.n_simulations for t in ordered),
        n_nodes=sum(t.plan.n_nodes for t in ordered),
        n_steps=sum(t.plan.n_steps for t in ordered),
        n_feasibility_checks=sum(t.plan.n_feasibility_checks for t in ordered),
        n_node_visits=sum(t.plan.n_node_visits for t in ordered),
        started=started,
        wall_time=wall_time,
        search_time=sum(t.plan.wall_time for t in ordered),
        cpu_time=sum(t.cpu_time for t in ordered),
    )


# ----- the planner -----------------------------------------------------------------------------
def _is_problem(obj: object) -> bool:
    return all(
        callable(getattr(obj, m, None)) for m in ("snapshot", "restore", "step", "action_bounds")
    )


def plan_root_parallel(
    problem: PlanningProblem | ProblemFactory,
    planner: str | MCTSConfig = "voot",
    n_simulations: int = 1000,
    seed: int | np.random.SeedSequence | None = 0,
    *,
    n_trees: int = 2,
    merge: MergeRule | str = MergeRule.MAX_Q,
    vote_radius: float = 0.1,
    executor: str | TreeExecutor | Any = "process",
    max_workers: int | None = None,
    record_info: str | None = None,
    keep_trees: bool = False,
    time_limit: float | None = None,
    **options: Any,
) -> RootParallelResult:
    """Root-parallel search: ``n_trees`` independent trees, merged at the root.

    Args:
        problem: the planning problem (its current state is the root), or a zero-argument
            factory that builds it in the root state (for problems that do not pickle, or
            not cheaply, e.g. MuJoCo environments; it must build the same state every call).
        planner: a planner name or an :class:`~voot.tree.MCTSConfig` (every tree's).
        n_simulations: simulations *per tree* (:math:`N`; the trees run :math:`K N` in all).
        seed: the base seed; tree :math:`k` gets ``tree_seeds(seed, K)[k]``.
        n_trees: :math:`K`.
        merge: the root merge rule (``max_q``, ``most_visited``, ``vote``).
        vote_radius: the ``vote`` neighbourhood radius (see :class:`RootParallelConfig`).
        executor: ``"process"`` (a :class:`LocalProcessExecutor` of
            ``min(K, max_workers or os.cpu_count())`` workers for this call only; pass your
            own to keep it between calls), ``"serial"``, or any object with
            ``map(fn, items)`` (or ``map_unordered``), e.g. a
            :class:`concurrent.futures.Executor`.
        max_workers: worker processes of ``executor="process"``.
        record_info: a step-info key recorded at each tree's best leaf (see
            :meth:`voot.tree.MCTS.search`) and merged into ``info_curve``.
        keep_trees: keep each tree's search object in ``trees[k].plan.mcts``; only with
            an in-process executor (``"serial"``).
        time_limit: seconds of search after which each tree stops, even before
            ``n_simulations`` (an anytime planner with a deadline). With a time limit the
            result depends on the machine's speed and load: it is *not* deterministic.
        **options: :class:`~voot.tree.MCTSConfig` fields overriding the planner's.

    Without ``time_limit`` the merged result depends only on the problem, the
    configuration and ``seed``: not on the executor, the number of workers, or the order
    in which trees finish.

    >>> from voot.tree.null_problem import NullProblem
    >>> res = plan_root_parallel(NullProblem(dim=2), "voot", 20, seed=0, n_trees=3,
    ...                          executor="serial", depth_limit=3)
    >>> res.best_return_curve.shape, res.total_simulations
    ((20,), 60)
    """
    n = check_n_simulations(n_simulations)
    parallel = RootParallelConfig(n_trees=n_trees, merge=merge, vote_radius=vote_radius)
    if isinstance(planner, MCTSConfig):
        config = planner.replace(**options) if options else planner
    else:
        config = planner_config(planner, **options)
    if record_info is not None and not isinstance(record_info, str):
        raise ValueError(
            f"record_info must be a step-info key (a string) or None, got {record_info!r}"
        )
    if not isinstance(keep_trees, bool):
        raise ValueError(f"keep_trees must be True or False, got {keep_trees!r}")
    if time_limit is not None and (
        isinstance(time_limit, bool)
        or not isinstance(time_limit, int | float)
        or not math.isfinite(time_limit)
        or time_limit <= 0
    ):
        raise ValueError(f"time_limit must be a number of seconds > 0 or None, got {time_limit!r}")
    is_factory = not _is_problem(problem)
    if is_factory and not callable(problem):
        raise ValueError(
            f"problem must be a PlanningProblem (snapshot, restore, step, action_bounds) or a"
            f" zero-argument factory building one; got {type(problem).__name__}"
        )
    own_pool: LocalProcessExecutor | None = None
    if max_workers is not None and executor != "process":
        raise ValueError("max_workers applies to executor='process' only")
    if isinstance(executor, str):
        if executor == "serial":
            executor = SerialExecutor()
        elif executor == "process":
            if max_workers is not None and (
                isinstance(max_workers, bool) or not isinstance(max_workers, int) or max_workers < 1
            ):
                raise ValueError(f"max_workers must be an integer >= 1, got {max_workers!r}")
            workers = min(parallel.n_trees, max_workers or os.cpu_count() or 1)
            executor = own_pool = LocalProcessExecutor(workers)
        else:
            raise ValueError(
                f"unknown executor {executor!r}; valid executors are: {', '.join(EXECUTORS)}"
                " (or an object with map(fn, items))"
            )
    in_process = bool(getattr(executor, "in_process", False))
    if keep_trees and not in_process:
        raise ValueError(
            "keep_trees=True needs an in-process executor (executor='serial'): a tree built"
            " in another process is not sent back"
        )
    root_snapshot = None
    if not is_factory:
        root_snapshot = problem.snapshot()  # type: ignore[union-attr]
        if not in_process:
            try:
                pickle.dumps(problem)
            except Exception as exc:
                raise ValueError(
                    f"{type(problem).__name__} cannot be sent to worker processes ({exc});"
                    " pass a zero-argument factory that builds it, or executor='serial'"
                ) from None
    tasks = [
        TreeTask(
            index=k,
            source=problem,
            is_factory=is_factory,
            root_snapshot=root_snapshot,
            config=config,
            n_simulations=n,
            seed=s,
            record_info=record_info,
            keep_tree=keep_trees,
            time_limit=None if time_limit is None else float(time_limit),
        )
        for k, s in enumerate(tree_seeds(seed, parallel.n_trees))
    ]
    started = time.time()
    t0 = time.perf_counter()
    failed = True
    try:
        results = list(_map(executor, run_tree, tasks))
        failed = False
    finally:
        if own_pool is not None:
            own_pool.close(kill=failed)
        if not is_factory:
            problem.restore(root_snapshot)  # type: ignore[union-attr]
    return merge_trees(results, parallel, started, time.perf_counter() - t0)
