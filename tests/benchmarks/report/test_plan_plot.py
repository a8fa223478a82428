"""Tests of voot.bench.report.plan_plot: the wall-clock grid and the Figure-4 drawings (simulations,
seconds and the cost axes; the objects band)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from plan_fixtures import kitchen_rows, plan_row, with_costs

from voot.bench.report.plan_plot import on_time_grid, plot_plan_figure
from voot.bench.report.plan_runs import plan_data


def test_time_grid() -> None:
    values = np.array([[1.0, 2.0, 3.0], [10.0, 20.0, 30.0]])
    elapsed = np.array([[0.1, 0.2, 0.3], [0.2, 0.4, 0.6]])
    times, samples = on_time_grid(values, elapsed, points=3)
    assert np.allclose(times, [0.2, 0.25, 0.3])  # from the last first to the first last
    assert samples[0].tolist() == [2.0, 2.0, 3.0] and samples[1].tolist() == [10.0, 10.0, 10.0]
    empty_t, empty = on_time_grid(values, np.full((2, 3), np.nan))
    assert empty_t.size == 0 and empty.shape == (2, 0)


def test_figures(tmp_path: Path) -> None:
    data = plan_data(kitchen_rows())
    png = plot_plan_figure(data, tmp_path / "sub" / "fig4.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    secs = plot_plan_figure(data, tmp_path / "fig4-seconds.png", x="seconds")
    assert secs.stat().st_size > 10_000
    with pytest.raises(ValueError, match="no finished plan runs"):
        plot_plan_figure([], tmp_path / "empty.png")
    with pytest.raises(ValueError, match="x must be one of simulations, calls, cpu, seconds"):
        plot_plan_figure(data, tmp_path / "bad.png", x="hours")


def test_objects_band_stays_in_the_count_and_few_seeds_get_no_band(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With 2 seeds a t-band on 'objects left' ran from -20 to +40 for a count in [0, 7]."""
    from matplotlib.collections import PolyCollection
    from matplotlib.figure import Figure

    rng = np.random.default_rng(0)
    few = [
        plan_row(rng.uniform(-2, 0, 30).tolist(), planner="voot", seed=s, left=[7.0, 3.0] * 15)
        for s in range(2)
    ]
    many = [
        plan_row(
            rng.uniform(-2, 0, 30).tolist(), planner="pw_uct", seed=s, left=[7.0 * (s % 2)] * 30
        )
        for s in range(4)
    ]
    data = plan_data(few + many)
    captured = {}
    original = Figure.savefig

    def spy(self: Figure, *args: object, **kwargs: object) -> object:
        captured["fig"] = self
        return original(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Figure, "savefig", spy)
    plot_plan_figure(data, tmp_path / "f.png")
    ax_objects = captured["fig"].axes[1]
    bands = [c for c in ax_objects.collections if isinstance(c, PolyCollection)]
    assert len(bands) == 1  # only the 4-seed planner has a band
    ys = np.concatenate([p.vertices[:, 1] for p in bands[0].get_paths()])
    assert ys.min() >= 0.0 and ys.max() <= 7.0


def test_cost_axes_figures(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The calls and CPU axes read each seed's own costs; a planner's x range ends where
    its seeds end; rows lacking the keys say so instead of drawing a curve."""
    from matplotlib.figure import Figure

    rows = [
        with_costs(r, 3 if r["config"]["planner"] == "voot" else 1, 0.01) for r in kitchen_rows()
    ]
    data = plan_data(rows)
    captured: list[Figure] = []
    original = Figure.savefig

    def spy(self: Figure, *args: object, **kwargs: object) -> object:
        captured.append(self)
        return original(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Figure, "savefig", spy)
    plot_plan_figure(data, tmp_path / "calls.png", x="calls", note="a note")
    ax = captured[-1].axes[0]
    ends = {line.get_label(): max(line.get_xdata()) for line in ax.get_lines()}
    assert ends["voot"] == 12.0 and ends["pw_uct"] == 4.0  # 3 calls per simulation vs 1
    labels = {a.get_xlabel() for a in captured[-1].axes}
    assert labels == {"", "simulator calls (steps + pre-checks)"}
    assert captured[-1].get_suptitle() == "a note"
    plot_plan_figure(data, tmp_path / "cpu.png", x="cpu")
    assert "CPU seconds" in {a.get_xlabel() for a in captured[-1].axes}
    # an older store: no calls_curve, no cpu_elapsed
    plot_plan_figure(plan_data(kitchen_rows()), tmp_path / "old.png", x="calls")
    texts = [t.get_text() for t in captured[-1].axes[0].texts]
    assert any("lack calls_curve" in t for t in texts) and not captured[-1].axes[0].get_lines()
    plot_plan_figure(plan_data(kitchen_rows()), tmp_path / "old-sims.png")
    assert captured[-1].axes[0].get_lines()  # still drawn against simulations


def test_figures_of_held_out_layouts(tmp_path: Path) -> None:
    from plan_fixtures import layout_rows

    rows = [with_costs(r, 2, 0.01) for r in layout_rows()]
    rows[-1] = {k: v for k, v in rows[-1].items() if k != "calls_curve"}  # one lacks the curve
    data = plan_data(rows, tuning_layouts=[1000, 1001])
    for x in ("simulations", "seconds", "calls", "cpu"):
        png = plot_plan_figure(data, tmp_path / f"{x}.png", x=x)
        assert png.stat().st_size > 10_000
