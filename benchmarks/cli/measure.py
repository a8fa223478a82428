"""Measurement subcommands with options of their own: ``speed`` (cost per ask of VOO,
CMA-ES and GP-UCB) and ``difficulty`` (planner-agnostic difficulty of the robot
domains)."""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError, split_list
from voot.bench.cli.types import seed_argument
from voot.bench.protocol.ladder import LEVELS as LADDER_LEVELS

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers

#: Default cases of ``voot-bench speed``: (method, number of told points). GP-UCB gets a
#: small n because reaching n means running GP-UCB for n evaluations first.
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


def cmd_speed(args: argparse.Namespace) -> int:
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


def cmd_difficulty(args: argparse.Namespace) -> int:
    """Print (and optionally write) the difficulty tables of :mod:`voot.bench.protocol.difficulty`."""
    from voot.bench.protocol import difficulty
    from voot.bench.protocol.problems import normalize_problem

    if args.seed < 0:
        raise CLIError(f"--seed must be >= 0, got {args.seed}")
    envs = (
        difficulty.DEFAULT_ENVS if args.envs is None else [normalize_problem(e) for e in args.envs]
    )
    text = difficulty.report(envs, args.samples, args.rollouts, args.seed)
    print(text)
    if args.markdown:
        Path(args.markdown).write_text(text + "\n")
    return 0


def cmd_ladder(args: argparse.Namespace) -> int:
    """Print (and optionally write) a generated family's difficulty ladder
    (:mod:`voot.bench.protocol.ladder`)."""
    from voot.bench.cli.plan import parse_layout_seeds
    from voot.bench.protocol import ladder
    from voot.bench.protocol.problems import normalize_problem

    for name in ("samples", "rollouts"):
        if getattr(args, name) < 1:
            raise CLIError(f"--{name} must be >= 1, got {getattr(args, name)}")
    env_id = normalize_problem(args.env)
    layouts = parse_layout_seeds(args.layouts, "--layouts")
    rows: list = []
    if args.store is not None:
        from voot.bench.cli.report import load_rows

        _, rows = load_rows(args.store, "plan")
    text = ladder.ladder_report(
        env_id, args.levels, layouts, args.samples, args.rollouts, args.seed, rows
    )
    print(text)
    if args.markdown:
        Path(args.markdown).write_text(text + "\n")
    return 0


def register(sub: Subparsers) -> None:
    """Add ``speed``, ``difficulty`` and ``ladder``."""
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
        "difficulty",
        help="planner-agnostic difficulty of the robot domains (v0, v1): feasibility rates,"
        " random-rollout success, the scripted solution",
    )
    p.add_argument(
        "--envs", nargs="+", default=None, metavar="ID", help="default: v0 and v1 of both"
    )
    p.add_argument("--samples", type=int, default=2000, help="uniform actions per node type")
    p.add_argument("--rollouts", type=int, default=200, help="random rollouts per environment")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--markdown", default=None, help="also write the tables to this file")
    p.set_defaults(func=cmd_difficulty)

    p = sub.add_parser(
        "ladder",
        help="difficulty ladder of a generated family (v2): feasibility by cause and random"
        " rollouts per level, planner success from a plan store",
    )
    p.add_argument("--env", default="voot/KitchenClearing-v2", help="default: %(default)s")
    p.add_argument("--levels", nargs="+", default=list(LADDER_LEVELS), help="default: %(default)s")
    p.add_argument("--layouts", nargs="+", default=["0:5"], help="layout seeds (default: 0:5)")
    p.add_argument("--samples", type=int, default=500, help="uniform actions per node and layout")
    p.add_argument("--rollouts", type=int, default=40, help="random rollouts per layout")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--store", default=None, help="a plan store with runs on the levels")
    p.add_argument("--markdown", default=None, help="also write the tables to this file")
    p.set_defaults(func=cmd_ladder)
