"""``voot-bench bbfo``: the black-box sweep of the paper's Figure 3 (resumable, parallel;
``--instance K`` runs it on test functions with shifted optima)."""

from __future__ import annotations

import argparse
import os
import sys
from typing import TYPE_CHECKING

from voot.bench.cli import common as C

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_bbfo(args: argparse.Namespace) -> int:
    """Run (or, with ``--dry-run``, list) the black-box sweep of :mod:`voot.bench.sweep.bbfo`."""
    from voot.bench.sweep import bbfo as B
    from voot.bench.sweep.backends import make_backend

    C.check_output(args.out, "--out", folder=True)
    C.check_workers(args)
    seeds = C.parse_range(args.seeds, "--seeds")
    specs = B.build_specs(
        C.split_list(args.functions) or B.PAPER_FUNCTIONS,
        C.parse_int_list(args.dims, "--dims") or B.PAPER_DIMS,
        C.split_list(args.methods) or B.PAPER_METHODS,
        seeds,
        grid=args.grid,
        budget_scale=args.budget_scale,
        budget=args.budget,
        instance=args.instance,
        fixed=C.parse_assignments(args.set, "--set"),
    )
    if not specs:
        raise C.CLIError("the grid is empty (e.g. rembo is not run in 3-D); widen --dims/--methods")
    evaluations = sum(s.budget for s in specs)
    instance = f", instance {args.instance}" if args.instance else ""
    print(
        f"{len(specs)} runs, {evaluations} evaluations, seeds {seeds[0]}..{seeds[-1]}{instance}"
        f"{C.stored_note(args.out, specs)}",
        file=sys.stderr,
    )
    if args.dry_run:
        print(B.summarize_specs(specs))
        return 0
    store = C.open_store(args.out)
    backend = make_backend(args.backend, args.workers)
    print(f"results: {store.path}", file=sys.stderr)
    return 1 if C.run_specs(args, specs, store, backend).failed else 0


def register(sub: Subparsers) -> None:
    """Add ``bbfo``."""
    from voot.bench.sweep.backends import BACKENDS
    from voot.bench.sweep.engine import GRIDS

    p = sub.add_parser("bbfo", help="run the black-box sweep of Figure 3 (resumable)")
    p.add_argument(
        "--out", default="results/bbfo", help="result store directory (default: %(default)s)"
    )
    C.add_filters(p, defaults=True)
    p.add_argument(
        "--seeds", default="20", help="N (seeds 0..N-1) or START:STOP (default: %(default)s)"
    )
    p.add_argument(
        "--grid", choices=GRIDS, default="paper", help="hyperparameter grid (default: %(default)s)"
    )
    p.add_argument("--budget-scale", type=float, default=1.0, help="multiply the paper budgets")
    p.add_argument("--budget", type=int, default=None, help="one fixed budget for every run")
    p.add_argument(
        "--instance",
        type=int,
        default=0,
        metavar="K",
        help="test-function instance: 0 = the paper's functions (default), K >= 1 = optima"
        " moved off the box centre (voot.functions)",
    )
    p.add_argument(
        "--set",
        nargs="+",
        metavar="NAME=VALUE",
        help="an optimiser parameter for every run, on top of the grid (e.g. sampler=gaussian"
        " with --methods voo); it joins every setting's label",
    )
    p.add_argument(
        "--workers", type=int, default=os.cpu_count() or 1, help="processes (default: %(default)s)"
    )
    p.add_argument("--backend", choices=BACKENDS, default="process", help="where runs execute")
    C.add_run_options(p, dry_run="list the runs per cell and exit")
    p.set_defaults(func=cmd_bbfo)
