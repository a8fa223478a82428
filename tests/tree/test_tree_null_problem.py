"""Tests of voot.tree.null_problem: the problem with a nearly free step."""

from __future__ import annotations

import numpy as np
import pytest

from voot.tree.null_problem import NullProblem


def test_null_problem_rewards_peak_at_the_optimum() -> None:
    p = NullProblem(4)
    assert p.step(p.optimum).reward == 1.0
    assert 0.0 <= p.step(np.full(4, -1.0)).reward < 1.0
    assert p.snapshot() is None and p.action_bounds().dim == 4
    with pytest.raises(ValueError, match="dim"):
        NullProblem(0)
