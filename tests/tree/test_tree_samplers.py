"""Per-node samplers (voot.tree.samplers): the proposal comparison the search uses."""

from __future__ import annotations

import numpy as np
import pytest

from voot.tree.samplers import same_point

CASES = [
    (np.array([0.1, -0.2]), np.array([0.1, -0.2])),
    (np.array([0.1, -0.2]), np.array([0.1, -0.20000000000000004])),
    (np.array([0.0, 1.0]), np.array([-0.0, 1.0])),  # -0.0 == 0.0
    (np.array([np.nan, 1.0]), np.array([np.nan, 1.0])),  # NaN != NaN
    (np.array([1.0, 2.0]), np.array([1.0, 2.0, 3.0])),  # shapes differ
    (np.array([1.0, 2.0]), np.array([[1.0, 2.0]])),
    (np.array([1, 2]), np.array([1.0, 2.0])),  # not float64: numpy decides
    (np.zeros(0), np.zeros(0)),
]


@pytest.mark.parametrize(("a", "b"), CASES)
def test_same_point_is_array_equal(a: np.ndarray, b: np.ndarray) -> None:
    assert same_point(a, b) is bool(np.array_equal(a, b))
    assert same_point(b, a) is bool(np.array_equal(b, a))


def test_same_point_on_random_proposals() -> None:
    rng = np.random.default_rng(1)
    for _ in range(200):
        a = rng.uniform(-1, 1, 6)
        b = a.copy()
        assert same_point(a, b)
        b[rng.integers(6)] = np.nextafter(b[0], 2.0)
        assert same_point(a, b) is bool(np.array_equal(a, b))
