"""The project's own measurements of what voot costs, under ``voot-bench measure``:
``speed`` (cost per ask of VOO, CMA-ES and GP-UCB), ``voo-speed`` (VOO's ask + tell on
several objectives), ``overhead`` (the planner's own cost per node visit),
``record-overhead`` (the cost of recording a search), ``memory`` (memory of a long
search against its tree), ``root-parallel`` (speed-up of root-parallel search) and
``store-speed`` (size and load time of result stores). The environments' costs are in
:mod:`voot.bench.cli.env_cost`, the comparison with an older commit in
:mod:`voot.bench.cli.speedup`.

Each command's work is a function of :mod:`voot.bench.measure`, imported when the command
runs; its options are parsed here.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import TYPE_CHECKING

from voot.bench.cli.common import (
    CLIError,
    add_compact_options,
    check_output,
    compact_config,
    split_list,
)
from voot.bench.cli.types import seed_argument

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers

#: Default cases of ``voot-bench measure speed``: (method, number of told points). GP-UCB
#: gets a small n because reaching n means running GP-UCB for n evaluations first.
SPEED_CASES: tuple[tuple[str, int], ...] = (
    ("voo", 1000),
    ("voo", 5000),
    ("cmaes", 1000),
    ("cmaes", 5000),
    ("gp_ucb", 100),
)


def parse_cases(values: Sequence[str] | None) -> list[tuple[str, int]]:
    """``["voo:1000", "cmaes:5000"]`` -> ``[("voo", 1000), ("cmaes", 5000)]``."""
    from voot.optim.registry import normalize_method

    if not values:
        return list(SPEED_CASES)
    out = []
    for item in split_list(values):
        method, _, n = item.partition(":")
        try:
            count = int(n)
        except ValueError:
            raise CLIError(f"--cases: {item!r} is not METHOD:N (e.g. voo:1000)") from None
        if count < 1:
            raise CLIError(f"--cases: N must be >= 1 in {item!r}")
        out.append((normalize_method(method), count))
    return out


def at_least(args: argparse.Namespace, minimum: int, *names: str) -> None:
    """A CLIError ``--NAME must be >= MINIMUM`` for the first option of ``names`` below
    ``minimum``."""
    for name in names:
        if getattr(args, name) < minimum:
            raise CLIError(f"--{name.replace('_', '-')} must be >= {minimum}")


def cmd_speed(args: argparse.Namespace) -> int:
    """Print the cost per ask of each case (:func:`voot.bench.measure.speed.measure_ask_cost`)."""
    cases = parse_cases(args.cases)
    try:
        from voot.bench.measure.speed import measure_ask_cost
    except ImportError as exc:
        raise CLIError(f"voot.bench.measure.speed is not available ({exc})") from None
    if args.dim < 1 or args.repeats < 1:
        raise CLIError("--dim and --repeats must be >= 1")
    print(
        f"cost after n evaluations, d = {args.dim}, mean of {args.repeats} repeats"
        " (per ask; per ask + tell for methods that work on tell, e.g. cmaes, gp_ucb)"
    )
    print("| method | n | ms |")
    print("| --- | ---: | ---: |")
    failed = 0
    for method, n in cases:
        try:
            seconds = measure_ask_cost(method, n, args.dim, args.repeats, args.seed)
            cell = f"{1000.0 * seconds:.3f}"
        except Exception as exc:  # report and go on with the other cases
            failed += 1
            cell = f"error: {type(exc).__name__}: {exc}"
        print(f"| {method} | {n} | {cell} |", flush=True)
    return 1 if failed else 0


def cmd_voo_speed(args: argparse.Namespace) -> int:
    """Print VOO's cost per ask + tell (:func:`voot.bench.measure.speed.print_voo_cost`)."""
    from voot.bench.measure.speed import print_voo_cost

    at_least(args, 0, "n")
    at_least(args, 1, "dim", "repeats", "seeds")
    seeds = range(args.seed, args.seed + args.seeds)
    print_voo_cost(
        args.objectives,
        args.n,
        args.dim,
        args.repeats,
        seeds,
        omega=args.omega,
        sampler=args.sampler,
    )
    return 0


def cmd_overhead(args: argparse.Namespace) -> int:
    """Print the planner's overhead (:func:`voot.bench.measure.overhead.print_tree_overhead`)."""
    from voot.bench.measure.overhead import print_tree_overhead

    print_tree_overhead(args.planners, args.dims, args.simulations, args.depth, args.seed)
    return 0


def cmd_record_overhead(args: argparse.Namespace) -> int:
    """Print the cost of recording (:func:`voot.bench.measure.overhead.print_record_overhead`)."""
    from voot.bench.measure.overhead import print_record_overhead

    print_record_overhead(
        args.problems, args.dim, args.simulations, args.planner, args.seed, args.repeats
    )
    return 0


def cmd_memory(args: argparse.Namespace) -> int:
    """Measure and print the memory tables of :func:`voot.bench.measure.memory.measure_cases`."""
    from voot.bench.measure.memory import DEFAULT_PLANNERS, format_cases, measure_cases

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


def cmd_root_parallel(args: argparse.Namespace) -> int:
    """Measure root-parallel search (:func:`voot.bench.measure.root_parallel.run_and_report`)."""
    from voot.bench.measure.root_parallel import run_and_report

    budgets = args.budget or [None] * len(args.problems)
    if len(budgets) not in (1, len(args.problems)):
        raise CLIError("--budget takes one value, or one per problem")
    if len(budgets) == 1:
        budgets = budgets * len(args.problems)
    seeds = args.seeds if len(args.seeds) > 1 else args.seeds * len(args.problems)
    if len(seeds) != len(args.problems) or min(seeds) < 1:
        raise CLIError("--seeds takes one count >= 1, or one per problem")
    check_output(args.figure or None, "--figure")
    check_output(args.json or None, "--json")
    run_and_report(
        args.problems,
        budgets,
        seeds,
        dim=args.dim,
        trees=args.trees,
        workers=args.workers,
        merge=args.merge,
        long_runs=not args.no_long,
        figure=args.figure,
        json_path=args.json,
    )
    return 0


def cmd_store_speed(args: argparse.Namespace) -> int:
    """Print the size and load time of synthetic plan-row stores, full and compact."""
    from voot.bench.measure.store_speed import time_load

    if args.rows < 1 or args.length < 1:
        raise CLIError("--rows and --length must be >= 1")
    print(f"{args.rows} plan-like rows of {args.length} simulations (five curves each)")
    print(
        "| store | MB of rows | KB per row | write s | first load s | load s (lists)"
        " | load s (arrays) | verify s |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, config in (("full", None), ("compact", compact_config(args))):
        t = time_load(args.rows, args.length, args.repeats, plan=True, compact=config)
        print(
            f"| {name} | {t['mb']:.2f} | {1000 * t['mb'] / args.rows:.1f} | {t['write']:.2f}"
            f" | {t['cold']:.3f} | {t['warm']:.3f} | {t['warm_arrays']:.3f} | {t['verify']:.3f} |",
            flush=True,
        )
    return 0


def register(sub: Subparsers) -> None:
    """Add ``speed``, ``voo-speed``, ``overhead``, ``record-overhead``, ``memory``,
    ``root-parallel`` and ``store-speed``."""
    _register_optimiser_costs(sub)
    _register_search_costs(sub)
    _register_store_speed(sub)


def _register_optimiser_costs(sub: Subparsers) -> None:
    """``speed`` and ``voo-speed``."""
    from voot.bench.measure.speed import VOO_SPEED_OBJECTIVES, voo_objectives

    p = sub.add_parser("speed", help="cost per ask of VOO, CMA-ES and GP-UCB")
    p.add_argument(
        "--cases",
        nargs="+",
        metavar="METHOD:N",
        help="default: " + " ".join(f"{m}:{n}" for m, n in SPEED_CASES),
    )
    p.add_argument("--dim", type=int, default=20)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--seed", type=seed_argument, default=0)
    p.set_defaults(func=cmd_speed)

    p = sub.add_parser(
        "voo-speed",
        help="VOO's cost per ask + tell on several objectives",
        description="CPU time of one VOO ask + tell after n evaluations, per objective.",
    )
    objectives = voo_objectives()
    p.add_argument(
        "--objectives",
        nargs="+",
        default=list(VOO_SPEED_OBJECTIVES),
        choices=objectives,
        metavar="NAME",
        help=f"default: {' '.join(VOO_SPEED_OBJECTIVES)}; any of {', '.join(objectives)}",
    )
    p.add_argument("--n", type=int, default=5000, help="evaluations before timing (5000)")
    p.add_argument("--dim", type=int, default=20)
    p.add_argument("--repeats", type=int, default=500, help="timed evaluations (500)")
    p.add_argument("--seeds", type=int, default=1, help="seeds 0..SEEDS-1, each timed (1)")
    p.add_argument("--seed", type=seed_argument, default=0, help="first seed (0)")
    p.add_argument("--omega", type=float, default=0.001)
    p.add_argument("--sampler", default="centered_uniform")
    p.set_defaults(func=cmd_voo_speed)


def _register_search_costs(sub: Subparsers) -> None:
    """``overhead``, ``record-overhead``, ``memory`` and ``root-parallel``."""
    from voot.bench.measure import memory, overhead, root_parallel

    text = "the planner's own overhead per node visit"
    p = sub.add_parser("overhead", help=text, description=text)
    p.add_argument("--planners", nargs="+", default=list(overhead.DEFAULT_PLANNERS))
    p.add_argument("--dims", nargs="+", type=int, default=[6, 9])
    p.add_argument("--simulations", nargs="+", type=int, default=[1000, 10000])
    p.add_argument("--depth", type=int, default=5)
    p.add_argument("--seed", type=seed_argument, default=0)
    p.set_defaults(func=cmd_overhead)

    text = "the cost of recording a search"
    p = sub.add_parser("record-overhead", help=text, description=text)
    problems = overhead.PROBLEMS
    p.add_argument("--problems", nargs="+", default=list(problems), choices=problems)
    p.add_argument("--dim", type=int, default=10)
    p.add_argument("--simulations", type=int, default=1000)
    p.add_argument("--planner", default="voot")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--repeats", type=int, default=3)
    p.set_defaults(func=cmd_record_overhead)

    p = sub.add_parser(
        "memory",
        help="memory (tracemalloc, RSS) of a long tree search vs its number of nodes",
    )
    p.add_argument("--problem", default=memory.DEFAULT_PROBLEM, help="problem (%(default)s)")
    p.add_argument(
        "--planners",
        nargs="+",
        default=None,
        metavar="NAME",
        help="tree planners (default: " + " ".join(memory.DEFAULT_PLANNERS) + ")",
    )
    p.add_argument("--simulations", type=int, default=10_000, help="simulations (%(default)s)")
    p.add_argument("--checkpoints", type=int, default=10, help="checkpoints (%(default)s)")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.set_defaults(func=cmd_memory)

    p = sub.add_parser(
        "root-parallel",
        help="root-parallel search: speed-up and quality against one tree",
        description="Speed-up and quality of root-parallel search"
        " (voot.bench.measure.root_parallel).",
    )
    problems = root_parallel.PROBLEMS
    p.add_argument("--problems", nargs="+", default=["shekel"], choices=problems)
    p.add_argument("--dim", type=int, default=10, help="Shekel chain dimension (3, 10, 20)")
    p.add_argument("--trees", nargs="+", type=int, default=[1, 2, 4], help="values of K")
    p.add_argument("--workers", nargs="+", type=int, default=[1, 2], help="values of W")
    p.add_argument("--seeds", type=int, nargs="+", default=[3], help="seeds 0 .. N-1 (per problem)")
    p.add_argument("--budget", type=int, nargs="+", default=None, help="S per problem")
    p.add_argument("--merge", default="max_q")
    p.add_argument("--no-long", action="store_true", help="skip the equal-wall-time runs")
    p.add_argument("--figure", default=root_parallel.DEFAULT_FIGURE, help="PNG path ('' for none)")
    p.add_argument("--json", default="", help="write the table rows to this JSON file")
    p.set_defaults(func=cmd_root_parallel)


def _register_store_speed(sub: Subparsers) -> None:
    """``store-speed``."""
    p = sub.add_parser(
        "store-speed",
        help="size and load time of a store of synthetic plan rows, full vs compact",
    )
    p.add_argument("--rows", type=int, default=1000, help="rows (default: %(default)s)")
    p.add_argument(
        "--length", type=int, default=3000, help="simulations per row (default: %(default)s)"
    )
    p.add_argument(
        "--repeats", type=int, default=3, help="loads timed, best kept (default: %(default)s)"
    )
    add_compact_options(p, "")
    p.set_defaults(func=cmd_store_speed)
