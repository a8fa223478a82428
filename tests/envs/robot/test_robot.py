"""The robot wrapper, SE(2) helpers and the base-motion disc (voot.envs.robot.model)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from voot.envs.core.scene import load_model
from voot.envs.robot.model import (
    BASE_HALF,
    ROBOT_DISC,
    ROBOT_RADIUS,
    TUCK,
    Robot,
    base_footprint,
    carry_disc,
    compose2d,
    compose_inverse2d,
    inverse2d,
)


def test_named_access() -> None:
    model = load_model("kitchen")
    data = mujoco.MjData(model)
    robot = Robot(model)
    robot.set_base(data, (1.0, 2.0, 0.5))
    robot.set_arm(data, TUCK)
    np.testing.assert_array_equal(robot.base_pose(data), [1.0, 2.0, 0.5])
    np.testing.assert_array_equal(robot.arm(data), TUCK)
    mujoco.mj_kinematics(model, data)
    np.testing.assert_allclose(data.site("base_center").xpos[:2], [1.0, 2.0])
    assert set(robot.gripper_geoms) < set(robot.geoms)


def test_robot_disc_holds_the_base() -> None:
    assert ROBOT_RADIUS > math.sqrt(2) * BASE_HALF
    corners = base_footprint((0.0, 0.0, 0.3)).corners()
    assert np.all(np.hypot(corners[:, 0], corners[:, 1]) <= ROBOT_DISC.radius)


def test_carry_disc_holds_robot_and_object_for_any_heading() -> None:
    obj = np.array([[0.4, 0.3], [1.0, 0.3], [1.0, -0.3], [0.4, -0.3]])
    disc = carry_disc(obj)
    assert disc.offset == pytest.approx((0.34, 0.0))
    square = BASE_HALF * np.array([[1, 1], [-1, 1], [-1, -1], [1, -1]])
    pts = np.concatenate([square, obj])
    assert np.max(np.hypot(pts[:, 0] - 0.34, pts[:, 1])) < disc.radius
    # the path of the centre maps back to base poses
    base = np.array([2.0, -1.0, 1.2])
    centre = disc.center(base)
    np.testing.assert_allclose(disc.base(centre[None, :])[0], base, atol=1e-12)


def test_se2_compose_inverse() -> None:
    a = (1.0, 2.0, 0.7)
    b = (-0.3, 0.5, -2.0)
    ab = compose2d(a, b)
    np.testing.assert_allclose(compose2d(inverse2d(a), ab), b, atol=1e-12)
    np.testing.assert_allclose(compose2d(a, inverse2d(a))[:2], [0.0, 0.0], atol=1e-12)


def test_float_se2_helpers_match_numpy() -> None:
    """compose2d/inverse2d on floats give the numbers the numpy-scalar versions gave."""
    rng = np.random.default_rng(0)
    for a, b in rng.uniform(-7, 7, (500, 2, 3)):
        c, s = math.cos(a[2]), math.sin(a[2])
        ref = np.array([a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2]])
        assert compose2d(a, b).tobytes() == ref.tobytes()
        assert compose2d(tuple(a.tolist()), list(b)).tobytes() == ref.tobytes()
        inv = np.array([-c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2]])
        assert inverse2d(a).tobytes() == inv.tobytes()
        assert inverse2d(tuple(a.tolist())).tobytes() == inv.tobytes()  # remembered
        assert inverse2d(tuple(a.tolist())).tobytes() == inv.tobytes()
        rel = tuple(b.tolist())
        assert compose_inverse2d(a, rel).tobytes() == compose2d(a, inverse2d(b)).tobytes()
    out = inverse2d((1.0, 2.0, 0.5))
    out[0] = 99.0  # a fresh array every time
    assert inverse2d((1.0, 2.0, 0.5))[0] != 99.0


def test_compose_inverse_tuple_is_pose_tuple_of_the_array() -> None:
    from voot.envs.core.state import pose_tuple
    from voot.envs.robot.model import compose_inverse_tuple

    rng = np.random.default_rng(1)
    for a, b in rng.uniform(-7, 7, (300, 2, 3)):
        rel = tuple(b.tolist())
        got = compose_inverse_tuple(tuple(a.tolist()), rel)
        assert got == pose_tuple(compose_inverse2d(a, rel))
        assert all(type(v) is float for v in got)


def test_carry_disc_on_floats_matches_the_array_disc() -> None:
    from voot.envs.motion.planar import Box2D
    from voot.envs.robot.model import carry_disc_floats

    rng = np.random.default_rng(2)
    for _ in range(500):
        cx, cy = (float(v) for v in rng.uniform(-0.8, 0.8, 2))
        hx, hy = (float(v) for v in rng.uniform(0.05, 0.4, 2))
        yaw = float(rng.uniform(-math.pi, math.pi))
        exact = carry_disc(Box2D(cx, cy, hx, hy, yaw).corners())
        ox, oy, radius = carry_disc_floats(cx, cy, hx, hy, yaw)
        assert abs(ox - exact.offset[0]) < 1e-12 and abs(oy - exact.offset[1]) < 1e-12
        assert abs(radius - exact.radius) < 1e-12
