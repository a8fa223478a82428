"""The ``voot-bench`` command line.

Subcommands::

    voot-bench demo                       VOOT clearing the kitchen (recording + GIF)
    voot-bench demo-voo                   VOO on Shekel-20D with the paper's budget (5000)
    voot-bench bbfo --out results/bbfo    the Figure-3 sweep (resumable, parallel)
    voot-bench bbfo --instance 1 ...      the same on test functions with shifted optima
    voot-bench plan --out results/plan    planners x problems x seeds (Figure 4; Ray too)
    voot-bench select results/bbfo        the selected hyperparameters per method
    voot-bench claims results/plan        the paper's claims: ours, 95% interval, verdict
    voot-bench plot results/bbfo --png fig.png --markdown table.md
    voot-bench speed                      cost per ask of VOO, CMA-ES and GP-UCB
    voot-bench speedup                    tree search on the robot domains: 6af33b5 vs now

Errors in the input (unknown function or method, inverted ranges, a corrupt or foreign
result directory) print one line ``voot-bench: error: ...`` and exit with status 2.
Progress bars go to stderr, results and tables to stdout.

Size: one parser with one small handler per ``voot-bench`` subcommand; the work is in
the modules they call.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import sys
import time
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voot.bench.cli_types import seed_argument
from voot.bench.store import ResultStore, Row, StoreError
from voot.bench.sweep import Spec
from voot.rl.train import MissingExtraError

if TYPE_CHECKING:
    from voot.bench.plan_sweep import PlanSpec
    from voot.bench.sweep import SweepSummary

EXIT_USAGE = 2
EXIT_INTERRUPTED = 130

#: Default cases of ``voot-bench speed``: (method, number of told points). GP-UCB gets a
#: small n because reaching n means running GP-UCB for n evaluations first.
SPEED_CASES: tuple[tuple[str, int], ...] = (
    ("voo", 1000),
    ("voo", 5000),
    ("cmaes", 1000),
    ("cmaes", 5000),
    ("gp_ucb", 100),
)


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


@contextlib.contextmanager
def _sigterm_as_interrupt() -> Iterator[None]:
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


# ----- bbfo ----------------------------------------------------------------------------
def _add_filters(p: argparse.ArgumentParser, defaults: bool) -> None:
    from voot.bench.sweep import PAPER_DIMS, PAPER_FUNCTIONS, PAPER_METHODS

    def hint(values: Sequence[object]) -> str:
        return f" (default: {' '.join(map(str, values))})" if defaults else " (default: all)"

    p.add_argument(
        "--functions", nargs="+", metavar="NAME", help="test functions" + hint(PAPER_FUNCTIONS)
    )
    p.add_argument("--dims", nargs="+", metavar="D", help="dimensions" + hint(PAPER_DIMS))
    p.add_argument("--methods", nargs="+", metavar="NAME", help="optimisers" + hint(PAPER_METHODS))


def cmd_bbfo(args: argparse.Namespace) -> int:
    from voot.bench.sweep import (
        PAPER_DIMS,
        PAPER_FUNCTIONS,
        PAPER_METHODS,
        build_specs,
        make_backend,
        run_sweep,
        summarize_specs,
    )

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
        f"{_stored_note(args.out, specs)}",
        file=sys.stderr,
    )
    if args.dry_run:
        print(summarize_specs(specs))
        return 0
    store = _open_store(args.out)
    backend = make_backend(args.backend, args.workers)
    print(f"results: {store.path}", file=sys.stderr)
    with _sigterm_as_interrupt():
        summary = run_sweep(
            specs, store, backend, progress=not args.no_progress, retry_failed=not args.skip_failed
        )
    print(summary)
    return 1 if summary.failed else 0


# ----- plan ----------------------------------------------------------------------------
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


def cmd_plan(args: argparse.Namespace) -> int:
    from voot.bench.plan_sweep import build_plan_specs, summarize_plan_specs
    from voot.bench.problems import DEFAULT_PROBLEMS

    if args.backend != "ray" and (args.address is not None or args.max_tries is not None):
        raise CLIError("--address and --max-tries go with --backend ray")
    if args.record is not None:
        if args.backend == "ray":
            raise CLIError(
                "--record writes .rrd files where the search runs; use --backend process"
                " (or serial) for recorded runs"
            )
        try:
            from voot.record import SearchRecorder  # noqa: F401 - the recorder's entry point
        except ImportError as exc:
            raise CLIError(
                f"--record needs the recorder of voot.record ({exc}); install the [record]"
                " extra (pip install 'voot[record]')"
            ) from None
    seeds = parse_range(args.seeds, "--seeds") if args.seeds is not None else None
    if args.probe_simulations < 1:
        raise CLIError(f"--probe-simulations must be >= 1, got {args.probe_simulations}")

    def specs_of(seed_list: list[int] | None) -> list[PlanSpec]:
        return list(
            build_plan_specs(
                split_list(args.problems) or DEFAULT_PROBLEMS,
                parse_int_list(args.dims, "--dims") or None,
                split_list(args.planners) or None,
                seed_list,
                simulations=args.simulations,
                grid=args.grid,
                env_kwargs=parse_assignments(args.env_kwargs, "--env-kwargs"),
                fixed=parse_assignments(args.set, "--set"),
                record=args.record,
                horizon=args.horizon,
            )
        )

    if args.tuning_seeds is not None:
        if args.record is not None:
            raise CLIError("--record records single runs; it does not go with --tuning-seeds")
        return _plan_tuned(
            args, specs_of(parse_range(args.tuning_seeds, "--tuning-seeds")), specs_of(seeds)
        )
    specs = specs_of(seeds)
    if args.estimate:
        return _print_estimate(args, specs)
    simulations = sum(s.simulations for s in specs)
    print(
        f"{len(specs)} runs, {simulations} simulations{_stored_note(args.out, specs)}",
        file=sys.stderr,
    )
    if args.dry_run:
        print(summarize_plan_specs(specs))
        return 0
    summary = _run_plan_specs(
        args, specs, _open_store(args.out, _compact_config(args) if args.compact else None)
    )
    if args.record is not None and summary.skipped:
        print(
            f"note: {summary.skipped} runs were already in the store and were not recorded"
            " again (use a new --out to record them)",
            file=sys.stderr,
        )
    return 1 if summary.failed else 0


def _print_estimate(args: argparse.Namespace, specs: Sequence[PlanSpec]) -> int:
    """Print the estimated CPU-hours of ``specs`` (:mod:`voot.bench.estimate`); run nothing."""
    from voot.bench.estimate import estimate, format_estimate
    from voot.bench.sweep import pending_specs

    store = _existing_store(args.out)
    rows = store.load(status="ok") if store is not None else []
    pending = pending_specs(specs, store) if store is not None else list(specs)
    lines = estimate(
        specs, rows, {s.run_id for s in pending}, probe_simulations=args.probe_simulations
    )
    print(format_estimate(lines, args.workers or os.cpu_count() or 1))
    return 0


def _run_plan_specs(
    args: argparse.Namespace, specs: Sequence[PlanSpec], store: ResultStore
) -> SweepSummary:
    """Run ``specs`` into ``store`` with the backend of ``args``; the sweep's summary."""
    from voot.bench.sweep import make_backend, run_sweep

    backend = make_backend(
        args.backend, args.workers, address=args.address, max_tries=args.max_tries
    )
    layout = f", compact: {store.compact}" if store.compact is not None else ""
    print(f"results: {store.path} (backend: {backend.name}{layout})", file=sys.stderr)
    with _sigterm_as_interrupt():
        summary = run_sweep(
            specs, store, backend, progress=not args.no_progress, retry_failed=not args.skip_failed
        )
    print(summary)
    return summary


def _existing_store(path: str) -> ResultStore | None:
    """The result store at ``path`` if there is one (None: none, or not a store)."""
    try:
        return ResultStore(path, create=False)
    except (OSError, StoreError):
        return None


def _plan_tuned(
    args: argparse.Namespace, tuning: Sequence[PlanSpec], candidates: Sequence[PlanSpec]
) -> int:
    """``voot-bench plan --tuning-seeds``: the grid on the tuning seeds, the selection on
    them, the selected setting on the evaluation seeds (:mod:`voot.bench.tuning`)."""
    from voot.bench.plan_sweep import summarize_plan_specs
    from voot.bench.select import selection_table
    from voot.bench.tuning import (
        check_disjoint,
        seeds_text,
        selected_specs,
        tuning_note,
        tuning_selections,
    )

    tuning_seeds = sorted({s.seed for s in tuning})
    check_disjoint(tuning_seeds, {s.seed for s in candidates})
    existing = _existing_store(args.out)
    rows = existing.load(kind="plan", status="ok") if existing is not None else []
    selections = tuning_selections(tuning, rows)
    complete = existing is not None and not _pending(tuning, existing)
    if complete:
        evaluation = selected_specs(candidates, selections)
    else:  # the selection is not known yet: one setting per pair stands in for it
        evaluation = _one_setting_each(candidates)
    eval_seeds = seeds_text({s.seed for s in candidates})
    print(
        f"tuning: {len(tuning)} runs (every setting) on seeds {seeds_text(tuning_seeds)};"
        f" evaluation: {len(evaluation)} runs (the selected setting) on seeds {eval_seeds}"
        f"{'' if complete else ', after the tuning runs'}{_stored_note(args.out, tuning)}",
        file=sys.stderr,
    )
    if args.estimate:
        return _print_estimate(args, [*tuning, *evaluation])
    if args.dry_run:
        print("tuning runs:")
        print(summarize_plan_specs(tuning))
        print("evaluation runs (one setting per problem and planner):")
        print(summarize_plan_specs(evaluation))
        return 0
    store = _open_store(args.out, _compact_config(args) if args.compact else None)
    summary = _run_plan_specs(args, tuning, store)
    if summary.failed or _pending(tuning, store):
        print(
            "voot-bench: tuning runs failed or are missing; the evaluation waits for every"
            " tuning run (a selection on part of them would not be the protocol's)",
            file=sys.stderr,
        )
        return 1
    selections = tuning_selections(tuning, store.load(kind="plan", status="ok"))
    print(selection_table(selections, kind="plan"), file=sys.stderr)
    print(f"({tuning_note(tuning_seeds)})", file=sys.stderr)
    evaluation = selected_specs(candidates, selections)
    return 1 if _run_plan_specs(args, evaluation, store).failed else 0


def _pending(specs: Sequence[PlanSpec], store: ResultStore) -> list[PlanSpec]:
    from voot.bench.sweep import pending_specs

    return list(pending_specs(specs, store))


def _one_setting_each(specs: Sequence[PlanSpec]) -> list[PlanSpec]:
    """The specs of the first setting of every (problem, planner): stand-ins for the
    evaluation runs before the tuning selected their setting."""
    from voot.bench.estimate import pair_of

    first: dict[object, object] = {}
    out = []
    for s in specs:
        key = pair_of(s)
        if first.setdefault(key, s.params) == s.params:
            out.append(s)
    return out


# ----- select / plot -------------------------------------------------------------------
KINDS = ("bbfo", "plan")
INSTANCE_FILTER_HELP = (
    "bbfo runs: the test-function instance to use (default: the only one in the store;"
    " 0 = the paper's functions)"
)


def _load_rows(path: str, kind: str | None) -> tuple[str, list[Row]]:
    """Finished rows of ``kind`` (default: the one kind the store holds)."""
    from voot.bench.store import ResultStore

    store = ResultStore(path, create=False)
    rows = store.load(status="ok", arrays=True)
    kinds = sorted({r["kind"] for r in rows})
    if kind is None:
        if len(kinds) > 1:
            raise CLIError(
                f"{store.path} holds runs of kinds {', '.join(kinds)}; choose one with --kind"
            )
        kind = kinds[0] if kinds else "bbfo"
    chosen = [r for r in rows if r["kind"] == kind]
    if not chosen:
        raise CLIError(f"{store.path}: no finished {kind} runs in this store")
    return kind, chosen


def _load_bbfo(path: str) -> list[Row]:
    return _load_rows(path, "bbfo")[1]


def _one_instance(rows: list[Row], kind: str, instance: int | None) -> list[Row]:
    """The bbfo rows of one test-function instance (``--instance``, or the only one)."""
    from voot.bench.select import one_instance

    if kind != "bbfo":
        if instance is not None:
            raise CLIError("--instance applies to bbfo runs (test functions), not plan runs")
        return rows
    chosen, rows = one_instance(rows, instance)
    if chosen:
        print(f"test-function instance {chosen} (optima shifted)", file=sys.stderr)
    return rows


def cmd_select(args: argparse.Namespace) -> int:
    from voot.bench.select import largest_budget, select_hyperparameters, selection_table

    kind, rows = _load_rows(args.results, args.kind)
    rows = _one_instance(rows, kind, args.instance)
    selections = select_hyperparameters(largest_budget(rows))
    print(selection_table(selections, all_candidates=args.all, kind=kind))
    return 0


def _plan_filter(names: Sequence[str] | None) -> list[str] | None:
    from voot.bench.problems import normalize_problem, problem_label

    if not names:
        return None
    out = []
    for name in names:
        try:
            out.append(problem_label(normalize_problem(name)))
        except ValueError:
            out.append(name)  # e.g. a label with env keywords, as printed in the tables
    return out


def cmd_plot_plan(args: argparse.Namespace, rows: list[Row]) -> int:
    from voot.bench.plan_plot import plan_data, plan_report, plot_plan_figure
    from voot.bench.plan_sweep import normalize_plan_planner as normalize_planner

    if args.regret or args.log or args.functions or args.dims or args.methods:
        raise CLIError(
            "--regret, --log, --functions, --dims and --methods apply to bbfo runs;"
            " for plan runs filter with --problems and --planners"
        )
    planners = [normalize_planner(p) for p in split_list(args.planners)] or None
    tuning = _tuning_seeds(args.tuning_seeds)
    data = plan_data(
        rows,
        problems=_plan_filter(split_list(args.problems)),
        planners=planners,
        tuning_seeds=tuning,
    )
    if not data:
        if tuning is not None:
            raise CLIError(
                "no evaluation runs (seeds other than --tuning-seeds) of a setting selected"
                " on the tuning seeds match --problems/--planners"
            )
        raise CLIError("no finished plan runs match --problems/--planners")
    at = parse_int_list(args.at, "--at") or None
    if at is not None and min(at) < 1:
        raise CLIError("--at: simulation counts must be >= 1")
    longest = max(d.simulations for d in data)
    if at is not None and max(at) > longest:
        beyond = sorted(k for k in at if k > longest)
        raise CLIError(
            f"--at {' '.join(map(str, beyond))}: beyond the runs' budget (the longest has"
            f" {longest} simulations)"
        )
    report = plan_report(data, at)
    if args.axes_dir:
        from voot.bench.axes import AXES
        from voot.bench.plan_plot import figure_caption

        lines = ["### Figures", ""]
        for name, axis in AXES.items():
            path = plot_plan_figure(
                data, Path(args.axes_dir) / axis.png, x=name, note=_tuning_title(tuning)
            )
            print(f"figure: {path}", file=sys.stderr)
            lines.append(f"`{axis.png}`: {figure_caption(data, name)}")
            lines.append("")
        report = report + "\n" + "\n".join(lines)
    print(report)
    if args.png:
        path = plot_plan_figure(data, args.png, x="simulations")
        print(f"figure: {path}", file=sys.stderr)
    if args.png_seconds:
        path = plot_plan_figure(data, args.png_seconds, x="seconds")
        print(f"figure: {path}", file=sys.stderr)
    if args.markdown:
        md = Path(args.markdown)
        md.parent.mkdir(parents=True, exist_ok=True)
        md.write_text(report)
        print(f"markdown: {md}", file=sys.stderr)
    return 0


def _tuning_seeds(text: str | None) -> list[int] | None:
    """``--tuning-seeds`` as a list (None without the option)."""
    return None if text is None else parse_range(text, "--tuning-seeds")


def _tuning_title(tuning: Sequence[int] | None) -> str | None:
    from voot.bench.tuning import tuning_note

    return None if tuning is None else tuning_note(tuning)


def cmd_plot(args: argparse.Namespace) -> int:
    from voot.bench.plot import figure_data, final_table, plot_figure3, settings_table
    from voot.optim.registry import normalize_method

    if args.log and not args.regret:
        raise CLIError("--log needs --regret (best values can be negative)")
    kind, rows = _load_rows(args.results, args.kind)
    rows = _one_instance(rows, kind, args.instance)
    if kind == "plan":
        return cmd_plot_plan(args, rows)
    if (
        args.png_seconds
        or args.problems
        or args.planners
        or args.at
        or args.axes_dir
        or args.tuning_seeds
    ):
        raise CLIError(
            "--png-seconds, --axes-dir, --tuning-seeds, --problems, --planners and --at"
            " apply to plan runs;"
            " for bbfo runs filter with --functions, --dims and --methods"
        )
    functions = [f.lower() for f in split_list(args.functions)] or None
    dims = parse_int_list(args.dims, "--dims") or None
    methods = [normalize_method(m) for m in split_list(args.methods)] or None
    data = figure_data(
        rows,
        regret=args.regret,
        functions=functions,
        dims=dims,
        methods=methods,
        instance=args.instance,
    )
    if not data:
        raise CLIError("no finished runs match --functions/--dims/--methods")
    table = final_table(data, regret=args.regret)
    settings = settings_table(data)
    print(table)
    print()
    print(settings)
    if args.png:
        path = plot_figure3(data, args.png, regret=args.regret, log=args.log)
        print(f"figure: {path}", file=sys.stderr)
    if args.markdown:
        md = Path(args.markdown)
        md.parent.mkdir(parents=True, exist_ok=True)
        md.write_text(f"{table}\n\nSelected hyperparameters:\n\n{settings}\n")
        print(f"markdown: {md}", file=sys.stderr)
    return 0


# ----- claims --------------------------------------------------------------------------
def cmd_claims(args: argparse.Namespace) -> int:
    """The paper's claims against the store (:mod:`voot.bench.claims`)."""
    from voot.bench.claims import claims_table, evaluate
    from voot.bench.plan_plot import plan_data
    from voot.bench.tuning import tuning_sentence

    _, rows = _load_rows(args.results, "plan")
    tuning = _tuning_seeds(args.tuning_seeds)
    data = plan_data(rows, tuning_seeds=tuning)
    note = (
        "Settings selected on the same seeds (the paper's rule)."
        if tuning is None
        else tuning_sentence(tuning) + " The claims are judged on the evaluation seeds."
    )
    text = claims_table(evaluate(data), note)
    print(text)
    if args.markdown:
        md = Path(args.markdown)
        md.parent.mkdir(parents=True, exist_ok=True)
        md.write_text(text + "\n")
        print(f"markdown: {md}", file=sys.stderr)
    return 0


# ----- speed ---------------------------------------------------------------------------
def parse_cases(values: Sequence[str] | None) -> list[tuple[str, int]]:
    """``["voo:1000", "cmaes:5000"]`` -> ``[("voo", 1000), ("cmaes", 5000)]``."""
    from voot.optim.registry import normalize_method

    if not values:
        return list(SPEED_CASES)
    out = []
    for item in split_list(values):
        method, _, n = item.partition(":")
        try:
            count = int(n)
        except ValueError:
            raise CLIError(f"--cases: {item!r} is not METHOD:N (e.g. voo:1000)") from None
        if count < 1:
            raise CLIError(f"--cases: N must be >= 1 in {item!r}")
        out.append((normalize_method(method), count))
    return out


def cmd_speed(args: argparse.Namespace) -> int:
    cases = parse_cases(args.cases)
    try:
        from voot.bench.speed import measure_ask_cost
    except ImportError as exc:
        raise CLIError(f"voot.bench.speed is not available ({exc})") from None
    if args.dim < 1 or args.repeats < 1:
        raise CLIError("--dim and --repeats must be >= 1")
    print(
        f"cost after n evaluations, d = {args.dim}, mean of {args.repeats} repeats"
        " (per ask; per ask + tell for methods that work on tell, e.g. cmaes, gp_ucb)"
    )
    print("| method | n | ms |")
    print("| --- | ---: | ---: |")
    failed = 0
    for method, n in cases:
        try:
            seconds = measure_ask_cost(method, n, args.dim, args.repeats, args.seed)
            cell = f"{1000.0 * seconds:.3f}"
        except Exception as exc:  # report and go on with the other cases
            failed += 1
            cell = f"error: {type(exc).__name__}: {exc}"
        print(f"| {method} | {n} | {cell} |", flush=True)
    return 1 if failed else 0


def cmd_speedup(args: argparse.Namespace) -> int:
    """The baseline commit's code and the current code on the same workloads (see speedup)."""
    from voot.bench import speedup

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


# ----- demo ----------------------------------------------------------------------------
def cmd_demo(args: argparse.Namespace) -> int:
    """VOOT on the kitchen: prints obstacles cleared, writes ``.rrd``, ``.gif``, ``.json``."""
    from voot.bench import kitchen_demo
    from voot.bench.problems import normalize_problem

    sims = kitchen_demo.DEFAULT_SIMULATIONS if args.simulations is None else args.simulations
    seed = kitchen_demo.DEFAULT_SEED if args.seed is None else args.seed
    try:
        env_id = normalize_problem(args.env)
        kitchen_demo.run(args.out, sims, seed, args.planner, video=not args.no_video, env_id=env_id)
    except ValueError as exc:
        raise CLIError(str(exc)) from exc
    return 0


def cmd_figure5(args: argparse.Namespace) -> int:
    """Record the paper's Figure 5 on the kitchen and draw it (:mod:`voot.bench.kitchen_figure5`)."""
    from voot.bench.kitchen_figure5 import figure5
    from voot.bench.problems import normalize_problem

    if args.seed < 0:
        raise CLIError(f"--seed must be >= 0, got {args.seed}")
    figure5(
        args.out,
        args.seed,
        planners=args.planners,
        visits=args.visits,
        max_simulations=args.max_simulations,
        env_id=normalize_problem(args.env),
        image=args.image,
    )
    return 0


def cmd_demo_voo(args: argparse.Namespace) -> int:
    from voot.bench.sweep import RunSpec, check_functions, paper_budget, run_spec
    from voot.functions import get_function
    from voot.optim.registry import normalize_method

    function = check_functions([args.function])[0]
    method = normalize_method(args.method)
    if args.dim < 1:
        raise CLIError(f"--dim must be >= 1, got {args.dim}")
    budget = args.budget if args.budget is not None else paper_budget(function, args.dim)
    if budget < 1:
        raise CLIError(f"--budget must be >= 1, got {budget}")
    spec = RunSpec(function, args.dim, method, (), budget, args.seed)
    print(
        f"{method} on {function}-{args.dim}D, {budget} evaluations, seed {args.seed} ...",
        file=sys.stderr,
    )
    start = time.perf_counter()
    row = run_spec(spec)
    elapsed = time.perf_counter() - start
    if row["status"] != "ok":
        print(f"voot-bench: run failed: {row['error']}", file=sys.stderr)
        return 1
    best = float(row["best_so_far"][-1])
    optimum = get_function(function, args.dim).optimum_value
    print(
        f"{method} on {function}-{args.dim}D: {budget} evaluations in {elapsed:.1f} s (seed {args.seed})"
    )
    print(f"  best value found  {best:.6g}")
    if optimum is not None:
        print(f"  known optimum     {float(optimum):.6g}")
        print(f"  regret            {float(optimum) - best:.6g}")
    for k in (10, 100, 1000):
        if k < budget:
            print(f"  best after {k:>5}  {float(row['best_so_far'][k - 1]):.6g}")
    return 0


def _stored_note(path: str, specs: Sequence[Spec]) -> str:
    """``"; N already in the store"`` if the store at ``path`` exists and holds some."""
    from voot.bench.sweep import pending_specs

    store = _existing_store(path)
    if store is None:
        return ""
    unique = {s.run_id for s in specs}
    done = len(unique) - len({s.run_id for s in pending_specs(specs, store)})
    return f"; {done} already in the store" if done else ""


def _compact_config(args: argparse.Namespace) -> Any:
    """The :class:`~voot.bench.compact.CompactConfig` of ``--compact-points/--compact-spacing``."""
    from voot.bench.compact import CompactConfig

    return CompactConfig(points=args.compact_points, spacing=args.compact_spacing)


def _add_compact_options(p: argparse.ArgumentParser, prefix: str) -> None:
    from voot.bench.compact import DEFAULT_POINTS, SPACINGS

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


def cmd_compact(args: argparse.Namespace) -> int:
    """Convert a result store into a compact one (:func:`voot.bench.store.compact_store`)."""
    from voot.bench.store import compact_store

    out = compact_store(args.src, args.dst, _compact_config(args))
    mb_src, mb_dst = out["src_bytes"] / 1e6, out["dst_bytes"] / 1e6
    ratio = f", {out['src_bytes'] / out['dst_bytes']:.1f}x smaller" if out["dst_bytes"] else ""
    print(
        f"{out['rows']} rows in {args.src} ({mb_src:.2f} MB of rows); {out['copied']} copied"
        f" now, {out['rows'] - out['copied']} already there; {args.dst}: {mb_dst:.2f} MB of"
        f" rows{ratio}"
    )
    return 0


def cmd_shipped(args: argparse.Namespace) -> int:
    """Check the committed stores against their manifest and redraw their figures
    (:mod:`voot.bench.shipped`); with ``--write``, rewrite the manifest."""
    from voot.bench import shipped

    root = Path(args.root)
    if not root.is_dir():
        raise CLIError(f"{root}: no such folder (the committed stores are in docs/data)")
    if args.write:
        path = shipped.write_manifest(root)
        for name, entry in shipped.read_manifest(root).items():
            print(f"{name}: {entry['rows']} rows, sha256 {entry['sha256'][:12]}...")
        print(f"manifest: {path}", file=sys.stderr)
        return 0
    out = Path(args.out) if args.out else None
    for path in shipped.store_dirs(root):
        got = shipped.check_store(root, path.name)
        line = f"{path.name}: {got['rows']} rows, checksums and manifest ok"
        if out is not None:
            files = shipped.redraw(path, out / path.name)
            line += f"; redrawn: {', '.join(f.name for f in files)}"
        print(line, flush=True)
    return 0


def cmd_store_speed(args: argparse.Namespace) -> int:
    """Print the size and load time of synthetic plan-row stores, full and compact."""
    from voot.bench.store import time_load

    if args.rows < 1 or args.length < 1:
        raise CLIError("--rows and --length must be >= 1")
    print(f"{args.rows} plan-like rows of {args.length} simulations (five curves each)")
    print(
        "| store | MB of rows | KB per row | write s | first load s | load s (lists)"
        " | load s (arrays) | verify s |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, config in (("full", None), ("compact", _compact_config(args))):
        t = time_load(args.rows, args.length, args.repeats, plan=True, compact=config)
        print(
            f"| {name} | {t['mb']:.2f} | {1000 * t['mb'] / args.rows:.1f} | {t['write']:.2f}"
            f" | {t['cold']:.3f} | {t['warm']:.3f} | {t['warm_arrays']:.3f} | {t['verify']:.3f} |",
            flush=True,
        )
    return 0


def _open_store(path: str, compact: Any = None) -> ResultStore:
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


# ----- difficulty ----------------------------------------------------------------------
def cmd_difficulty(args: argparse.Namespace) -> int:
    """Print (and optionally write) the difficulty tables of :mod:`voot.bench.difficulty`."""
    from voot.bench import difficulty
    from voot.bench.problems import normalize_problem

    if args.seed < 0:
        raise CLIError(f"--seed must be >= 0, got {args.seed}")
    envs = (
        difficulty.DEFAULT_ENVS if args.envs is None else [normalize_problem(e) for e in args.envs]
    )
    text = difficulty.report(envs, args.samples, args.rollouts, args.seed)
    print(text)
    if args.markdown:
        Path(args.markdown).write_text(text + "\n")
    return 0


# ----- measurement commands with their own options -------------------------------------
#: ``voot-bench NAME ARGS...`` -> ``module:function(ARGS)``: commands whose options their
#: module parses (``voot-bench NAME --help`` lists them).
PASSTHROUGH: dict[str, tuple[str, str]] = {
    "overhead": ("voot.bench.overhead:tree_main", "the planner's own overhead per node visit"),
    "record-overhead": ("voot.bench.overhead:record_main", "the cost of recording a search"),
    "record-demo": (
        "voot.bench.record_demo:main",
        "recordings, Figure-5 panels and a GIF on the tiny pick-and-place demo",
    ),
    "env-speed": ("voot.bench.env_speed:main", "step costs and sparsity of the robot domains"),
    "voo-speed": ("voot.bench.speed:voo_main", "VOO's cost per ask + tell on several objectives"),
    "env-figures": ("voot.bench.env_figures:main", "render the environment figures of the docs"),
    "root-parallel": (
        "voot.bench.root_parallel_bench:main",
        "root-parallel search: speed-up and quality against one tree",
    ),
}


def cmd_passthrough(args: argparse.Namespace) -> int:
    """Run a :data:`PASSTHROUGH` command with the rest of the command line."""
    import importlib

    module, function = PASSTHROUGH[args.command][0].split(":")
    status = getattr(importlib.import_module(module), function)(list(args.rest))
    return int(status or 0)


# ----- parser --------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    from voot.bench.sweep import BACKENDS, GRIDS

    parser = argparse.ArgumentParser(
        prog="voot-bench",
        description="Benchmarks of voot: VOO and baselines (paper Figure 3), VOOT and its"
        " baselines (paper Figure 4).",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser(
        "demo",
        help="the README's main job: VOOT clearing the kitchen, with a rerun recording and a GIF",
    )
    p.add_argument("--out", default="kitchen_demo", help="output folder (default: kitchen_demo)")
    p.add_argument("--simulations", type=int, default=None, help="default: 1000")
    p.add_argument(
        "--seed", type=seed_argument, default=None, help="default: the documented demo seed"
    )
    p.add_argument("--planner", default="voot")
    p.add_argument("--no-video", action="store_true", help="skip the GIF")
    p.add_argument(
        "--env",
        default="kitchen_v1",
        help="kitchen_v1 (voot/KitchenClearing-v1, the authors' protocol; default) or kitchen"
        " (voot/KitchenClearing-v0)",
    )
    p.set_defaults(func=cmd_demo)

    p = sub.add_parser(
        "figure5",
        help="the paper's Figure 5 on the kitchen: placements sampled at the first place node",
    )
    p.add_argument("--out", default="kitchen_demo", help="output folder (default: kitchen_demo)")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--planners", nargs="+", default=["voot", "pw_uct"], metavar="NAME")
    p.add_argument("--visits", type=int, default=50, help="visits of the node (the paper's 50)")
    p.add_argument("--max-simulations", type=int, default=2000)
    p.add_argument("--env", default="kitchen", help="kitchen (v0, default) or kitchen_v1")
    p.add_argument(
        "--image",
        default="kitchen_figure5.png",
        help="image file name in --out (default: %(default)s); its counts go beside it as .json",
    )
    p.set_defaults(func=cmd_figure5)

    p = sub.add_parser("demo-voo", help="VOO on Shekel-20D with the paper's budget")
    p.add_argument("--function", default="shekel")
    p.add_argument("--dim", type=int, default=20)
    p.add_argument("--method", default="voo")
    p.add_argument("--budget", type=int, default=None, help="evaluations (default: the paper's)")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.set_defaults(func=cmd_demo_voo)

    p = sub.add_parser("bbfo", help="run the black-box sweep of Figure 3 (resumable)")
    p.add_argument(
        "--out", default="results/bbfo", help="result store directory (default: %(default)s)"
    )
    _add_filters(p, defaults=True)
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

    p = sub.add_parser(
        "plan",
        help="run planners x problems x seeds (paper Figure 4; resumable, local or Ray)",
        description="Tree-search sweep: every planner (with its hyperparameter grid) on every"
        " problem and seed, one row per run with the best return after every simulation."
        " Defaults are the paper's per problem: the Shekel chain in 10-D and 20-D (10,000"
        " simulations, 20 seeds, six planners); kitchen 2,000 simulations and 20 seeds;"
        " conveyor 3,000 simulations and 50 seeds (five planners).",
    )
    p.add_argument(
        "--out", default="results/plan", help="result store directory (default: %(default)s)"
    )
    p.add_argument(
        "--problems",
        nargs="+",
        metavar="NAME",
        help="shekel_chain griewank_chain rastrigin_chain, kitchen conveyor, or any"
        " gymnasium id with get_state/set_state (default: shekel_chain)",
    )
    p.add_argument("--dims", nargs="+", metavar="D", help="chain dimensions (default: 10 20)")
    p.add_argument(
        "--planners",
        nargs="+",
        metavar="NAME",
        help="voot doot rand_doot pw_uct voronoi_pw hoot uniform_t, or the sampling-based"
        " cem mppi predictive_sampling random_shooting, or the RL baselines ppo ddpg"
        " (budget matched to a voot search, docs/rl.md) (default: the paper's)",
    )
    p.add_argument(
        "--seeds", default=None, help="N (seeds 0..N-1) or START:STOP (default: the paper's)"
    )
    p.add_argument(
        "--simulations", type=int, default=None, help="simulations per run (default: the paper's)"
    )
    p.add_argument(
        "--grid", choices=GRIDS, default="paper", help="hyperparameter grid (default: %(default)s)"
    )
    p.add_argument(
        "--set",
        nargs="+",
        metavar="NAME=VALUE",
        help="a planner parameter for every run (e.g. depth_limit=5 omega=0.3; VOO's best-cell"
        " sampler: sampler=gaussian, or sampler.sampler=uniform to name it explicitly)",
    )
    p.add_argument(
        "--horizon",
        type=int,
        default=None,
        help="one planning horizon H from the root for every planner: a tree's depth_limit"
        " (no root commitment), a sampling-based planner's horizon (for control tasks that do"
        " not end by themselves)",
    )
    p.add_argument(
        "--env-kwargs",
        nargs="+",
        metavar="NAME=VALUE",
        help="keywords of gymnasium.make for the environments (e.g. dim=3)",
    )
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
    p.add_argument("--record", metavar="RUN.rrd", help="record each run's search with rerun")
    p.add_argument(
        "--skip-failed", action="store_true", help="do not retry runs that failed before"
    )
    p.add_argument(
        "--tuning-seeds",
        metavar="START:STOP",
        help="tune first: run every setting of the grid on these seeds, select per problem"
        " and planner the best mean final return, then run only that setting on --seeds"
        " (which must be disjoint); resumable at any point",
    )
    p.add_argument(
        "--estimate",
        action="store_true",
        help="print the estimated CPU-hours of the runs not yet in --out (cost per"
        " simulation from the store's rows, else a short probe run) and exit",
    )
    p.add_argument(
        "--probe-simulations",
        type=int,
        default=20,
        help="--estimate: simulations of a probe run (default: %(default)s)",
    )
    p.add_argument("--dry-run", action="store_true", help="list the runs per problem and exit")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument(
        "--compact",
        action="store_true",
        help="create --out as a compact store (step curves exact, cost curves at reduced"
        " resolution; kept in its header, so later runs into it are compact too)",
    )
    _add_compact_options(p, "compact-")
    p.set_defaults(func=cmd_plan)

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
    _add_compact_options(p, "")
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
    p.set_defaults(func=cmd_shipped)

    p = sub.add_parser(
        "store-speed",
        help="size and load time of a store of synthetic plan rows, full vs compact",
    )
    p.add_argument("--rows", type=int, default=1000, help="rows (default: %(default)s)")
    p.add_argument(
        "--length", type=int, default=3000, help="simulations per row (default: %(default)s)"
    )
    p.add_argument(
        "--repeats", type=int, default=3, help="loads timed, best kept (default: %(default)s)"
    )
    _add_compact_options(p, "")
    p.set_defaults(func=cmd_store_speed)

    p = sub.add_parser("select", help="selected hyperparameters per method (best mean final value)")
    p.add_argument("results", help="result store directory")
    p.add_argument("--all", action="store_true", help="list every setting tried")
    p.add_argument("--kind", choices=KINDS, help="bbfo or plan runs (default: what the store has)")
    p.add_argument("--instance", type=int, metavar="K", help=INSTANCE_FILTER_HELP)
    p.set_defaults(func=cmd_select)

    p = sub.add_parser("plot", help="Figure 3 (bbfo runs) or Figure 4 (plan runs), and tables")
    p.add_argument("results", help="result store directory")
    p.add_argument("--kind", choices=KINDS, help="bbfo or plan runs (default: what the store has)")
    p.add_argument("--png", help="write the figure here")
    p.add_argument("--png-seconds", help="plan runs: the figure against wall-clock seconds")
    p.add_argument(
        "--axes-dir",
        metavar="DIR",
        help="plan runs: one figure per x axis in DIR: plan-simulations.png (simulations, the"
        " paper's), plan-calls.png (simulator calls: executed steps + pre-checks) and"
        " plan-cpu-seconds.png (CPU seconds); their captions go into the tables' markdown",
    )
    p.add_argument(
        "--tuning-seeds",
        metavar="START:STOP",
        help="plan runs: select each planner's setting on these seeds (best mean final"
        " return) and draw every other seed (the evaluation seeds) with it (default: select"
        " on the drawn seeds, the paper's rule)",
    )
    p.add_argument("--markdown", help="write the tables here as markdown")
    p.add_argument("--regret", action="store_true", help="plot f* - best instead of best value")
    p.add_argument("--log", action="store_true", help="log y axis (with --regret)")
    _add_filters(p, defaults=False)
    p.add_argument("--instance", type=int, metavar="K", help=INSTANCE_FILTER_HELP)
    p.add_argument(
        "--problems", nargs="+", metavar="NAME", help="plan runs: problems (default: all)"
    )
    p.add_argument(
        "--planners", nargs="+", metavar="NAME", help="plan runs: planners (default: all)"
    )
    p.add_argument(
        "--at",
        nargs="+",
        metavar="N",
        help="plan runs: simulation counts of the tables (default: 1000 3000 10000 and the budget)",
    )
    p.set_defaults(func=cmd_plot)

    p = sub.add_parser(
        "claims",
        help="the paper's claims about Figure 4 against a plan store: ours with a 95%% interval"
        " and a verdict (reproduced, not reproduced, reversed, no data)",
    )
    p.add_argument("results", help="result store directory (plan runs)")
    p.add_argument(
        "--tuning-seeds",
        metavar="START:STOP",
        help="select each planner's setting on these seeds and judge the claims on every"
        " other seed (as plot --tuning-seeds; default: the paper's same-seed selection)",
    )
    p.add_argument("--markdown", help="also write the table here")
    p.set_defaults(func=cmd_claims)

    p = sub.add_parser("speed", help="cost per ask of VOO, CMA-ES and GP-UCB")
    p.add_argument(
        "--cases",
        nargs="+",
        metavar="METHOD:N",
        help="default: " + " ".join(f"{m}:{n}" for m, n in SPEED_CASES),
    )
    p.add_argument("--dim", type=int, default=20)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--seed", type=seed_argument, default=0)
    p.set_defaults(func=cmd_speed)

    p = sub.add_parser(
        "difficulty",
        help="planner-agnostic difficulty of the robot domains (v0, v1): feasibility rates,"
        " random-rollout success, the scripted solution",
    )
    p.add_argument(
        "--envs", nargs="+", default=None, metavar="ID", help="default: v0 and v1 of both"
    )
    p.add_argument("--samples", type=int, default=2000, help="uniform actions per node type")
    p.add_argument("--rollouts", type=int, default=200, help="random rollouts per environment")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--markdown", default=None, help="also write the tables to this file")
    p.set_defaults(func=cmd_difficulty)

    for name, (_, text) in PASSTHROUGH.items():
        p = sub.add_parser(name, help=text, add_help=False)
        p.add_argument("rest", nargs=argparse.REMAINDER, help="the command's own options")
        p.set_defaults(func=cmd_passthrough)

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
