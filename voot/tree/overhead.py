"""The planner's own overhead, measured on a problem whose step costs (almost) nothing.

Run ``python -m voot.tree.overhead`` (options: ``--help``). For every planner, action
dimension and budget it runs one search of depth ``--depth`` on :class:`NullProblem` and
prints the wall time per simulation and per node visit (a node visit is one action taken
inside a simulation, new or re-evaluated), and the process CPU time per node visit (the
figure to trust on a shared machine, where wall time includes waiting for a core). The null step is a few microseconds of Python,
so the figures are the search's cost: the goal is VOOT under 100 microseconds per node
visit, so that the simulator, not the search, bounds the speed.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence

import numpy as np

from voot.optim.base import Bounds, FloatArray
from voot.tree.config import planner_config
from voot.tree.mcts import MCTS
from voot.tree.problem import StepResult

#: The planners the paper compares, plus HOOT and Voronoi progressive widening.
DEFAULT_PLANNERS = ("voot", "doot", "rand_doot", "pw_uct", "voronoi_pw", "hoot")


class NullProblem:
    """A stateless problem with a nearly free step: reward :math:`1 - \\|a - c\\|_1 / (2d)`.

    Every action is feasible, nothing is terminal; the reward lies in [0, 1] and has a
    unique optimum 1 at ``c`` (``optimum``), so the samplers behave as on a real problem
    and longer plans are better. Snapshots are None.
    """

    def __init__(self, dim: int = 6, optimum: Sequence[float] | None = None) -> None:
        if isinstance(dim, bool) or not isinstance(dim, int) or dim < 1:
            raise ValueError(f"dim must be an integer >= 1, got {dim!r}")
        self.dim = dim
        self.bounds = Bounds.cube(-1.0, 1.0, dim)
        c = np.full(dim, 0.3) if optimum is None else np.asarray(optimum, dtype=np.float64)
        self.optimum = self.bounds.check_point(c, "optimum")
        self._scale = 0.5 / dim

    def snapshot(self) -> None:
        return None

    def restore(self, snapshot: object) -> None:
        pass

    def action_bounds(self) -> Bounds:
        return self.bounds

    def step(self, action: FloatArray) -> StepResult:
        return StepResult(1.0 - float(np.abs(action - self.optimum).sum()) * self._scale)


def measure(
    planner: str, dim: int, n_simulations: int, depth: int = 5, seed: int = 0
) -> dict[str, float | int | str]:
    """One timed search on :class:`NullProblem`; overhead figures in microseconds."""
    problem = NullProblem(dim)
    config = planner_config(planner, depth_limit=depth, root_commitment=None)
    mcts = MCTS(problem, config, seed=seed)
    t0, c0 = time.perf_counter(), time.process_time()
    res = mcts.search(n_simulations)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return {
        "planner": planner,
        "dim": dim,
        "simulations": n_simulations,
        "node_visits": res.n_node_visits,
        "nodes": res.n_nodes,
        "steps": res.n_steps,
        "seconds": wall,
        "cpu_seconds": cpu,
        "us_per_simulation": 1e6 * wall / n_simulations,
        "us_per_visit": 1e6 * wall / max(res.n_node_visits, 1),
        "cpu_us_per_visit": 1e6 * cpu / max(res.n_node_visits, 1),
    }


def main(argv: Sequence[str] | None = None) -> int:
    """Print the overhead table (see the module docstring)."""
    parser = argparse.ArgumentParser(
        prog="python -m voot.tree.overhead", description=__doc__.split("\n\n")[0]
    )
    parser.add_argument("--planners", nargs="+", default=list(DEFAULT_PLANNERS))
    parser.add_argument("--dims", nargs="+", type=int, default=[6, 9])
    parser.add_argument("--simulations", nargs="+", type=int, default=[1000, 10000])
    parser.add_argument("--depth", type=int, default=5)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    header = (
        f"{'planner':<11} {'dim':>3} {'sims':>6} {'visits':>7} {'nodes':>7} {'steps':>7}"
        f" {'s':>7} {'us/sim':>8} {'us/visit':>8} {'cpu us/visit':>12}"
    )
    print(f"null problem, depth {args.depth}, seed {args.seed}")
    print(header)
    for planner in args.planners:
        for dim in args.dims:
            for n in args.simulations:
                try:
                    row = measure(planner, dim, n, args.depth, args.seed)
                except ValueError as exc:  # e.g. a sampler whose module is missing
                    print(f"{planner:<11} {dim:>3} {n:>6} skipped: {exc}")
                    continue
                print(
                    f"{row['planner']:<11} {row['dim']:>3} {row['simulations']:>6}"
                    f" {row['node_visits']:>7} {row['nodes']:>7} {row['steps']:>7}"
                    f" {row['seconds']:>7.2f} {row['us_per_simulation']:>8.1f}"
                    f" {row['us_per_visit']:>8.1f} {row['cpu_us_per_visit']:>12.1f}",
                    flush=True,
                )
    return 0


if __name__ == "__main__":
    sys.exit(main())
