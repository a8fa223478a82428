"""The tables of the paper's Figure 4 (markdown) and the captions of its figures.

Tables (markdown): the best return at given simulation counts (default 1,000 / 3,000 /
10,000 and the budget); objects handled (objects at the start minus objects left) at
those counts; the simulations needed to handle every object (kitchen: clear the path),
median with a distribution-free 95% interval and the fraction of seeds that got there;
the cost of a simulation (milliseconds, simulator calls); and the executed steps against
the pre-checks per simulation (:func:`calls_table`).
:func:`plan_report` puts every table into one markdown document; :func:`figure_caption`
says what a figure of :mod:`voot.bench.report.plan_plot` shows. The data come from
:func:`voot.bench.report.plan_runs.plan_data`.

On a generated family (rows with layout seeds, :mod:`voot.bench.protocol.layouts`) a table's
problem is the family, its values the mean over the (layout, seed) runs, and its
intervals are over the per-layout means (medians: per-layout medians), the layout being
the unit; the notes under the tables say so.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from voot.bench.protocol.axes import has_axis_data
from voot.bench.protocol.select import method_order
from voot.bench.report.plan_runs import (
    PlannerRuns,
    first_reach,
    mean_ci,
    median_ci,
    ordered_cells,
    settled_reach,
    table_order,
)

#: Simulation counts of the tables, kept where below the budget (the budget is added).
CHECKPOINTS: tuple[int, ...] = (1_000, 3_000, 10_000)


def default_checkpoints(simulations: int) -> list[int]:
    """:data:`CHECKPOINTS` below the budget, then the budget."""
    return [c for c in CHECKPOINTS if c < simulations] + [int(simulations)]


def _fmt(x: float, digits: int = 4) -> str:
    return "nan" if not math.isfinite(x) else f"{x:.{digits}g}"


def _cell_text(mean: float, half: float, n: int) -> str:
    return f"{_fmt(mean)} ± {_fmt(half)} ({n})"


def _checkpoint_table(
    data: Sequence[PlannerRuns],
    at: Sequence[int] | None,
    what: str,
    values_of: object,
    note: str,
) -> str:
    planners = method_order(d.planner for d in data)
    lines = [
        f"| problem | simulations | {' | '.join(planners)} |",
        "| --- | ---: |" + " ---: |" * len(planners),
    ]
    for cell in ordered_cells(data):
        runs = {d.planner: d for d in data if d.cell == cell}
        title = next(iter(runs.values())).title
        budget = max(d.simulations for d in runs.values())
        for k in at if at is not None else default_checkpoints(budget):
            stats: dict[str, tuple[float, float, int]] = {}
            for p, d in runs.items():
                values = values_of(d)  # type: ignore[operator]
                if values is None or k > values.shape[1] or k < 1:
                    continue
                mean, half, n = mean_ci(d.units(values)[:, k - 1 : k])
                if n[0] > 0:
                    stats[p] = (float(mean[0]), float(half[0]), int(n[0]))
            if not stats:
                continue
            best = max(stats, key=lambda p: stats[p][0])
            cols = []
            for p in planners:
                if p not in stats:
                    cols.append("")
                    continue
                text = _cell_text(*stats[p])
                cols.append(f"**{text}**" if p == best else text)
            lines.append(f"| {title} | {k} | {' | '.join(cols)} |")
    if len(lines) == 2:
        return ""
    if any(d.has_layouts for d in data):
        note = _LAYOUT_CI_NOTE
    return "\n".join(lines) + f"\n\n{what}: {note}"


_CI_NOTE = (
    "mean ± half-width of the 95% t-interval over seeds (number of seeds), each planner"
    " with its selected hyperparameters; best mean in bold."
)
#: The note on a layout axis: the layout is the unit of the interval.
_LAYOUT_CI_NOTE = (
    "mean over the (layout, seed) runs ± half-width of the 95% t-interval over the"
    " per-layout means (number of layouts; a problem without layouts: over seeds), each"
    " planner with its selected hyperparameters; best mean in bold."
)


def returns_table(data: Sequence[PlannerRuns], at: Sequence[int] | None = None) -> str:
    """Best return (goal bonus excluded) at simulation counts ``at`` (default
    :func:`default_checkpoints` of each problem's budget), one row per problem and count."""
    return _checkpoint_table(
        data,
        at,
        "Best discounted return from the root (higher is better)",
        lambda d: d.returns,
        _CI_NOTE,
    )


def objects_table(data: Sequence[PlannerRuns], at: Sequence[int] | None = None) -> str:
    """Objects handled (at the start minus left at the best leaf) at ``at`` simulations,
    for the problems that report objects; empty if none does."""

    def handled(d: PlannerRuns) -> NDArray[np.float64] | None:
        if d.objects_left is None or d.objects_initial is None:
            return None
        return d.objects_initial[:, None] - d.objects_left

    return _checkpoint_table(
        data,
        at,
        "Objects handled (kitchen: obstacles cleared from the path; conveyor: boxes placed;"
        " higher is better)",
        handled,
        _CI_NOTE,
    )


def completion_table(data: Sequence[PlannerRuns]) -> str:
    """Simulations needed to handle every object (kitchen: clear the path), per problem
    and planner: median, distribution-free 95% interval, and seeds that got there."""
    lines = [
        "| problem | planner | seeds that got there | median simulations | 95% CI"
        " | seeds cleared at the end | median simulations, for good | 95% CI |",
        "| --- | --- | ---: | ---: | --- | ---: | ---: | --- |",
    ]
    for d in (d for d in table_order(data) if d.objects_left is not None):
        assert d.objects_left is not None
        first = first_reach(d.objects_left)
        med, lo, hi = median_ci(d.unit_medians(first))
        got = int(np.isfinite(first).sum())
        settled = settled_reach(d.objects_left)
        s_med, s_lo, s_hi = median_ci(d.unit_medians(settled))
        s_got = int(np.isfinite(settled).sum())

        def show(v: float, budget: int = d.simulations) -> str:
            if math.isnan(v):
                return "—"
            return f"> {budget}" if math.isinf(v) else f"{v:.0f}"

        def interval(lo: float, hi: float) -> str:
            return "—" if math.isnan(lo) else f"[{show(lo)}, {show(hi)}]"

        def share(k: int, n: int = d.n_seeds) -> str:
            return f"{k}/{n} ({100.0 * k / n:.0f}%)"

        lines.append(
            f"| {d.title} | {d.planner} | {share(got)} | {show(med)} | {interval(lo, hi)}"
            f" | {share(s_got)} | {show(s_med)} | {interval(s_lo, s_hi)} |"
        )
    if len(lines) == 2:
        return ""
    layouts = (
        " On layouts, the seeds are (layout, seed) runs and the median and its interval"
        " are over the per-layout medians."
        if any(d.has_layouts for d in data)
        else ""
    )
    return "\n".join(lines) + (
        "\n\nSimulations until the best plan (highest return) first handles every object, and"
        " from which it handles every object for the rest of the budget (the best plan can"
        " change to one that leaves an object); > budget: not within the budget, counted as"
        " never; interval: order statistics, distribution-free 95%." + layouts
    )


def cost_table(data: Sequence[PlannerRuns]) -> str:
    """Wall-clock milliseconds and simulator calls per simulation (mean over seeds)."""
    lines = [
        "| problem | planner | ms per simulation | simulator calls per simulation | search seconds |",
        "| --- | --- | ---: | ---: | ---: |",
    ]
    for d in table_order(data):
        total = np.array([np.nanmax(e) if np.any(~np.isnan(e)) else np.nan for e in d.elapsed])
        ms = (
            1000.0 * float(np.nanmean(total)) / d.simulations
            if np.any(~np.isnan(total))
            else math.nan
        )
        calls = (
            float(np.nanmean(d.simulator_calls)) / d.simulations
            if np.any(~np.isnan(d.simulator_calls))
            else math.nan
        )
        seconds = float(np.nanmean(total)) if np.any(~np.isnan(total)) else math.nan
        lines.append(
            f"| {d.title} | {d.planner} | {_fmt(ms, 3)} | {_fmt(calls, 3)} | {_fmt(seconds, 3)} |"
        )
    return "\n".join(lines)


def _sentence(text: str) -> str:
    return text[:1].upper() + text[1:] + "."


def calls_table(data: Sequence[PlannerRuns]) -> str:
    """Executed steps against kinematic pre-checks per simulation (mean over seeds), per
    problem and planner: how the simulator calls of the calls axis split."""
    lines = [
        "| problem | planner | executed steps per simulation | pre-checks per simulation"
        " | pre-checks per step | seeds with calls_curve |",
        "| --- | --- | ---: | ---: | ---: | ---: |",
    ]
    for d in table_order(data):
        if d.n_steps is None or d.n_feasibility_checks is None:
            continue
        steps = float(np.nanmean(d.n_steps)) if np.any(np.isfinite(d.n_steps)) else math.nan
        checks = d.n_feasibility_checks
        pre = float(np.nanmean(checks)) if np.any(np.isfinite(checks)) else math.nan
        with_curve = 0 if d.calls is None else int(has_axis_data(d.calls).sum())
        ratio = pre / steps if steps > 0 else math.nan
        lines.append(
            f"| {d.title} | {d.planner} | {_fmt(steps / d.simulations, 3)}"
            f" | {_fmt(pre / d.simulations, 3)} | {_fmt(ratio, 3)}"
            f" | {with_curve}/{d.n_seeds} |"
        )
    if len(lines) == 2:
        return ""
    return "\n".join(lines) + (
        "\n\nThe calls axis counts both as one simulator call each; a pre-check (IK,"
        " collisions, regions) costs less than an executed step. A sampling-based planner"
        " makes no pre-checks."
    )


def figure_caption(data: Sequence[PlannerRuns], x: str) -> str:
    """The caption of the figure on axis ``x`` (a name of :data:`voot.bench.protocol.axes.AXES`):
    what is drawn, the axis, and how the settings were selected."""
    from voot.bench.protocol.axes import MIN_SEED_SHARE, get_axis
    from voot.bench.protocol.tuning import tuning_note

    axis = get_axis(x)
    seeds = sorted({d.n_seeds for d in data})
    counts = "/".join(map(str, seeds))
    if any(d.has_layouts for d in data):
        n_lay = "/".join(map(str, sorted({d.n_layouts for d in data if d.has_layouts})))
        what = (
            f"mean over {counts} (layout, seed) runs on {n_lay} layouts with a 95% t-interval"
            " over the per-layout means (the layout is the unit)."
        )
    else:
        what = f"mean over {counts} seeds with a 95% t-interval."
    parts = [f"Best return (and objects left) against {axis.label}: {what}", axis.caption]
    if axis.key is not None:
        parts.append(
            "Each seed's best-so-far curve is a step function of its own cost, carried"
            " forward; a seed that has spent its whole budget keeps its final value to the"
            " axis's end (its search is over); no mean is drawn where fewer than"
            f" {MIN_SEED_SHARE:.0%} of the seeds have started."
        )
        total = sum(d.n_seeds for d in data)
        lacking = sum(
            d.n_seeds if (v := d.axis_values(axis.key)) is None else int((~has_axis_data(v)).sum())
            for d in data
        )
        if lacking:
            parts.append(
                f"{lacking} of {total} runs lack {axis.key} (written before it was recorded)"
                " and are left out of this figure."
            )
    tuned = {(d.tuning_seeds, d.tuning_layouts) for d in data}
    if tuned == {((), ())}:
        parts.append("Settings selected on the same seeds (the paper's rule).")
    else:
        notes = sorted(tuning_note(t, lay) for t, lay in tuned if t or lay)
        parts.append(_sentence("; ".join(notes)))
    return " ".join(parts)


def _tuning_notes(data: Sequence[PlannerRuns]) -> list[str]:
    """The distinct tuning notes of ``data`` (empty: selected on the reported seeds)."""
    from voot.bench.protocol.tuning import tuning_note

    tuned = sorted(
        {(d.tuning_seeds, d.tuning_layouts) for d in data if d.tuning_seeds or d.tuning_layouts}
    )
    return [tuning_note(t, lay) for t, lay in tuned]


def _runs_text(d: PlannerRuns) -> str:
    """The runs of ``d`` for the settings table: seeds, or layouts and runs."""
    return f"{d.n_layouts} layouts, {d.n_seeds} runs" if d.has_layouts else str(d.n_seeds)


def plan_settings_table(data: Sequence[PlannerRuns]) -> str:
    """The selected hyperparameters per problem and planner (and the seeds they were
    selected on when those were tuning seeds)."""
    lines = ["| problem | planner | selected setting | seeds |", "| --- | --- | --- | ---: |"]
    for d in table_order(data):
        lines.append(f"| {d.title} | {d.planner} | {d.label} | {_runs_text(d)} |")
    notes = _tuning_notes(data)
    if notes:
        lines.append("")
        lines.append(_sentence("; ".join(notes)))
    return "\n".join(lines)


def plan_report(data: Sequence[PlannerRuns], at: Sequence[int] | None = None) -> str:
    """Every table as one markdown document (sections without data are left out)."""
    parts = [("Best return", returns_table(data, at))]
    notes = _tuning_notes(data)
    if notes:
        held_out = any(d.tuning_layouts for d in data)
        reported = "the held-out layouts" if held_out else "the evaluation seeds"
        note = _sentence("; ".join(notes))
        parts.insert(0, ("Protocol", f"{note} The tables report {reported} only."))
    parts.append(("Objects handled", objects_table(data, at)))
    parts.append(("Simulations to handle every object", completion_table(data)))
    parts.append(("Cost of a simulation", cost_table(data)))
    parts.append(("Simulator calls: executed steps and pre-checks", calls_table(data)))
    parts.append(("Selected hyperparameters", plan_settings_table(data)))
    return "\n\n".join(f"### {title}\n\n{table}" for title, table in parts if table) + "\n"
