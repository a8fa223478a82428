"""The ``voot-bench`` command line: one parser, the researcher's commands at its top
(:data:`COMMANDS`) and the project's own measurements under ``voot-bench measure``
(:data:`MEASUREMENTS`).

The researcher's commands::

    voot-bench demo                       VOOT clearing the kitchen (recording + GIF)
    voot-bench demo-voo                   VOO on Shekel-20D with the paper's budget (5000)
    voot-bench bbfo --out results/bbfo    the Figure-3 sweep (resumable, parallel)
    voot-bench bbfo --instance 1 ...      the same on test functions with shifted optima
    voot-bench plan --out results/plan    planners x problems x seeds (Figure 4; Ray too)
    voot-bench ablation --list            the departures from the authors' code, one at a time
    voot-bench select results/bbfo        the selected hyperparameters per method
    voot-bench claims results/plan        the paper's claims: ours, 95% interval, verdict
    voot-bench plot results/bbfo --png fig.png --markdown table.md
    voot-bench difficulty                 how hard the robot domains are, planner-agnostic
    voot-bench export results/plan --parquet p.parquet   one row per run, for pandas

The measurements (``voot-bench measure --help`` lists them)::

    voot-bench measure speed              cost per ask of VOO, CMA-ES and GP-UCB
    voot-bench measure mesh-speed         cost of the trimesh object meshes and grasp lookups
    voot-bench measure footprint-speed    cost of the base planner's exact-footprint option
    voot-bench measure domain-ablation    the domains' departures, one at a time
    voot-bench measure speedup            tree search on the robot domains: 6af33b5 vs now

A measurement's old spelling without ``measure`` (``voot-bench speed``) still works; it is
not listed in ``voot-bench --help``. ``voot-bench --version`` prints the version.

Errors in the input (unknown function or method, inverted ranges, a corrupt or foreign
result directory) print one line ``voot-bench: error: ...`` and exit with status 2.
Progress bars go to stderr, results and tables to stdout.

Where the subcommands live: :mod:`~voot.bench.cli.demo` (``demo``, ``record-demo``,
``figure5``, ``demo-voo``, ``env-figures``), :mod:`~voot.bench.cli.bbfo`,
:mod:`~voot.bench.cli.plan`, :mod:`~voot.bench.cli.ablation`,
:mod:`~voot.bench.cli.report` (``select``, ``plot``, ``claims``),
:mod:`~voot.bench.cli.difficulty` (``difficulty``, ``ladder``),
:mod:`~voot.bench.cli.store` (``compact``, ``shipped``, ``export``); the measurements
in :mod:`~voot.bench.cli.measure` (the optimisers', the search's and the stores' costs),
:mod:`~voot.bench.cli.env_cost` (the environments') and :mod:`~voot.bench.cli.speedup`.
What they share is in :mod:`~voot.bench.cli.common`.

Adding a subcommand: a handler ``cmd_<name>(args) -> int`` (the exit status; raise
:class:`~voot.bench.cli.common.CLIError` for a user error) and a ``register(sub)`` that
adds its parser with ``sub.add_parser(name, help=...)`` and
``p.set_defaults(func=cmd_<name>)``, in the module of its concept; then list that
``register`` in :data:`COMMANDS` (a researcher's command) or :data:`MEASUREMENTS` (a
measurement of voot itself), at the place it should have in the help.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import voot
from voot.bench.cli import (
    ablation,
    bbfo,
    demo,
    difficulty,
    env_cost,
    leaderboard,
    measure,
    plan,
    report,
    speedup,
    store,
)
from voot.bench.cli.common import CLIError
from voot.bench.store.format import StoreError
from voot.rl.train import MissingExtraError

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers

EXIT_USAGE = 2
EXIT_INTERRUPTED = 130
#: The group of the measurements: ``voot-bench measure NAME``.
MEASURE = "measure"

#: The researcher's commands, each module's ``register``, in the order of ``voot-bench --help``.
COMMANDS: tuple[Callable[[Subparsers], None], ...] = (
    demo.register,  # demo, record-demo, figure5, demo-voo, env-figures
    bbfo.register,  # bbfo
    plan.register,  # plan
    ablation.register,  # ablation
    report.register,  # select, plot, claims
    difficulty.register,  # difficulty, ladder
    store.register,  # compact, shipped, export
    leaderboard.register,  # leaderboard run, report, card, verify
)

#: The project's own measurements (``voot-bench measure NAME``), in the order of
#: ``voot-bench measure --help``.
MEASUREMENTS: tuple[Callable[[Subparsers], None], ...] = (
    measure.register,  # speed, voo-speed, overhead, record-overhead, memory, root-parallel, ...
    env_cost.register,  # env-speed, mesh-speed, footprint-speed, domain-ablation
    speedup.register,  # speedup
)


def build_parser() -> argparse.ArgumentParser:
    """The ``voot-bench`` parser: every command of :data:`COMMANDS`, and ``measure`` with
    every measurement of :data:`MEASUREMENTS`."""
    parser = argparse.ArgumentParser(
        prog="voot-bench",
        description="Benchmarks of voot: VOO and baselines (paper Figure 3), VOOT and its"
        " baselines (paper Figure 4). The project's own measurements of voot's costs are"
        " under 'voot-bench measure'.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {voot.__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for register in COMMANDS:
        register(sub)
    group = sub.add_parser(
        MEASURE,
        help="the project's own measurements of what voot costs (optimisers, tree search,"
        " recording, memory, environments, stores); 'measure --help' lists them",
        description="Measurements of voot itself: the cost of its optimisers, tree search,"
        " recordings, environments and result stores, and the speed-up against an older"
        " commit. Tables go to stdout.",
    )
    measurements = group.add_subparsers(dest="measurement", required=True, metavar="NAME")
    for register in MEASUREMENTS:
        register(measurements)
    return parser


def measurement_names(parser: argparse.ArgumentParser) -> list[str]:
    """The names of the measurements of ``parser`` (``voot-bench measure NAME``)."""
    return list(_subcommands(_subcommands(parser)[MEASURE]))


def _subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    (action,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(action.choices)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``voot-bench``; returns the exit status."""
    parser = build_parser()
    words = list(sys.argv[1:] if argv is None else argv)
    if words and words[0] in measurement_names(parser):  # old spelling: voot-bench speed
        words.insert(0, MEASURE)
    args = parser.parse_args(words)
    try:
        return int(args.func(args))
    except (CLIError, StoreError, ValueError, MissingExtraError) as exc:
        print(f"voot-bench: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print(
            "\nvoot-bench: interrupted; finished runs are saved, run the same command again to resume",
            file=sys.stderr,
        )
        return EXIT_INTERRUPTED


if __name__ == "__main__":
    sys.exit(main())
