r"""The paper's Figure 4 from a result store (plan rows), against simulations and seconds,
and its tables.

Figure: one row of panels per problem (chains per dimension), with the best discounted
return from the root (goal bonus excluded) in the left panel and, when the problem
reports it, the objects still to handle at the best leaf in the right panel; one line per
planner with its selected hyperparameters (:mod:`voot.bench.select`, best mean final
return), the mean over seeds and a shaded 95% t-interval (:func:`mean_ci`, seeds whose
value is unknown at a point left out there; the objects' band is clipped to the count's
range, 0 to the objects at the start; with fewer than
:data:`~voot.bench.plot.MIN_SEEDS_FOR_BAND` seeds the mean is dashed and has no band). The x axis is the number of simulations
(:func:`plot_plan_figure`), the wall-clock seconds since the search started
(``x="seconds"``: each run's curve is read as a step function of its own clock
(``elapsed``), on a grid up to the time by which every seed of the planner had finished),
or a cost axis of :mod:`voot.bench.axes` (``x="calls"``: steps + pre-checks; ``x="cpu"``:
CPU seconds), one figure each, captioned by :func:`figure_caption`. With tuning seeds
(:func:`plan_data`'s ``tuning_seeds``) the settings are selected on those seeds and the
other seeds are drawn (:mod:`voot.bench.tuning`).

Tables (markdown): the best return at given simulation counts (default 1,000 / 3,000 /
10,000 and the budget); objects handled (objects at the start minus objects left) at
those counts; the simulations needed to handle every object (kitchen: clear the path),
median with a distribution-free 95% interval and the fraction of seeds that got there;
the cost of a simulation (milliseconds, simulator calls); and the executed steps against
the pre-checks per simulation (:func:`calls_table`).
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from voot.bench.axes import has_axis_data
from voot.bench.plan_sweep import PLAN_PLANNERS
from voot.bench.plot import CONFIDENCE, curve_style
from voot.bench.select import (
    cell_of,
    function_order,
    largest_budget,
    method_order,
    select_hyperparameters,
    selected_rows,
)
from voot.bench.store import Row

#: Simulation counts of the tables, kept where below the budget (the budget is added).
CHECKPOINTS: tuple[int, ...] = (1_000, 3_000, 10_000)
#: Points of the wall-clock grid.
TIME_POINTS = 256


def _stack(values: Iterable[object], width: int) -> NDArray[np.float64]:
    """Rows of possibly ragged or missing (None) curves as an ``(n, width)`` NaN-padded array."""
    lists = list(values)
    out = np.full((len(lists), width), np.nan)
    for i, v in enumerate(lists):
        if v is None:
            continue
        a = np.asarray(v, dtype=np.float64)[:width]  # None entries -> NaN
        out[i, : a.size] = a
    return out


@dataclass(frozen=True)
class PlannerRuns:
    """The selected runs of one planner on one problem (one row per seed).

    Attributes:
        problem: the problem's display name (alias, env keywords), without the dimension.
        dim: the chain's dimension, 0 for an environment.
        simulations: the budget.
        planner: the planner's name.
        label: the selected hyperparameter setting.
        seeds: the seeds, in row order.
        returns: best return after every simulation, ``(n_seeds, simulations)``.
        elapsed: seconds since the search started after every simulation (NaN unknown).
        objects_left: objects still to handle at the best leaf (None if never reported).
        objects_initial: objects at the start per seed (NaN unknown; None if never).
        simulator_calls: simulator calls per seed (the problem's own count, see
            :mod:`voot.bench.plan_sweep`).
        calls: cumulative steps + pre-checks after every simulation (``calls_curve``;
            NaN rows: the row lacks it).
        cpu_elapsed: CPU seconds since the search started after every simulation (NaN
            rows: the row lacks it).
        n_steps: executed steps per seed.
        n_feasibility_checks: pre-checks per seed.
        tuning_seeds: the seeds its setting was selected on (empty: selected on these
            very seeds, the paper's rule).
    """

    problem: str
    dim: int
    simulations: int
    planner: str
    label: str
    seeds: tuple[int, ...]
    returns: NDArray[np.float64]
    elapsed: NDArray[np.float64]
    objects_left: NDArray[np.float64] | None
    objects_initial: NDArray[np.float64] | None
    simulator_calls: NDArray[np.float64]
    calls: NDArray[np.float64] | None = None
    cpu_elapsed: NDArray[np.float64] | None = None
    n_steps: NDArray[np.float64] | None = None
    n_feasibility_checks: NDArray[np.float64] | None = None
    tuning_seeds: tuple[int, ...] = ()

    def axis_values(self, key: str | None) -> NDArray[np.float64] | None:
        """The x values of a cost axis (``calls_curve`` or ``cpu_elapsed``); None for the
        simulation count."""
        if key is None:
            return None
        return {"calls_curve": self.calls, "cpu_elapsed": self.cpu_elapsed}[key]

    @property
    def n_seeds(self) -> int:
        return len(self.seeds)

    @property
    def title(self) -> str:
        return f"{self.problem} {self.dim}-D" if self.dim else self.problem

    @property
    def cell(self) -> tuple[str, int]:
        return (self.problem, self.dim)


def mean_ci(
    samples: NDArray[np.float64], confidence: float = CONFIDENCE
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]:
    """Mean, t-interval half-width and count along axis 0, ignoring NaN entries.

    Where fewer than 2 values are known the half-width is NaN (and the mean NaN where
    none is).
    """
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence}")
    arr = np.asarray(samples, dtype=np.float64)
    known = ~np.isnan(arr)
    n = known.sum(axis=0)
    total = np.where(known, arr, 0.0).sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(n > 0, total / np.maximum(n, 1), np.nan)
        dev = np.where(known, arr - mean, 0.0)
        var = (dev**2).sum(axis=0) / np.maximum(n - 1, 1)
        from scipy.stats import t

        q = t.ppf(0.5 + confidence / 2.0, np.maximum(n - 1, 1))
        half = np.where(n >= 2, q * np.sqrt(var) / np.sqrt(np.maximum(n, 1)), np.nan)
    return mean, half, n


def median_ci(
    values: Sequence[float] | NDArray[np.float64], confidence: float = CONFIDENCE
) -> tuple[float, float, float]:
    r"""Median and a distribution-free confidence interval ``(median, low, high)``.

    The interval is :math:`[x_{(l)}, x_{(n-l+1)}]` of the sorted values with
    :math:`l` the :math:`(1-c)/2` quantile of :math:`\mathrm{Binomial}(n, 1/2)`, which
    covers the median with probability at least ``confidence``; NaN bounds when ``n`` is
    too small for one. Censored values (a seed that never got there) enter as ``inf``.
    """
    x = np.sort(np.asarray(values, dtype=np.float64))
    n = x.size
    if n == 0:
        return math.nan, math.nan, math.nan
    median = float(np.median(x))
    from scipy.stats import binom

    low_rank = int(binom.ppf((1.0 - confidence) / 2.0, n, 0.5))
    if low_rank < 1:
        return median, math.nan, math.nan
    return median, float(x[low_rank - 1]), float(x[n - low_rank])


def plan_data(
    rows: Iterable[Row],
    *,
    problems: Sequence[str] | None = None,
    planners: Sequence[str] | None = None,
    tuning_seeds: Collection[int] | None = None,
) -> list[PlannerRuns]:
    """The selected runs of every planner per problem.

    Rows are filtered to finished ``"plan"`` rows of the given problems (display names,
    e.g. ``kitchen``, ``shekel_chain``) and planners, and to the largest budget per
    problem; each planner's setting is then selected by best mean final return: on the
    same seeds (the paper's rule), or, with ``tuning_seeds``, on the rows of those seeds,
    and the runs returned are then those of every other seed (the evaluation seeds) with
    the selected setting (:func:`voot.bench.tuning.select_on_tuning`; planners without
    tuning rows are left out).
    """
    keep = []
    for r in rows:
        if r.get("status") != "ok" or r.get("kind") != "plan":
            continue
        problem, _, _, planner = cell_of(r)
        if problems is not None and problem not in problems:
            continue
        if planners is not None and planner not in planners:
            continue
        keep.append(r)
    keep = largest_budget(keep)
    tuned: tuple[int, ...] = ()
    if tuning_seeds is None:
        selections = select_hyperparameters(keep)
        chosen = selected_rows(keep, selections)
    else:
        from voot.bench.tuning import select_on_tuning

        tuned = tuple(sorted(set(int(t) for t in tuning_seeds)))
        outcome = select_on_tuning(keep, tuned)
        selections, chosen = list(outcome.selections), list(outcome.rows)
    out = []
    for s in selections:
        group = [r for r in chosen if cell_of(r) == s.key]
        if not group:  # tuned, but no evaluation runs yet
            continue
        group.sort(key=lambda r: int(r["config"]["seed"]))
        width = s.budget
        has_objects = any(r.get("objects_left") is not None for r in group)
        initial = [r.get("objects_initial") for r in group]
        out.append(
            PlannerRuns(
                problem=s.function,
                dim=s.dim,
                simulations=s.budget,
                planner=s.method,
                label=s.best.label,
                seeds=tuple(int(r["config"]["seed"]) for r in group),
                returns=_stack((r["best_so_far"] for r in group), width),
                elapsed=_stack((r.get("elapsed") for r in group), width),
                objects_left=(
                    _stack((r.get("objects_left") for r in group), width) if has_objects else None
                ),
                objects_initial=(
                    np.array([np.nan if v is None else float(v) for v in initial])
                    if has_objects
                    else None
                ),
                simulator_calls=np.array([float(r.get("simulator_calls", np.nan)) for r in group]),
                calls=_stack((r.get("calls_curve") for r in group), width),
                cpu_elapsed=_stack((r.get("cpu_elapsed") for r in group), width),
                n_steps=np.array([float(r.get("n_steps", np.nan)) for r in group]),
                n_feasibility_checks=np.array(
                    [float(r.get("n_feasibility_checks", np.nan)) for r in group]
                ),
                tuning_seeds=tuned,
            )
        )
    return out


def _objects_top(d: PlannerRuns) -> float:
    """The most objects a run of ``d`` had at the start (inf if unknown): the band's top."""
    initial = d.objects_initial
    if initial is None or not np.any(np.isfinite(initial)):
        return float("inf")
    return float(np.nanmax(initial))


def _cells(data: Sequence[PlannerRuns]) -> list[tuple[str, int]]:
    problems = function_order(d.problem for d in data)
    cells = sorted({d.cell for d in data}, key=lambda c: (problems.index(c[0]), c[1]))
    return cells


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
        data: from :func:`plan_data`.
        path: the PNG to write (its folder is created).
        x: ``"simulations"``, ``"seconds"`` (wall-clock time of the search, all seeds
            known at every point, :func:`on_time_grid`), or a cost axis of
            :mod:`voot.bench.axes`: ``"calls"`` (steps + pre-checks) or ``"cpu"`` (CPU
            seconds), read per seed as a step function on a common grid
            (:func:`voot.bench.axes.on_cost_grid`). A panel whose rows lack the cost
            axis's data says so instead of a curve.
        note: a line drawn under the figure's title (e.g. the tuning seeds).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    from voot.bench.axes import AXES, get_axis, on_cost_grid

    if x not in (*AXES, "seconds"):
        raise ValueError(f"x must be one of {', '.join((*AXES, 'seconds'))}, got {x!r}")
    axis = get_axis(x) if x != "seconds" else None
    if not data:
        raise ValueError(
            "no finished plan runs to plot (is the store empty or the filter too strict?)"
        )
    cells = _cells(data)
    planners = method_order(d.planner for d in data)
    colors = planner_colors(planners)
    ncols = 2 if any(d.objects_left is not None for d in data) else 1
    fig = Figure(figsize=(5.0 * ncols, 3.3 * len(cells)), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(cells), ncols, squeeze=False)
    handles: dict[str, Line2D] = {}
    for i, cell in enumerate(cells):
        runs = sorted((d for d in data if d.cell == cell), key=lambda d: planners.index(d.planner))
        title = runs[0].title
        panels = [("returns", "best return")]
        if ncols == 2:
            panels.append(("objects_left", "objects left"))
        for j, (attr, ylabel) in enumerate(panels):
            ax = axes[i][j]
            drawn = False
            lacking = False
            for d in runs:
                values = getattr(d, attr)
                if values is None:
                    continue
                if x == "seconds":
                    xs, samples = on_time_grid(values, d.elapsed)
                    if xs.size == 0:
                        continue
                elif axis is not None and axis.key is not None:
                    cost = d.axis_values(axis.key)
                    if cost is None:
                        lacking = True
                        continue
                    xs, samples = on_cost_grid(values, cost)
                    if xs.size == 0:
                        lacking = True
                        continue
                else:
                    xs, samples = np.arange(1, values.shape[1] + 1), values
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
                continue
            ax.set_title(f"{title}: {ylabel}")
            ax.grid(alpha=0.3)
            ax.set_ylabel(ylabel)
            if i == len(cells) - 1:
                ax.set_xlabel(axis.label if axis is not None else "wall-clock seconds")
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


# ----- tables -------------------------------------------------------------------------------
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
    for cell in _cells(data):
        runs = {d.planner: d for d in data if d.cell == cell}
        title = next(iter(runs.values())).title
        budget = max(d.simulations for d in runs.values())
        for k in at if at is not None else default_checkpoints(budget):
            stats: dict[str, tuple[float, float, int]] = {}
            for p, d in runs.items():
                values = values_of(d)  # type: ignore[operator]
                if values is None or k > values.shape[1] or k < 1:
                    continue
                mean, half, n = mean_ci(values[:, k - 1 : k])
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
    return "\n".join(lines) + f"\n\n{what}: {note}"


_CI_NOTE = (
    "mean ± half-width of the 95% t-interval over seeds (number of seeds), each planner"
    " with its selected hyperparameters; best mean in bold."
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


def first_reach(objects_left: NDArray[np.float64]) -> NDArray[np.float64]:
    """Per seed, the first simulation (1-based) whose best leaf has no object left;
    ``inf`` if none has."""
    done = objects_left <= 0
    reached = done.any(axis=1)
    first = np.argmax(done, axis=1).astype(np.float64) + 1.0
    return np.where(reached, first, np.inf)


def settled_reach(objects_left: NDArray[np.float64]) -> NDArray[np.float64]:
    """Per seed, the first simulation (1-based) from which the best leaf has no object left
    for the rest of the budget; ``inf`` if it still has one at the end.

    The best leaf is the best-return leaf, not the one that handles most objects, so a
    later, better plan can leave an object again: :func:`first_reach` is when a complete
    plan was first the best one, this is when the best plan stopped changing that answer.
    """
    done = objects_left <= 0
    settled = done[:, -1]
    not_done_rev = ~done[:, ::-1]
    last_open = objects_left.shape[1] - 1 - np.argmax(not_done_rev, axis=1)
    start = np.where(not_done_rev.any(axis=1), last_open + 2, 1).astype(np.float64)
    return np.where(settled, start, np.inf)


def completion_table(data: Sequence[PlannerRuns]) -> str:
    """Simulations needed to handle every object (kitchen: clear the path), per problem
    and planner: median, distribution-free 95% interval, and seeds that got there."""
    lines = [
        "| problem | planner | seeds that got there | median simulations | 95% CI"
        " | seeds cleared at the end | median simulations, for good | 95% CI |",
        "| --- | --- | ---: | ---: | --- | ---: | ---: | --- |",
    ]
    planners = method_order(d.planner for d in data)
    for cell in _cells(data):
        for d in sorted(
            (d for d in data if d.cell == cell and d.objects_left is not None),
            key=lambda d: planners.index(d.planner),
        ):
            assert d.objects_left is not None
            first = first_reach(d.objects_left)
            med, lo, hi = median_ci(first)
            got = int(np.isfinite(first).sum())
            settled = settled_reach(d.objects_left)
            s_med, s_lo, s_hi = median_ci(settled)
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
    return "\n".join(lines) + (
        "\n\nSimulations until the best plan (highest return) first handles every object, and"
        " from which it handles every object for the rest of the budget (the best plan can"
        " change to one that leaves an object); > budget: not within the budget, counted as"
        " never; interval: order statistics, distribution-free 95%."
    )


def cost_table(data: Sequence[PlannerRuns]) -> str:
    """Wall-clock milliseconds and simulator calls per simulation (mean over seeds)."""
    lines = [
        "| problem | planner | ms per simulation | simulator calls per simulation | search seconds |",
        "| --- | --- | ---: | ---: | ---: |",
    ]
    planners = method_order(d.planner for d in data)
    for cell in _cells(data):
        for d in sorted(
            (d for d in data if d.cell == cell), key=lambda d: planners.index(d.planner)
        ):
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
    planners = method_order(d.planner for d in data)
    for cell in _cells(data):
        for d in sorted(
            (d for d in data if d.cell == cell), key=lambda d: planners.index(d.planner)
        ):
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
    """The caption of the figure on axis ``x`` (a name of :data:`voot.bench.axes.AXES`):
    what is drawn, the axis, and how the settings were selected."""
    from voot.bench.axes import MIN_SEED_SHARE, get_axis
    from voot.bench.tuning import tuning_note

    axis = get_axis(x)
    seeds = sorted({d.n_seeds for d in data})
    counts = "/".join(map(str, seeds))
    parts = [
        f"Best return (and objects left) against {axis.label}: mean over {counts} seeds"
        " with a 95% t-interval.",
        axis.caption,
    ]
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
    tuned = {d.tuning_seeds for d in data}
    if tuned == {()}:
        parts.append("Settings selected on the same seeds (the paper's rule).")
    else:
        notes = sorted(tuning_note(t) for t in tuned if t)
        parts.append(_sentence("; ".join(notes)))
    return " ".join(parts)


def plan_settings_table(data: Sequence[PlannerRuns]) -> str:
    """The selected hyperparameters per problem and planner (and the seeds they were
    selected on when those were tuning seeds)."""
    lines = ["| problem | planner | selected setting | seeds |", "| --- | --- | --- | ---: |"]
    planners = method_order(d.planner for d in data)
    for cell in _cells(data):
        for d in sorted(
            (d for d in data if d.cell == cell), key=lambda d: planners.index(d.planner)
        ):
            lines.append(f"| {d.title} | {d.planner} | {d.label} | {d.n_seeds} |")
    tuned = sorted({d.tuning_seeds for d in data if d.tuning_seeds})
    if tuned:
        from voot.bench.tuning import tuning_note

        lines.append("")
        lines.append(_sentence("; ".join(tuning_note(t) for t in tuned)))
    return "\n".join(lines)


def plan_report(data: Sequence[PlannerRuns], at: Sequence[int] | None = None) -> str:
    """Every table as one markdown document (sections without data are left out)."""
    parts = [("Best return", returns_table(data, at))]
    tuned = sorted({d.tuning_seeds for d in data if d.tuning_seeds})
    if tuned:
        from voot.bench.tuning import tuning_note

        note = _sentence("; ".join(tuning_note(t) for t in tuned))
        parts.insert(0, ("Protocol", f"{note} The tables report the evaluation seeds only."))
    parts.append(("Objects handled", objects_table(data, at)))
    parts.append(("Simulations to handle every object", completion_table(data)))
    parts.append(("Cost of a simulation", cost_table(data)))
    parts.append(("Simulator calls: executed steps and pre-checks", calls_table(data)))
    parts.append(("Selected hyperparameters", plan_settings_table(data)))
    return "\n\n".join(f"### {title}\n\n{table}" for title, table in parts if table) + "\n"
