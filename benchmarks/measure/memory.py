"""Memory of a long tree search against the size of its tree (``voot-bench measure memory``).

A search of ``n`` simulations adds at most one node per simulation (progressive
widening adds fewer), and nothing else in the planner should grow with ``n``: the best
plan, the curves (one float per simulation) and the statistics of each node are all
O(nodes) or O(n). :func:`measure_search_memory` checks this on a real search: it runs
one planner of :mod:`voot.bench.sweep.plan` exactly as a sweep runs it (same spec, same
seed) and at ``checkpoints`` evenly spaced simulations records

* the tree's node count (``len(mcts.nodes)``),
* the bytes the Python heap holds for the search (:mod:`tracemalloc`, started after
  the environment was built, so it counts what the search allocated and still keeps),
  and its peak so far,
* the process's resident set size (``/proc/self/statm``; the environment, MuJoCo's C
  arrays and the interpreter included, so it has a constant offset).

Growth *at most linear in the tree* means the traced bytes per node do not rise from
checkpoint to checkpoint: :func:`growth_ratio` is the bytes per node at the last
checkpoint over that at the middle one (about 1 for linear growth, > 1 for faster
growth, below 1 when a fixed cost is being amortised). Each measured case runs in a fresh
process, so one case's heap and RSS are not in another's figures.

tracemalloc slows Python allocation down (the search runs roughly 1.5-3x slower while
measured); the figures are memory, not speed.
"""

from __future__ import annotations

import os
import resource
import sys
import tracemalloc
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from multiprocessing import get_context
from typing import Any

from voot import validation as V

#: Planners measured by default (the two the long-run check names).
DEFAULT_PLANNERS: tuple[str, ...] = ("voot", "pw_uct")
#: Problem measured by default.
DEFAULT_PROBLEM = "kitchen_v1"


@dataclass(frozen=True)
class MemoryPoint:
    """Memory of a search after ``simulations`` simulations (one checkpoint)."""

    simulations: int
    nodes: int
    traced_bytes: int
    traced_peak_bytes: int
    rss_bytes: int

    @property
    def bytes_per_node(self) -> float:
        """Traced bytes per tree node (the figure that must not grow for linear memory)."""
        return self.traced_bytes / max(self.nodes, 1)


@dataclass(frozen=True)
class MemoryCase:
    """One measured search: its problem, planner, seed and checkpoints."""

    problem: str
    planner: str
    seed: int
    points: tuple[MemoryPoint, ...]
    max_rss_bytes: int

    @property
    def growth_ratio(self) -> float:
        """See :func:`growth_ratio`."""
        return growth_ratio(self.points)


def growth_ratio(points: tuple[MemoryPoint, ...] | list[MemoryPoint]) -> float:
    """Traced bytes per node at the last checkpoint over bytes per node at the middle one.

    ``~1`` for memory linear in the tree, ``> 1`` if it grows faster (a quadratic growth
    would give about 2 between half and the full search). NaN with fewer than two points.
    """
    if len(points) < 2:
        return float("nan")
    middle = points[(len(points) - 1) // 2]
    return points[-1].bytes_per_node / max(middle.bytes_per_node, 1e-12)


def _rss_bytes() -> int:
    """Resident set size now (Linux ``/proc/self/statm``; else the peak from getrusage)."""
    try:
        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):  # pragma: no cover - not Linux
        return _max_rss_bytes()


def _max_rss_bytes() -> int:
    """Peak resident set size of this process (``ru_maxrss``: KiB on Linux, bytes on macOS)."""
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return int(peak) if sys.platform == "darwin" else int(peak) * 1024


def measure_search_memory(
    problem: str = DEFAULT_PROBLEM,
    planner: str = "voot",
    simulations: int = 10_000,
    *,
    seed: int = 0,
    checkpoints: int = 10,
) -> MemoryCase:
    """Run one search (the planner's default parameters) and record its memory.

    Args:
        problem: a problem name of :mod:`voot.bench.protocol.problems` (an environment or chain;
            a chain gets its default dimension).
        planner: a tree planner (one whose search has ``nodes``: the MCTS planners).
        simulations: simulations of the search.
        seed: the run's seed (as ``voot-bench plan --seeds``).
        checkpoints: number of evenly spaced checkpoints (the last is the end).

    Raises:
        ValueError: bad counts, or a planner without a tree (the message says which).
    """
    from voot.bench.protocol import problems as P
    from voot.bench.sweep.plan import build_plan_specs
    from voot.bench.sweep.search import search_seed
    from voot.tree.mcts import MCTS, MCTSConfig

    V.integer(simulations, "simulations", 1)
    V.integer(checkpoints, "checkpoints", 1)
    spec = build_plan_specs(
        [problem], planners=[planner], seeds=[seed], simulations=simulations, grid="default"
    )[0]
    config = spec.run_config()
    if not isinstance(config, MCTSConfig):
        raise ValueError(
            f"planner {planner!r} does not build a search tree; measure a tree planner"
            f" (e.g. {', '.join(DEFAULT_PLANNERS)})"
        )
    inst = P.make_instance(spec.problem, spec.dim, spec.env_kwargs_dict, spec.seed)
    mcts = MCTS(inst.problem, config, seed=search_seed(spec))
    marks = sorted({max(1, round(simulations * (k + 1) / checkpoints)) for k in range(checkpoints)})
    wanted = set(marks)
    points: list[MemoryPoint] = []

    def callback(m: Any, i: int) -> bool:
        if i + 1 in wanted:
            current, peak = tracemalloc.get_traced_memory()
            points.append(MemoryPoint(i + 1, len(m.nodes), current, peak, _rss_bytes()))
        return False

    tracemalloc.start()
    try:
        mcts.search(simulations, callback=callback)
    finally:
        tracemalloc.stop()
    return MemoryCase(problem, planner, seed, tuple(points), _max_rss_bytes())


def _measure(args: tuple[str, str, int, int, int]) -> MemoryCase:
    problem, planner, simulations, seed, checkpoints = args
    return measure_search_memory(problem, planner, simulations, seed=seed, checkpoints=checkpoints)


def measure_cases(
    problem: str,
    planners: tuple[str, ...] | list[str],
    simulations: int,
    *,
    seed: int = 0,
    checkpoints: int = 10,
) -> list[MemoryCase]:
    """:func:`measure_search_memory` of every planner, each in a fresh spawned process
    (one after the other, so the processes' RSS are not mixed)."""
    out = []
    for planner in planners:
        with ProcessPoolExecutor(1, mp_context=get_context("spawn")) as pool:
            out.append(
                pool.submit(_measure, (problem, planner, simulations, seed, checkpoints)).result()
            )
    return out


def format_cases(cases: list[MemoryCase]) -> str:
    """A Markdown table per case (checkpoints) and a line with its growth ratio."""
    mib = 1024.0 * 1024.0
    lines = []
    for case in cases:
        lines.append(f"{case.planner} on {case.problem}, seed {case.seed}:")
        lines.append("")
        lines.append(
            "| simulations | nodes | traced MiB | traced peak MiB | bytes/node | RSS MiB |"
        )
        lines.append("| ---: | ---: | ---: | ---: | ---: | ---: |")
        for p in case.points:
            lines.append(
                f"| {p.simulations} | {p.nodes} | {p.traced_bytes / mib:.2f} |"
                f" {p.traced_peak_bytes / mib:.2f} | {p.bytes_per_node:.0f} |"
                f" {p.rss_bytes / mib:.1f} |"
            )
        lines.append("")
        lines.append(
            f"bytes/node at the end over bytes/node at mid-search: {case.growth_ratio:.2f}"
            f" (1 = linear in the tree); peak RSS {case.max_rss_bytes / mib:.1f} MiB"
        )
        lines.append("")
    return "\n".join(lines).rstrip() + "\n"
