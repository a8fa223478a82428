"""Tests of voot.bench.report.plan_tables: the markdown tables, the report and the figure captions."""

from __future__ import annotations

import pytest
from plan_fixtures import kitchen_rows, with_costs

from voot.bench.report.plan_runs import plan_data
from voot.bench.report.plan_tables import (
    calls_table,
    completion_table,
    cost_table,
    default_checkpoints,
    figure_caption,
    objects_table,
    plan_report,
    plan_settings_table,
    returns_table,
)


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


def test_calls_table_captions_and_the_tuned_report() -> None:
    rows = [
        with_costs(r, 3 if r["config"]["planner"] == "voot" else 1, 0.01) for r in kitchen_rows()
    ]
    data = plan_data(rows)
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


def test_tables_on_held_out_layouts_take_the_layout_as_the_unit() -> None:
    from plan_fixtures import LAYOUT_LABEL, layout_rows

    data = plan_data(layout_rows(), tuning_layouts=[1000, 1001])
    ret = returns_table(data, at=[3])
    assert f"| {LAYOUT_LABEL} | 3 | **4 ± 4.968 (3)** | 1 ± 0 (3) |" in ret
    assert "over the per-layout means (number of layouts" in ret
    done = completion_table(data)
    # voot clears on seed 0 of every layout at simulation 3, never on seed 1: per-layout
    # medians are inf, so the median is too
    assert f"| {LAYOUT_LABEL} | voot | 3/6 (50%) | > 3 |" in done
    assert "over the per-layout medians" in done
    caption = figure_caption(data, "simulations")
    assert "mean over 6 (layout, seed) runs on 3 layouts" in caption
    assert "Settings selected on training layouts 1000-1001, disjoint from the held-out" in caption
    assert f"| {LAYOUT_LABEL} | voot | omega=0.1 | 3 layouts, 6 runs |" in plan_settings_table(data)
    report = plan_report(data)
    assert report.startswith("### Protocol") and "report the held-out layouts only" in report
