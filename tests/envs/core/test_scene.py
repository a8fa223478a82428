"""Reading the floor plan back from the compiled scenes (voot.envs.core.scene)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from voot.envs.core.scene import (
    load_model,
    movable_objects,
    object_footprint,
    object_pose,
    quat_of_yaw,
    set_object_pose,
    static_footprints,
    yaw_of_quat,
)
from voot.envs.motion.planar import Box2D


def _by_name(boxes: list[Box2D]) -> dict[str, Box2D]:
    return {b.name: b for b in boxes}


def test_kitchen_static_footprints() -> None:
    boxes = _by_name(static_footprints(load_model("kitchen")))
    assert "floor" not in boxes and "sink_basin" not in boxes  # no collision / decoration
    counter = boxes["counter_north"]
    assert (counter.cx, counter.cy) == pytest.approx((0.0, 3.675))
    assert (counter.half_x, counter.half_y) == pytest.approx((2.0, 0.325))
    # the door to the large rooms: 0.9 m between the two wall pieces at x = 2.8
    s, n = boxes["wall_rooms_s"], boxes["wall_rooms_n"]
    assert (n.cy - n.half_y) - (s.cy + s.half_y) == pytest.approx(0.9)


def test_conveyor_door_width() -> None:
    boxes = _by_name(static_footprints(load_model("conveyor")))
    w, e = boxes["wall_room1_s_w"], boxes["wall_room1_s_e"]
    assert (e.cx - e.half_x) - (w.cx + w.half_x) == pytest.approx(1.62)


def test_objects_and_footprints() -> None:
    objs = {o.name: o for o in movable_objects(load_model("kitchen"))}
    chair = objs["obj_chair1"]
    assert tuple(chair.half) == pytest.approx((0.23, 0.23))
    assert chair.height == pytest.approx(0.89)
    box = object_footprint(objs["obj_box1"], 1.0, 2.0, 0.5)
    assert (box.cx, box.cy, box.yaw) == pytest.approx((1.0, 2.0, 0.5))
    assert (box.half_x, box.half_y) == pytest.approx((0.2, 0.2))


def test_yaw_quaternion_round_trip() -> None:
    for yaw in (-3.0, -1.0, 0.0, 0.7, 3.1):
        assert yaw_of_quat(quat_of_yaw(yaw)) == pytest.approx(yaw)


def test_set_and_read_object_pose() -> None:
    model = load_model("kitchen")
    data = mujoco.MjData(model)
    obj = movable_objects(model)[0]
    set_object_pose(data, obj, (1.0, -2.0, 0.0, 2.5))
    np.testing.assert_allclose(object_pose(data, obj), [1.0, -2.0, 0.0, 2.5], atol=1e-12)


_PRISM = "0 0 0  0.3 0 0  0 0.1 0  0 0 0.2  0.3 0 0.2  0 0.1 0.2"  # a right-triangle prism
_MESH_SCENE = f"""<mujoco>
  <asset><mesh name="prism" vertex="{_PRISM}"/></asset>
  <worldbody>
    <geom name="static_prism" type="mesh" mesh="prism" pos="1 1 0" contype="2" conaffinity="5"/>
    <body name="obj_prism" pos="2 0 0">
      <freejoint name="obj_prism"/>
      <geom name="obj_prism" type="mesh" mesh="prism" contype="4" conaffinity="7"/>
    </body>
  </worldbody>
</mujoco>"""


def test_a_mesh_geom_s_footprint_is_its_vertices_rectangle() -> None:
    model = mujoco.MjModel.from_xml_string(_MESH_SCENE)
    # MuJoCo puts the mesh in its principal frame, turned in the horizontal plane: the
    # corners of geom_aabb there would give a larger rectangle than the prism's
    geom = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "obj_prism")
    assert abs(model.geom_quat[geom][0]) < 0.999
    (obj,) = movable_objects(model)
    np.testing.assert_allclose(obj.center, [0.15, 0.05], atol=1e-6)
    np.testing.assert_allclose(obj.half, [0.15, 0.05], atol=1e-6)
    assert obj.height == pytest.approx(0.2, abs=1e-6)
    (box,) = static_footprints(model)
    corners = np.array([[x, y] for x, y, _ in np.array(_PRISM.split(), float).reshape(-1, 3)])
    c, s = math.cos(box.yaw), math.sin(box.yaw)
    offset = np.array([1.0 - box.cx, 1.0 - box.cy])
    local = (corners + offset) @ np.array([[c, -s], [s, c]])
    # the static footprint holds every vertex and touches the prism on all four sides
    slack = np.array([box.half_x, box.half_y]) - np.abs(local)
    assert np.all(slack >= -1e-6)
    assert np.all(np.abs(local).max(axis=0) >= [box.half_x - 1e-6, box.half_y - 1e-6])
