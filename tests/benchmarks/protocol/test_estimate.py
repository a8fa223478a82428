"""Tests of voot.bench.protocol.estimate: CPU-hours of a sweep from stored rows or a probe."""

from __future__ import annotations

from typing import Any

import pytest

from voot.bench.protocol.estimate import (
    PROBE_SIMULATIONS,
    CostLine,
    estimate,
    format_estimate,
    pair_of,
    probe_cost,
    stored_cost,
)
from voot.bench.store.format import Row, make_row
from voot.bench.sweep.plan import build_plan_specs


def stored(spec: Any, search_time: float, simulations: int | None = None) -> Row:
    config = spec.config()
    if simulations is not None:
        config = {**config, "simulations": simulations}
    return make_row(
        "plan",
        config,
        status="ok",
        wall_time=search_time,
        best_so_far=[0.0],
        search_time=search_time,
    )


def specs() -> list[Any]:
    return build_plan_specs(
        ["shekel_chain"], [3], ["voot", "hoot"], [0, 1], simulations=100, grid="default"
    )


def test_stored_cost_prefers_rows_of_the_same_budget() -> None:
    voot = specs()[0]
    pair = pair_of(voot)
    assert pair == ("shekel_chain", 3, "voot") and pair_of(stored(voot, 1.0)) == pair
    rows = [stored(voot, 2.0), stored(voot, 100.0, simulations=1000)]
    assert stored_cost(rows, pair, 100) == (0.02, 1)
    assert stored_cost(rows, pair, 500) == (102.0 / 1100, 2)  # none of 500: every row
    assert stored_cost(rows, ("shekel_chain", 3, "hoot"), 100) is None
    failed = {**stored(voot, 1.0), "status": "failed"}
    assert stored_cost([failed], pair, 100) is None


def test_probe_runs_a_short_unstored_copy() -> None:
    seen: list[Any] = []

    def run(spec: Any) -> Row:
        seen.append(spec)
        return {"status": "ok", "search_time": 0.5}

    assert probe_cost(specs()[0], 10, run) == 0.05
    assert seen[0].simulations == 10 and seen[0].planner == "voot"
    with pytest.raises(ValueError, match="the probe of voot on shekel_chain-3D failed: boom"):
        probe_cost(specs()[0], 10, lambda s: {"status": "failed", "error": "boom"})


def test_estimate_lines_sources_and_pending_runs() -> None:
    all_specs = specs()
    voot = [s for s in all_specs if s.planner == "voot"]
    rows = [stored(voot[0], 3.6)]  # 36 ms per simulation
    probes: list[int] = []

    def run(spec: Any) -> Row:
        probes.append(spec.simulations)
        return {"status": "ok", "search_time": 0.72 * spec.simulations / 100.0}

    pending = {s.run_id for s in all_specs} - {voot[0].run_id}
    lines = estimate(all_specs, rows, pending, run=run)
    assert [(c.planner, c.runs, c.pending, c.simulations) for c in lines] == [
        ("voot", 2, 1, 100),
        ("hoot", 2, 2, 200),
    ]
    assert lines[0].source == "store: 1 rows"
    assert lines[0].seconds_per_simulation == pytest.approx(0.036)
    assert lines[1].source == f"probe: {PROBE_SIMULATIONS} simulations"
    assert probes == [PROBE_SIMULATIONS]
    assert lines[1].cpu_hours == pytest.approx(200 * 0.0072 / 3600)
    with pytest.raises(ValueError, match="probe_simulations"):
        estimate(all_specs, rows, pending, probe_simulations=0, run=run)


def test_format_estimate_totals_and_wall_hours() -> None:
    lines = [
        CostLine("kitchen_v1", "voot", 20, 10, 7_200_000, 0.001, "store: 5 rows"),
        CostLine("kitchen_v1", "pw_uct", 20, 20, 3_600_000, 0.002, "probe: 20 simulations"),
    ]
    assert lines[0].cpu_hours == 2.0 and lines[1].cpu_hours == 2.0
    text = format_estimate(lines, 2)
    assert "| kitchen_v1 | voot | 20 | 10 | 7200000 | 1 | store: 5 rows | 2 |" in text
    assert "total: 30 runs to run, 4 CPU-hours; about 2 wall-hours on 2 workers" in text
    with pytest.raises(ValueError, match="workers"):
        format_estimate(lines, 0)
