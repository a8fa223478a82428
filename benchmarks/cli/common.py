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
import os
import signal
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voot.bench.store.format import StoreError
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.engine import Spec
from voot.envs.core.arguments import LAYOUT_SEEDS, check_layout_seed

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


#: The most values one ``N`` or ``START:STOP`` option may hold: far above any sweep
#: (the paper's largest has 50 seeds), far below what a list of them would not fit in.
MAX_RANGE_LENGTH = 1_000_000


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
    if stop - start > MAX_RANGE_LENGTH:
        raise CLIError(
            f"{what}: {text!r} holds {stop - start} values, more than a sweep can run (at"
            f" most {MAX_RANGE_LENGTH})"
        )
    return list(range(start, stop))


def parse_assignments(values: Sequence[str] | None, what: str) -> dict[str, object]:
    """``["omega=0.3", "depth_limit=5,gamma=0.99"]`` -> a dict; values are JSON
    (``0.3``, ``true``, ``null``, ``"text"``) or else plain strings. A name given twice is
    refused (the last would silently win over a value the user also typed)."""
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
        if name in out:
            raise CLIError(
                f"{what}: {name} is given twice ({name}={out[name]!r} and {name}={value!r});"
                " give each name once"
            )
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
        raise CLIError(
            f"--out {path}: cannot create the result store there ({_reason(exc)});"
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
    check_workers(args)
    if args.max_tries is not None and args.max_tries < 1:
        raise CLIError(f"--max-tries must be >= 1, got {args.max_tries}")
    if args.probe_simulations < 1:
        raise CLIError(f"--probe-simulations must be >= 1, got {args.probe_simulations}")


def check_workers(args: argparse.Namespace) -> None:
    """``--workers`` must be >= 1 when given: checked before the store is created (the
    backend would refuse it only after)."""
    if args.workers is not None and args.workers < 1:
        raise CLIError(f"--workers must be >= 1 (default: every CPU), got {args.workers}")


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
    try:
        md.parent.mkdir(parents=True, exist_ok=True)
        md.write_text(text)
    except OSError as exc:
        raise CLIError(f"--markdown {path}: cannot write the file ({_reason(exc)})") from None
    print(f"markdown: {md}", file=sys.stderr)


def _reason(exc: OSError) -> str:
    """``"Not a directory: 'a/b'"``: an OSError in one line, without its traceback."""
    reason = exc.strerror or type(exc).__name__
    return f"{reason}: {exc.filename}" if exc.filename is not None else reason


def check_output(path: str | os.PathLike[str] | None, option: str, folder: bool = False) -> None:
    """Refuse an output path that cannot be written, before any work is done.

    ``path`` (None: the option is not given) is a file to write, or with ``folder`` a
    folder to write into (made if missing). Nothing is created: the path's nearest
    existing ancestor must be a folder this process may write in, and the path itself, if
    it exists, must be a file (a folder with ``folder``) that may be written. The
    CLIError names ``option``, the path and what is wrong with it, so a sweep or a
    measurement never runs to the end and then fails to save what it made.
    """
    if path is None:
        return
    target = Path(path)
    if str(path) == "":
        raise CLIError(f"{option}: an empty path; give a {'folder' if folder else 'file'}")
    if target.exists():
        if folder and not target.is_dir():
            raise CLIError(f"{option} {path}: is a file, not a folder; give a folder")
        if not folder and target.is_dir():
            raise CLIError(f"{option} {path}: is a folder; give a file name")
        if not os.access(target, os.W_OK | (os.X_OK if folder else 0)):
            raise CLIError(f"{option} {path}: not writable by this user")
        return
    ancestor = target.absolute().parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise CLIError(
            f"{option} {path}: {ancestor} is a file, not a folder, so nothing can be written"
            " under it; give a path in a folder"
        )
    if not os.access(ancestor, os.W_OK | os.X_OK):
        raise CLIError(
            f"{option} {path}: the folder {ancestor} is not writable by this user; give a"
            " path in a folder you can write"
        )


#: The largest layout seed a generated family takes (the envs' own range,
#: :data:`voot.envs.core.arguments.LAYOUT_SEEDS`).
MAX_LAYOUT_SEED = LAYOUT_SEEDS.stop - 1


def check_layout_value(value: object, option: str) -> None:
    """Refuse a ``layout_seed`` given as an env keyword unless the families' own validator
    (:func:`voot.envs.core.arguments.check_layout_seed`: an integer in ``[0,
    MAX_LAYOUT_SEED]``; a bool, a float such as ``1.5`` or ``1.0``, or a string refused)
    takes it: one rule for the envs and the command line. JSON keeps ``1.0`` a float, and
    an env must not round it to a layout."""
    try:
        check_layout_seed(value)
    except ValueError as exc:
        raise CLIError(f"{option}: {exc} ({type(value).__name__})") from None


def check_envs(
    specs: Sequence[Any], option: str = "--env-kwargs", layout_option: str | None = None
) -> int:
    """Make one environment of every problem the planning runs ``specs`` ask for, with
    their env keywords, before the first run is written; return how many were made.

    A keyword the env does not take, a level it does not have or a layout seed out of its
    range would otherwise fail every run of the sweep (a store full of failed rows) or
    only after minutes of other runs. Per problem and env keywords (the layout seed
    aside) the env is made with the smallest and the largest layout seed of the runs,
    the ends of the range an env checks (every seed is an integer >= 0 already); chains
    make no env. The env's own ValueError/TypeError (or gymnasium's error for an id it
    does not know) becomes a one-line CLIError naming ``option`` and the problem; the
    env's message names the parameter and its valid choices. ``layout_option`` names
    the option the layout seeds came from (``--layout-seeds``; default ``option``): an env
    that can be made without its layout seed but not with one takes no layouts, and the
    error says so under that option, naming the families that have them.
    """
    from voot.bench.protocol import problems as P
    from voot.bench.protocol.layouts import LAYOUT_KEY

    groups: dict[tuple[str, str], tuple[dict[str, Any], set[int]]] = {}
    for spec in specs:
        if P.is_chain(spec.problem):
            continue
        kwargs = dict(spec.env_kwargs)
        explicit = LAYOUT_KEY in kwargs
        layout = kwargs.pop(LAYOUT_KEY, None)
        if explicit:  # null too: omit the keyword for the default layout, one spelling
            check_layout_value(layout, option)
        key = (spec.problem, json.dumps(kwargs, sort_keys=True, default=repr))
        entry = groups.setdefault(key, (kwargs, set()))
        if layout is not None:
            entry[1].add(int(layout))
    made = 0
    for (problem, _), (kwargs, layouts) in groups.items():
        ends = sorted({min(layouts), max(layouts)}) if layouts else [None]
        for layout in ends:
            if layout is None:
                _make_checked(problem, kwargs, option)
            else:
                try:
                    _make_checked(problem, {**kwargs, LAYOUT_KEY: layout}, option)
                except CLIError:
                    _make_checked(problem, kwargs, option)  # fine without: takes no layouts
                    from voot.bench.protocol.layouts import LAYOUT_SETS

                    raise CLIError(
                        f"{layout_option or option}: {problem} takes no {LAYOUT_KEY}; layout"
                        f" seeds apply to the generated families ({', '.join(LAYOUT_SETS)})"
                    ) from None
            made += 1
    return made


def _make_checked(problem: str, kwargs: dict[str, Any], option: str) -> None:
    """``gymnasium.make(problem, **kwargs)`` and close it, or a one-line CLIError."""
    import warnings

    import gymnasium

    import voot  # noqa: F401 - registers the voot/... ids

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FutureWarning)  # an old id's alias note
            env = gymnasium.make(problem, disable_env_checker=True, **kwargs)
    except (ValueError, TypeError, gymnasium.error.Error) as exc:
        shown = ", ".join(f"{k}={v!r}" for k, v in sorted(kwargs.items())) or "no keywords"
        message = " ".join(str(exc).split())
        raise CLIError(f"{option}: {problem} ({shown}) cannot be made: {message}") from None
    env.close()
