"""``voot-bench memory``: memory of a long tree search against the size of its tree
(:mod:`voot.bench.measure.memory`), one fresh process per planner."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError, split_list
from voot.bench.cli.types import seed_argument
from voot.bench.measure.memory import DEFAULT_PLANNERS, DEFAULT_PROBLEM

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_memory(args: argparse.Namespace) -> int:
    """Measure and print the memory tables of :func:`voot.bench.measure.memory.measure_cases`."""
    from voot.bench.measure.memory import format_cases, measure_cases

    planners = split_list(args.planners) or list(DEFAULT_PLANNERS)
    if args.simulations < 1 or args.checkpoints < 1:
        raise CLIError("--simulations and --checkpoints must be >= 1")
    print(
        f"memory of a {args.simulations}-simulation search on {args.problem}"
        f" (tracemalloc from the first simulation; RSS of the whole process)",
        flush=True,
    )
    cases = measure_cases(
        args.problem,
        planners,
        args.simulations,
        seed=args.seed,
        checkpoints=args.checkpoints,
    )
    print(format_cases(cases), end="")
    return 0


def register(sub: Subparsers) -> None:
    """Add ``memory``."""
    p = sub.add_parser(
        "memory",
        help="memory (tracemalloc, RSS) of a long tree search vs its number of nodes",
    )
    p.add_argument("--problem", default=DEFAULT_PROBLEM, help="problem (%(default)s)")
    p.add_argument(
        "--planners",
        nargs="+",
        default=None,
        metavar="NAME",
        help="tree planners (default: " + " ".join(DEFAULT_PLANNERS) + ")",
    )
    p.add_argument("--simulations", type=int, default=10_000, help="simulations (%(default)s)")
    p.add_argument("--checkpoints", type=int, default=10, help="checkpoints (%(default)s)")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.set_defaults(func=cmd_memory)
