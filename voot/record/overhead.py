"""The cost of recording: the same search timed with and without a :class:`SearchRecorder`.

Run ``python -m voot.record.overhead`` (options: ``--help``). For each problem it runs
the search without a recorder and with one (the recorder's ``finish``, which logs the
tree, the plan and the blueprint and closes the file, included; the one-off start-up of
rerun in a process is measured apart on a warm-up recording), alternating
``--repeats`` times and keeping the fastest run of each (the machine is shared; wall
time and process CPU time are both reported, the latter less disturbed by other
processes), checks
that both searches gave the same curve (recording must not change the search), and
prints the ratio ``on / off``. The goal: at most 1.5.

Problems: ``shekel`` (the synthetic Shekel chain in ``--dim`` dimensions with the
authors' chain settings, see :func:`voot.tree.chain_planner_options`) and ``null``
(:class:`voot.tree.overhead.NullProblem` at depth 5: a step that costs nothing, the
worst case for the recorder's relative cost).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from voot.record.config import RecorderConfig
from voot.record.recorder import SearchRecorder
from voot.tree.chains import chain_planner_options, make_chain
from voot.tree.config import planner_config
from voot.tree.mcts import MCTS
from voot.tree.overhead import NullProblem

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
    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise ValueError(f"repeats must be an integer >= 1, got {repeats!r}")
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


def main(argv: Sequence[str] | None = None) -> int:
    """Print the overhead of recording (see the module docstring)."""
    parser = argparse.ArgumentParser(
        prog="python -m voot.record.overhead", description=(__doc__ or "").split("\n\n")[0]
    )
    parser.add_argument("--problems", nargs="+", default=list(PROBLEMS), choices=PROBLEMS)
    parser.add_argument("--dim", type=int, default=10)
    parser.add_argument("--simulations", type=int, default=1000)
    parser.add_argument("--planner", default="voot")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(
        f"{'problem':<8} {'dim':>3} {'planner':<8} {'sims':>6} {'nodes':>6} {'off s':>7}"
        f" {'on s':>7} {'ratio':>6} {'cpu off':>7} {'cpu on':>7} {'ratio':>6}"
        f" {'setup s':>7} {'rrd kB':>7}"
    )
    for name in args.problems:
        row = measure_overhead(
            name, args.dim, args.simulations, args.planner, args.seed, args.repeats
        )
        print(
            f"{row['problem']:<8} {row['dim']:>3} {row['planner']:<8} {row['simulations']:>6}"
            f" {row['n_nodes']:>6} {row['off_s']:>7.3f} {row['on_s']:>7.3f} {row['ratio']:>6.3f}"
            f" {row['off_cpu_s']:>7.3f} {row['on_cpu_s']:>7.3f} {row['cpu_ratio']:>6.3f}"
            f" {row['setup_s']:>7.3f} {row['rrd_bytes'] / 1024:>7.0f}",
            flush=True,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
