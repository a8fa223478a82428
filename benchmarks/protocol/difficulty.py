"""How hard a robot domain is, measured without any planner: ``voot-bench difficulty``.

Planner-agnostic statistics of a domain version (v0 or v1), from uniform random actions:

* **per node type** (kitchen: the first pick and the first place; conveyor: the first
  place of three boxes), the fraction of uniform actions that pass the pre-check
  (stage 1, :mod:`voot.tree.problem`) and, of those, the fraction that then pass
  execution (stage 2), with the reasons of the execution failures (by the step info's
  ``reason_code``). Under v0 the
  pre-check is the whole step, so every action that passes it is executed successfully;
* **random rollouts**: from the start, every action is drawn uniformly until it passes
  the pre-check (at most ``retries`` draws, the planners' 50; if all fail the last is
  executed), then executed; a rollout ends at an infeasible action or the goal. The
  fraction of rollouts that clear everything estimates the chance that a random
  pre-check-feasible rollout solves the task, with a 95% Wilson interval;
* **the scripted solution** (:mod:`voot.envs.kitchen.scripted`, :mod:`voot.envs.conveyor.scripted`): whether it still solves the
  version, and its return.

Same arguments and seed -> the same numbers (the envs and the draws are deterministic).
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from voot import validation as V
from voot.problems import problem_record
from voot.tree.step_info import StepInfo

#: Domain versions reported by default.
DEFAULT_ENVS: tuple[str, ...] = (
    "voot/KitchenClearing-v0",
    "voot/KitchenClearing-v1",
    "voot/ConveyorPacking-v0",
    "voot/ConveyorPacking-v1",
)
#: The planners' feasibility retries per new action (the paper's 50).
RETRIES = 50


@dataclass(frozen=True)
class NodeStats:
    """Uniform actions at one node: how many pass each stage, and why execution fails."""

    env_id: str
    node: str
    samples: int
    passed_precheck: int
    passed_execution: int
    execution_failures: dict[str, int] = field(default_factory=dict)

    @property
    def precheck_rate(self) -> float:
        return self.passed_precheck / self.samples

    @property
    def execution_rate(self) -> float:
        """Of the actions that passed the pre-check, the fraction executed feasibly."""
        return self.passed_execution / self.passed_precheck if self.passed_precheck else math.nan


@dataclass(frozen=True)
class RolloutStats:
    """Random pre-check-feasible rollouts from the start."""

    env_id: str
    rollouts: int
    solved: int
    mean_handled: float
    initial_objects: int

    def interval(self) -> tuple[float, float]:
        """95% Wilson interval of the solve rate."""
        return wilson(self.solved, self.rollouts)


@dataclass(frozen=True)
class ScriptedStats:
    """The hand-made solution replayed on the version."""

    env_id: str
    solved: bool
    actions: int
    total_return: float
    failure: str


def wilson(k: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion ``k / n``."""
    if n <= 0:
        return (math.nan, math.nan)
    p = k / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denom
    return (max(0.0, centre - half), min(1.0, centre + half))


def _problem(env_id: str, env_kwargs: Mapping[str, Any] | None = None) -> Any:
    import gymnasium

    from voot.envs.core.problem import EnvProblem

    env = gymnasium.make(env_id, disable_env_checker=True, **dict(env_kwargs or {}))
    return EnvProblem(env.unwrapped, seed=0)


def _nodes(problem: Any) -> list[tuple[str, Any]]:
    """(name, snapshot) of the node types measured: the start's, and the node after the
    env's known solution's first action if its operator differs (the kitchen's first pick
    and place; the conveyor's first place)."""
    u = problem.unwrapped
    start = problem.snapshot()
    first = u.current_operator()
    nodes = [(u.node_label(first), start)]
    res = problem.step(u.solution_actions()[0][: problem.action_bounds().dim])
    if not res.feasible:  # pragma: no cover - the known solutions are tested
        raise RuntimeError(f"the known solution's first action is infeasible: {res.info['reason']}")
    operator = u.current_operator()
    if operator != first:
        nodes.append((u.node_label(operator), problem.snapshot()))
    problem.restore(start)
    return nodes


def node_stats(
    env_id: str, samples: int, seed: int = 0, env_kwargs: Mapping[str, Any] | None = None
) -> list[NodeStats]:
    """Pre-check and execution rates of ``samples`` uniform actions per node type."""
    problem = _problem(env_id, env_kwargs)
    rng = np.random.default_rng(seed)
    out = []
    for name, snapshot in _nodes(problem):
        passed, executed, failures = uniform_draws(problem, snapshot, samples, rng)
        out.append(NodeStats(env_id, name, samples, passed, executed, dict(failures)))
    return out


def uniform_draws(
    problem: Any, snapshot: Any, samples: int, rng: np.random.Generator
) -> tuple[int, int, Counter[str]]:
    """Draw ``samples`` uniform actions at the node ``snapshot`` of ``problem`` (an
    :class:`~voot.envs.core.problem.EnvProblem`), each from that node: how many pass the
    pre-check, how many of those execute, and the execution failures by reason code
    (:attr:`~voot.tree.step_info.StepInfo.reason_code`). The problem is left at ``snapshot``."""
    problem.restore(snapshot)
    bounds = problem.action_bounds()
    passed = executed = 0
    failures: Counter[str] = Counter()
    for _ in range(samples):
        a = bounds.sample(rng)
        problem.restore(snapshot)
        if not problem.is_feasible(a):
            continue
        passed += 1
        res = problem.step(a)
        if res.feasible:
            executed += 1
        else:
            failures[StepInfo.of(res.info).reason_code] += 1
    problem.restore(snapshot)
    return passed, executed, failures


def rollout_stats(
    env_id: str,
    rollouts: int,
    seed: int = 0,
    retries: int = RETRIES,
    env_kwargs: Mapping[str, Any] | None = None,
) -> RolloutStats:
    """Random pre-check-feasible rollouts (see the module docstring)."""
    problem = _problem(env_id, env_kwargs)
    rng = np.random.default_rng(seed)
    start = problem.snapshot()
    initial = int(problem.unwrapped.objects_left)
    solved = 0
    handled = 0
    for _ in range(rollouts):
        problem.restore(start)
        while True:
            bounds = problem.action_bounds()
            a = bounds.sample(rng)
            for _t in range(retries - 1):
                if problem.is_feasible(a):
                    break
                a = bounds.sample(rng)
            res = problem.step(a)
            if not res.feasible or res.terminal:
                break
        left = int(problem.unwrapped.objects_left)
        handled += initial - left
        solved += int(left == 0)
    problem.restore(start)
    return RolloutStats(env_id, rollouts, solved, handled / rollouts, initial)


def scripted_stats(env_id: str, env_kwargs: Mapping[str, Any] | None = None) -> ScriptedStats:
    """Replay the env's known solution (``solution_actions()``) on ``env_id``, discounted
    by the authors' discount of the problem (its record's)."""
    problem = _problem(env_id, env_kwargs)
    u = problem.unwrapped
    actions = u.solution_actions()
    gamma = problem_record(env_id).discount or 1.0
    total, discount, failure, n = 0.0, 1.0, "", 0
    for a in actions:
        res = problem.step(a[: problem.action_bounds().dim])
        n += 1
        total += discount * res.reward
        discount *= gamma
        if not res.feasible:
            failure = f"action {n}: {StepInfo.of(res.info).reason}"
            break
    solved = not failure and int(u.objects_left) == 0
    return ScriptedStats(env_id, solved, n, total, failure)


def report(
    env_ids: Sequence[str] = DEFAULT_ENVS,
    samples: int = 2000,
    rollouts: int = 200,
    seed: int = 0,
) -> str:
    """The difficulty tables as Markdown (what ``voot-bench difficulty`` prints)."""
    for name, v in (("samples", samples), ("rollouts", rollouts)):
        V.integer(v, name, 1)
    lines = [
        f"Uniform actions per node type ({samples} samples, seed {seed}):",
        "",
        "| environment | node | pass pre-check | of those, pass execution | execution failures |",
        "|---|---|---:|---:|---|",
    ]
    rollout_rows, scripted_rows = [], []
    for env_id in env_ids:
        for s in node_stats(env_id, samples, seed):
            fails = ", ".join(
                f"{k} {v / s.samples:.1%}"
                for k, v in sorted(s.execution_failures.items(), key=lambda kv: -kv[1])
            )
            exe = "-" if math.isnan(s.execution_rate) else f"{s.execution_rate:.1%}"
            lines.append(
                f"| {env_id} | {s.node} | {s.precheck_rate:.1%} | {exe} | {fails or '-'} |"
            )
        r = rollout_stats(env_id, rollouts, seed)
        lo, hi = r.interval()
        rollout_rows.append(
            f"| {env_id} | {r.rollouts} | {r.solved / r.rollouts:.1%} [{lo:.1%}, {hi:.1%}]"
            f" | {r.mean_handled:.2f} of {r.initial_objects} |"
        )
        sc = scripted_stats(env_id)
        scripted_rows.append(
            f"| {env_id} | {'yes' if sc.solved else 'no'} | {sc.actions} | {sc.total_return:.2f}"
            f" | {sc.failure or '-'} |"
        )
    lines += [
        "",
        f"Random pre-check-feasible rollouts ({RETRIES} draws per action, seed {seed}):",
        "",
        "| environment | rollouts | solved (95% CI) | objects handled (mean) |",
        "|---|---:|---:|---:|",
        *rollout_rows,
        "",
        "The scripted solution (the env's solution_actions(): voot.envs.kitchen.scripted,"
        " voot.envs.conveyor.scripted):",
        "",
        "| environment | solves | actions | discounted return | failure |",
        "|---|---|---:|---:|---|",
        *scripted_rows,
    ]
    return "\n".join(lines)
