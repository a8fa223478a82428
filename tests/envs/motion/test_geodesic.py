"""Tests of voot.envs.motion.geodesic: lattice distances around obstacles."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voot.envs.motion.footprint_astar import numba_available
from voot.envs.motion.geodesic import geodesic_steps


def test_geodesic_steps_follow_the_walls() -> None:
    passable = np.ones((5, 7), dtype=bool)
    passable[2, 1:] = False  # a wall across row 2, open at column 0
    passable[4, 6] = False
    d = geodesic_steps(passable, 0, 6)
    assert d.shape == (5, 7)
    assert d[0, 6] == 0.0 and d[0, 3] == 3.0 and d[1, 5] == math.sqrt(2.0)
    # to (3, 6) the way goes round the wall's end at column 0
    assert d[3, 6] == pytest.approx(9.0 + 3.0 * math.sqrt(2.0))
    assert math.isinf(d[4, 6]) and math.isinf(d[2, 3])  # not passable
    assert np.isinf(geodesic_steps(~passable, 0, 0)).all()  # the target is not passable


def test_geodesic_steps_is_a_lower_bound_of_no_less_than_the_straight_line() -> None:
    grid = np.random.default_rng(2).random((30, 20)) < 0.75
    grid[0, 0] = True
    d = geodesic_steps(grid, 0, 0)
    i, j = np.nonzero(np.isfinite(d))
    assert len(i) > 50
    assert np.all(d[i, j] >= np.hypot(i, j) - 1e-12)


@pytest.mark.skipif(not numba_available(), reason="numba is not installed")
def test_the_compiled_function_gives_the_same_table_bit_for_bit() -> None:
    from voot.envs.motion.footprint_kernels import geodesic

    grid = np.random.default_rng(4).random((40, 30)) < 0.7
    grid[7, 9] = True
    a, b = geodesic(grid, 7, 9), geodesic_steps(grid, 7, 9)
    assert a.tobytes() == b.tobytes() and np.isinf(a).any() and np.isfinite(a).sum() > 100
