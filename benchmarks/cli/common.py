"""What the ``voot-bench`` subcommands share: the user error (:class:`CLIError`), the
parsers of list, range and ``NAME=VALUE`` options, opening a result store for a sweep,
running a sweep into it (SIGTERM as Ctrl-C), writing a markdown file, and the argument
groups that more than one subcommand adds (test-function filters, the backend of a sweep,
the run options of a sweep, compact-store settings, a checked count).

The subcommands themselves live in the modules of this package whose ``register``
functions :mod:`voot.bench.cli.main` lists in :data:`~voot.bench.cli.main.COMMANDS`
and :data:`~voot.bench.cli.main.MEASUREMENTS`.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import signal
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voot.bench.store.format import StoreError
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.engine import Spec

if TYPE_CHECKING:
    from voot.bench.sweep.backends import Backend
    from voot.bench.sweep.engine import SweepSummary

    #: The object ``add_subparsers`` returns; every ``register`` adds its parsers to it.
    Subparsers = argparse._SubParsersAction[argparse.ArgumentParser]


class CLIError(ValueError):
    """A user error reported as ``voot-bench: error: ...``."""


def split_list(values: Sequence[str] | None) -> list[str]:
    """Flatten ``["a,b", "c"]`` into ``["a", "b", "c"]``."""
    out: list[str] = []
    for v in values or []:
        out.extend(p for p in (s.strip() for s in v.split(",")) if p)
    return out


def parse_int_list(values: Sequence[str] | None, what: str) -> list[int]:
    """Integers from ``["3", "10,20"]``; ``"A:B"`` expands to ``A .. B-1``."""
    out: list[int] = []
    for item in split_list(values):
        if ":" in item:
            out.extend(parse_range(item, what))
            continue
        try:
            out.append(int(item))
        except ValueError:
            raise CLIError(f"{what}: {item!r} is not an integer") from None
    return out


def parse_range(text: str, what: str) -> list[int]:
    """``"N"`` -> ``0 .. N-1``; ``"A:B"`` -> ``A .. B-1`` (error if ``B <= A``)."""
    parts = text.split(":")
    try:
        if len(parts) == 1:
            start, stop = 0, int(parts[0])
        elif len(parts) == 2:
            start, stop = int(parts[0]), int(parts[1])
        else:
            raise ValueError
    except ValueError:
        raise CLIError(f"{what}: {text!r} is not N or START:STOP") from None
    if start < 0:
        raise CLIError(f"{what}: {text!r} starts below 0")
    if stop <= start:
        raise CLIError(
            f"{what}: inverted or empty range {text!r} (need START < STOP, e.g. 0:20)"
            if len(parts) == 2
            else f"{what}: need at least 1, got {text!r}"
        )
    return list(range(start, stop))


def parse_assignments(values: Sequence[str] | None, what: str) -> dict[str, object]:
    """``["omega=0.3", "depth_limit=5,gamma=0.99"]`` -> a dict; values are JSON
    (``0.3``, ``true``, ``null``, ``"text"``) or else plain strings."""
    out: dict[str, object] = {}
    for item in split_list(values):
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise CLIError(f"{what}: {item!r} is not NAME=VALUE (e.g. omega=0.3)")
        text = text.strip()
        if text in ("None", "none"):
            value: object = None
        else:
            try:
                value = json.loads(text)
            except ValueError:
                value = text
        out[name] = value
    return out


@contextlib.contextmanager
def sigterm_as_interrupt() -> Iterator[None]:
    """Treat SIGTERM (a job scheduler, ``kill``) like Ctrl-C, so a sweep stops its workers
    and exits cleanly; finished rows are already on disk."""

    def handler(signum: int, frame: object) -> None:
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGTERM, handler)
    except ValueError:  # not the main thread: leave signals alone
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def existing_store(path: str) -> ResultStore | None:
    """The result store at ``path`` if there is one (None: none, or not a store)."""
    try:
        return ResultStore(path, create=False)
    except (OSError, StoreError):
        return None


def open_store(path: str, compact: Any = None) -> ResultStore:
    """The result store at ``path`` (created if missing, compact if ``compact``), or a
    CLIError saying why not."""
    try:
        return ResultStore(path, compact=compact)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise CLIError(
            f"--out {path}: cannot create the result store there ({reason}: {exc.filename});"
            " give a folder that exists or can be created"
        ) from None


def stored_note(path: str, specs: Sequence[Spec]) -> str:
    """``"; N already in the store"`` if the store at ``path`` exists and holds some."""
    from voot.bench.sweep.engine import pending_specs

    store = existing_store(path)
    if store is None:
        return ""
    unique = {s.run_id for s in specs}
    done = len(unique) - len({s.run_id for s in pending_specs(specs, store)})
    return f"; {done} already in the store" if done else ""


def compact_config(args: argparse.Namespace) -> Any:
    """The :class:`~voot.bench.store.compact.CompactConfig` of ``--compact-points/--compact-spacing``."""
    from voot.bench.store.compact import CompactConfig

    return CompactConfig(points=args.compact_points, spacing=args.compact_spacing)


def add_compact_options(p: argparse.ArgumentParser, prefix: str) -> None:
    from voot.bench.store.compact import DEFAULT_POINTS, SPACINGS

    p.add_argument(
        f"--{prefix}points",
        dest="compact_points",
        type=int,
        default=DEFAULT_POINTS,
        help="simulation indices kept per cost curve (elapsed, cpu_elapsed, calls_curve),"
        " plus the first and the last (default: %(default)s)",
    )
    p.add_argument(
        f"--{prefix}spacing",
        dest="compact_spacing",
        choices=SPACINGS,
        default="log",
        help="spacing of those indices (default: %(default)s)",
    )


def add_filters(p: argparse.ArgumentParser, defaults: bool) -> None:
    from voot.bench.sweep.bbfo import PAPER_DIMS, PAPER_FUNCTIONS, PAPER_METHODS

    def hint(values: Sequence[object]) -> str:
        return f" (default: {' '.join(map(str, values))})" if defaults else " (default: all)"

    p.add_argument(
        "--functions", nargs="+", metavar="NAME", help="test functions" + hint(PAPER_FUNCTIONS)
    )
    p.add_argument("--dims", nargs="+", metavar="D", help="dimensions" + hint(PAPER_DIMS))
    p.add_argument("--methods", nargs="+", metavar="NAME", help="optimisers" + hint(PAPER_METHODS))


def add_backend_options(p: argparse.ArgumentParser) -> None:
    """``--workers``, ``--backend``, ``--address`` and ``--max-tries`` of a sweep."""
    from voot.bench.sweep.backends import BACKENDS

    p.add_argument(
        "--workers",
        type=int,
        default=None,
        help="processes or Ray actors (default: every CPU)",
    )
    p.add_argument("--backend", choices=BACKENDS, default="process", help="where runs execute")
    p.add_argument("--address", default=None, help="Ray cluster address (e.g. auto)")
    p.add_argument(
        "--max-tries", type=int, default=None, help="Ray: tries of a run whose worker dies (3)"
    )


def check_sweep_options(args: argparse.Namespace) -> None:
    """The checks of a planning sweep's options (Ray-only options, the probe's length)."""
    if args.backend != "ray" and (args.address is not None or args.max_tries is not None):
        raise CLIError("--address and --max-tries go with --backend ray")
    if args.probe_simulations < 1:
        raise CLIError(f"--probe-simulations must be >= 1, got {args.probe_simulations}")


def add_run_options(p: argparse.ArgumentParser, dry_run: str) -> None:
    """``--skip-failed``, ``--dry-run`` (``dry_run``: its help) and ``--no-progress`` of a
    sweep: how :func:`run_specs` runs it."""
    p.add_argument(
        "--skip-failed", action="store_true", help="do not retry runs that failed before"
    )
    p.add_argument("--dry-run", action="store_true", help=dry_run)
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def add_estimate_options(p: argparse.ArgumentParser, estimate: str) -> None:
    """``--estimate`` (``estimate``: its help) and ``--probe-simulations`` of a planning
    sweep (:mod:`voot.bench.protocol.estimate`)."""
    p.add_argument("--estimate", action="store_true", help=estimate)
    p.add_argument(
        "--probe-simulations",
        type=int,
        default=20,
        help="--estimate: simulations of a probe run (default: %(default)s)",
    )


def add_compact_store_options(p: argparse.ArgumentParser, compact: str) -> None:
    """``--compact`` (``compact``: its help) and the compact settings
    (``--compact-points``, ``--compact-spacing``) of a planning sweep's new store."""
    p.add_argument("--compact", action="store_true", help=compact)
    add_compact_options(p, "compact-")


def run_specs(
    args: argparse.Namespace, specs: Sequence[Any], store: ResultStore, backend: Backend
) -> SweepSummary:
    """Run ``specs`` into ``store`` on ``backend`` as the options of :func:`add_run_options`
    say (SIGTERM as Ctrl-C); print the sweep's summary and return it."""
    from voot.bench.sweep.engine import run_sweep

    with sigterm_as_interrupt():
        summary = run_sweep(
            specs, store, backend, progress=not args.no_progress, retry_failed=not args.skip_failed
        )
    print(summary)
    return summary


def write_markdown(path: str, text: str) -> None:
    """Write ``text`` to the markdown file ``path`` (its folder created) and say so on stderr."""
    md = Path(path)
    md.parent.mkdir(parents=True, exist_ok=True)
    md.write_text(text)
    print(f"markdown: {md}", file=sys.stderr)
