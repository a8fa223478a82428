"""Tests of voot.bench.plan_runs: the statistics over seeds and the selection of plan rows."""

from __future__ import annotations

import math

import numpy as np
import pytest
from plan_fixtures import kitchen_rows, with_costs

from voot.bench.plan_runs import (
    first_reach,
    mean_ci,
    median_ci,
    plan_data,
    settled_reach,
)
from voot.bench.plot import t_interval


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


def test_first_and_settled_reach() -> None:
    left = np.array([[3.0, 0.0, 0.0], [np.nan, 2.0, 1.0]])
    assert list(first_reach(left)) == [2.0, math.inf]
    # the best plan clears everything at 2, leaves one again at 3, clears for good at 4
    wobble = np.array([[3.0, 0.0, 1.0, 0.0, 0.0], [0.0] * 5, [0.0, 0.0, 0.0, 0.0, 1.0]])
    assert list(first_reach(wobble)) == [2.0, 1.0, 1.0]
    assert list(settled_reach(wobble)) == [4.0, 1.0, math.inf]
    assert list(settled_reach(left)) == [2.0, math.inf]


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


def test_plan_data_reads_the_cost_curves_and_counts() -> None:
    rows = [
        with_costs(r, 3 if r["config"]["planner"] == "voot" else 1, 0.01) for r in kitchen_rows()
    ]
    voot = next(d for d in plan_data(rows) if d.planner == "voot")
    assert voot.calls is not None and voot.calls[0].tolist() == [3.0, 6.0, 9.0, 12.0]
    assert voot.n_feasibility_checks is not None and voot.n_feasibility_checks.tolist() == [8.0] * 3
    assert voot.axis_values("calls_curve") is voot.calls and voot.axis_values(None) is None


def test_plan_data_on_held_out_layouts() -> None:
    from plan_fixtures import LAYOUT_PROBLEM, layout_rows

    data = plan_data(layout_rows(), tuning_layouts=[1000, 1001])
    by = {d.planner: d for d in data}
    voot = by["voot"]
    assert voot.problem == LAYOUT_PROBLEM and voot.label == "omega=0.1"  # tuned on 1000-1001
    assert voot.layouts == (0, 0, 1, 1, 2, 2) and voot.seeds == (0, 1) * 3
    assert voot.has_layouts and voot.n_layouts == 3 and voot.n_units == 3 and voot.n_seeds == 6
    assert voot.tuning_layouts == (1000, 1001) and voot.tuning_seeds == ()
    units = voot.units(voot.returns)
    assert units[:, -1].tolist() == [2.0, 4.0, 6.0]  # per-layout means
    mean, half, n = mean_ci(units[:, -1:])
    assert mean[0] == 4.0 and n[0] == 3 and half[0] == pytest.approx(4.968, abs=1e-3)
    # a mask of the rows kept (a cost axis leaves out rows without its data)
    keep = np.array([True, False, True, True, True, True])
    assert voot.units(voot.returns[keep], keep)[:, -1].tolist() == [1.0, 4.0, 6.0]
    assert voot.unit_medians(np.array([1.0, 3.0, 4.0, 4.0, np.inf, np.inf])).tolist() == [
        2.0,
        4.0,
        np.inf,
    ]
    # pw_uct: one setting, tuned on the training layouts too
    assert by["pw_uct"].n_layouts == 3
    # per problem id, as plot --heldout gives them
    same = plan_data(layout_rows(), tuning_layouts={LAYOUT_PROBLEM: [1000, 1001]})
    assert [d.label for d in same] == [d.label for d in data]
    # the same-seed rule on every layout: one family, every layout pooled
    (all_voot,) = [d for d in plan_data(layout_rows()) if d.planner == "voot"]
    assert all_voot.label == "omega=0.3" and all_voot.n_layouts == 5
    # rows without layouts: the units are the seeds, as before
    plain = next(d for d in plan_data(kitchen_rows()) if d.planner == "voot")
    assert not plain.has_layouts and plain.layouts == () and plain.n_units == 3
    assert plain.units(plain.returns) is plain.returns
