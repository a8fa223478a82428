"""Tests of voot.bench.protocol.ladder: the verdicts and the planner table (pure), and one small
measured ladder on a generated family."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from voot.bench.protocol import ladder


def test_monotone_orders_levels_and_refuses_missing_data() -> None:
    assert ladder.monotone([0.5, 0.3, 0.1])
    assert ladder.monotone([0.5, 0.5, 0.1])  # a tie is not easier
    assert not ladder.monotone([0.3, 0.5, 0.1])
    assert ladder.monotone([0.1, 0.3], decreasing=False)
    assert not ladder.monotone([0.5, math.nan, 0.1])


def _row(planner: str, level: str, left: float, *, status: str = "ok", **cfg: Any) -> dict:
    return {
        "status": status,
        "objects_initial": 4.0,
        "objects_left": np.array([4.0, 2.0, left]),
        "config": {
            "problem": "voot/KitchenClearing-v2",
            "planner": planner,
            "env_kwargs": {"layout_seed": 0, "difficulty": level},
            **cfg,
        },
    }


def test_planner_levels_counts_solved_runs_per_level() -> None:
    rows = [
        _row("voot", "easy", 0.0),
        _row("voot", "easy", 1.0),
        _row("voot", "hard", 2.0),
        _row("pw_uct", "medium", 0.0, variant="pw_authors"),
        _row("voot", "easy", 0.0, status="error"),  # failed: left out
        {**_row("voot", "easy", 0.0), "objects_left": None},  # no curve: left out
        {**_row("voot", "easy", 0.0), "config": {"problem": "other", "planner": "voot"}},
    ]
    out = ladder.planner_levels(rows, "voot/KitchenClearing-v2")
    got = [(p.planner, p.level, p.runs, p.solved, p.handled) for p in out]
    assert got == [
        ("pw_uct[pw_authors]", "medium", 1, 1, 1.0),
        ("voot", "easy", 2, 1, pytest.approx(0.875)),
        ("voot", "hard", 1, 0, 0.5),
    ]
    lo, hi = out[1].interval()
    assert 0.0 < lo < 0.5 < hi < 1.0


def test_level_stats_refuses_bad_arguments() -> None:
    with pytest.raises(ValueError, match="samples"):
        ladder.level_stats("voot/KitchenClearing-v2", "easy", samples=0)
    with pytest.raises(ValueError, match="at least one layout"):
        ladder.level_stats("voot/KitchenClearing-v2", "easy", layouts=())


def test_a_small_ladder_of_generated_kitchens_is_measured_and_reproducible() -> None:
    a = ladder.level_stats("voot/KitchenClearing-v2", "easy", layouts=(0,), samples=20, rollouts=2)
    assert a.layouts == (0,) and a.rollouts == 2 and set(a.precheck) == {"pick", "place"}
    for node in ("pick", "place"):
        assert 0 <= a.executed[node] <= a.precheck[node] <= 20
    assert 0.0 <= a.feasible_share <= 1.0 and 0.0 <= a.handled <= 1.0
    b = ladder.level_stats("voot/KitchenClearing-v2", "easy", layouts=(0,), samples=20, rollouts=2)
    assert a == b  # same arguments, same numbers


def test_the_report_gives_a_verdict_per_statistic() -> None:
    rows = [_row("voot", "easy", 0.0), _row("voot", "hard", 0.0)]
    text = ladder.ladder_report(
        "voot/KitchenClearing-v2", ("easy", "hard"), (0,), samples=10, rollouts=1, rows=rows
    )
    assert "| voot | easy | 1 | 100%" in text
    assert "- objects handled by voot: yes (100.0% / 100.0%)" in text
    assert "- feasible share of uniform actions:" in text
