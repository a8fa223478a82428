"""Subcommands on whole result stores: ``compact`` (copy a store into a compact one),
``shipped`` (check the committed stores against their manifest and redraw them) and
``export`` (a store as a Parquet table, :mod:`voot.bench.store.frame`). The size
and load time of stores is a measurement (``voot-bench measure store-speed``,
:mod:`voot.bench.cli.measure`)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError, add_compact_options, check_output, compact_config
from voot.bench.cli.report import KINDS
from voot.bench.store.format import STATUSES

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_compact(args: argparse.Namespace) -> int:
    """Convert a result store into a compact one (:func:`voot.bench.store.result_store.compact_store`)."""
    from voot.bench.store.result_store import compact_store

    check_output(args.dst, "DST", folder=True)
    out = compact_store(args.src, args.dst, compact_config(args))
    mb_src, mb_dst = out["src_bytes"] / 1e6, out["dst_bytes"] / 1e6
    # the size ratio compares like with like only when DST holds SRC's rows alone (a
    # conversion); merged into a store with other runs, DST's size is not SRC's compacted
    conversion = out["dst_rows"] == out["rows"] and out["dst_bytes"] > 0
    ratio = f", {out['src_bytes'] / out['dst_bytes']:.1f}x smaller" if conversion else ""
    print(
        f"{out['rows']} rows in {args.src} ({mb_src:.2f} MB of rows); {out['copied']} copied"
        f" now, {out['rows'] - out['copied']} already there; {args.dst}: {out['dst_rows']}"
        f" rows, {mb_dst:.2f} MB{ratio}"
    )
    return 0


def _plot_command(argv: list[str]) -> int:
    """``voot-bench plot ...`` by the ``plot`` subcommand alone (the whole command line,
    :mod:`voot.bench.cli.main`, imports this module)."""
    from voot.bench.cli import report as cli_report

    parser = argparse.ArgumentParser(prog="voot-bench")
    cli_report.register(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(argv)
    return int(args.func(args))


def cmd_shipped(args: argparse.Namespace) -> int:
    """Check the committed stores against their manifest and redraw their figures
    (:mod:`voot.bench.store.shipped`); with ``--write``, rewrite the manifest."""
    from voot.bench.store import shipped

    root = Path(args.root)
    if not root.is_dir():
        raise CLIError(f"{root}: no such folder (the committed stores are in docs/data)")
    if args.add_checksums:
        for path in shipped.store_dirs(root):
            n = shipped.add_row_checksums(path)
            print(f"{path.name}: {n} rows given a checksum")
        print("now rewrite the manifest: voot-bench shipped --write", file=sys.stderr)
        return 0
    if args.write:
        path = shipped.write_manifest(root)
        for name, entry in shipped.read_manifest(root).items():
            print(f"{name}: {entry['rows']} rows, sha256 {entry['sha256'][:12]}...")
        print(f"manifest: {path}", file=sys.stderr)
        return 0
    check_output(args.out, "--out", folder=True)
    out = Path(args.out) if args.out else None
    for path in shipped.store_dirs(root):
        got = shipped.check_store(root, path.name)
        line = f"{path.name}: {got['rows']} rows, checksums and manifest ok"
        if out is not None:
            files = shipped.redraw(path, out / path.name, _plot_command)
            line += f"; redrawn: {', '.join(f.name for f in files)}"
        print(line, flush=True)
    return 0


def cmd_export(args: argparse.Namespace) -> int:
    """Write a store's table, one row per run, to a Parquet file
    (:func:`voot.bench.store.frame.write_parquet`)."""
    from voot.bench.store.frame import write_parquet

    check_output(args.parquet, "--parquet")
    try:
        n = write_parquet(args.store, args.parquet, kind=args.kind, status=args.status)
    except ImportError as exc:
        raise CLIError(str(exc)) from None
    print(f"{n} runs of {args.store} written to {args.parquet}")
    return 0


def register(sub: Subparsers) -> None:
    """Add ``compact``, ``shipped`` and ``export``."""
    p = sub.add_parser(
        "compact",
        help="copy a result store into a compact one (resumable; the source is only read)",
        description="Every row of SRC into the compact store DST: best_so_far and"
        " objects_left exactly (their change points), elapsed, cpu_elapsed and calls_curve at"
        " reduced resolution with their first and last values exact. Run ids are unchanged,"
        " so a sweep resumed on DST skips every copied run.",
    )
    p.add_argument("src", help="the result store to read")
    p.add_argument("dst", help="the compact store to write (created if missing)")
    add_compact_options(p, "")
    p.set_defaults(func=cmd_compact)

    p = sub.add_parser(
        "shipped",
        help="check the committed result stores (docs/data) against their manifest and"
        " redraw their figures and tables",
    )
    p.add_argument(
        "--root", default="docs/data", help="folder of the stores (default: %(default)s)"
    )
    p.add_argument("--out", default=None, help="redraw every store's figures and tables here")
    p.add_argument("--write", action="store_true", help="rewrite the manifest (stores.json)")
    p.add_argument(
        "--add-checksums",
        action="store_true",
        help="give the rows of stores written before row checksums theirs (then --write)",
    )
    p.set_defaults(func=cmd_shipped)

    p = sub.add_parser(
        "export",
        help="a result store as a table for analysis elsewhere: one row per run, to Parquet",
        description="Every run of STORE as one row of a Parquet file: run id, kind, status and"
        " timings, the config flattened into columns (objects such as params as JSON text),"
        " the curves (best_so_far, objects_left, elapsed, cpu_elapsed, calls_curve) as list"
        " columns, and the row's other values. Read it with pandas.read_parquet, polars,"
        " DuckDB or R's arrow. Needs pandas and pyarrow (the bench extra).",
    )
    p.add_argument("store", help="the result store to read")
    p.add_argument("--parquet", required=True, metavar="OUT", help="the Parquet file to write")
    p.add_argument("--kind", choices=KINDS, default=None, help="only runs of this kind")
    p.add_argument(
        "--status", choices=STATUSES, default=None, help="only runs of this status (default: all)"
    )
    p.set_defaults(func=cmd_export)
