"""Subcommands whose module parses its own options (``voot-bench overhead ...``,
``env-speed``, ``root-parallel`` ...): :data:`PASSTHROUGH` names each one's module and
function, and :func:`voot.bench.cli.main.main` hands them the rest of the command line
unparsed."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


#: ``voot-bench NAME ARGS...`` -> ``module:function(ARGS)``: commands whose options their
#: module parses (``voot-bench NAME --help`` lists them).
PASSTHROUGH: dict[str, tuple[str, str]] = {
    "overhead": (
        "voot.bench.measure.overhead:tree_main",
        "the planner's own overhead per node visit",
    ),
    "record-overhead": (
        "voot.bench.measure.overhead:record_main",
        "the cost of recording a search",
    ),
    "record-demo": (
        "voot.bench.demos.record_demo:main",
        "recordings, Figure-5 panels and a GIF on the tiny pick-and-place demo",
    ),
    "env-speed": (
        "voot.bench.measure.env_speed:main",
        "step costs and sparsity of the robot domains",
    ),
    "env-figures": (
        "voot.bench.demos.env_figures:main",
        "render the environment figures of the docs",
    ),
    "root-parallel": (
        "voot.bench.measure.root_parallel:main",
        "root-parallel search: speed-up and quality against one tree",
    ),
    "voo-speed": (
        "voot.bench.measure.speed:voo_main",
        "VOO's cost per ask + tell on several objectives",
    ),
}


def cmd_passthrough(args: argparse.Namespace) -> int:
    """Run a :data:`PASSTHROUGH` command with the rest of the command line."""
    import importlib

    module, function = PASSTHROUGH[args.command][0].split(":")
    status = getattr(importlib.import_module(module), function)(list(args.rest))
    return int(status or 0)


def register(sub: Subparsers) -> None:
    """Add every :data:`PASSTHROUGH` command."""
    for name, (_, text) in PASSTHROUGH.items():
        p = sub.add_parser(name, help=text, add_help=False)
        p.add_argument("rest", nargs=argparse.REMAINDER, help="the command's own options")
        p.set_defaults(func=cmd_passthrough)
