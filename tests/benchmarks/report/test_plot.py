"""Tests of voot.bench.report.bbfo_plot: confidence intervals, the figure, the table of final values."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from voot.bench.report.bbfo_plot import (
    MIN_SEEDS_FOR_BAND,
    curve_style,
    figure_data,
    final_table,
    plot_figure3,
    settings_table,
    t_interval,
)
from voot.bench.store.format import Row, make_row
from voot.functions import get_function


def curve_row(
    curve: list[float], *, method: str, seed: int, params: dict | None = None, dim: int = 3
) -> Row:
    config = {
        "function": "rastrigin",
        "dim": dim,
        "method": method,
        "params": params or {},
        "budget": len(curve),
        "seed": seed,
        "protocol": 1,
    }
    return make_row("bbfo", config, status="ok", wall_time=0.1, best_so_far=curve)


def rows_fixture() -> list[Row]:
    rows = []
    for seed in range(3):
        rows.append(
            curve_row([-9.0, -5.0, -1.0 - seed], method="voo", seed=seed, params={"omega": 0.1})
        )
        rows.append(curve_row([-9.0, -8.0, -7.0], method="voo", seed=seed, params={"omega": 0.5}))
        rows.append(curve_row([-9.0, -6.0, -4.0 - seed], method="random", seed=seed))
        rows.append(curve_row([-3.0, -2.0, -1.0], method="random", seed=seed, dim=10))
    return rows


def test_t_interval_matches_the_t_quantile() -> None:
    samples = np.array([[1.0, 0.0], [3.0, 0.0]])
    mean, half = t_interval(samples)
    assert np.allclose(mean, [2.0, 0.0])
    # n = 2: t_{0.975, 1} = 12.7062..., s = sqrt(2), half = t * s / sqrt(2)
    assert half[0] == pytest.approx(12.7062047, rel=1e-6)
    assert half[1] == 0.0
    mean1, half1 = t_interval(np.array([[5.0]]))
    assert mean1[0] == 5.0 and np.isnan(half1[0])
    with pytest.raises(ValueError, match="confidence"):
        t_interval(samples, confidence=1.5)


def test_figure_data_uses_selected_settings_and_regret() -> None:
    data = figure_data(rows_fixture())
    cells = {(c.dim, c.method): c for c in data}
    assert set(cells) == {(3, "voo"), (3, "random"), (10, "random")}
    voo = cells[(3, "voo")]
    assert voo.label == "omega=0.1" and voo.n_seeds == 3
    assert np.array_equal(voo.values[:, -1], [-1.0, -2.0, -3.0])
    regret = figure_data(rows_fixture(), regret=True, methods=["voo"])
    optimum = get_function("rastrigin", 3).optimum_value
    assert np.allclose(regret[0].values, optimum - voo.values)
    assert figure_data(rows_fixture(), dims=[10])[0].dim == 10


def test_final_table_marks_the_best_mean() -> None:
    data = figure_data(rows_fixture())
    table = final_table(data)
    line3 = next(line for line in table.splitlines() if line.startswith("| rastrigin | 3 |"))
    assert "**-2 ± " in line3  # voo mean -2 beats random mean -5
    assert "-5 ± " in line3 and "(3)" in line3
    regret_table = final_table(figure_data(rows_fixture(), regret=True), regret=True)
    assert "lower is better" in regret_table
    assert "| rastrigin | 3 | voo | omega=0.1 |" in settings_table(data)


def test_plot_writes_a_png(tmp_path: Path) -> None:
    out = plot_figure3(figure_data(rows_fixture()), tmp_path / "sub" / "fig.png")
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    log = plot_figure3(
        figure_data(rows_fixture(), regret=True), tmp_path / "regret.png", regret=True, log=True
    )
    assert log.stat().st_size > 10_000
    with pytest.raises(ValueError, match="no finished bbfo runs"):
        plot_figure3([], tmp_path / "empty.png")


def test_curves_from_few_seeds_are_dashed_without_a_band() -> None:
    assert MIN_SEEDS_FOR_BAND == 3
    assert curve_style(2) == ("--", False) and curve_style(1) == ("--", False)
    assert curve_style(3) == ("-", True) and curve_style(20) == ("-", True)


def test_instances_are_plotted_apart(tmp_path: Path) -> None:
    moved = [
        make_row(
            "bbfo",
            {**r["config"], "instance": 2},
            status="ok",
            wall_time=0.1,
            best_so_far=list(r["best_so_far"]),
        )
        for r in rows_fixture()
    ]
    with pytest.raises(ValueError, match=r"several test-function instances \(0, 2\)"):
        figure_data(rows_fixture() + moved)
    data = figure_data(rows_fixture() + moved, instance=2, regret=True)
    assert {c.instance for c in data} == {2}
    optimum = get_function("rastrigin", 3, instance=2).optimum_value
    voo = next(c for c in data if (c.dim, c.method) == (3, "voo"))
    assert np.array_equal(voo.values[:, -1], optimum - np.array([-1.0, -2.0, -3.0]))
    assert "instance 2" in final_table(data, regret=True)
    assert "instance" not in final_table(figure_data(rows_fixture(), instance=0))
    assert plot_figure3(data, tmp_path / "moved.png").stat().st_size > 10_000
    with pytest.raises(ValueError, match="draw one instance at a time"):
        final_table(figure_data(rows_fixture()) + data)
