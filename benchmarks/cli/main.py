"""The ``voot-bench`` command line: one parser, its subcommands added by the ``cli_*``
modules listed in :data:`SUBCOMMANDS`.

Subcommands::

    voot-bench demo                       VOOT clearing the kitchen (recording + GIF)
    voot-bench demo-voo                   VOO on Shekel-20D with the paper's budget (5000)
    voot-bench bbfo --out results/bbfo    the Figure-3 sweep (resumable, parallel)
    voot-bench bbfo --instance 1 ...      the same on test functions with shifted optima
    voot-bench plan --out results/plan    planners x problems x seeds (Figure 4; Ray too)
    voot-bench ablation --list            the departures from the authors' code, one at a time
    voot-bench select results/bbfo        the selected hyperparameters per method
    voot-bench claims results/plan        the paper's claims: ours, 95% interval, verdict
    voot-bench plot results/bbfo --png fig.png --markdown table.md
    voot-bench speed                      cost per ask of VOO, CMA-ES and GP-UCB
    voot-bench mesh-speed                 cost of the trimesh object meshes and grasp lookups
    voot-bench speedup                    tree search on the robot domains: 6af33b5 vs now

Errors in the input (unknown function or method, inverted ranges, a corrupt or foreign
result directory) print one line ``voot-bench: error: ...`` and exit with status 2.
Progress bars go to stderr, results and tables to stdout.

Where the subcommands live: :mod:`~voot.bench.cli.demo` (``demo``, ``figure5``,
``demo-voo``), :mod:`~voot.bench.cli.bbfo`, :mod:`~voot.bench.cli.plan`,
:mod:`~voot.bench.cli.ablation`, :mod:`~voot.bench.cli.store` (``compact``, ``shipped``, ``store-speed``),
:mod:`~voot.bench.cli.report` (``select``, ``plot``, ``claims``),
:mod:`~voot.bench.cli.measure` (``speed``, ``difficulty``), :mod:`~voot.bench.cli.mesh`
(``mesh-speed``),
:mod:`~voot.bench.cli.passthrough` (commands that parse their own options) and
:mod:`~voot.bench.cli.speedup`; what they share is in :mod:`~voot.bench.cli.common`.

Adding a subcommand: a module ``benchmarks/cli_<name>.py`` with a handler
``cmd_<name>(args) -> int`` (the exit status; raise :class:`~voot.bench.cli.common.CLIError`
for a user error) and a ``register(sub)`` that adds its parser with
``sub.add_parser(...)`` and ``p.set_defaults(func=cmd_<name>)``; then list its
``register`` in :data:`SUBCOMMANDS`, at the place it should have in ``voot-bench --help``.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from voot.bench.cli import ablation as cli_ablation
from voot.bench.cli import bbfo as cli_bbfo
from voot.bench.cli import demo as cli_demo
from voot.bench.cli import measure as cli_measure
from voot.bench.cli import memory as cli_memory
from voot.bench.cli import mesh as cli_mesh
from voot.bench.cli import passthrough as cli_passthrough
from voot.bench.cli import plan as cli_plan
from voot.bench.cli import report as cli_report
from voot.bench.cli import speedup as cli_speedup
from voot.bench.cli import store as cli_store
from voot.bench.cli.common import CLIError
from voot.bench.cli.passthrough import PASSTHROUGH, cmd_passthrough
from voot.bench.store.format import StoreError
from voot.rl.train import MissingExtraError

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers

EXIT_USAGE = 2
EXIT_INTERRUPTED = 130

#: Every subcommand module's ``register``, in the order of ``voot-bench --help``.
SUBCOMMANDS: tuple[Callable[[Subparsers], None], ...] = (
    cli_demo.register,  # demo, figure5, demo-voo
    cli_bbfo.register,  # bbfo
    cli_plan.register,  # plan
    cli_ablation.register,  # ablation
    cli_store.register,  # compact, shipped, store-speed
    cli_report.register,  # select, plot, claims
    cli_measure.register,  # speed, difficulty
    cli_mesh.register,  # mesh-speed
    cli_memory.register,  # memory
    cli_passthrough.register,  # overhead, record-overhead, record-demo, env-speed, ...
    cli_speedup.register,  # speedup
)


def build_parser() -> argparse.ArgumentParser:
    """The ``voot-bench`` parser with every subcommand of :data:`SUBCOMMANDS`."""
    parser = argparse.ArgumentParser(
        prog="voot-bench",
        description="Benchmarks of voot: VOO and baselines (paper Figure 3), VOOT and its"
        " baselines (paper Figure 4).",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for register in SUBCOMMANDS:
        register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``voot-bench``; returns the exit status."""
    parser = build_parser()
    words = list(sys.argv[1:] if argv is None else argv)
    if words and words[0] in PASSTHROUGH:  # its module parses the rest (argparse would not)
        args = argparse.Namespace(command=words[0], rest=words[1:], func=cmd_passthrough)
    else:
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
