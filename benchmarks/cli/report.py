"""Subcommands that read a result store and report: ``select`` (the selected
hyperparameters), ``plot`` (Figure 3 of bbfo runs or Figure 4 of plan runs, and their
tables) and ``claims`` (the paper's claims against a plan store)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voot.bench.cli.common import (
    CLIError,
    add_filters,
    check_output,
    parse_int_list,
    parse_range,
    split_list,
    write_markdown,
)
from voot.bench.store.format import Row

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers
    from voot.bench.protocol.layouts import TuningLayoutsArg
    from voot.bench.report.plan_runs import PlannerRuns


KINDS = ("bbfo", "plan")
INSTANCE_FILTER_HELP = (
    "bbfo runs: the test-function instance to use (default: the only one in the store;"
    " 0 = the paper's functions)"
)


def load_rows(path: str, kind: str | None) -> tuple[str, list[Row]]:
    """Finished rows of ``kind`` (default: the one kind the store holds)."""
    from voot.bench.store.result_store import ResultStore

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


def _one_instance(rows: list[Row], kind: str, instance: int | None) -> list[Row]:
    """The bbfo rows of one test-function instance (``--instance``, or the only one)."""
    from voot.bench.protocol.select import one_instance

    if kind != "bbfo":
        if instance is not None:
            raise CLIError("--instance applies to bbfo runs (test functions), not plan runs")
        return rows
    chosen, rows = one_instance(rows, instance)
    if chosen:
        print(f"test-function instance {chosen} (optima shifted)", file=sys.stderr)
    return rows


def cmd_select(args: argparse.Namespace) -> int:
    from voot.bench.protocol.select import largest_budget, select_hyperparameters, selection_table

    kind, rows = load_rows(args.results, args.kind)
    rows = _one_instance(rows, kind, args.instance)
    selections = select_hyperparameters(largest_budget(rows))
    print(selection_table(selections, all_candidates=args.all, kind=kind))
    return 0


def _plan_filter(names: Sequence[str] | None) -> list[str] | None:
    from voot.bench.protocol.problems import normalize_problem, problem_label

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
    from voot.bench.report.plan_plot import plot_plan_figure
    from voot.bench.report.plan_runs import plan_data
    from voot.bench.report.plan_tables import plan_report
    from voot.bench.sweep.planners import normalize_plan_planner as normalize_planner

    if args.regret or args.log or args.functions or args.dims or args.methods:
        raise CLIError(
            "--regret, --log, --functions, --dims and --methods apply to bbfo runs;"
            " for plan runs filter with --problems and --planners"
        )
    # a planner name, or an ablation variant's label (``voot[kappa_off]``); a name the
    # store holds is taken as it is (an outside planner need not be installed to be drawn)
    stored = {str(r.get("config", {}).get("planner")) for r in rows}
    planners = [
        (base if base in stored else normalize_planner(base)) + sep + rest
        for base, sep, rest in (p.partition("[") for p in split_list(args.planners))
    ] or None
    layouts = tuning_layouts_of(args, rows)
    tuning = _tuning_seeds(args.tuning_seeds, rows, split=layouts is None)
    data = plan_data(
        rows,
        problems=_plan_filter(split_list(args.problems)),
        planners=planners,
        tuning_seeds=tuning,
        tuning_layouts=layouts,
    )
    if not data:
        if layouts is not None:
            raise CLIError(
                "no runs on held-out layouts (layouts other than the tuning layouts) of a"
                " setting selected on the tuning layouts match --problems/--planners"
            )
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
        from voot.bench.protocol.axes import AXES
        from voot.bench.report.plan_tables import figure_caption

        lines = ["### Figures", ""]
        for name, axis in AXES.items():
            path = plot_plan_figure(
                data, Path(args.axes_dir) / axis.png, x=name, note=_tuning_title(tuning, data)
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
        write_markdown(args.markdown, report)
    return 0


def _tuning_seeds(text: str | None, rows: Sequence[Row], split: bool = True) -> list[int] | None:
    """``--tuning-seeds`` as a list (None without the option), checked against the
    store's ``rows`` when ``split``: some runs of a tuning seed and some of another seed
    (:func:`voot.bench.protocol.tuning.check_tuning_split`), else a CLIError. With tuning layouts
    (``split=False``) the layouts split the store, and the same seeds serve both sides."""
    if text is None:
        return None
    from voot.bench.protocol.tuning import check_tuning_split

    seeds = parse_range(text, "--tuning-seeds")
    if not split:
        return seeds
    try:
        check_tuning_split(rows, seeds)
    except ValueError as exc:
        raise CLIError(f"--tuning-seeds: {exc}") from None
    return seeds


def _tuning_title(tuning: Sequence[int] | None, data: Sequence[PlannerRuns]) -> str | None:
    """The figure's note: how the settings were selected (None: the paper's rule)."""
    from voot.bench.protocol.tuning import tuning_note

    layouts = sorted({v for d in data for v in d.tuning_layouts})
    if tuning is None and not layouts:
        return None
    return tuning_note(tuning or (), layouts)


def tuning_layouts_of(args: argparse.Namespace, rows: Sequence[Row]) -> TuningLayoutsArg | None:
    """The tuning layouts of ``--tuning-layouts`` or ``--heldout`` (None: neither): with
    ``--heldout``, the training layouts of each family of the rows
    (:data:`voot.bench.protocol.layouts.LAYOUT_SETS`)."""
    from voot.bench.cli.plan import parse_layout_seeds
    from voot.bench.protocol.layouts import LAYOUT_SETS, layout_of

    if args.heldout and args.tuning_layouts is not None:
        raise CLIError("give --heldout or --tuning-layouts, not both")
    from voot.bench.protocol.tuning import check_layout_split

    if args.tuning_layouts is not None:
        layouts = parse_layout_seeds(args.tuning_layouts, "--tuning-layouts")
        try:
            check_layout_split(rows, layouts)
        except ValueError as exc:
            raise CLIError(f"--tuning-layouts: {exc}") from None
        return layouts
    if not args.heldout:
        return None
    families = {str(r["config"]["problem"]) for r in rows if layout_of(r["config"]) is not None}
    known = {p: LAYOUT_SETS[p].training for p in sorted(families) if p in LAYOUT_SETS}
    if not known:
        raise CLIError(
            "--heldout: no runs on the layouts of a family with a held-out set"
            f" ({', '.join(LAYOUT_SETS)}); for another env give --tuning-layouts"
        )
    try:
        check_layout_split(rows, known)
    except ValueError as exc:
        raise CLIError(f"--heldout: {exc}") from None
    return known


def cmd_plot(args: argparse.Namespace) -> int:
    from voot.bench.report.bbfo_plot import figure_data, final_table, plot_figure3, settings_table
    from voot.optim.registry import normalize_method

    if args.log and not args.regret:
        raise CLIError("--log needs --regret (best values can be negative)")
    for option, path in (("--png", args.png), ("--png-seconds", args.png_seconds)):
        check_output(path, option)
    check_output(args.markdown, "--markdown")
    check_output(args.axes_dir, "--axes-dir", folder=True)
    kind, rows = load_rows(args.results, args.kind)
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
        or args.tuning_layouts
        or args.heldout
    ):
        raise CLIError(
            "--png-seconds, --axes-dir, --tuning-seeds, --tuning-layouts, --heldout,"
            " --problems, --planners and --at apply to plan runs;"
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
        write_markdown(args.markdown, f"{table}\n\nSelected hyperparameters:\n\n{settings}\n")
    return 0


def print_ablation_table(
    path: str,
    tuning_seeds: str,
    markdown: str | None,
    problems: Sequence[str] | None = None,
    env_kwargs: Mapping[str, Any] | None = None,
) -> int:
    """Print (and write to ``markdown``) the ablation's table of the store at ``path``
    (:mod:`voot.bench.report.ablation_table`), settings selected on ``tuning_seeds``, of
    ``problems`` only if given, of the runs in the domain ``env_kwargs`` if given."""
    from voot.bench.protocol.problems import normalize_problem, problem_label
    from voot.bench.report.ablation_table import ablation_table

    _, rows = load_rows(path, "plan")
    labels = [problem_label(normalize_problem(p)) for p in problems] if problems else None
    seeds = _tuning_seeds(tuning_seeds, rows)
    assert seeds is not None
    text = ablation_table(rows, seeds, labels, env_kwargs)
    print(text)
    if markdown:
        write_markdown(markdown, text + "\n")
    return 0


def cmd_claims(args: argparse.Namespace) -> int:
    """The paper's claims against the store (:mod:`voot.bench.protocol.claims`); with ``--ablation``,
    the ablation's table (:func:`print_ablation_table`)."""
    from voot.bench.protocol.claims import claims_table, evaluate
    from voot.bench.protocol.tuning import tuning_sentence
    from voot.bench.report.plan_runs import plan_data

    check_output(args.markdown, "--markdown")
    if args.ablation:
        if args.tuning_seeds is None:
            raise CLIError(
                "--ablation: the ablation's settings are selected on tuning seeds; give"
                " --tuning-seeds (the documented run: 1000:1005)"
            )
        return print_ablation_table(args.results, args.tuning_seeds, args.markdown)
    _, rows = load_rows(args.results, "plan")
    layouts = tuning_layouts_of(args, rows)
    tuning = _tuning_seeds(args.tuning_seeds, rows, split=layouts is None)
    data = plan_data(rows, tuning_seeds=tuning, tuning_layouts=layouts)
    trained = sorted({v for d in data for v in d.tuning_layouts})
    if layouts is not None:
        note = (
            tuning_sentence(tuning or (), trained)
            + " The claims are judged on the held-out layouts, the layout being the unit of"
            " the intervals."
        )
    elif tuning is None:
        note = "Settings selected on the same seeds (the paper's rule)."
    else:
        note = tuning_sentence(tuning) + " The claims are judged on the evaluation seeds."
    text = claims_table(evaluate(data), note)
    print(text)
    if args.markdown:
        write_markdown(args.markdown, text + "\n")
    return 0


def register(sub: Subparsers) -> None:
    """Add ``select``, ``plot`` and ``claims``."""
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
    _add_layout_filters(p, "draw")
    p.add_argument("--markdown", help="write the tables here as markdown")
    p.add_argument("--regret", action="store_true", help="plot f* - best instead of best value")
    p.add_argument("--log", action="store_true", help="log y axis (with --regret)")
    add_filters(p, defaults=False)
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
    _add_layout_filters(p, "judge")
    p.add_argument(
        "--ablation",
        action="store_true",
        help="the ablation's table instead (a store of voot-bench ablation): per switch"
        " VOOT's and PW-UCT's claim metrics, verdicts and flips, and VOOT minus PW-UCT",
    )
    p.add_argument("--markdown", help="also write the table here")
    p.set_defaults(func=cmd_claims)


def _add_layout_filters(p: argparse.ArgumentParser, verb: str) -> None:
    """``--tuning-layouts`` and ``--heldout`` of ``plot`` and ``claims``."""
    p.add_argument(
        "--tuning-layouts",
        nargs="+",
        metavar="SEEDS",
        help=f"plan runs on layouts: select each planner's setting on the runs of these"
        f" layouts (of --tuning-seeds if given), pooled per family, and {verb} the runs of"
        " every other layout (the held-out layouts) with it",
    )
    p.add_argument(
        "--heldout",
        action="store_true",
        help="--tuning-layouts with each family's fixed training layouts (voot.bench.protocol.layouts)",
    )
