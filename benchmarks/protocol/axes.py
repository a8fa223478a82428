r"""The three x axes of the planning curves: simulations, simulator calls, CPU seconds.

A planner that is ahead per simulation can be behind per unit of work, so every curve
of the full protocol is drawn three times:

``simulations``
    the paper's axis: the best return after the k-th simulation (``best_so_far[k-1]``).
``calls``
    simulator calls: the row's ``calls_curve``, the cumulative executed steps **plus**
    kinematic pre-checks after every simulation (:mod:`voot.bench.sweep.plan`). Both are
    counted as one call each although a pre-check (IK, collisions, regions) costs less
    than an executed step; the table of steps against pre-checks
    (:func:`voot.bench.report.plan_tables.calls_table`) says how the calls split.
``cpu``
    CPU seconds of the search's process (``cpu_elapsed``, :func:`time.process_time`),
    which, unlike wall-clock time, does not grow when other jobs share the cores.

On the two cost axes every seed reaches a given simulation at a different x, so the
seeds are read on a common grid (:func:`on_cost_grid`) the honest way for a
best-so-far curve, which is a step function: at grid point ``x`` a seed's value is its
value after the last simulation with cost at most ``x`` (carried forward, never
interpolated); before its first simulation a seed contributes no value. Past its own
last simulation a seed has spent its whole budget: by default (``hold_final=True``) it
keeps its final value up to the axis's right end, because its search is over and its
best is final. Dropping finished seeds instead (``hold_final=False``) leaves a mean of
the slowest seeds only, and those are slow because they went further (more executed
steps per simulation), which biases the curve's end upwards. Where fewer than
``min_share`` of the seeds contribute (before most have started), no mean is drawn.

Rows written before ``calls_curve`` and ``cpu_elapsed`` existed still draw on the
simulation axis; on the other two they count as lacking the data.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from voot import validation as V

#: Points of the common grid of a cost axis.
GRID_POINTS = 256
#: Least share of a planner's seeds that must still contribute at a grid point for its
#: mean to be drawn there (see the module docstring).
MIN_SEED_SHARE = 0.5


@dataclass(frozen=True)
class Axis:
    """One x axis of the planning figures.

    Attributes:
        name: ``simulations``, ``calls`` or ``cpu``.
        key: the row key holding the x value after every simulation (None: the count).
        label: the axis label.
        png: the PNG file name of its figure (in the folder ``voot-bench plot --axes-dir``).
        caption: what the axis means, for the figure's caption.
    """

    name: str
    key: str | None
    label: str
    png: str
    caption: str


AXES: dict[str, Axis] = {
    "simulations": Axis(
        "simulations",
        None,
        "simulations",
        "plan-simulations.png",
        "x axis: simulations (the paper's).",
    ),
    "calls": Axis(
        "calls",
        "calls_curve",
        "simulator calls (steps + pre-checks)",
        "plan-calls.png",
        "x axis: simulator calls, the executed steps and the kinematic pre-checks counted"
        " together, one call each (the split per planner is in the table of steps and"
        " pre-checks).",
    ),
    "cpu": Axis(
        "cpu",
        "cpu_elapsed",
        "CPU seconds",
        "plan-cpu-seconds.png",
        "x axis: CPU seconds of the search's process (time.process_time).",
    ),
}
#: The axes in drawing order.
AXIS_NAMES: tuple[str, ...] = tuple(AXES)


def get_axis(name: str) -> Axis:
    """The axis called ``name``; a ValueError naming the valid ones otherwise."""
    try:
        return AXES[name]
    except KeyError:
        raise ValueError(f"unknown axis {name!r}; valid axes are: {', '.join(AXES)}") from None


def has_axis_data(x: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Per seed (row of ``x``), whether it has any x value (rows lacking the key are NaN)."""
    return ~np.all(np.isnan(np.asarray(x, dtype=np.float64)), axis=1)


def read_steps(
    values: NDArray[np.float64],
    x: NDArray[np.float64],
    grid: NDArray[np.float64],
    *,
    hold_final: bool = False,
) -> NDArray[np.float64]:
    """Each seed's step function ``x -> value`` read at ``grid``.

    Row ``i`` of ``values`` is seed ``i``'s value after every simulation, row ``i`` of
    ``x`` its (non-decreasing) cost after every simulation, NaN where unknown. At grid
    point ``g`` the value is that of the last simulation with ``x <= g``; NaN before the
    seed's first simulation, and past its last NaN too unless ``hold_final`` (then the
    final value: the finished search's best).
    """
    values = np.asarray(values, dtype=np.float64)
    x = np.asarray(x, dtype=np.float64)
    grid = np.asarray(grid, dtype=np.float64)
    if values.shape != x.shape:
        raise ValueError(f"values {values.shape} and x {x.shape} must have the same shape")
    out = np.full((values.shape[0], grid.size), np.nan)
    for i in range(values.shape[0]):
        known = ~np.isnan(x[i])
        xi, vi = x[i][known], values[i][known]
        if xi.size == 0:
            continue
        if np.any(np.diff(xi) < 0):
            raise ValueError(f"seed row {i}: the x values must not decrease")
        idx = np.searchsorted(xi, grid, side="right") - 1
        inside = (idx >= 0) & ((grid <= xi[-1]) | bool(hold_final))
        out[i] = np.where(inside, vi[np.clip(idx, 0, None)], np.nan)
    return out


def on_cost_grid(
    values: NDArray[np.float64],
    x: NDArray[np.float64],
    *,
    points: int = GRID_POINTS,
    min_share: float = MIN_SEED_SHARE,
    hold_final: bool = True,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per-seed curves on a common grid of a cost axis (:func:`read_steps`; a finished
    seed keeps its final value unless ``hold_final`` is False, see the module docstring).

    Seeds without x values (rows lacking the key) are left out. The grid runs linearly
    from the smallest first x to the largest last x over the seeds; grid points where
    fewer than ``ceil(min_share * seeds)`` seeds contribute are NaN for every seed, so
    no mean is drawn there.

    Returns:
        ``(grid, samples)``, ``samples`` of shape ``(seeds with data, grid points)``;
        both empty when no seed has x values.
    """
    n_points = V.integer(points, "points", 2)
    share = V.number(min_share, "min_share", 0.0, 1.0)
    values = np.asarray(values, dtype=np.float64)
    x = np.asarray(x, dtype=np.float64)
    ok = has_axis_data(x)
    if not ok.any():
        return np.empty(0), np.empty((0, 0))
    xs, vs = x[ok], values[ok]
    lo = float(np.nanmin(xs))
    hi = float(max(np.nanmax(row) for row in xs))
    grid = np.linspace(lo, hi, n_points)
    samples = read_steps(vs, xs, grid, hold_final=hold_final)
    need = max(1, math.ceil(share * xs.shape[0]))
    count = (~np.isnan(samples)).sum(axis=0)
    samples[:, count < need] = np.nan
    return grid, samples
