"""Tests of voot.bench.measure.memory: checkpoints of a real (short) search, the growth ratio, the
table, and a clear error for a planner without a tree."""

from __future__ import annotations

import pytest

from voot.bench.measure.memory import (
    MemoryCase,
    MemoryPoint,
    format_cases,
    growth_ratio,
    measure_cases,
    measure_search_memory,
)


def test_a_chain_search_is_measured_at_its_checkpoints() -> None:
    case = measure_search_memory("shekel_chain", "voot", 60, checkpoints=3)
    assert [p.simulations for p in case.points] == [20, 40, 60]
    nodes = [p.nodes for p in case.points]
    assert nodes == sorted(nodes) and nodes[0] > 1  # the tree grows
    assert all(p.traced_bytes > 0 and p.traced_peak_bytes >= p.traced_bytes for p in case.points)
    assert all(p.rss_bytes > 0 for p in case.points) and case.max_rss_bytes > 0
    assert case.growth_ratio == growth_ratio(case.points) > 0


def test_growth_ratio_tells_linear_from_quadratic() -> None:
    linear = [MemoryPoint(n, n, 1000 * n, 1000 * n, 1) for n in (10, 20, 30, 40)]
    quadratic = [MemoryPoint(n, n, 10 * n * n, 10 * n * n, 1) for n in (10, 20, 30, 40)]
    assert growth_ratio(linear) == pytest.approx(1.0)
    assert growth_ratio(quadratic) == pytest.approx(2.0)  # 40 / 20
    assert growth_ratio(linear[:1]) != growth_ratio(linear[:1])  # NaN: one point


def test_format_cases_prints_every_checkpoint() -> None:
    points = (MemoryPoint(5, 7, 7000, 8000, 2**20), MemoryPoint(10, 14, 14000, 15000, 2**21))
    text = format_cases([MemoryCase("kitchen_v1", "voot", 0, points, 2**21)])
    assert "voot on kitchen_v1, seed 0" in text
    assert "| 10 | 14 |" in text and "| 1000 |" in text  # bytes per node
    assert "mid-search: 1.00" in text


def test_measure_cases_runs_each_planner_in_its_own_process() -> None:
    cases = measure_cases("shekel_chain", ["voot", "pw_uct"], 10, checkpoints=1)
    assert [c.planner for c in cases] == ["voot", "pw_uct"]
    assert [len(c.points) for c in cases] == [1, 1]


def test_a_planner_without_a_tree_is_a_clear_error() -> None:
    with pytest.raises(ValueError, match="does not build a search tree"):
        measure_search_memory("shekel_chain", "random_shooting", 10)


@pytest.mark.parametrize("kwargs", [{"simulations": 0}, {"checkpoints": 0}])
def test_bad_counts(kwargs: dict[str, int]) -> None:
    with pytest.raises(ValueError):
        measure_search_memory("shekel_chain", "voot", **kwargs)
