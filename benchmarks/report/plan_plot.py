r"""The paper's Figure 4 from a result store (plan rows), against simulations, seconds or
a cost axis.

Figure: one row of panels per problem (chains per dimension), with the best discounted
return from the root (goal bonus excluded) in the left panel and, when the problem
reports it, the objects still to handle at the best leaf in the right panel; one line per
planner with its selected hyperparameters (:mod:`voot.bench.protocol.select`, best mean final
return), the mean over seeds and a shaded 95% t-interval
(:func:`~voot.bench.report.plan_runs.mean_ci`, seeds whose value is unknown at a point left out
there; the objects' band is clipped to the count's range, 0 to the objects at the start;
with fewer than :data:`~voot.bench.report.bbfo_plot.MIN_SEEDS_FOR_BAND` seeds the mean is dashed and
has no band). The x axis is the number of simulations (:func:`plot_plan_figure`), the
wall-clock seconds since the search started (``x="seconds"``: each run's curve is read
as a step function of its own clock (``elapsed``), on a grid up to the time by which
every seed of the planner had finished), or a cost axis of :mod:`voot.bench.protocol.axes`
(``x="calls"``: steps + pre-checks; ``x="cpu"``: CPU seconds), one figure each,
captioned by :func:`~voot.bench.report.plan_tables.figure_caption`. With tuning seeds
(:func:`~voot.bench.report.plan_runs.plan_data`'s ``tuning_seeds``) the settings are selected
on those seeds and the other seeds are drawn (:mod:`voot.bench.protocol.tuning`).

On a generated family (rows with layout seeds, :mod:`voot.bench.protocol.layouts`) a panel is
the family: each planner's line is the mean over its (layout, seed) runs and the band
is the t-interval over the per-layout means (the layout is the unit; with fewer than
:data:`~voot.bench.report.bbfo_plot.MIN_SEEDS_FOR_BAND` layouts the line is dashed, without a band).

The data come from :func:`voot.bench.report.plan_runs.plan_data`, the tables and the figures'
captions from :mod:`voot.bench.report.plan_tables`.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from voot.bench.protocol.select import method_order
from voot.bench.report.bbfo_plot import curve_style
from voot.bench.report.plan_runs import PlannerRuns, mean_ci, ordered_cells, table_order
from voot.bench.sweep.planners import PLAN_PLANNERS

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.lines import Line2D

    from voot.bench.protocol.axes import Axis

#: Points of the wall-clock grid.
TIME_POINTS = 256


def _objects_top(d: PlannerRuns) -> float:
    """The most objects a run of ``d`` had at the start (inf if unknown): the band's top."""
    initial = d.objects_initial
    if initial is None or not np.any(np.isfinite(initial)):
        return float("inf")
    return float(np.nanmax(initial))


def planner_colors(planners: Iterable[str]) -> dict[str, tuple[float, float, float, float]]:
    """A fixed colour per planner (the same in every figure)."""
    from matplotlib import colormaps

    rank = {p: i for i, p in enumerate(PLAN_PLANNERS)}
    names = list(planners)
    extra = [p for p in method_order(names) if p not in rank]
    for i, p in enumerate(extra):
        rank[p] = len(PLAN_PLANNERS) + i
    # tab10 for the first ten (the colours the published figures have), then tab20's
    # light shades: every planner of PLAN_PLANNERS gets its own colour
    first, more = colormaps["tab10"], colormaps["tab20"]

    def colour(k: int) -> tuple[float, float, float, float]:
        return first(k) if k < 10 else more((2 * (k - 10) + 1) % 20)

    return {p: colour(rank[p]) for p in names}


def on_time_grid(
    values: NDArray[np.float64], elapsed: NDArray[np.float64], points: int = TIME_POINTS
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per-seed curves read at common wall-clock times.

    Each seed's value at time ``t`` is its value after the last simulation finished by
    ``t`` (a step function of its own ``elapsed``). The grid runs from the time by which
    every seed finished its first simulation to the time by which every seed finished
    its last, so all seeds are known at every grid point.

    Returns:
        ``(times, samples)`` with ``samples`` of shape ``(n_seeds, len(times))``; empty
        when no seed has timings.
    """
    ok = ~np.all(np.isnan(elapsed), axis=1)
    if not ok.any():
        return np.empty(0), np.empty((values.shape[0], 0))
    el = elapsed[ok]
    vals = values[ok]
    last = np.array([np.nanmax(e) for e in el])
    first = np.array([np.nanmin(e) for e in el])
    t0, t1 = float(first.max()), float(last.min())
    if not t1 > t0:
        t1 = t0
    times = np.linspace(t0, t1, points)
    out = np.empty((vals.shape[0], times.size))
    for i, (e, v) in enumerate(zip(el, vals, strict=True)):
        known = ~np.isnan(e)
        idx = np.searchsorted(e[known], times, side="right") - 1
        vv = v[known]
        out[i] = np.where(idx >= 0, vv[np.clip(idx, 0, None)], np.nan)
    return times, out


def plot_plan_figure(
    data: Sequence[PlannerRuns],
    path: str | Path,
    *,
    x: str = "simulations",
    dpi: int = 130,
    note: str | None = None,
) -> Path:
    """Draw Figure 4 (one row per problem: best return | objects left) to a PNG.

    Args:
        data: from :func:`~voot.bench.report.plan_runs.plan_data`.
        path: the PNG to write (its folder is created).
        x: ``"simulations"``, ``"seconds"`` (wall-clock time of the search, all seeds
            known at every point, :func:`on_time_grid`), or a cost axis of
            :mod:`voot.bench.protocol.axes`: ``"calls"`` (steps + pre-checks) or ``"cpu"`` (CPU
            seconds), read per seed as a step function on a common grid
            (:func:`voot.bench.protocol.axes.on_cost_grid`). A panel whose rows lack the cost
            axis's data says so instead of a curve.
        note: a line drawn under the figure's title (e.g. the tuning seeds).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from voot.bench.protocol.axes import AXES, get_axis

    if x not in (*AXES, "seconds"):
        raise ValueError(f"x must be one of {', '.join((*AXES, 'seconds'))}, got {x!r}")
    axis = get_axis(x) if x != "seconds" else None
    if not data:
        raise ValueError(
            "no finished plan runs to plot (is the store empty or the filter too strict?)"
        )
    cells = ordered_cells(data)
    planners = method_order(d.planner for d in data)
    ordered = table_order(data)
    colors = planner_colors(planners)
    ncols = 2 if any(d.objects_left is not None for d in data) else 1
    fig = Figure(figsize=(5.0 * ncols, 3.3 * len(cells)), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(cells), ncols, squeeze=False)
    handles: dict[str, Line2D] = {}
    for i, cell in enumerate(cells):
        runs = [d for d in ordered if d.cell == cell]
        panels = [("returns", "best return")]
        if ncols == 2:
            panels.append(("objects_left", "objects left"))
        for j, (attr, ylabel) in enumerate(panels):
            _draw_panel(
                axes[i][j], runs, attr, ylabel, x, axis, colors, handles, i == len(cells) - 1
            )
    if note:
        fig.suptitle(note, fontsize="small")
    order = [p for p in planners if p in handles]
    fig.legend(
        [handles[p] for p in order],
        order,
        loc="outside lower center",
        ncols=min(len(order), 3 * ncols),  # a one-column figure is narrow
        frameon=False,
    )
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    return path


def _curve(
    d: PlannerRuns, values: NDArray[np.float64], x: str, axis: Axis | None
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | bool:
    """The x values and the samples of one curve of ``d`` on the axis ``x``, one row per
    unit (seed, or layout: :meth:`~voot.bench.report.plan_runs.PlannerRuns.units`); if there is
    nothing to draw, whether that is because the rows lack the cost axis's data."""
    from voot.bench.protocol.axes import has_axis_data, on_cost_grid

    if x == "seconds":
        xs, samples = on_time_grid(values, d.elapsed)
        kept = ~np.all(np.isnan(d.elapsed), axis=1)  # the rows on_time_grid keeps
        return (xs, d.units(samples, kept)) if xs.size else False
    if axis is not None and axis.key is not None:
        cost = d.axis_values(axis.key)
        if cost is None:
            return True
        xs, samples = on_cost_grid(values, cost)
        return (xs, d.units(samples, has_axis_data(cost))) if xs.size else True
    return np.arange(1, values.shape[1] + 1), d.units(values)


def _draw_panel(
    ax: Axes,
    runs: Sequence[PlannerRuns],
    attr: str,
    ylabel: str,
    x: str,
    axis: Axis | None,
    colors: dict[str, tuple[float, float, float, float]],
    handles: dict[str, Line2D],
    last_row: bool,
) -> None:
    """One panel of :func:`plot_plan_figure`: the mean and band of ``attr`` (``returns``
    or ``objects_left``) of every planner of one problem, or a note saying why there is
    none; the first line of each planner goes into ``handles`` (the legend)."""
    title = runs[0].title
    drawn = False
    lacking = False
    for d in runs:
        values = getattr(d, attr)
        if values is None:
            continue
        curve = _curve(d, values, x, axis)
        if isinstance(curve, bool):
            lacking = lacking or curve
            continue
        xs, samples = curve
        mean, half, _ = mean_ci(samples)
        style, band = curve_style(samples.shape[0])
        (line,) = ax.plot(xs, mean, style, color=colors[d.planner], lw=1.4, label=d.planner)
        if band and np.any(np.isfinite(half)):
            low, high = mean - half, mean + half
            if attr == "objects_left":  # a count in [0, objects at the start]
                top = _objects_top(d)
                low, high = np.clip(low, 0.0, top), np.clip(high, 0.0, top)
            ax.fill_between(xs, low, high, color=colors[d.planner], alpha=0.2, lw=0)
        handles.setdefault(d.planner, line)
        drawn = True
    if not drawn:
        missing = (
            f"{title}: the rows lack {axis.key}\n(written before it was recorded);"
            f"\nno {axis.label} axis"
            if lacking and axis is not None
            else f"{title}: no {ylabel} reported"
        )
        ax.text(
            0.5,
            0.5,
            missing,
            ha="center",
            va="center",
            transform=ax.transAxes,
        )
        ax.set_axis_off()
        return
    ax.set_title(f"{title}: {ylabel}")
    ax.grid(alpha=0.3)
    ax.set_ylabel(ylabel)
    if last_row:
        ax.set_xlabel(axis.label if axis is not None else "wall-clock seconds")
