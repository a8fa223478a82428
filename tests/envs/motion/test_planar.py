"""Tests of voot.envs.motion.planar: poses, boxes, paths and their SE(2) lengths."""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest
import shapely
from floor_plans import path_length_arrays

from voot.envs.motion.planar import BasePath, Box2D, Pose2D, path_length, se2_distance, wrap_angle


def test_pose_and_box_validation() -> None:
    with pytest.raises(ValueError, match=r"Pose2D\.x"):
        Pose2D(float("nan"), 0.0, 0.0)
    with pytest.raises(ValueError, match="half_x and half_y must be > 0"):
        Box2D(0.0, 0.0, 0.0, 1.0)
    with pytest.raises(ValueError, match=r"Box2D\.yaw"):
        Box2D(0.0, 0.0, 1.0, 1.0, float("inf"))
    with pytest.raises(ValueError, match="xmin < xmax"):
        Box2D.from_bounds(1.0, 0.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="Pose2D or"):
        Pose2D.coerce([1.0, 2.0])
    assert Pose2D.coerce(np.array([1.0, 2.0, 3.0])) == Pose2D(1.0, 2.0, 3.0)


def test_box_corners_rotated() -> None:
    b = Box2D(1.0, 2.0, 0.5, 0.25, math.pi / 2, "b")
    c = b.corners()
    # a quarter turn maps the local (+x, +y) corner (0.5, 0.25) to (-0.25, 0.5)
    np.testing.assert_allclose(c[0], [1.0 - 0.25, 2.0 + 0.5], atol=1e-12)
    assert shapely.Polygon(c).area == pytest.approx(0.5)


def test_box_hash_and_equality() -> None:
    a = Box2D(1.0, 2.0, 0.5, 0.25, 0.1, "a")
    b = Box2D(1.0, 2.0, 0.5, 0.25, 0.1, "a")
    assert a == b and hash(a) == hash(b)
    assert a != Box2D(1.0, 2.0, 0.5, 0.25, 0.1, "c")
    c = pickle.loads(pickle.dumps(a))
    assert c == a and hash(c) == hash(a) and c.__dict__ == a.__dict__
    assert copy.deepcopy(a) == a


def test_box_fast_is_the_constructed_box() -> None:
    a = Box2D(1.0, -2.0, 0.5, 0.25, 0.3, "x")
    b = Box2D.fast(np.float64(1.0), -2.0, 0.5, 0.25, 0.3, "x")
    assert a == b and hash(a) == hash(b) and vars(a) == vars(b)
    assert pickle.loads(pickle.dumps(b)) == a
    with pytest.raises(ValueError, match="half_x"):
        Box2D.fast(0.0, 0.0, -1.0, 1.0, 0.0, "bad")
    with pytest.raises(ValueError, match="finite"):
        Box2D.fast(math.nan, 0.0, 1.0, 1.0, 0.0, "bad")


def test_wrap_and_se2_distance() -> None:
    assert float(wrap_angle(3 * math.pi / 2)) == pytest.approx(-math.pi / 2)
    assert se2_distance((0, 0, 0.1), (3, 4, 2 * math.pi - 0.1), 1.0) == pytest.approx(5.2)
    assert se2_distance((0, 0, 0.0), (0, 0, math.pi), 0.5) == pytest.approx(math.pi / 2)


def test_base_path_value_type() -> None:
    path = BasePath.from_waypoints([[0, 0, 0], [1, 0, 0], [1, 1, math.pi / 2]], 1.0)
    assert path.length == pytest.approx(2 + math.pi / 2)
    with pytest.raises(ValueError):
        path.waypoints[0, 0] = 5.0  # read-only
    with pytest.raises(ValueError, match="shape"):
        BasePath(np.zeros((3, 2)), 1.0)
    dense = path.interpolate(0.1)
    np.testing.assert_array_equal(dense[0], path.waypoints[0])
    np.testing.assert_array_equal(dense[-1], path.waypoints[-1])
    steps = np.hypot(*np.diff(dense[:, :2], axis=0).T)
    assert steps.max() <= 0.1 + 1e-12
    assert path == BasePath.from_waypoints(path.waypoints, 1.0)


def test_straight_paths_are_the_array_version() -> None:
    rng = np.random.default_rng(8)
    for w in rng.uniform(-7, 7, (2000, 2, 3)):
        for rw in (1.0, 0.3):
            assert path_length(w, rw) == path_length_arrays(w, rw)
    w = np.array([[0.0, 0.0, math.pi], [1.0, 1.0, -math.pi]])  # a turn of exactly 2 pi
    assert path_length(w, 1.0) == path_length_arrays(w, 1.0)
