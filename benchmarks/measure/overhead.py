r"""What the search itself costs: ``voot-bench measure overhead`` and ``record-overhead``.

**The planner's own overhead** (:func:`measure`, :func:`print_tree_overhead`,
``voot-bench measure overhead``): for every planner, action dimension and budget, one
search of depth ``--depth`` on :class:`~voot.tree.null_problem.NullProblem`, printing
the wall time per simulation and per node visit (one action taken inside a simulation,
new or re-evaluated) and the process CPU time per node visit (the figure to trust on a
shared machine). The null step is a few microseconds of Python, so the figures are the
search's cost: the goal is VOOT under 100 microseconds per node visit, so that the
simulator, not the search, bounds the speed.

**The cost of recording** (:func:`measure_overhead`, :func:`print_record_overhead`,
``voot-bench measure record-overhead``): the same search timed with and without a
:class:`~voot.record.SearchRecorder` (its ``finish`` included; rerun's one-off start-up
measured apart on a warm-up recording), alternating ``--repeats`` times and keeping the
fastest run of each (wall and process CPU time), checking that both gave the same curve,
and printing ``on / off`` (goal: at most 1.5). Problems: ``shekel`` (the Shekel chain in
``--dim`` dimensions with the authors' chain settings) and ``null`` (the null problem at
depth 5, the worst case for the recorder's relative cost).
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from voot import validation as V
from voot.record.config import RecorderConfig
from voot.record.recorder import SearchRecorder
from voot.tree.chains import chain_planner_options, make_chain
from voot.tree.config import planner_config
from voot.tree.mcts import MCTS
from voot.tree.null_problem import NullProblem

#: The planners the paper compares, plus HOOT and Voronoi progressive widening.
DEFAULT_PLANNERS = ("voot", "doot", "rand_doot", "pw_uct", "voronoi_pw", "hoot")


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


def print_tree_overhead(
    planners: Sequence[str],
    dims: Sequence[int],
    simulations: Sequence[int],
    depth: int = 5,
    seed: int = 0,
) -> None:
    """``voot-bench measure overhead``: print the planner's overhead table, a row per
    planner, dimension and budget (:func:`measure`) as each is measured."""
    header = (
        f"{'planner':<11} {'dim':>3} {'sims':>6} {'visits':>7} {'nodes':>7} {'steps':>7}"
        f" {'s':>7} {'us/sim':>8} {'us/visit':>8} {'cpu us/visit':>12}"
    )
    print(f"null problem, depth {depth}, seed {seed}")
    print(header)
    for planner in planners:
        for dim in dims:
            for n in simulations:
                try:
                    row = measure(planner, dim, n, depth, seed)
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


#: Problems :func:`measure_overhead` knows.
PROBLEMS = ("shekel", "null")


def _setup(problem: str, dim: int, planner: str) -> tuple[Any, Any]:
    if problem == "shekel":
        options = chain_planner_options("shekel", dim)
        if planner in ("voot", "voronoi_pw"):
            options["sampler_options"] = {"sampler": "centered_uniform"}
        return make_chain("shekel", dim), planner_config(planner, **options)
    if problem == "null":
        return NullProblem(dim), planner_config(planner, depth_limit=5, root_commitment=None)
    raise ValueError(f"unknown problem {problem!r}; valid problems are: {', '.join(PROBLEMS)}")


def measure_overhead(
    problem: str = "shekel",
    dim: int = 10,
    n_simulations: int = 1000,
    planner: str = "voot",
    seed: int = 0,
    repeats: int = 1,
    config: RecorderConfig | None = None,
    directory: str | Path | None = None,
) -> dict[str, Any]:
    """Time one search with and without recording; return the figures.

    Returns a dict with ``off_s`` and ``on_s`` (wall time, fastest of ``repeats``),
    ``ratio`` (``on_s / off_s``), the same in process CPU time (``off_cpu_s``,
    ``on_cpu_s``, ``cpu_ratio``: all threads of the process, rerun's writer included;
    steadier than wall time on a shared machine), ``setup_s`` (the one-off cost of the process's first recording:
    importing rerun, starting its threads; measured on a warm-up recording and *not* in
    ``on_s``), ``rrd_bytes``, ``n_nodes`` and the settings. Raises a
    RuntimeError if recording changed the search's best-return curve.
    """
    V.integer(repeats, "repeats", 1)
    off: list[float] = []
    on: list[float] = []
    off_cpu: list[float] = []
    on_cpu: list[float] = []
    size = 0
    n_nodes = 0
    with tempfile.TemporaryDirectory(dir=directory) as tmp:
        path = Path(tmp) / "overhead.rrd"
        # Warm-up: the first recording of a process imports rerun and pyarrow and starts
        # rerun's threads (about a second, once); timed apart as ``setup_s``.
        t0 = time.perf_counter()
        warm = NullProblem(2)
        with SearchRecorder(Path(tmp) / "warmup.rrd", warm, config) as recorder:
            MCTS(warm, planner_config(planner, depth_limit=2), seed=0).search(20, callback=recorder)
        setup = time.perf_counter() - t0
        for _ in range(repeats):
            prob, cfg = _setup(problem, dim, planner)
            mcts = MCTS(prob, cfg, seed=seed)
            t0, c0 = time.perf_counter(), time.process_time()
            ref = mcts.search(n_simulations)
            off.append(time.perf_counter() - t0)
            off_cpu.append(time.process_time() - c0)
            prob, cfg = _setup(problem, dim, planner)
            mcts = MCTS(prob, cfg, seed=seed)
            t0, c0 = time.perf_counter(), time.process_time()
            recorder = SearchRecorder(path, prob, config)
            res = mcts.search(n_simulations, callback=recorder)
            recorder.finish()
            on.append(time.perf_counter() - t0)
            on_cpu.append(time.process_time() - c0)
            if not np.array_equal(ref.best_return_curve, res.best_return_curve):
                raise RuntimeError("recording changed the search: the best-return curves differ")
            size = path.stat().st_size
            n_nodes = res.n_nodes
    return {
        "problem": problem,
        "dim": dim,
        "planner": planner,
        "simulations": n_simulations,
        "n_nodes": n_nodes,
        "off_s": min(off),
        "on_s": min(on),
        "ratio": min(on) / min(off),
        "off_cpu_s": min(off_cpu),
        "on_cpu_s": min(on_cpu),
        "cpu_ratio": min(on_cpu) / min(off_cpu),
        "setup_s": setup,
        "rrd_bytes": size,
    }


def print_record_overhead(
    problems: Sequence[str] = PROBLEMS,
    dim: int = 10,
    n_simulations: int = 1000,
    planner: str = "voot",
    seed: int = 0,
    repeats: int = 3,
) -> None:
    """``voot-bench measure record-overhead``: print the overhead of recording, a row per
    problem (:func:`measure_overhead`) as each is measured."""
    print(
        f"{'problem':<8} {'dim':>3} {'planner':<8} {'sims':>6} {'nodes':>6} {'off s':>7}"
        f" {'on s':>7} {'ratio':>6} {'cpu off':>7} {'cpu on':>7} {'ratio':>6}"
        f" {'setup s':>7} {'rrd kB':>7}"
    )
    for name in problems:
        row = measure_overhead(name, dim, n_simulations, planner, seed, repeats)
        print(
            f"{row['problem']:<8} {row['dim']:>3} {row['planner']:<8} {row['simulations']:>6}"
            f" {row['n_nodes']:>6} {row['off_s']:>7.3f} {row['on_s']:>7.3f} {row['ratio']:>6.3f}"
            f" {row['off_cpu_s']:>7.3f} {row['on_cpu_s']:>7.3f} {row['cpu_ratio']:>6.3f}"
            f" {row['setup_s']:>7.3f} {row['rrd_bytes'] / 1024:>7.0f}",
            flush=True,
        )
