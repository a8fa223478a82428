r"""The data of the paper's Figure 4 and its tables: the selected runs of every planner per
problem (:func:`plan_data` gives one :class:`PlannerRuns` per problem and planner, with
the hyperparameters selected by best mean final return, :mod:`voot.bench.protocol.select`; with
tuning seeds, selected on those seeds and the other seeds kept, :mod:`voot.bench.protocol.tuning`),
and the statistics over seeds that the figure, the tables and the claims
(:mod:`voot.bench.protocol.claims`) report: the mean with a t-interval (:func:`mean_ci`), the
median with a distribution-free interval (:func:`median_ci`), and when a run first and
for good handled every object (:func:`first_reach`, :func:`settled_reach`).

On a generated family (rows with a ``layout_seed``, :mod:`voot.bench.protocol.layouts`) a
:class:`PlannerRuns` holds every (layout, seed) run of the family; its curve is the mean
over them, and its intervals take the layout as the unit (:meth:`PlannerRuns.units`: the
per-layout means, :func:`voot.bench.protocol.layouts.layout_means`), since runs on one layout are
not independent draws of the family.

The figure is drawn by :mod:`voot.bench.report.plan_plot`, the tables are written by
:mod:`voot.bench.report.plan_tables`.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from voot.bench.protocol.layouts import (
    TuningLayoutsArg,
    layout_means,
    layout_medians,
    layout_of,
    n_layouts,
)
from voot.bench.protocol.select import (
    cell_of,
    function_order,
    largest_budget,
    method_order,
    select_hyperparameters,
    selected_rows,
)
from voot.bench.report.bbfo_plot import CONFIDENCE
from voot.bench.store.format import Row


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
            :mod:`voot.bench.sweep.plan`).
        calls: cumulative steps + pre-checks after every simulation (``calls_curve``;
            NaN rows: the row lacks it).
        cpu_elapsed: CPU seconds since the search started after every simulation (NaN
            rows: the row lacks it).
        n_steps: executed steps per seed.
        n_feasibility_checks: pre-checks per seed.
        tuning_seeds: the seeds its setting was selected on (empty: selected on these
            very seeds, the paper's rule).
        layouts: the layout seed of every row, in row order (None: a row without one;
            empty: no row has one).
        tuning_layouts: the training layouts its setting was selected on (empty: none).
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
    layouts: tuple[int | None, ...] = ()
    tuning_layouts: tuple[int, ...] = ()

    @property
    def has_layouts(self) -> bool:
        """Whether the rows are on layouts of a generated family."""
        return any(v is not None for v in self.layouts)

    @property
    def n_layouts(self) -> int:
        """Distinct layouts of the rows (0 without layouts)."""
        return n_layouts(self.layouts)

    @property
    def n_units(self) -> int:
        """The independent units of the intervals: layouts if the rows have them, else seeds."""
        return self.n_layouts if self.has_layouts else self.n_seeds

    def units(
        self, samples: NDArray[np.float64], rows: NDArray[np.bool_] | None = None
    ) -> NDArray[np.float64]:
        """``samples`` (one row per run, or per run of ``rows``, a mask of the runs kept)
        as the units of an interval: the per-layout means on a layout axis, else the runs
        themselves (:func:`voot.bench.protocol.layouts.layout_means`)."""
        if not self.has_layouts:
            return samples
        layouts = list(self.layouts)
        if rows is not None:
            layouts = [v for v, keep in zip(layouts, rows, strict=True) if keep]
        return layout_means(samples, layouts)

    def unit_medians(self, values: NDArray[np.float64]) -> NDArray[np.float64]:
        """One value per run as the units of a median: per-layout medians on a layout axis."""
        return layout_medians(values, list(self.layouts)) if self.has_layouts else values

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

    Coverage (tested in ``tests/benchmarks/report/test_plan_runs.py``): exact for normal values at every
    n >= 2; skewed values undercover (at 95%, exponential about 0.89 at n = 5 and 0.94
    at n = 80, lognormal with sigma = 1 about 0.83 at n = 5 and 0.91 at n = 60); 0/1
    values (success rates) undercover erratically, to at most 1 - p^n - (1-p)^n (an
    all-equal sample has a zero-width interval) and within [0.905, 0.970] once
    n min(p, 1-p) >= 10.
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
    too small for one (at 95%: fewer than 6 values). Censored values (a seed that never
    got there) enter as ``inf``. The coverage holds for any distribution, discrete and
    censored ones included (tested in ``tests/benchmarks/report/test_plan_runs.py``).
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
    tuning_layouts: TuningLayoutsArg | None = None,
) -> list[PlannerRuns]:
    """The selected runs of every planner per problem (per family, on a layout axis).

    Rows are filtered to finished ``"plan"`` rows of the given problems (display names,
    e.g. ``kitchen``, ``shekel_chain``) and planners, and to the largest budget per
    problem; each planner's setting is then selected by best mean final return: on the
    same seeds (the paper's rule), or, with ``tuning_seeds``, on the rows of those seeds,
    and the runs returned are then those of every other seed (the evaluation seeds) with
    the selected setting (:func:`voot.bench.protocol.tuning.select_on_tuning`; planners without
    tuning rows are left out). With ``tuning_layouts`` (one collection, or per problem
    id) the settings are selected on the rows of those layouts (of ``tuning_seeds`` if
    given) and the rows of every other layout are returned: the held-out protocol.
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
    if tuning_seeds is None and tuning_layouts is None:
        selections = select_hyperparameters(keep)
        chosen = selected_rows(keep, selections)
    else:
        from voot.bench.protocol.tuning import select_on_tuning

        tuned = tuple(sorted(set(int(t) for t in tuning_seeds or ())))
        outcome = select_on_tuning(
            keep, tuned if tuning_seeds is not None else None, tuning_layouts
        )
        selections, chosen = list(outcome.selections), list(outcome.rows)
    out = []
    for s in selections:
        group = [r for r in chosen if cell_of(r) == s.key]
        if not group:  # tuned, but no evaluation runs yet
            continue
        group.sort(key=lambda r: (_layout_rank(r), int(r["config"]["seed"])))
        layouts = tuple(layout_of(r["config"]) for r in group)
        # the tuning layouts this cell's setting was selected on (those with rows)
        present = {layout_of(r["config"]) for r in keep if cell_of(r) == s.key}
        problems = [r["config"]["problem"] for r in group]
        trained = sorted(v for v in _tuning_layouts_of(tuning_layouts, problems) if v in present)
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
                layouts=layouts if any(v is not None for v in layouts) else (),
                tuning_layouts=tuple(trained),
            )
        )
    return out


def _layout_rank(row: Row) -> int:
    """Sort key of a row's layout (rows without one first)."""
    layout = layout_of(row["config"])
    return -1 if layout is None else layout


def _tuning_layouts_of(
    tuning_layouts: TuningLayoutsArg | None, problems: Iterable[str]
) -> set[int]:
    """The tuning layouts of ``problems`` (every problem's, given one per problem)."""
    if tuning_layouts is None:
        return set()
    from collections.abc import Mapping

    if isinstance(tuning_layouts, Mapping):
        return {int(v) for p in set(problems) for v in tuning_layouts.get(p, ())}
    return {int(v) for v in tuning_layouts}


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


def ordered_cells(data: Sequence[PlannerRuns]) -> list[tuple[str, int]]:
    """The (problem, dimension) cells of ``data`` in display order: problems as
    :func:`voot.bench.protocol.select.function_order` sorts them, then by dimension."""
    problems = function_order(d.problem for d in data)
    cells = sorted({d.cell for d in data}, key=lambda c: (problems.index(c[0]), c[1]))
    return cells


def table_order(data: Sequence[PlannerRuns]) -> list[PlannerRuns]:
    """``data`` in display order: by cell (:func:`ordered_cells`), then by planner
    (:func:`voot.bench.protocol.select.method_order`)."""
    cells = ordered_cells(data)
    planners = method_order(d.planner for d in data)
    return sorted(data, key=lambda d: (cells.index(d.cell), planners.index(d.planner)))
