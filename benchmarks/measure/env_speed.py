"""Speed benchmark of the two environments (a command, not a test).

``voot-bench measure env-speed [--n N] [--seed S]`` prints (:func:`run`, :func:`report`),
per operator (kitchen pick,
kitchen place, conveyor 3-box place):

* the median cost of one step, split into IK, collision checks and base motion planning
  (from :attr:`ManipulationEnv.last_timing`), for feasible and infeasible actions;
* steps per second for uniformly random actions (mean over all of them, including
  observation and info construction);
* how many of ``N`` uniformly random actions are feasible at the operator's first node
  (kitchen: the start state for picks, the state after the scripted first pick for
  places; conveyor: the start state): the sparsity of the reward;

and the median cost of ``get_state()`` and ``set_state()`` (snapshot restore).

Timed states: the start state and the states along the scripted solutions
(:mod:`voot.envs.kitchen.scripted`, :mod:`voot.envs.conveyor.scripted`), N uniformly random actions spread over them. Run it on an
otherwise idle core (``OMP_NUM_THREADS=1``) for figures comparable with the goals: a pick
check under 2 ms, a place including its base path under 5 ms, a restore under 50 us.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.scripted import conveyor_actions
from voot.envs.core.env import ManipulationEnv
from voot.envs.core.state import EnvState
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.scripted import kitchen_actions


@dataclass
class OperatorStats:
    """Timings (seconds) of random actions of one operator."""

    name: str
    feasible: list[dict[str, float]] = field(default_factory=list)
    infeasible: list[dict[str, float]] = field(default_factory=list)
    n_first_node: int = 0
    n_first_node_feasible: int = 0
    n_first_node_first_box: int = -1  # conveyor: actions whose first placement passed

    def add(self, timing: dict[str, float], feasible: bool) -> None:
        (self.feasible if feasible else self.infeasible).append(timing)

    @property
    def n(self) -> int:
        return len(self.feasible) + len(self.infeasible)

    def median(self, key: str, which: str) -> float:
        rows = self.feasible if which == "feasible" else self.infeasible
        return statistics.median(r[key] for r in rows) if rows else float("nan")

    def steps_per_second(self) -> float:
        wall = [r["wall"] for r in self.feasible + self.infeasible]
        return len(wall) / sum(wall) if wall else float("nan")


def _time_actions(
    env: ManipulationEnv[Any],
    states: list[EnvState[Any]],
    n: int,
    rng: np.random.Generator,
    stats: OperatorStats,
) -> None:
    dim = env.action_dim
    for k in range(n):
        env.set_state(states[k % len(states)])
        a = rng.uniform(-1.0, 1.0, dim)
        t0 = time.perf_counter()
        _, _, _, _, info = env.step(a)
        wall = time.perf_counter() - t0
        t = env.last_timing
        stats.add(
            {
                "ik": t.ik,
                "collision": t.collision,
                "planning": t.planning,
                "step": t.total,
                "wall": wall,
            },
            bool(info["feasible"]),
        )


def _count_feasible(
    env: ManipulationEnv[Any], state: EnvState[Any], n: int, rng: np.random.Generator
) -> tuple[int, int]:
    """Feasible actions among ``n`` uniform ones, and those whose first box passed."""
    dim = env.action_dim
    count = first = 0
    for _ in range(n):
        env.set_state(state)
        _, _, _, _, info = env.step(rng.uniform(-1.0, 1.0, dim))
        count += bool(info["feasible"])
        first += bool(info["feasible"]) or info.get("failed_box") != 0
    return count, first


def _median_time(fn: Callable[[], Any], repeats: int) -> float:
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return statistics.median(out)


def run(n: int = 1000, seed: int = 0) -> dict[str, Any]:
    """Measure everything; returns the figures (also used by the docs)."""
    rng = np.random.default_rng(seed)
    kitchen = KitchenClearingEnv()
    kitchen.reset(seed=seed)
    pick_states: list[EnvState[Any]] = []
    place_states: list[EnvState[Any]] = []
    for a in kitchen_actions(kitchen):
        (pick_states if kitchen.task.operator == "pick" else place_states).append(
            kitchen.get_state()
        )
        kitchen.step(a)
    pick = OperatorStats("kitchen pick (6-D)")
    place = OperatorStats("kitchen place (3-D)")
    _time_actions(kitchen, pick_states, n, rng, pick)
    _time_actions(kitchen, place_states, n, rng, place)
    pick.n_first_node = place.n_first_node = n
    pick.n_first_node_feasible = _count_feasible(kitchen, pick_states[0], n, rng)[0]
    place.n_first_node_feasible = _count_feasible(kitchen, place_states[0], n, rng)[0]
    restore = _median_time(lambda: kitchen.set_state(pick_states[3]), 2000)
    snapshot = _median_time(kitchen.get_state, 2000)

    conveyor = ConveyorPackingEnv()
    conveyor.reset(seed=seed)
    conv_states: list[EnvState[Any]] = []
    for a in conveyor_actions(conveyor):
        conv_states.append(conveyor.get_state())
        conveyor.step(a)
    conv = OperatorStats("conveyor place x3 (9-D)")
    _time_actions(conveyor, conv_states, n, rng, conv)
    conv.n_first_node = n
    conv.n_first_node_feasible, conv.n_first_node_first_box = _count_feasible(
        conveyor, conv_states[0], n, rng
    )
    conv_restore = _median_time(lambda: conveyor.set_state(conv_states[3]), 2000)
    return {
        "operators": [pick, place, conv],
        "kitchen_restore": restore,
        "kitchen_snapshot": snapshot,
        "conveyor_restore": conv_restore,
    }


def report(results: dict[str, Any]) -> str:
    """Format :func:`run`'s results as a text table (milliseconds)."""
    lines = [
        "median ms per step       |      feasible: IK  coll  plan  step |    infeasible: IK  coll  plan  step | steps/s | feasible/N at first node",
    ]
    for s in results["operators"]:
        f = [s.median(k, "feasible") * 1e3 for k in ("ik", "collision", "planning", "step")]
        i = [s.median(k, "infeasible") * 1e3 for k in ("ik", "collision", "planning", "step")]
        lines.append(
            f"{s.name:<25}| n={len(s.feasible):<5}"
            + " ".join(f"{v:5.2f}" for v in f)
            + f" | n={len(s.infeasible):<5}"
            + " ".join(f"{v:5.2f}" for v in i)
            + f" | {s.steps_per_second():7.0f} | {s.n_first_node_feasible}/{s.n_first_node}"
            + (f" (first box: {s.n_first_node_first_box})" if s.n_first_node_first_box >= 0 else "")
        )
    lines.append(
        f"snapshot restore (set_state): kitchen {results['kitchen_restore'] * 1e6:.1f} us, "
        f"conveyor {results['conveyor_restore'] * 1e6:.1f} us; "
        f"get_state: kitchen {results['kitchen_snapshot'] * 1e6:.1f} us"
    )
    return "\n".join(lines)
