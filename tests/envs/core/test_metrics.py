"""Tests of voot.envs.core.metrics: the authors' per-operator distances."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voot.envs.core.metrics import pick_distance, place_distance, to_action_units
from voot.envs.robot.model import ARM_REACH


def test_place_distance_ignores_headings() -> None:
    d = place_distance()
    pts = np.array([[1.0, 2.0, 0.0], [1.0, 2.0, 3.0], [4.0, 6.0, 1.0]])
    np.testing.assert_allclose(d(pts, np.array([1.0, 2.0, 5.0])), [0.0, 0.0, 5.0])
    d3 = place_distance(3)
    a = np.zeros((1, 9))
    a[0, [0, 4, 6]] = (3.0, 4.0, 12.0)
    np.testing.assert_allclose(d3(a, np.zeros(9)), [13.0])


def test_pick_distance_is_se2_of_the_base_plus_the_grasp_norm() -> None:
    d = pick_distance(rotation_weight=0.5)
    # same grasp, base angles 0 and pi/2 at full reach fraction 1: a quarter circle apart
    a = np.array([[1.0, 0.7, 0.5, 1.0, 0.0, 0.0]])
    b = np.array([1.0, 0.7, 0.5, 1.0, math.pi / 2, 0.0])
    chord = ARM_REACH * math.sqrt(2.0)
    assert d(a, b)[0] == pytest.approx(chord + 0.5 * math.pi / 2)
    # headings wrap: base angle 2 pi - 0.1 vs 0.1 is 0.2 rad apart
    c = np.array([[1.0, 0.7, 0.5, 0.0, 2 * math.pi - 0.1, 0.0]])
    e = np.array([1.0, 0.7, 0.5, 0.0, 0.1, 0.0])
    assert d(c, e)[0] == pytest.approx(0.5 * 0.2)
    # grasp parameters add their Euclidean norm
    g = np.array([[1.3, 0.7, 0.9, 1.0, 0.0, 0.0]])
    assert d(g, a[0])[0] == pytest.approx(0.5)
    with pytest.raises(ValueError, match="rotation_weight"):
        pick_distance(rotation_weight=-1.0)


def test_action_units() -> None:
    d = to_action_units(place_distance(), np.array([4.0, 4.0, 3.0]), np.array([2.0, 0.0, 3.0]))
    pts = np.array([[0.5, 0.0, -1.0]])
    assert d(pts, np.array([0.0, 0.0, 1.0]))[0] == pytest.approx(2.0)


def test_pairwise_rows_are_the_single_calls() -> None:
    rng = np.random.default_rng(0)
    for metric, dim in ((pick_distance(0.7), 6), (place_distance(), 3), (place_distance(3), 9)):
        scaled = to_action_units(metric, np.full(dim, 2.0), np.full(dim, 0.5))
        points, ys = rng.uniform(-1, 1, (40, dim)), rng.uniform(-1, 1, (5, dim))
        for m in (metric, scaled):
            table = m.pairwise(points, ys)
            assert table.shape == (5, 40)
            for k in range(5):
                assert table[k].tobytes() == m(points, ys[k]).tobytes()
