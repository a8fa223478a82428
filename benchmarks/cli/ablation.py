"""``voot-bench ablation``: one departure from the authors' code at a time.

Builds the runs of :mod:`voot.bench.protocol.ablation` (the v1 defaults and every switch's variant
of VOOT and PW-UCT) and runs them as ``voot-bench plan --tuning-seeds`` does
(:func:`voot.bench.cli.plan.plan_tuned`): every variant's grid on the tuning seeds, then
its selected setting on the evaluation seeds; resumable at any point. ``--table`` draws
the ablation's table from the store (as ``voot-bench claims --ablation``).
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import TYPE_CHECKING

from voot.bench.cli import common as C
from voot.bench.cli.plan import plan_tuned
from voot.bench.cli.report import print_ablation_table
from voot.bench.sweep.plan import PlanSpec

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_ablation(args: argparse.Namespace) -> int:
    """Run (or, with ``--list``/``--table``, describe) the ablation."""
    from voot.bench.protocol import ablation as A

    if args.list:
        print(A.switch_list())
        return 0
    try:
        switches = A.check_switches(C.split_list(args.switches) or None)
    except ValueError as exc:
        raise C.CLIError(str(exc)) from None
    C.check_output(args.markdown, "--markdown")
    if args.table:
        problems = _problem_list(args.problems) or None
        env_kwargs = C.parse_assignments(args.env_kwargs, "--env-kwargs")
        return print_ablation_table(
            args.out, args.tuning_seeds, args.markdown, problems, env_kwargs or None
        )
    if args.markdown is not None:
        raise C.CLIError("--markdown writes the table of --table; give --table with it")
    C.check_sweep_options(args)
    C.check_output(args.out, "--out", folder=True)
    if args.simulations is not None and args.simulations < 1:
        raise C.CLIError(
            f"--simulations must be >= 1, got {args.simulations} (leave it out for the"
            " paper's budget per problem)"
        )
    problems = _problem_list(args.problems) or [
        # by default the problems the chosen switches apply to (all without switches)
        p
        for p in A.ABLATION_PROBLEMS
        if not switches or any(p in s.problems for s in switches)
    ]
    try:
        A.check_applicable(switches, problems, named=args.switches is not None)
    except ValueError as exc:
        raise C.CLIError(str(exc)) from None

    env_kwargs = C.parse_assignments(args.env_kwargs, "--env-kwargs")

    def specs_of(seeds: Sequence[int]) -> list[PlanSpec]:
        return A.ablation_specs(
            switches,
            seeds,
            problems=problems,
            include_baseline=not args.no_baseline,
            simulations=args.simulations,
            env_kwargs=env_kwargs,
        )

    tuning = specs_of(C.parse_range(args.tuning_seeds, "--tuning-seeds"))
    evaluation = specs_of(C.parse_range(args.seeds, "--seeds"))
    C.check_envs([*tuning, *evaluation], "--problems")
    args.record = None
    return plan_tuned(args, tuning, evaluation)


def _problem_list(values: Sequence[str] | None) -> list[str]:
    """``--problems`` as a list, each problem once (a repeated name would list every run of
    it twice)."""
    return list(dict.fromkeys(C.split_list(values)))


def register(sub: Subparsers) -> None:
    """Add ``ablation``."""
    from voot.bench.protocol import problems as P

    p = sub.add_parser(
        "ablation",
        help="one switch at a time from the v1 defaults to the authors' code, for VOOT and"
        " PW-UCT (tuned as the protocol; resumable); --table draws its table",
        description="The ablation: every departure of voot's v1 defaults from the"
        " authors' code as a variant of VOOT and PW-UCT (one switch at a time, and all at"
        " once), each variant's grid on the tuning seeds, its selected setting on the"
        " evaluation seeds of both v1 domains. --list prints the switches.",
    )
    p.add_argument(
        "--out", default="results/ablation-v1", help="result store directory (%(default)s)"
    )
    p.add_argument("--switches", nargs="+", metavar="NAME", help="switches (default: all)")
    p.add_argument(
        "--problems",
        nargs="+",
        metavar="NAME",
        help=f"{' and/or '.join(P.recorded_names())} (the paper's protocol; default: all)",
    )
    p.add_argument("--seeds", default="0:20", help="evaluation seeds (default: %(default)s)")
    p.add_argument(
        "--tuning-seeds", default="1000:1005", help="tuning seeds (default: %(default)s)"
    )
    p.add_argument(
        "--simulations", type=int, default=None, help="simulations per run (default: the paper's)"
    )
    p.add_argument(
        "--no-baseline", action="store_true", help="do not run the v1 defaults (no variant)"
    )
    p.add_argument(
        "--env-kwargs",
        nargs="+",
        metavar="NAME=VALUE",
        help="keywords of gymnasium.make: every variant on that version of the domain (e.g."
        " base_model=footprint big_box_ban=true rooms=authors, the domain ablation's"
        " authors_domain); its runs are tuned and tabled apart",
    )
    p.add_argument("--list", action="store_true", help="print the switches and exit")
    p.add_argument(
        "--table",
        action="store_true",
        help="print the ablation table from --out (runs nothing): per switch VOOT's and"
        " PW-UCT's claim metrics with 95%% intervals, and whether a verdict flips (with"
        " --env-kwargs, of the runs in that domain)",
    )
    p.add_argument("--markdown", help="--table: also write the table here")
    C.add_backend_options(p)
    C.add_estimate_options(p, estimate="print the estimated CPU-hours and exit")
    C.add_run_options(p, dry_run="list the runs and exit")
    C.add_compact_store_options(p, compact="create --out as a compact store (as plan)")
    p.set_defaults(func=cmd_ablation)
