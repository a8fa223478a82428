"""The leaderboard's tables, figure and page, drawn from a store by one command
(``voot-bench leaderboard report STORE --page docs/leaderboard.md``).

From the scores of :mod:`voot.bench.leaderboard.scores` (fraction of objects handled, in
[0, 1]; best return per cell), on the **complete cells only**:

* per (family, level): each entry's interquartile mean with its stratified-bootstrap 95%
  interval (:func:`voot.bench.report.stats.aggregate_intervals`) at matched simulator
  calls, at matched CPU time and at the suite's budget, and the IQM of its best return;
  the runs of a cell are its held-out layouts x seeds (a layout is the random draw of a
  family, :mod:`voot.bench.protocol.layouts`), so the bootstrap resamples layouts;
* aggregated over the complete cells (the tasks of the stratified bootstrap: runs are
  resampled within each cell): IQM and its interval at matched calls and CPU time, and
  the probability of improvement of the leader over every other entry
  (:func:`voot.bench.report.stats.improvement_interval`);
* the run-score performance profiles at matched calls and CPU time, with pointwise
  bootstrap bands (:func:`voot.bench.report.stats.performance_profiles`), as a figure.

The fraction handled is bounded, so its percentile intervals stay in [0, 1] (as do
``P(X > Y)``'s). The page states the coverage (finished runs per cell and entry), the
measured CPU cost of the runs still to do, and the command that resumes the run; a
leader is named only on complete cells, as measured there.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from voot.bench.leaderboard.scores import Budget, Cell, Coverage, RunScore, score_matrix
from voot.bench.leaderboard.suite import Entry, Suite
from voot.bench.report import stats
from voot.bench.store.format import Row

#: Thresholds of the performance profiles (fraction of objects handled).
TAUS = np.linspace(0.0, 1.0, 21)
#: The budgets the aggregate reports, in order.
MATCHED: tuple[Budget, ...] = (Budget.CALLS, Budget.CPU)
#: Column titles of the budgets.
BUDGET_TITLES: Mapping[Budget, str] = {
    Budget.CALLS: "matched simulator calls",
    Budget.CPU: "matched CPU time",
    Budget.SIMULATIONS: "at the budget",
}


@dataclass(frozen=True)
class Report:
    """A leaderboard drawn from a store: the text (markdown) and what it rests on."""

    markdown: str
    coverage: Coverage
    complete: tuple[Cell, ...]
    leader: Mapping[Budget, str]


def _iv(i: stats.Interval, digits: int = 3) -> str:
    return f"{i.estimate:.{digits}f} [{i.low:.{digits}f}, {i.high:.{digits}f}]"


def _cell_name(cell: Cell) -> str:
    from voot.bench.leaderboard.plan import short_name

    return f"{short_name(cell[0])} {cell[1]}"


def cell_table(
    scores: Sequence[RunScore],
    entries: Sequence[str],
    cell: Cell,
    points: Mapping[Budget, float],
    bootstrap: stats.Bootstrap,
) -> str:
    """One cell's table: per entry the IQM [95% CI] of the fraction handled at matched
    calls, matched CPU time and the budget, and of the best return at the budget."""
    lines = [
        f"#### {_cell_name(cell)}",
        "",
        f"Matched at {points[Budget.CALLS]:.0f} simulator calls and"
        f" {points[Budget.CPU]:.3g} CPU seconds of search per run (the smallest median"
        " final count of an entry in the cell). IQM over held-out"
        " layouts [95% stratified-bootstrap interval].",
        "",
        "| entry | handled, matched calls | handled, matched CPU | handled, at budget"
        " | best return, at budget |",
        "| --- | --- | --- | --- | --- |",
    ]
    handled = {
        b: stats.aggregate_intervals(
            {e: score_matrix(scores, e, [cell], b) for e in entries}, ["iqm"], bootstrap
        )
        for b in (Budget.CALLS, Budget.CPU, Budget.SIMULATIONS)
    }
    ret = stats.aggregate_intervals(
        {e: score_matrix(scores, e, [cell], Budget.SIMULATIONS, "ret") for e in entries},
        ["iqm"],
        bootstrap,
    )
    for e in entries:
        lines.append(
            f"| {e} | "
            + " | ".join(_iv(handled[b][e][stats.Metric.IQM]) for b in handled)
            + f" | {_iv(ret[e][stats.Metric.IQM])} |"
        )
    top = max(ret[e][stats.Metric.IQM].estimate for e in entries)
    best = [e for e in entries if ret[e][stats.Metric.IQM].estimate == top]
    lines += ["", f"Highest IQM of the best return at the budget: {', '.join(best)}."]
    return "\n".join(lines)


def coverage_table(cov: Coverage) -> str:
    """Finished / listed evaluation runs per cell (columns) and entry (rows)."""
    head = "| entry | " + " | ".join(_cell_name(c) for c in cov.cells) + " |"
    lines = [head, "| --- |" + " ---: |" * len(cov.cells)]
    for e in cov.entries:
        cells = [f"{cov.done.get((c, e), 0)}/{cov.listed.get((c, e), 0)}" for c in cov.cells]
        lines.append(f"| {e} | " + " | ".join(cells) + " |")
    done = ", ".join(_cell_name(c) for c in cov.complete) or "none"
    lines += ["", f"Complete cells (every entry, every listed run): {done}."]
    return "\n".join(lines)


def aggregate(
    scores: Sequence[RunScore],
    entries: Sequence[str],
    cells: Sequence[Cell],
    bootstrap: stats.Bootstrap,
) -> tuple[str, dict[Budget, str], dict[Budget, dict[str, stats.Interval]]]:
    """The aggregated table (IQM and P(ref > entry) at matched calls and CPU time), the
    leaders per budget (every entry at the highest IQM, comma-separated: the reference
    ``ref`` of P is the first of them), and the IQM intervals."""
    iqm: dict[Budget, dict[str, stats.Interval]] = {}
    leader: dict[Budget, str] = {}
    improve: dict[Budget, dict[str, stats.Interval]] = {}
    for b in MATCHED:
        arrays = {e: score_matrix(scores, e, cells, b) for e in entries}
        got = stats.aggregate_intervals(arrays, ["iqm"], bootstrap)
        iqm[b] = {e: got[e][stats.Metric.IQM] for e in entries}
        top = max(iqm[b][e].estimate for e in entries)
        tied = [e for e in entries if iqm[b][e].estimate == top]
        best = tied[0]  # the reference of P(ref > entry): the first of the tied leaders
        leader[b] = ", ".join(tied)
        improve[b] = {
            e: stats.improvement_interval(arrays[best], arrays[e], bootstrap, names=(best, e))
            for e in entries
            if e != best
        }
    lines = [
        "| entry | IQM, matched calls | P(ref > entry), matched calls | IQM, matched CPU"
        " | P(ref > entry), matched CPU |",
        "| --- | --- | --- | --- | --- |",
    ]
    order = sorted(entries, key=lambda e: -iqm[Budget.CALLS][e].estimate)
    for e in order:
        cols = []
        for b in MATCHED:
            p = improve[b].get(e)
            cols += [_iv(iqm[b][e]), "ref" if p is None else _iv(p, 2)]
        lines.append(f"| {e} | " + " | ".join(cols) + " |")
    return "\n".join(lines), leader, iqm


def profiles_figure(
    scores: Sequence[RunScore],
    entries: Sequence[str],
    cells: Sequence[Cell],
    path: str | Path,
    bootstrap: stats.Bootstrap,
) -> Path:
    """The run-score performance profiles at matched calls and CPU time, with their
    pointwise 95% bands, as a PNG at ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    colors = plt.get_cmap("tab20")
    for ax, b in zip(axes, MATCHED, strict=True):
        prof = stats.performance_profiles(
            {e: score_matrix(scores, e, cells, b) for e in entries}, TAUS, "runs", bootstrap
        )
        for k, e in enumerate(entries):
            p = prof[e]
            ax.plot(p.taus, p.fraction, label=e, color=colors(k % 20), lw=1.6)
            ax.fill_between(p.taus, p.low, p.high, color=colors(k % 20), alpha=0.15, lw=0)
        ax.set_title(f"at {BUDGET_TITLES[b]}")
        ax.set_xlabel(r"fraction of objects handled $\tau$")
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1.02)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(r"fraction of runs with score $> \tau$")
    axes[1].legend(fontsize=7, loc="upper right", ncol=2)
    fig.suptitle(f"Performance profiles over {len(cells)} complete cell(s)", fontsize=10)
    fig.tight_layout()
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def remaining_cost(
    suite: Suite, entries: Sequence[Entry], rows: Sequence[Row]
) -> tuple[int, float, str]:
    """``(runs to do, CPU-hours, note)`` of the rest of the suite, from measured costs only
    (the store's rows, else the committed stores'; a pair measured nowhere is named)."""
    from voot.bench.leaderboard.plan import (
        all_specs,
        measured_cost,
        pair_key,
        reference_rows,
        short_name,
    )

    tuning, evaluation, _ = all_specs(suite, entries, rows)
    done = {r["run_id"] for r in rows if r.get("status") == "ok"}
    todo = [s for s in dict.fromkeys([*tuning, *evaluation]) if s.run_id not in done]
    by_pair: dict[tuple[str, str], list[Row]] = {}
    for r in [*rows, *reference_rows()]:
        if r.get("status") == "ok":
            by_pair.setdefault(pair_key(r), []).append(r)
    seconds = 0.0
    unmeasured: dict[str, int] = {}
    for s in todo:
        got = measured_cost(by_pair.get(pair_key(s), []), s.simulations)
        if got is None:
            name = f"{short_name(pair_key(s)[0])} {pair_key(s)[1]}"
            unmeasured[name] = unmeasured.get(name, 0) + 1
        else:
            seconds += got[0] * s.simulations
    note = ""
    if unmeasured:
        n = sum(unmeasured.values())
        note = (
            f", plus {n} runs of pairs with no finished run to measure yet (not counted:"
            f" {', '.join(sorted(unmeasured))}; the estimate made before the run is above)"
        )
    return len(todo), seconds / 3600.0, note


def build_report(
    store_path: str | Path,
    suite: Suite,
    entries: Sequence[Entry] | None = None,
    *,
    figure: str | Path | None = None,
    figure_link: str | None = None,
    bootstrap: stats.Bootstrap | None = None,
    store_label: str | None = None,
    suite_label: str | None = None,
) -> Report:
    """The leaderboard of the store at ``store_path`` (see the module), and its profiles
    figure at ``figure`` (linked on the page as ``figure_link``). ``store_label`` and
    ``suite_label`` are how the page names the store and the suite in its commands
    (default: the path given, and the suite's name or file)."""
    from voot.bench.leaderboard.card import entries_in
    from voot.bench.leaderboard.plan import RUN_COMMAND
    from voot.bench.leaderboard.scores import coverage, run_scores
    from voot.bench.store.result_store import ResultStore

    bs = bootstrap or stats.Bootstrap()
    store = ResultStore(store_path, create=False)
    rows = store.load(kind="plan", status="ok", arrays=True)
    if entries is not None:
        ents = list(entries)
    else:  # the suite's entries, then any other entry the store holds
        ents = [*suite.entries, *(e for e in entries_in(rows, suite) if e not in suite.entries)]
    names = [e.name for e in ents]
    cov = coverage(suite, ents, rows)
    complete = cov.complete
    label = store_label or str(store_path)
    suite_ref = suite_label or suite.ref
    runs_left, hours_left, unmeasured = remaining_cost(suite, ents, rows)
    resume = RUN_COMMAND.format(suite=suite_ref, out=label)
    families = ", ".join(f"{f.problem} ({f.simulations} simulations)" for f in suite.families)
    status = (
        "complete: every cell of the suite is finished"
        if len(complete) == len(cov.cells)
        else f"**partial**: {len(complete)} of {len(cov.cells)} cells complete"
    )
    parts = [
        f"<!-- drawn by: voot-bench leaderboard report {label} --suite {suite_ref}"
        " --page PAGE --figure FIGURE; do not edit by hand -->",
        "",
        f"Suite {suite.name} (`{Path(suite.source).name}`, sha256 `{suite.digest[:16]}…`):"
        f" {families}; levels {', '.join(suite.levels)}; held-out layouts"
        f" {_ranges(suite.heldout_layouts)} x seeds {_ranges(suite.seeds)}; settings selected"
        f" on training layouts {_ranges(suite.tuning_layouts)} (level {suite.tuning_level}).",
        "",
        f"Store `{label}`: {cov.finished_runs} evaluation runs finished; {status}.",
        "",
        "### Coverage",
        "",
        coverage_table(cov),
        "",
        f"Still to run: {runs_left} runs (tuning and evaluation), about {hours_left:.2f}"
        f" CPU-hours of search at the measured cost per simulation{unmeasured}. Resume with",
        "",
        "```bash",
        resume,
        "```",
        "",
    ]
    leader: dict[Budget, str] = {}
    if complete:
        scores, points = run_scores(suite, ents, rows, complete)
        table, leader, _ = aggregate(scores, names, complete, bs)
        where = ", ".join(_cell_name(c) for c in complete)
        parts += [
            "### Aggregated over the complete cells",
            "",
            f"Cells: {where}. Score: the fraction of objects handled by the best plan"
            " found (in [0, 1]). IQM over every run x cell, 95% stratified-bootstrap interval"
            f" (layouts resampled within each cell, {bs.reps} replicates); P(ref > entry):"
            " the probability that a run of the reference (the first entry at the highest"
            " IQM) handles more than a run of the entry on the same cell (ties count one"
            " half), with its interval.",
            "",
            table,
            "",
            "Highest IQM, as measured on these cells only: at matched simulator calls"
            f" **{leader[Budget.CALLS]}**; at matched CPU time **{leader[Budget.CPU]}**"
            " (several names: tied. Read the intervals and P(ref > entry) before calling"
            " anything a win: an interval of P that contains 0.5 is no evidence of a"
            " difference).",
            "",
        ]
        if figure is not None:
            fig_path = profiles_figure(scores, names, complete, figure, bs)
            parts += [
                f"![Performance profiles]({figure_link or fig_path.name})",
                "",
                "Run-score performance profiles: the fraction of runs (over the complete"
                " cells) handling more than a fraction tau of the objects, with pointwise 95%"
                " bootstrap bands.",
                "",
            ]
        parts += ["### Per family and level", ""]
        for cell in complete:
            parts += [cell_table(scores, names, cell, points[cell], bs), ""]
    else:
        parts += ["No cell is complete yet: no result is reported.", ""]
    return Report("\n".join(parts).rstrip() + "\n", cov, complete, leader)


def _ranges(values: Sequence[int]) -> str:
    from voot.bench.protocol.layouts import layouts_text

    return layouts_text(values)


def splice_page(page: str, body: str) -> str:
    """``page`` with the text between its leaderboard markers replaced by ``body``."""
    start, end = "<!-- leaderboard:start -->", "<!-- leaderboard:end -->"
    if start not in page or end not in page:
        raise ValueError(
            f"the page has no {start} ... {end} markers to draw the leaderboard between"
        )
    head, _, rest = page.partition(start)
    _, _, tail = rest.partition(end)
    return f"{head}{start}\n{body}{end}{tail}"
