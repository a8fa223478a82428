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
    rect_inside,
    rect_overlaps,
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


def test_rectangle_region_tests() -> None:
    region = (0.0, 4.0, 0.0, 2.0)
    assert rect_inside(Box2D(1.0, 1.0, 0.5, 0.5), region)
    assert not rect_inside(Box2D(1.0, 1.0, 0.5, 0.5, math.pi / 4), (0.0, 4.0, 0.0, 1.6))
    assert rect_overlaps(Box2D(4.2, 1.0, 0.5, 0.5), region)
    assert not rect_overlaps(Box2D(5.0, 1.0, 0.5, 0.5), region)
    # a rotated box whose bounding box overlaps but which itself does not
    assert not rect_overlaps(Box2D(4.6, 2.6, 0.5, 0.1, -math.pi / 4), region)


# ----- the float shortcuts decide as the corner arrays do ---------------------------------
def _inside_corners(box: Box2D, b: tuple[float, float, float, float]) -> bool:
    c = box.corners()
    return bool(
        (c[:, 0] >= b[0]).all() and (c[:, 0] <= b[1]).all() and (c[:, 1] >= b[2]).all()
        and (c[:, 1] <= b[3]).all()
    )  # fmt: skip


def _random_boxes(n: int, bounds: tuple[float, float, float, float]) -> list[Box2D]:
    """Random rectangles, half of them moved to touch an edge of ``bounds`` within 1e-12."""
    import numpy as np

    rng = np.random.default_rng(7)
    out = []
    for k in range(n):
        hx, hy = rng.uniform(0.05, 0.6, 2)
        yaw = float(rng.choice([0.0, math.pi / 2, math.pi / 4, rng.uniform(0, 2 * math.pi)]))
        cx, cy = rng.uniform(bounds[0], bounds[1]), rng.uniform(bounds[2], bounds[3])
        box = Box2D(float(cx), float(cy), float(hx), float(hy), yaw, "b")
        if k % 2:  # shift so that the extreme corner lies (almost) on an edge
            c = box.corners()
            edge = int(rng.integers(4))
            delta = float(rng.choice([0.0, 1e-12, -1e-12, 5e-10, -5e-10]))
            if edge == 0:
                cx += bounds[0] - c[:, 0].min() + delta
            elif edge == 1:
                cx += bounds[1] - c[:, 0].max() + delta
            elif edge == 2:
                cy += bounds[2] - c[:, 1].min() + delta
            else:
                cy += bounds[3] - c[:, 1].max() + delta
            box = Box2D(float(cx), float(cy), float(hx), float(hy), yaw, "b")
        out.append(box)
    return out


def test_rect_inside_and_overlaps_agree_with_the_corner_tests() -> None:
    from voot.envs.core import scene

    bounds = (-2.0, 6.0, -4.0, 4.0)
    for box in _random_boxes(3000, bounds):
        assert rect_inside(box, bounds) == _inside_corners(box, bounds)
        assert rect_overlaps(box, bounds) == scene._rect_overlaps_sat(box, bounds)


def test_rect_tests_on_fields_match_the_box_tests() -> None:
    """rect_fields_inside / rect_fields_overlap decide as rect_inside / rect_overlaps."""
    from voot.envs.core.scene import (
        rect_fields_inside,
        rect_fields_overlap,
        rect_inside,
        rect_overlaps,
    )

    rng = np.random.default_rng(4)
    bounds = (-1.0, 2.0, -0.5, 1.5)
    seen = set()
    for k in range(3000):
        hx, hy = (float(v) for v in rng.uniform(0.05, 0.6, 2))
        yaw = float(rng.uniform(-np.pi, np.pi)) if k % 4 else 0.0
        cx, cy = (float(v) for v in rng.uniform(-1.8, 2.8, 2))
        if k % 5 == 0:  # right at an edge, where the corner arrays decide
            cx = bounds[0] + hx
        box = Box2D(cx, cy, hx, hy, yaw, "b")
        inside = rect_fields_inside(cx, cy, hx, hy, yaw, bounds)
        overlap = rect_fields_overlap(cx, cy, hx, hy, yaw, bounds)
        assert inside == rect_inside(box, bounds)
        assert overlap == rect_overlaps(box, bounds)
        seen.add((inside, overlap))
    assert seen == {(True, True), (False, True), (False, False)}


def test_float_separating_axes_agree_with_the_corner_arrays_or_abstain() -> None:
    from voot.envs.core import scene

    rng = np.random.default_rng(9)
    bounds = (-1.0, 2.0, -0.5, 1.5)
    told = abstained = 0
    for k in range(4000):
        hx, hy = (float(v) for v in rng.uniform(0.05, 0.6, 2))
        yaw = float(rng.uniform(-np.pi, np.pi))
        cx, cy = (float(v) for v in rng.uniform(-1.8, 2.8, 2))
        box = Box2D(cx, cy, hx, hy, yaw, "b")
        if k % 7 == 0:  # a corner exactly on an edge: the floats must abstain or agree
            c = box.corners()
            cx += bounds[0] - float(c[:, 0].max())
            box = Box2D(cx, cy, hx, hy, yaw, "b")
        sure = scene._rect_overlaps_floats(cx, cy, hx, hy, yaw, bounds)
        if sure is None:
            abstained += 1
        else:
            told += 1
            assert sure == scene._rect_overlaps_sat(box, bounds)
    assert told > 3000 and abstained > 0


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
