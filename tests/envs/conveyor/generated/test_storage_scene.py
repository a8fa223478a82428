"""Tests of voot.envs.conveyor.generated.scene: a generated layout as a MuJoCo scene."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from voot.envs.assets.meshes import mesh_name
from voot.envs.assets.mjcf import CONVEYOR_START, belt_pose
from voot.envs.conveyor.generated.layout import DIFFICULTIES, generate_storage_layout
from voot.envs.conveyor.generated.scene import (
    box_material,
    box_shapes,
    compile_storage_scene,
    storage_xml,
)
from voot.envs.core.scene import movable_objects, object_pose, static_footprints
from voot.envs.motion.planner import BasePlanner, BasePlannerConfig
from voot.envs.robot.model import ROBOT_RADIUS, Robot


@pytest.mark.parametrize("difficulty", list(DIFFICULTIES))
def test_the_scene_holds_the_layout(difficulty: str) -> None:
    layout = generate_storage_layout(5, difficulty)
    model = compile_storage_scene(layout)
    Robot(model)  # the robot is included
    # the boxes: one movable object per box, in belt order, of the box's size, queued
    objects = movable_objects(model)
    assert [o.name for o in objects] == [f"obj_{i:02d}" for i in range(layout.n_boxes)]
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    for i, (obj, box) in enumerate(zip(objects, layout.boxes, strict=True)):
        np.testing.assert_allclose(2 * obj.half, box.size[:2], atol=1e-4)
        assert obj.height == pytest.approx(box.size[2], abs=1e-4)
        np.testing.assert_allclose(obj.center, np.zeros(2), atol=1e-12)  # centred footprint
        np.testing.assert_allclose(object_pose(data, obj), belt_pose(i))
    # the walls: every wall of the layout is a static footprint of its size
    boxes = {b.name: b for b in static_footprints(model)}
    for w in layout.walls:
        b = boxes[w.name]
        assert b.cx == pytest.approx(0.5 * (w.xmin + w.xmax), abs=1e-4)
        assert b.cy == pytest.approx(0.5 * (w.ymin + w.ymax), abs=1e-4)
        assert 2 * b.half_x == pytest.approx(w.xmax - w.xmin, abs=1e-4)
        assert 2 * b.half_y == pytest.approx(w.ymax - w.ymin, abs=1e-4)
    assert "belt_frame" in boxes
    # each box's shape and material
    for i, box in enumerate(layout.boxes):
        body = objects[i].body
        geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] == body]
        assert all(model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH for g in geoms)
        assert model.body_mass[body] > 0
        mat = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_MATERIAL, model.geom_matid[geoms[0]])
        assert mat == box_material(box.big, box.kind)
    assert set(boxes) == {w.name for w in layout.walls} | {"belt_frame"}


def test_the_robot_alone_reaches_every_room() -> None:
    """Every door is wider than the robot's disc: from the start, each room's centre
    is reachable by the base planner on the compiled scene's floor plan."""
    for difficulty in DIFFICULTIES:
        for seed in range(3):
            layout = generate_storage_layout(seed, difficulty)
            model = compile_storage_scene(layout)
            planner = BasePlanner(layout.workspace, static_footprints(model), BasePlannerConfig())
            start = np.array(CONVEYOR_START)
            for room in layout.rooms:
                goal = (0.5 * (room.xmin + room.xmax), 0.5 * (room.ymin + room.ymax), 0.0)
                assert planner.plan(start, goal, ROBOT_RADIUS, []) is not None, (room, seed)


def test_the_xml_is_a_function_of_the_layout() -> None:
    a = generate_storage_layout(2, "medium")
    assert storage_xml(a) == storage_xml(generate_storage_layout(2, "medium"))
    assert storage_xml(a) != storage_xml(generate_storage_layout(3, "medium"))
    text = storage_xml(a)
    assert '<include file="robot.xml"/>' in text
    assert text.count("<freejoint") == a.n_boxes
    # the boxes are meshes: one visual mesh geom each, named in the asset section
    assert text.count('type="mesh"') > text.count('_visual" class="decor" type="mesh"')
    assert text.count('_visual" class="decor" type="mesh"') == a.n_boxes
    for spec in box_shapes(a):
        assert f'<mesh name="{mesh_name(spec)}" file="{mesh_name(spec)}.stl"/>' in text
    assert text.count('class="decor" type="box" size=') >= len(a.doors) + len(a.rooms)


def test_the_top_down_camera_frames_the_area() -> None:
    layout = generate_storage_layout(1, "hard")
    model = compile_storage_scene(layout)
    cam = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "top_down")
    x0, _x1, y0, y1 = layout.area
    cx, cy, _ = model.cam_pos[cam]
    assert x0 < cx < 1.5 and y0 < cy < y1
    height = float(model.cam_fovy[cam])  # orthographic: the view's height in metres
    assert height >= y1 - y0 and height * 4 / 3 >= 1.5 - x0
