"""Tests of voot.bench.leaderboard.scores: reading a run at a matched budget, the matched
points, bounded scores, coverage and the (runs, tasks) arrays."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from leaderboard_fixtures import tiny_store, tiny_suite_file

from voot.bench.leaderboard import scores as S
from voot.bench.leaderboard.suite import load_suite
from voot.bench.store.result_store import ResultStore


def row(calls: list[float], cpu: list[float], left: list[Any], ret: list[float]) -> dict[str, Any]:
    return {
        "run_id": "r",
        "calls_curve": calls,
        "cpu_elapsed": cpu,
        "objects_left": left,
        "objects_initial": 4,
        "best_so_far": ret,
    }


def test_value_at_is_the_last_simulation_within_the_budget() -> None:
    cost = np.array([3.0, 5.0, 9.0])
    assert S.value_at(cost, 2.9) == -1
    assert S.value_at(cost, 3.0) == 0
    assert S.value_at(cost, 8.0) == 1
    assert S.value_at(cost, 100.0) == 2


def test_matched_points_are_the_most_frugal_entrys_median() -> None:
    a = [("a", row([1, 10], [0.1, 1.0], [4, 4], [0, 0])) for _ in range(3)]
    b = [("b", row([5, c], [0.5, 2.0], [4, 2], [0, 1])) for c in (20, 30, 40)]
    pts = S.matched_points([*a, *b])
    assert pts == {S.Budget.CALLS: 10.0, S.Budget.CPU: 1.0}
    with pytest.raises(ValueError, match="no runs"):
        S.matched_points([])


def test_the_fraction_handled_stays_in_its_bounds() -> None:
    r = row([1, 2, 3], [1, 2, 3], [None, 3, -1], [0, 1, 2])
    assert S._handled(r, -1) == 0.0  # nothing simulated yet
    assert S._handled(r, 0) == 0.0  # no leaf yet (NaN)
    assert S._handled(r, 1) == 0.25
    assert S._handled(r, 2) == 1.0  # clipped
    with pytest.raises(ValueError, match="objects_initial"):
        S._handled({**r, "objects_initial": 0}, 1)


def test_scores_and_coverage_of_the_tiny_store(tmp_path: Path) -> None:
    suite = load_suite(str(tiny_suite_file()))
    rows = ResultStore(tiny_store(tmp_path), create=False).load(kind="plan", arrays=True)
    cov = S.coverage(suite, suite.entries, rows)
    cell = ("voot/GeneratedKitchen-v0", "easy")
    assert cov.complete == (cell,) and cov.finished_runs == 4
    scores, points = S.run_scores(suite, suite.entries, rows, [cell])
    assert len(scores) == 4  # evaluation runs only, no tuning run
    assert {s.layout for s in scores} == {0, 1}
    assert points[cell][S.Budget.CALLS] > 0
    for s in scores:
        assert all(0.0 <= v <= 1.0 for v in s.handled.values())
        assert s.handled[S.Budget.SIMULATIONS] >= s.handled[S.Budget.CALLS]
    m = S.score_matrix(scores, "random_shooting", [cell], S.Budget.CALLS)
    assert m.shape == (2, 1)
    partial = [
        r
        for r in rows
        if r["config"]["planner"] != "doot" or r["config"]["env_kwargs"]["layout_seed"] != 0
    ]
    assert S.coverage(suite, suite.entries, partial).complete == ()
