"""The difficulty of the robot domains, for choosing what to run: ``difficulty``
(planner-agnostic: feasibility rates, random-rollout success and the scripted solution of
the v0 and v1 domains, :mod:`voot.bench.protocol.difficulty`) and ``ladder`` (a generated
family's levels: feasibility by cause, random rollouts, planner success from a plan store,
:mod:`voot.bench.protocol.ladder`)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError, check_output, write_markdown
from voot.bench.cli.types import seed_argument
from voot.bench.protocol.ladder import LEVELS as LADDER_LEVELS

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_difficulty(args: argparse.Namespace) -> int:
    """Print (and optionally write) the difficulty tables of :mod:`voot.bench.protocol.difficulty`."""
    from voot.bench.protocol import difficulty
    from voot.bench.protocol.problems import normalize_problem

    if args.seed < 0:
        raise CLIError(f"--seed must be >= 0, got {args.seed}")
    check_output(args.markdown, "--markdown")
    envs = (
        difficulty.DEFAULT_ENVS if args.envs is None else [normalize_problem(e) for e in args.envs]
    )
    text = difficulty.report(envs, args.samples, args.rollouts, args.seed)
    print(text)
    if args.markdown:
        write_markdown(args.markdown, text + "\n")
    return 0


def cmd_ladder(args: argparse.Namespace) -> int:
    """Print (and optionally write) a generated family's difficulty ladder
    (:mod:`voot.bench.protocol.ladder`)."""
    from voot.bench.cli.plan import parse_layout_seeds
    from voot.bench.protocol import ladder

    for name in ("samples", "rollouts"):
        if getattr(args, name) < 1:
            raise CLIError(f"--{name} must be >= 1, got {getattr(args, name)}")
    check_output(args.markdown, "--markdown")
    env_id = check_generated(args.env)
    unknown = [level for level in args.levels if level not in LADDER_LEVELS]
    if unknown or not args.levels:
        raise CLIError(
            f"--levels: unknown level(s) {', '.join(map(repr, unknown)) or '(none given)'};"
            f" valid levels are: {', '.join(LADDER_LEVELS)}"
        )
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
        write_markdown(args.markdown, text + "\n")
    return 0


def check_generated(name: str) -> str:
    """The id of the generated family ``name`` (an alias or an id), or a CLIError naming
    the generated families: the ladder's levels and layouts exist only for them."""
    from voot.bench.protocol import problems as P
    from voot.bench.protocol.layouts import LAYOUT_SETS

    env_id = P.normalize_problem(name)
    generated = P.recorded_names(kinds=("generated",))
    if env_id not in LAYOUT_SETS:
        raise CLIError(
            f"--env {name}: {env_id} is not a generated family; the ladder's levels and"
            f" layouts exist for {', '.join(f'{g} ({P.normalize_problem(g)})' for g in generated)}"
        )
    return env_id


def register(sub: Subparsers) -> None:
    """Add ``difficulty`` and ``ladder``."""
    from voot.bench.protocol import problems as P

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
    generated = P.recorded_names(kinds=("generated",))
    p.add_argument(
        "--env",
        default=P.normalize_problem(generated[0]),
        help=f"a generated family: {' '.join(generated)} or its id (default: %(default)s)",
    )
    p.add_argument("--levels", nargs="+", default=list(LADDER_LEVELS), help="default: %(default)s")
    p.add_argument("--layouts", nargs="+", default=["0:5"], help="layout seeds (default: 0:5)")
    p.add_argument("--samples", type=int, default=500, help="uniform actions per node and layout")
    p.add_argument("--rollouts", type=int, default=40, help="random rollouts per layout")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--store", default=None, help="a plan store with runs on the levels")
    p.add_argument("--markdown", default=None, help="also write the tables to this file")
    p.set_defaults(func=cmd_ladder)
