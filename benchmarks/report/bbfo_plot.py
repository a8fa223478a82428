r"""The paper's Figure 3 from a result store, and the table of final values.

Figure: one panel per (function, dim) (rows: functions, columns: dimensions), one line
per optimiser with its selected hyperparameters (:mod:`voot.bench.protocol.select`): the mean
over seeds of the best value so far (or of the regret ``f* - best``) against the number of
evaluations, with a shaded 95% confidence interval.

Confidence intervals use the **t-distribution**: with ``n`` seeds, sample mean
:math:`\bar y` and sample standard deviation :math:`s` (``ddof=1``), the interval is

.. math::  \bar y \pm t_{0.975,\,n-1}\, s / \sqrt{n},

computed independently at every evaluation count. With a single seed there is no interval
(it is reported as NaN and not drawn).

Rows of different test-function instances (shifted optima, see :mod:`voot.functions`)
are never drawn together: :func:`figure_data` takes one ``instance`` (or the only one the
rows hold), and the panel titles and tables name a nonzero instance.

Drawing uses matplotlib's object API with the Agg canvas, so importing this module never
changes the pyplot backend of the caller.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from voot.bench.protocol.select import (
    function_order,
    largest_budget,
    method_order,
    one_instance,
    select_hyperparameters,
    selected_rows,
)
from voot.bench.store.format import Row, curves
from voot.bench.sweep.bbfo import PAPER_METHODS

#: Confidence level of the intervals.
CONFIDENCE = 0.95


def t_interval(
    samples: NDArray[np.float64], confidence: float = CONFIDENCE
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Mean and half-width of the t confidence interval along axis 0.

    Args:
        samples: shape ``(n, ...)``, one row per seed.
        confidence: two-sided level in (0, 1).

    Returns:
        ``(mean, half_width)``, each of shape ``samples.shape[1:]``; the half-width is
        NaN when ``n < 2``.
    """
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence}")
    arr = np.asarray(samples, dtype=np.float64)
    n = arr.shape[0]
    if n == 0:
        raise ValueError("need at least one sample for a mean")
    mean = arr.mean(axis=0)
    if n < 2:
        return mean, np.full_like(mean, np.nan)
    from scipy.stats import t

    q = float(t.ppf(0.5 + confidence / 2.0, n - 1))
    return mean, q * arr.std(axis=0, ddof=1) / math.sqrt(n)


@dataclass(frozen=True)
class MethodCurves:
    """The selected runs of one method in one (function, dim) cell."""

    function: str
    dim: int
    budget: int
    method: str
    label: str
    #: best value (or regret) after each evaluation, shape ``(n_seeds, budget)``
    values: NDArray[np.float64]
    #: test-function instance (0: the paper's function)
    instance: int = 0

    @property
    def n_seeds(self) -> int:
        return int(self.values.shape[0])


def optimum_of(function: str, dim: int, instance: int = 0) -> float:
    """The documented optimum ``f*`` of a function (for regret)."""
    from voot.functions import get_function

    value = get_function(function, dim, instance).optimum_value
    if value is None or not math.isfinite(float(value)):
        raise ValueError(f"{function}-{dim}D has no known optimum, so no regret can be computed")
    return float(value)


def figure_data(
    rows: Iterable[Row],
    *,
    regret: bool = False,
    functions: Sequence[str] | None = None,
    dims: Sequence[int] | None = None,
    methods: Sequence[str] | None = None,
    instance: int | None = None,
) -> list[MethodCurves]:
    """Curves of the selected setting of every method, per (function, dim).

    Rows are filtered to ``"ok"``, to the given functions/dims/methods, to one
    test-function ``instance`` (default: the only one present; a ``ValueError`` names them
    if there are several), and to the largest budget per (function, dim);
    hyperparameters are selected on what remains.
    """
    keep = [
        r
        for r in rows
        if r.get("status") == "ok"
        and r.get("kind") == "bbfo"
        and (functions is None or r["config"]["function"] in functions)
        and (dims is None or int(r["config"]["dim"]) in dims)
        and (methods is None or r["config"]["method"] in methods)
    ]
    instance, keep = one_instance(keep, instance)
    keep = largest_budget(keep)
    selections = select_hyperparameters(keep)
    chosen = selected_rows(keep, selections)
    out = []
    for s in selections:
        group = [
            r
            for r in chosen
            if (r["config"]["function"], int(r["config"]["dim"]), r["config"]["method"])
            == (s.function, s.dim, s.method)
        ]
        group.sort(key=lambda r: int(r["config"]["seed"]))
        values = curves(group)
        if regret:
            values = optimum_of(s.function, s.dim, instance) - values
        out.append(
            MethodCurves(s.function, s.dim, s.budget, s.method, s.best.label, values, instance)
        )
    return out


def _cells(data: Sequence[MethodCurves]) -> tuple[list[str], list[int]]:
    return function_order(c.function for c in data), sorted({c.dim for c in data})


def _instance(data: Sequence[MethodCurves]) -> int:
    """The one instance of ``data`` (figures and tables never mix instances)."""
    instances = sorted({c.instance for c in data})
    if len(instances) > 1:
        raise ValueError(
            f"curves of several test-function instances ({', '.join(map(str, instances))});"
            " draw one instance at a time (figure_data(..., instance=K))"
        )
    return instances[0] if instances else 0


def _instance_tag(instance: int) -> str:
    return f" (instance {instance})" if instance else ""


def method_colors(methods: Iterable[str]) -> dict[str, tuple[float, float, float, float]]:
    """A fixed colour per method (the paper's methods keep theirs in every figure)."""
    from matplotlib import colormaps

    cmap = colormaps["tab10"]
    rank = {m: i for i, m in enumerate(PAPER_METHODS)}
    extra = [m for m in method_order(methods) if m not in rank]
    for i, m in enumerate(extra):
        rank[m] = len(PAPER_METHODS) + i
    return {m: cmap(rank[m] % 10) for m in methods}


#: Fewest seeds for which a curve gets its confidence band: with two seeds the 95%
#: t-interval is :math:`\pm 12.7\, s/\sqrt 2`, wide enough to hide every other curve.
MIN_SEEDS_FOR_BAND = 3


def curve_style(n_seeds: int) -> tuple[str, bool]:
    """Line style of a mean curve over ``n_seeds`` seeds and whether it gets a band:
    solid with a band from :data:`MIN_SEEDS_FOR_BAND` seeds on, else dashed without."""
    return ("-", True) if n_seeds >= MIN_SEEDS_FOR_BAND else ("--", False)


def plot_figure3(
    data: Sequence[MethodCurves],
    path: str | Path,
    *,
    regret: bool = False,
    log: bool = False,
    dpi: int = 130,
) -> Path:
    """Draw the Figure-3 grid to a PNG at ``path`` and return the path.

    Each curve is the mean over seeds with its 95% t-band; curves from fewer than
    :data:`MIN_SEEDS_FOR_BAND` seeds are drawn dashed and without a band.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    if not data:
        raise ValueError(
            "no finished bbfo runs to plot (is the store empty or the filter too strict?)"
        )
    functions, dims = _cells(data)
    tag = _instance_tag(_instance(data))
    methods = method_order(c.method for c in data)
    colors = method_colors(methods)
    fig = Figure(figsize=(4.2 * len(dims), 3.2 * len(functions)), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(functions), len(dims), squeeze=False)
    handles: dict[str, Line2D] = {}
    for i, function in enumerate(functions):
        for j, dim in enumerate(dims):
            ax = axes[i][j]
            cell = [c for c in data if c.function == function and c.dim == dim]
            ax.set_title(f"{function.capitalize()} {dim}-D{tag}")
            if not cell:
                ax.text(0.5, 0.5, "no runs", ha="center", va="center", transform=ax.transAxes)
                ax.set_axis_off()
                continue
            for c in sorted(cell, key=lambda c: methods.index(c.method)):
                mean, half = t_interval(c.values)
                x = np.arange(1, mean.size + 1)
                style, band = curve_style(c.n_seeds)
                (line,) = ax.plot(x, mean, color=colors[c.method], lw=1.4, ls=style, label=c.method)
                if band and np.any(np.isfinite(half)):
                    ax.fill_between(
                        x, mean - half, mean + half, color=colors[c.method], alpha=0.2, lw=0
                    )
                handles.setdefault(c.method, line)
            if log:
                ax.set_yscale("log")
            ax.grid(alpha=0.3)
            if i == len(functions) - 1:
                ax.set_xlabel("evaluations")
            if j == 0:
                ax.set_ylabel("regret" if regret else "best value")
    order = [m for m in methods if m in handles]
    fig.legend(
        [handles[m] for m in order],
        order,
        loc="outside lower center",
        ncols=min(len(order), 9),
        frameon=False,
    )
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    return path


def _fmt(x: float) -> str:
    return "nan" if not math.isfinite(x) else f"{x:.4g}"


def final_table(data: Sequence[MethodCurves], *, regret: bool = False) -> str:
    """A markdown table of final values: one row per (function, dim), one column per method.

    Each cell is ``mean ± half-width (n)`` of the value after the last evaluation, with the
    95% t-interval; the best mean of each row (highest value, or lowest regret) is bold.
    """
    functions, dims = _cells(data)
    instance = _instance(data)
    methods = method_order(c.method for c in data)
    what = "final regret (lower is better)" if regret else "final best value (higher is better)"
    lines = [
        f"| function | dim | budget | {' | '.join(methods)} |",
        "| --- | ---: | ---: |" + " ---: |" * len(methods),
    ]
    for function in functions:
        for dim in dims:
            cell = {c.method: c for c in data if c.function == function and c.dim == dim}
            if not cell:
                continue
            stats = {}
            for m, c in cell.items():
                mean, half = t_interval(c.values[:, -1:])
                stats[m] = (float(mean[0]), float(half[0]), c.n_seeds)
            pick = min if regret else max
            best = pick(stats, key=lambda m: stats[m][0])
            budget = next(iter(cell.values())).budget
            cols = []
            for m in methods:
                if m not in stats:
                    cols.append("")
                    continue
                mean_, half_, n = stats[m]
                text = f"{_fmt(mean_)} ± {_fmt(half_)} ({n})"
                cols.append(f"**{text}**" if m == best else text)
            lines.append(f"| {function} | {dim} | {budget} | {' | '.join(cols)} |")
    note = (
        f"\n\n{what}: mean ± half-width of the 95% t-interval over seeds (number of seeds),"
        " each method with its selected hyperparameters; best mean in bold."
        + (
            f" Test functions of instance {instance}: optima shifted off the box centre"
            " (voot.functions)."
            if instance
            else ""
        )
    )
    return "\n".join(lines) + note


def settings_table(data: Sequence[MethodCurves]) -> str:
    """A markdown table of the selected hyperparameters plotted per cell."""
    lines = ["| function | dim | method | selected setting |", "| --- | ---: | --- | --- |"]
    methods = method_order(c.method for c in data)
    functions, _ = _cells(data)
    for c in sorted(
        data, key=lambda c: (functions.index(c.function), c.dim, methods.index(c.method))
    ):
        lines.append(f"| {c.function} | {c.dim} | {c.method} | {c.label} |")
    return "\n".join(lines)
