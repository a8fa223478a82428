"""``voot-bench bbfo``: the black-box sweep of the paper's Figure 3 (resumable, parallel;
``--instance K`` runs it on test functions with shifted optima)."""

from __future__ import annotations

import argparse
import os
import sys
from typing import TYPE_CHECKING

from voot.bench.cli.common import (
    CLIError,
    add_filters,
    open_store,
    parse_assignments,
    parse_int_list,
    parse_range,
    sigterm_as_interrupt,
    split_list,
    stored_note,
)

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_bbfo(args: argparse.Namespace) -> int:
    from voot.bench.sweep.backends import make_backend
    from voot.bench.sweep.bbfo import (
        PAPER_DIMS,
        PAPER_FUNCTIONS,
        PAPER_METHODS,
        build_specs,
        summarize_specs,
    )
    from voot.bench.sweep.engine import run_sweep

    seeds = parse_range(args.seeds, "--seeds")
    specs = build_specs(
        split_list(args.functions) or PAPER_FUNCTIONS,
        parse_int_list(args.dims, "--dims") or PAPER_DIMS,
        split_list(args.methods) or PAPER_METHODS,
        seeds,
        grid=args.grid,
        budget_scale=args.budget_scale,
        budget=args.budget,
        instance=args.instance,
        fixed=parse_assignments(args.set, "--set"),
    )
    if not specs:
        raise CLIError("the grid is empty (e.g. rembo is not run in 3-D); widen --dims/--methods")
    evaluations = sum(s.budget for s in specs)
    instance = f", instance {args.instance}" if args.instance else ""
    print(
        f"{len(specs)} runs, {evaluations} evaluations, seeds {seeds[0]}..{seeds[-1]}{instance}"
        f"{stored_note(args.out, specs)}",
        file=sys.stderr,
    )
    if args.dry_run:
        print(summarize_specs(specs))
        return 0
    store = open_store(args.out)
    backend = make_backend(args.backend, args.workers)
    print(f"results: {store.path}", file=sys.stderr)
    with sigterm_as_interrupt():
        summary = run_sweep(
            specs, store, backend, progress=not args.no_progress, retry_failed=not args.skip_failed
        )
    print(summary)
    return 1 if summary.failed else 0


def register(sub: Subparsers) -> None:
    """Add ``bbfo``."""
    from voot.bench.sweep.backends import BACKENDS
    from voot.bench.sweep.engine import GRIDS

    p = sub.add_parser("bbfo", help="run the black-box sweep of Figure 3 (resumable)")
    p.add_argument(
        "--out", default="results/bbfo", help="result store directory (default: %(default)s)"
    )
    add_filters(p, defaults=True)
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
    p.add_argument(
        "--skip-failed", action="store_true", help="do not retry runs that failed before"
    )
    p.add_argument("--dry-run", action="store_true", help="list the runs per cell and exit")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_bbfo)
