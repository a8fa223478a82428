"""The kitchen's actions decoded into poses (voot.envs.kitchen.poses)."""

from __future__ import annotations

import math

import numpy as np

from voot.envs.kitchen.poses import (
    OPERATORS,
    pick_base,
    place_base,
    relative_pose,
    relative_pose_floats,
)
from voot.envs.motion.planner import Box2D
from voot.envs.robot.model import ARM_REACH, compose2d, inverse2d


def test_operators_alternate_pick_then_place() -> None:
    assert OPERATORS == ("pick", "place")


def test_pick_base_stands_at_the_distance_and_angle_facing_the_object() -> None:
    box = Box2D(1.0, -0.5, 0.2, 0.3, 0.7, "obj")
    rng = np.random.default_rng(1)
    for _ in range(50):
        p = rng.uniform(-1.0, 1.0, 6)
        p[3] = rng.uniform(0.4, 0.9)
        x, y, theta = pick_base(box, p)
        assert abs(math.hypot(x - box.cx, y - box.cy) - p[3] * ARM_REACH) < 1e-12
        angle = math.atan2(y - box.cy, x - box.cx)
        assert abs(math.remainder(angle - (box.yaw + p[4]), 2 * math.pi)) < 1e-9
        facing = math.atan2(box.cy - y, box.cx - x)
        assert abs(math.remainder(theta - facing - p[5], 2 * math.pi)) < 1e-12


def test_relative_pose_is_the_pose_in_the_base_frame_and_place_base_inverts_it() -> None:
    rng = np.random.default_rng(2)
    for _ in range(100):
        base = rng.uniform(-3.0, 3.0, 3)
        pose = rng.uniform(-3.0, 3.0, 4)  # (x, y, z, yaw)
        rel = relative_pose(base, pose)
        ref = compose2d(inverse2d(base), (pose[0], pose[1], pose[3]))
        np.testing.assert_allclose(rel, ref, atol=1e-12)
        # the float form is the same numbers, bit for bit
        bx, by, bt = base.tolist()
        floats = relative_pose_floats(bx, by, bt, (float(pose[0]), float(pose[1]), float(pose[3])))
        assert floats == rel
        # placing the object where it is puts the base back where it was
        back = place_base((float(pose[0]), float(pose[1]), float(pose[3])), rel)
        np.testing.assert_allclose(back[:2], base[:2], atol=1e-12)
        assert abs(math.remainder(back[2] - base[2], 2 * math.pi)) < 1e-12
