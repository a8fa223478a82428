"""``voot-bench leaderboard``: run a versioned suite for any planners (``run``), build the
table (``report``), write result cards (``card``) and re-run a sample of a store to check
it (``verify``); see :mod:`voot.bench.leaderboard`."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from voot.bench.cli import common as C

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers
    from voot.bench.leaderboard.suite import Entry, Suite


def _suite(args: argparse.Namespace) -> Suite:
    from voot.bench.leaderboard.suite import load_suite

    return load_suite(args.suite)


def _entries(suite: Suite, names: Sequence[str] | None) -> list[Entry]:
    """The suite's entries named by ``--planners`` (default or ``all``: the suite's)."""
    from voot.bench.sweep.planners import normalize_plan_planner

    items = C.split_list(names)
    if not items or items == ["all"]:
        return list(suite.entries)
    out = []
    for name in items:
        entry = suite.entry(name)
        try:
            planner = normalize_plan_planner(entry.planner)
        except ValueError as exc:
            raise C.CLIError(f"--planners: {exc}") from None
        out.append(entry if entry in suite.entries else type(entry)(planner))
    return out


def cmd_run(args: argparse.Namespace) -> int:
    from voot.bench.leaderboard import plan as L
    from voot.bench.store.compact import CompactConfig

    C.check_sweep_options(args)
    C.check_output(args.out, "--out", folder=True)
    suite = _suite(args)
    entries = _entries(suite, args.planners)
    workers = args.workers or os.cpu_count() or 1
    existing = C.existing_store(args.out)
    rows = existing.load(kind="plan", status="ok") if existing is not None else []
    tuning, evaluation, _ = L.all_specs(suite, entries, rows)
    specs = [*tuning, *evaluation]
    pending = L.pending_of(specs, existing)
    print(
        f"suite {suite.name} ({suite.digest[:12]}): {len(entries)} entries x"
        f" {len(suite.families)} families x {len(suite.levels)} levels x"
        f" {len(suite.heldout_layouts)} held-out layouts x {len(suite.seeds)} seeds;"
        f" {len(tuning)} tuning runs, {len(evaluation)} evaluation runs,"
        f" {len(specs) - len(pending)} already in {args.out}",
        file=sys.stderr,
    )
    costs = L.estimate_suite(
        specs,
        rows,
        {s.run_id for s in pending},
        reference=L.reference_rows(),
        probe_simulations=args.probe_simulations,
    )
    print("CPU cost of the runs still to do (before running):")
    print(L.format_costs(costs, workers))
    sys.stdout.flush()
    if args.estimate_only:
        return 0
    from voot.bench.sweep.backends import make_backend

    # an existing store keeps its own layout (compact or not); a new one is compact
    store = existing or C.open_store(args.out, None if args.full else CompactConfig())
    backend = make_backend(
        args.backend, args.workers, address=args.address, max_tries=args.max_tries
    )
    print(f"results: {store.path} (backend: {backend.name})", file=sys.stderr)

    def run_batch(batch: Sequence[Any]) -> int:
        return C.run_specs(args, batch, store, backend).failed

    failed = L.run_suite(suite, entries, store, run_batch)
    from voot.bench.leaderboard.card import write_cards

    for path in write_cards(store.path, suite):
        print(f"card: {path}", file=sys.stderr)
    return 1 if failed else 0


def _store_path(path: str) -> str:
    """``path`` if it holds a result store, else a CLIError naming it."""
    if C.existing_store(path) is None:
        raise C.CLIError(f"{path}: no voot result store here")
    return path


def cmd_report(args: argparse.Namespace) -> int:
    from pathlib import Path

    from voot.bench.leaderboard.table import build_report, splice_page

    suite = _suite(args)
    store = _store_path(args.store)
    entries = _entries(suite, args.planners) if args.planners else None
    figure_link = None
    if args.figure is not None and args.page is not None:
        figure_link = os.path.relpath(args.figure, Path(args.page).parent)
    report = build_report(store, suite, entries, figure=args.figure, figure_link=figure_link)
    if args.page is not None:
        page = Path(args.page)
        try:
            text = page.read_text(encoding="utf-8")
        except OSError as exc:
            raise C.CLIError(f"--page {page}: cannot read it ({exc.strerror})") from None
        try:
            page.write_text(splice_page(text, report.markdown), encoding="utf-8")
        except ValueError as exc:
            raise C.CLIError(f"--page {page}: {exc}") from None
        print(f"page: {page}", file=sys.stderr)
    else:
        print(report.markdown, end="")
    if args.figure is not None and report.complete:
        print(f"figure: {args.figure}", file=sys.stderr)
    return 0


def cmd_card(args: argparse.Namespace) -> int:
    from voot.bench.leaderboard.card import write_cards

    paths = write_cards(_store_path(args.store), _suite(args))
    for p in paths:
        print(p)
    return 0


def cmd_verify(args: argparse.Namespace) -> int:
    from voot.bench.leaderboard.card import check_cards, verify_store

    store = _store_path(args.store)
    if args.sample < 1:
        raise C.CLIError(f"--sample must be >= 1, got {args.sample}")
    cards = check_cards(store, _suite(args))
    print(f"{len(cards)} cards match the store's checksum and the suite's digest")
    n, mismatches = verify_store(store, args.sample, seed=args.seed)
    for m in mismatches:
        print(f"MISMATCH {m.run_id} ({m.description}): {', '.join(m.fields)}", file=sys.stderr)
    print(f"re-ran {n} runs: {n - len(mismatches)} match bit for bit, {len(mismatches)} differ")
    return 1 if mismatches else 0


def _usage(parser: argparse.ArgumentParser) -> int:
    """The group's usage, for a call without an action (exit status 2)."""
    parser.print_usage(sys.stderr)
    return 2


def _suite_option(p: argparse.ArgumentParser) -> None:
    from voot.bench.leaderboard.suite import DEFAULT_SUITE, SUITES

    p.add_argument(
        "--suite",
        default=DEFAULT_SUITE,
        help=f"suite name ({', '.join(SUITES)}) or a .toml file (default: %(default)s)",
    )


def register(sub: Subparsers) -> None:
    p = sub.add_parser(
        "leaderboard",
        help="the leaderboard: run a versioned suite for any planners, report, cards, verify",
        description="The leaderboard of planners on a versioned suite (voot.bench.leaderboard).",
    )
    p.set_defaults(func=lambda args: _usage(p))  # argparse asks for an ACTION first
    lsub = p.add_subparsers(dest="leaderboard_command", required=True, metavar="ACTION")
    r = lsub.add_parser(
        "run",
        help="run the suite (resumable; the CPU-cost estimate first)",
        description="Run the suite for the given planners into a store: tuning on training"
        " layouts (or the committed protocol's selection), then every level x held-out"
        " layout x seed. Resumable: run the same command again after an interruption.",
    )
    r.add_argument(
        "--planners",
        nargs="+",
        metavar="NAME",
        help="suite entries or any planner name (built-in, entry point, module:attr);"
        " default or 'all': the suite's entries",
    )
    _suite_option(r)
    r.add_argument("--out", required=True, help="the result store (created if missing)")
    C.add_backend_options(r)
    r.add_argument(
        "--estimate-only", action="store_true", help="print the CPU-cost estimate; run nothing"
    )
    r.add_argument(
        "--probe-simulations",
        type=int,
        default=20,
        help="simulations of a probe run for a pair without measured cost (default: %(default)s)",
    )
    r.add_argument(
        "--full", action="store_true", help="a store of full-resolution rows (default: compact)"
    )
    r.add_argument(
        "--skip-failed", action="store_true", help="do not retry runs that failed before"
    )
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    r.set_defaults(func=cmd_run)

    rep = lsub.add_parser(
        "report",
        help="the leaderboard of a store: tables, performance profiles, the docs page",
        description="IQM with stratified-bootstrap 95% intervals per family x level and"
        " aggregated, performance profiles and probability of improvement, at matched"
        " simulator calls and CPU time, on the complete cells of the store.",
    )
    rep.add_argument("store", help="the leaderboard's result store")
    _suite_option(rep)
    rep.add_argument("--planners", nargs="+", metavar="NAME", help="entries (default: the store's)")
    rep.add_argument(
        "--page",
        default=None,
        help="a markdown page to draw the leaderboard into (between its"
        " <!-- leaderboard:start/end --> markers); default: print it",
    )
    rep.add_argument("--figure", default=None, help="the performance profiles figure (.png)")
    rep.set_defaults(func=cmd_report)
    card = lsub.add_parser("card", help="write the result card of every entry in a store")
    card.add_argument("store", help="the leaderboard's result store")
    _suite_option(card)
    card.set_defaults(func=cmd_card)
    ver = lsub.add_parser(
        "verify",
        help="check a store's cards and re-run a sample of its runs bit for bit",
        description="Check the result cards against the store and the suite, then re-run"
        " a sample of the store's runs and compare every deterministic field (timings"
        " excluded). Exit 1 naming the runs and fields that differ.",
    )
    ver.add_argument("store", help="the leaderboard's result store")
    _suite_option(ver)
    ver.add_argument("--sample", type=int, default=5, help="runs re-run (default: %(default)s)")
    ver.add_argument(
        "--seed", type=int, default=0, help="seed of the sample (default: %(default)s)"
    )
    ver.set_defaults(func=cmd_verify)
