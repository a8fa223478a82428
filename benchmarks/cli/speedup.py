"""``voot-bench measure speedup``: tree search on the robot domains with a baseline commit's code
and the current code side by side (CPU time, bit-identical curves), or with ``--v1`` the
v1 domains' cost per simulation (:mod:`voot.bench.measure.speedup`)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError, check_output, split_list

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_speedup(args: argparse.Namespace) -> int:
    """The baseline commit's code and the current code on the same workloads (see speedup)."""
    from voot.bench.measure import speedup

    check_output(args.json, "--json")
    if args.v1:
        try:
            sims = int(args.simulations[0]) if args.simulations else None
            runs = speedup.v1_cost(sims, timeout=args.timeout, log=sys.stderr)
        except (speedup.SpeedupError, ValueError) as exc:
            raise CLIError(str(exc)) from exc
        print(speedup.format_v1(runs), end="", flush=True)
        return 0
    try:
        workloads = speedup.select_workloads(split_list(args.workloads), args.simulations)
        baseline, current, comparisons = speedup.compare(
            workloads,
            args.baseline,
            split=not args.no_split,
            timeout=args.timeout,
            log=sys.stderr,
            repeats=args.repeats,
        )
    except speedup.SpeedupError as exc:
        raise CLIError(str(exc)) from exc
    print(speedup.format_report(baseline, current, comparisons), end="", flush=True)
    if args.json:
        Path(args.json).write_text(
            json.dumps(speedup.report_json(baseline, current, comparisons), indent=2) + "\n"
        )
    return 0 if all(c.identical for c in comparisons) else 1


def register(sub: Subparsers) -> None:
    """Add ``speedup``."""
    p = sub.add_parser(
        "speedup",
        help="tree search on the robot domains: CPU time of a baseline commit's code and the"
        " current code side by side, and whether the best-return curves are bit-identical",
    )
    p.add_argument(
        "--baseline",
        default="6af33b5",
        help="commit to compare against (default: 6af33b5, main before the speed work)",
    )
    p.add_argument(
        "--workloads",
        nargs="+",
        metavar="NAME",
        help="kitchen-voot (KitchenClearing-v0, VOOT, 2000 sims) and/or conveyor-pwuct"
        " (ConveyorPacking-v0, PW-UCT, 3000 sims); default: both",
    )
    p.add_argument(
        "--simulations",
        nargs="+",
        metavar="N|NAME=N",
        help="scale down: N simulations for every workload, or NAME=N for one",
    )
    p.add_argument("--json", metavar="PATH", help="also write the numbers as JSON")
    p.add_argument(
        "--v1",
        action="store_true",
        help="instead: the v1 domains' cost per simulation and its split (current code only)",
    )
    p.add_argument("--no-split", action="store_true", help="skip the per-simulation time split")
    p.add_argument(
        "--repeats",
        type=int,
        default=1,
        help="alternating runs of each code; the fastest of each is compared (default: 1)",
    )
    p.add_argument(
        "--timeout", type=float, default=None, help="seconds allowed per run (default: none)"
    )
    p.set_defaults(func=cmd_speedup)
