"""Tests of voot.envs.motion.footprint.geodesic: lattice distances around obstacles."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voot.envs.motion.footprint.astar import numba_available
from voot.envs.motion.footprint.geodesic import geodesic_steps


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
@pytest.mark.parametrize("seed", [4, 5, 6])
@pytest.mark.parametrize("density", [0.7, 0.95, 1.0])
def test_the_compiled_function_gives_the_same_table_bit_for_bit(seed: int, density: float) -> None:
    """The compiled Dijkstra (flat-array heap) and the reference compiled as it is."""
    from voot.envs.motion.footprint.kernels import geodesic, geodesic_reference

    grid = np.random.default_rng(seed).random((60, 45)) < density
    grid[7, 9] = True
    a, b = geodesic(grid, 7, 9), geodesic_steps(grid, 7, 9)
    assert a.tobytes() == b.tobytes() and np.isfinite(a).sum() > 100
    assert geodesic_reference(grid, 7, 9).tobytes() == b.tobytes()
    if density < 1.0:
        assert np.isinf(a).any()
    blocked = grid.copy()
    blocked[7, 9] = False
    assert np.isinf(geodesic(blocked, 7, 9)).all()
