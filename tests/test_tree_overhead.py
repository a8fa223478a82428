"""Tests of voot.tree.overhead: the null problem and the overhead command."""

from __future__ import annotations

import numpy as np
import pytest

from voot.tree.overhead import NullProblem, main, measure


def test_null_problem_rewards_peak_at_the_optimum() -> None:
    p = NullProblem(4)
    assert p.step(p.optimum).reward == 1.0
    assert 0.0 <= p.step(np.full(4, -1.0)).reward < 1.0
    assert p.snapshot() is None and p.action_bounds().dim == 4
    with pytest.raises(ValueError, match="dim"):
        NullProblem(0)


def test_measure_counts_visits() -> None:
    row = measure("voot", 3, 50, depth=5)
    assert row["node_visits"] == 250 and row["simulations"] == 50
    assert float(row["us_per_visit"]) > 0


def test_main_prints_a_table(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--planners", "voot", "hoot", "--dims", "2", "--simulations", "20"]) == 0
    out = capsys.readouterr().out
    assert "us/visit" in out and "voot" in out and "hoot" in out
