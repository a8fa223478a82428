"""Tests of voot.bench.plan_plot: statistics, selection of plan rows, tables, figures."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from voot.bench.plan_plot import (
    calls_table,
    completion_table,
    cost_table,
    default_checkpoints,
    figure_caption,
    first_reach,
    mean_ci,
    median_ci,
    objects_table,
    on_time_grid,
    plan_data,
    plan_report,
    plan_settings_table,
    plot_plan_figure,
    returns_table,
    settled_reach,
)
from voot.bench.plot import t_interval
from voot.bench.store import Row, make_row


def plan_row(
    returns: list[float],
    *,
    planner: str,
    seed: int,
    problem: str = "voot/KitchenClearing-v0",
    dim: int | None = None,
    params: dict | None = None,
    left: list[float | None] | None = None,
    initial: float | None = 7.0,
    ms: float = 10.0,
) -> Row:
    config = {
        "problem": problem,
        "dim": dim,
        "env_kwargs": {},
        "planner": planner,
        "params": params or {},
        "simulations": len(returns),
        "seed": seed,
        "protocol": 1,
    }
    extra: dict = {
        "elapsed": [ms / 1000.0 * (i + 1) for i in range(len(returns))],
        "simulator_calls": 2 * len(returns),
    }
    if left is not None:
        extra.update(objects_left=left, objects_initial=initial)
    return make_row("plan", config, status="ok", wall_time=1.0, best_so_far=returns, **extra)


def kitchen_rows() -> list[Row]:
    rows = []
    for seed in range(3):
        # voot: two settings, omega=0.1 is better; it clears everything at simulation 2 or 3
        rows.append(
            plan_row(
                [0.0, 1.0, 2.0 + seed, 3.0],
                planner="voot",
                seed=seed,
                params={"omega": 0.1},
                left=[None, 3.0, 0.0 if seed else 1.0, 0.0],
            )
        )
        rows.append(
            plan_row(
                [0.0, 0.0, 0.0, 0.5],
                planner="voot",
                seed=seed,
                params={"omega": 0.3},
                left=[7.0, 7.0, 7.0, 6.0],
            )
        )
        # pw_uct never clears the path and takes twice as long per simulation
        rows.append(
            plan_row([0.0, 0.5, 0.5, 1.0], planner="pw_uct", seed=seed, left=[7, 6, 5, 5], ms=20.0)
        )
        rows.append(
            plan_row(
                [-1.0, -0.5, -0.2, -0.1], planner="voot", seed=seed, problem="shekel_chain", dim=10
            )
        )
    return rows


def test_mean_ci_matches_t_interval_and_ignores_nan() -> None:
    x = np.array([[1.0, 2.0], [3.0, 2.0], [5.0, 8.0]])
    mean, half, n = mean_ci(x)
    m2, h2 = t_interval(x)
    assert np.allclose(mean, m2) and np.allclose(half, h2) and list(n) == [3, 3]
    y = np.array([[1.0, np.nan], [3.0, np.nan], [np.nan, 4.0]])
    mean, half, n = mean_ci(y)
    assert list(n) == [2, 1] and mean[0] == 2.0 and mean[1] == 4.0
    assert half[0] == pytest.approx(12.7062047, rel=1e-6) and np.isnan(half[1])
    with pytest.raises(ValueError, match="confidence"):
        mean_ci(x, confidence=0.0)


def test_median_ci_order_statistics() -> None:
    values = np.arange(1.0, 21.0)  # n = 20: ranks 6 and 15
    med, lo, hi = median_ci(values)
    assert med == 10.5 and lo == 6.0 and hi == 15.0
    med, lo, hi = median_ci([3.0, 1.0, 2.0])  # too few for a 95% interval
    assert med == 2.0 and math.isnan(lo) and math.isnan(hi)
    med, *_ = median_ci([1.0, math.inf, math.inf])  # most seeds never got there
    assert math.isinf(med)
    assert all(math.isnan(v) for v in median_ci([]))


def test_first_reach_and_time_grid() -> None:
    left = np.array([[3.0, 0.0, 0.0], [np.nan, 2.0, 1.0]])
    assert list(first_reach(left)) == [2.0, math.inf]
    # the best plan clears everything at 2, leaves one again at 3, clears for good at 4
    wobble = np.array([[3.0, 0.0, 1.0, 0.0, 0.0], [0.0] * 5, [0.0, 0.0, 0.0, 0.0, 1.0]])
    assert list(first_reach(wobble)) == [2.0, 1.0, 1.0]
    assert list(settled_reach(wobble)) == [4.0, 1.0, math.inf]
    assert list(settled_reach(left)) == [2.0, math.inf]
    values = np.array([[1.0, 2.0, 3.0], [10.0, 20.0, 30.0]])
    elapsed = np.array([[0.1, 0.2, 0.3], [0.2, 0.4, 0.6]])
    times, samples = on_time_grid(values, elapsed, points=3)
    assert np.allclose(times, [0.2, 0.25, 0.3])  # from the last first to the first last
    assert samples[0].tolist() == [2.0, 2.0, 3.0] and samples[1].tolist() == [10.0, 10.0, 10.0]
    empty_t, empty = on_time_grid(values, np.full((2, 3), np.nan))
    assert empty_t.size == 0 and empty.shape == (2, 0)


def test_plan_data_selects_and_stacks() -> None:
    data = plan_data(kitchen_rows())
    by = {(d.problem, d.planner): d for d in data}
    assert set(by) == {("kitchen", "voot"), ("kitchen", "pw_uct"), ("shekel_chain", "voot")}
    voot = by[("kitchen", "voot")]
    assert voot.label == "omega=0.1" and voot.seeds == (0, 1, 2) and voot.title == "kitchen"
    assert voot.returns.shape == (3, 4) and voot.objects_left is not None
    assert np.isnan(voot.objects_left[0, 0]) and list(voot.objects_initial) == [7.0] * 3
    chain = by[("shekel_chain", "voot")]
    assert chain.dim == 10 and chain.title == "shekel_chain 10-D" and chain.objects_left is None
    only = plan_data(kitchen_rows(), problems=["kitchen"], planners=["pw_uct"])
    assert [(d.problem, d.planner) for d in only] == [("kitchen", "pw_uct")]


def test_tables() -> None:
    data = plan_data(kitchen_rows())
    assert default_checkpoints(10_000) == [1000, 3000, 10_000]
    assert default_checkpoints(2000) == [1000, 2000] and default_checkpoints(4) == [4]
    ret = returns_table(data, at=[2, 4])
    assert "| problem | simulations | voot | pw_uct |" in ret
    assert "| kitchen | 4 | **3 ± 0 (3)** | 1 ± 0 (3) |" in ret
    assert "| shekel_chain 10-D | 2 | **-0.5 ± 0 (3)** |  |" in ret
    obj = objects_table(data, at=[2])
    assert "| kitchen | 2 | **4 ± 0 (3)** | 1 ± 0 (3) |" in obj and "shekel" not in obj
    done = completion_table(data)
    assert "| kitchen | voot | 3/3 (100%) | 3 | — | 3/3 (100%) | 3 | — |" in done
    assert "| kitchen | pw_uct | 0/3 (0%) | > 4 | — | 0/3 (0%) | > 4 | — |" in done
    cost = cost_table(data)
    assert "| kitchen | voot | 10 | 2 | 0.04 |" in cost and "| kitchen | pw_uct | 20 |" in cost
    assert "| kitchen | voot | omega=0.1 | 3 |" in plan_settings_table(data)
    report = plan_report(data)
    for title in (
        "### Best return",
        "### Objects handled",
        "### Simulations to handle",
        "### Cost",
    ):
        assert title in report
    chain_only = plan_data(kitchen_rows(), problems=["shekel_chain"])
    assert objects_table(chain_only) == "" and completion_table(chain_only) == ""
    assert "### Objects handled" not in plan_report(chain_only)


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

    from voot.bench import plan_plot

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
    data = plan_plot.plan_data(few + many)
    captured = {}
    original = Figure.savefig

    def spy(self: Figure, *args: object, **kwargs: object) -> object:
        captured["fig"] = self
        return original(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Figure, "savefig", spy)
    plan_plot.plot_plan_figure(data, tmp_path / "f.png")
    ax_objects = captured["fig"].axes[1]
    bands = [c for c in ax_objects.collections if isinstance(c, PolyCollection)]
    assert len(bands) == 1  # only the 4-seed planner has a band
    ys = np.concatenate([p.vertices[:, 1] for p in bands[0].get_paths()])
    assert ys.min() >= 0.0 and ys.max() <= 7.0


def _with_costs(r: Row, calls_per_sim: int, cpu_per_sim: float) -> Row:
    n = len(r["best_so_far"])
    out = dict(r)
    out["calls_curve"] = [calls_per_sim * (i + 1) for i in range(n)]
    out["cpu_elapsed"] = [cpu_per_sim * (i + 1) for i in range(n)]
    out["n_steps"] = n
    out["n_feasibility_checks"] = (calls_per_sim - 1) * n
    return out


def test_cost_axes_figures_tables_and_captions(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The calls and CPU axes read each seed's own costs; a planner's x range ends where
    its seeds end; rows lacking the keys say so instead of drawing a curve."""
    from matplotlib.figure import Figure

    from voot.bench import plan_plot

    rows = [
        _with_costs(r, 3 if r["config"]["planner"] == "voot" else 1, 0.01) for r in kitchen_rows()
    ]
    data = plan_data(rows)
    voot = next(d for d in data if d.planner == "voot")
    assert voot.calls is not None and voot.calls[0].tolist() == [3.0, 6.0, 9.0, 12.0]
    assert voot.n_feasibility_checks is not None and voot.n_feasibility_checks.tolist() == [8.0] * 3
    captured: list[Figure] = []
    original = Figure.savefig

    def spy(self: Figure, *args: object, **kwargs: object) -> object:
        captured.append(self)
        return original(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Figure, "savefig", spy)
    plan_plot.plot_plan_figure(data, tmp_path / "calls.png", x="calls", note="a note")
    ax = captured[-1].axes[0]
    ends = {line.get_label(): max(line.get_xdata()) for line in ax.get_lines()}
    assert ends["voot"] == 12.0 and ends["pw_uct"] == 4.0  # 3 calls per simulation vs 1
    labels = {a.get_xlabel() for a in captured[-1].axes}
    assert labels == {"", "simulator calls (steps + pre-checks)"}
    assert captured[-1].get_suptitle() == "a note"
    plan_plot.plot_plan_figure(data, tmp_path / "cpu.png", x="cpu")
    assert "CPU seconds" in {a.get_xlabel() for a in captured[-1].axes}
    # an older store: no calls_curve, no cpu_elapsed
    plan_plot.plot_plan_figure(plan_data(kitchen_rows()), tmp_path / "old.png", x="calls")
    texts = [t.get_text() for t in captured[-1].axes[0].texts]
    assert any("lack calls_curve" in t for t in texts) and not captured[-1].axes[0].get_lines()
    plan_plot.plot_plan_figure(plan_data(kitchen_rows()), tmp_path / "old-sims.png")
    assert captured[-1].axes[0].get_lines()  # still drawn against simulations

    table = calls_table(data)
    assert "| kitchen | voot | 1 | 2 | 2 | 3/3 |" in table
    assert "| kitchen | pw_uct | 1 | 0 | 0 | 3/3 |" in table
    assert "| kitchen | voot | 1 | 2 | 2 | 0/3 |" in calls_table(
        plan_data([{**r, "n_steps": 4, "n_feasibility_checks": 8} for r in kitchen_rows()])
    )
    caption = figure_caption(data, "calls")
    assert "steps and the kinematic pre-checks counted together" in caption
    assert "keeps its final value" in caption and "the paper's rule" in caption
    assert "lack" not in caption
    old_caption = figure_caption(plan_data(kitchen_rows()), "cpu")
    assert "9 of 9 runs lack cpu_elapsed (written before it was recorded)" in old_caption
    tuned = plan_data(
        rows + [{**r, "config": {**r["config"], "seed": 1000 + r["config"]["seed"]}} for r in rows],
        tuning_seeds=[1000, 1001, 1002],
    )
    assert all(d.tuning_seeds == (1000, 1001, 1002) for d in tuned)
    assert (
        "Settings selected on tuning seeds 1000-1002, disjoint from the evaluation seeds."
        in figure_caption(tuned, "simulations")
    )
    report = plan_report(tuned)
    assert report.startswith("### Protocol") and "evaluation seeds only" in report
    with pytest.raises(ValueError, match="valid axes"):
        figure_caption(data, "hours")
