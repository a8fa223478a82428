"""Tests of voot.envs.robot.grasp: the side grasp, and its float version against numpy."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pytest

from voot.envs.core.scene import load_model, movable_objects
from voot.envs.robot.grasp import side_grasp


def test_side_grasp_faces_the_robot() -> None:
    model = load_model("kitchen")
    box = next(o for o in movable_objects(model) if o.name == "obj_box2")
    pose = (1.0, 2.0, 0.0, 0.0)
    # robot west of the box, heading east: grasps the -x face
    g = side_grasp(box, pose, 0.0, math.pi / 2, 0.75, 0.5)
    assert g.face == "-x"
    assert g.position[0] == pytest.approx(1.0 - box.half[0])
    assert g.position[1] == pytest.approx(2.0)
    assert g.position[2] == pytest.approx(0.75 * box.height)
    np.testing.assert_allclose(g.rotation[:, 0], [1.0, 0.0, 0.0], atol=1e-12)  # approach
    np.testing.assert_allclose(g.rotation.T @ g.rotation, np.eye(3), atol=1e-12)
    assert np.linalg.det(g.rotation) == pytest.approx(1.0)
    # depth fraction moves the point across the face; heading north picks the -y face
    g2 = side_grasp(box, pose, math.pi / 2, math.pi / 2, 0.5, 0.9)
    assert g2.face == "-y" and g2.position[1] == pytest.approx(2.0 - box.half[1])
    assert g2.position[0] == pytest.approx(1.0 + 0.8 * box.half[0])


def _side_grasp_numpy(obj, obj_pose, base_heading, grasp_angle, hf, df, standoff=0.0):  # type: ignore[no-untyped-def]
    """side_grasp as it was written with numpy vectors (the reference)."""
    x, y, z, yaw = (float(v) for v in np.asarray(obj_pose, dtype=np.float64))
    c, s = math.cos(yaw), math.sin(yaw)
    faces = (
        ("+x", np.array([c, s]), float(obj.half[0]), float(obj.half[1])),
        ("-x", np.array([-c, -s]), float(obj.half[0]), float(obj.half[1])),
        ("+y", np.array([-s, c]), float(obj.half[1]), float(obj.half[0])),
        ("-y", np.array([s, -c]), float(obj.half[1]), float(obj.half[0])),
    )
    heading = np.array([math.cos(base_heading), math.sin(base_heading)])
    k = int(np.argmin([float(n @ heading) for _, n, _, _ in faces]))
    face, n, half_normal, half_across = faces[k]
    tangent = np.array([-n[1], n[0]])
    cx = x + c * obj.center[0] - s * obj.center[1]
    cy = y + s * obj.center[0] + c * obj.center[1]
    p_xy = (
        np.array([cx, cy]) + (half_normal + standoff) * n + (2.0 * df - 1.0) * half_across * tangent
    )
    p = np.array([p_xy[0], p_xy[1], z + hf * obj.height])
    approach = np.array([-n[0], -n[1], 0.0])
    y0 = np.array([tangent[0], tangent[1], 0.0])
    z0 = np.cross(approach, y0)
    ca, sa = math.cos(grasp_angle), math.sin(grasp_angle)
    y_axis = ca * y0 + sa * z0
    z_axis = np.cross(approach, y_axis)
    return p, np.column_stack([approach, y_axis, z_axis]), face


def test_side_grasp_is_bit_identical_to_the_numpy_version() -> None:
    model = load_model("kitchen")
    objects = movable_objects(model)
    rng = np.random.default_rng(5)
    for k in range(800):
        obj = objects[k % len(objects)]
        if k % 3 == 0:  # a footprint off the body origin (the kitchen's are centred)
            obj = dataclasses.replace(obj, center=rng.uniform(-0.2, 0.2, 2))
        yaw = float(rng.uniform(-4, 4))
        pose: Any = (*rng.uniform(-3, 3, 3).tolist(), yaw)
        if k % 2:  # an array pose takes the fast path
            pose = np.array(pose)
        # every 4th heading at 45 degrees to the object: two faces tie
        heading = (
            yaw + math.pi / 4 + math.pi / 2 * int(rng.integers(4))
            if k % 4 == 0
            else float(rng.uniform(-4, 4))
        )
        args = (
            np.float64(rng.uniform(0.7, 3.2)),
            np.float64(rng.uniform(0.5, 1)),
            np.float64(rng.uniform(0.1, 0.9)),
        )
        g = side_grasp(obj, pose, heading, *args, standoff=0.01 * (k % 2))
        p, r, face = _side_grasp_numpy(obj, pose, heading, *args, standoff=0.01 * (k % 2))
        assert g.face == face
        assert g.position.tobytes() == p.tobytes() and g.rotation.tobytes() == r.tobytes()


def test_an_off_centre_footprint_moves_the_grasp_with_the_body() -> None:
    model = load_model("kitchen")
    box = next(o for o in movable_objects(model) if o.name == "obj_box2")
    shifted = dataclasses.replace(box, center=np.array([0.1, 0.05]))
    # body turned a quarter: the footprint's centre (0.1, 0.05) is at (-0.05, 0.1)
    pose = np.array([1.0, 2.0, 0.0, math.pi / 2])
    g = side_grasp(shifted, pose, 0.0, math.pi / 2, 0.75, 0.5)
    assert g.face == "+y"  # the body's +y side faces west, towards the robot
    assert g.position[0] == pytest.approx(1.0 - 0.05 - box.half[1])
    assert g.position[1] == pytest.approx(2.0 + 0.1)
