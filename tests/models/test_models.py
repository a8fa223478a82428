"""The MJCF models (voot.models): they load, are current, and have the documented structure."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from voot.envs.assets import fixed_scenes, mjcf
from voot.envs.core.scene import (
    OBJECT_BIT,
    ROBOT_BIT,
    SCENE_BIT,
    load_model,
    model_path,
    movable_objects,
)
from voot.envs.robot.model import ARM_JOINTS, ARM_REACH, BASE_HALF, TUCK, Robot
from voot.models import generate_scenes


@pytest.mark.parametrize("scene", ["robot", "kitchen", "conveyor"])
def test_scene_loads_on_its_own(scene: str) -> None:
    model = mujoco.MjModel.from_xml_path(str(model_path(scene)))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert model.nbody > 1 and np.all(np.isfinite(data.xpos))


def test_unknown_scene_lists_choices() -> None:
    with pytest.raises(ValueError, match="kitchen, conveyor, robot"):
        model_path("garage")


@pytest.mark.parametrize(
    ("name", "build"),
    [("kitchen.xml", fixed_scenes.kitchen_xml), ("conveyor.xml", fixed_scenes.conveyor_xml)],
)
def test_committed_xml_is_what_the_generator_writes(name: str, build: object) -> None:
    assert callable(build)
    assert (generate_scenes.HERE / name).read_text() == build()


def test_robot_structure() -> None:
    model = load_model("robot")
    robot = Robot(model)
    for name in ARM_JOINTS:
        j = model.joint(name)
        assert j.type[0] == mujoco.mjtJoint.mjJNT_HINGE and model.jnt_limited[j.id]
        assert j.range[0] < j.range[1]
    for name, kind in (("base_x", 2), ("base_y", 2), ("base_yaw", 3)):
        assert model.joint(name).type[0] == kind  # slide, slide, hinge
    assert robot.grasp_site >= 0
    # PR2-class size: 0.64 m base, about 0.9 m reach from the shoulder
    assert model.geom("base_body").size[0] == pytest.approx(BASE_HALF)
    assert 0.85 <= ARM_REACH <= 0.95


def test_straight_arm_reach_matches_constant() -> None:
    model = load_model("robot")
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    shoulder = data.body("shoulder_pan_link").xpos.copy()
    reach = np.linalg.norm(data.site("grasp").xpos - shoulder)
    assert reach == pytest.approx(ARM_REACH, abs=1e-9)


def test_tucked_arm_stays_inside_the_base_footprint() -> None:
    model = load_model("robot")
    data = mujoco.MjData(model)
    robot = Robot(model)
    robot.set_arm(data, TUCK)
    mujoco.mj_kinematics(model, data)
    for g in robot.geoms:
        if model.geom_bodyid[g] < 2:  # base body
            continue
        rot = data.geom_xmat[g].reshape(3, 3)
        aabb = model.geom_aabb[g]
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        world = (aabb[:3] + corners * aabb[3:]) @ rot.T + data.geom_xpos[g]
        assert np.all(np.abs(world[:, :2]) <= BASE_HALF), model.geom(g).name


@pytest.mark.parametrize("scene", ["kitchen", "conveyor"])
def test_collision_groups(scene: str) -> None:
    model = load_model(scene)
    robot = Robot(model)
    objects = movable_objects(model)
    object_geoms = {g for o in objects for g in o.geoms}
    for g in range(model.ngeom):
        ct, ca = int(model.geom_contype[g]), int(model.geom_conaffinity[g])
        if g in robot.geoms:
            assert (ct, ca) in ((ROBOT_BIT, SCENE_BIT | OBJECT_BIT), (0, 0))
        elif g in object_geoms:
            assert (ct, ca) == (OBJECT_BIT, ROBOT_BIT | SCENE_BIT | OBJECT_BIT)
        else:
            assert model.geom_bodyid[g] == 0
            assert (ct, ca) in ((SCENE_BIT, ROBOT_BIT | OBJECT_BIT), (0, 0))
    assert (model.geom("floor").contype, model.geom("floor").conaffinity) == (0, 0)


def test_scenes_start_without_contacts() -> None:
    starts = {"kitchen": mjcf.KITCHEN_START, "conveyor": mjcf.CONVEYOR_START}
    for scene, start in starts.items():
        model = load_model(scene)
        data = mujoco.MjData(model)
        robot = Robot(model)
        robot.set_base(data, start)
        robot.set_arm(data, TUCK)
        mujoco.mj_forward(model, data)
        assert data.ncon == 0, scene


def test_kitchen_objects() -> None:
    objects = movable_objects(load_model("kitchen"))
    names = [o.name for o in objects]
    assert sum(n.startswith("obj_chair") for n in names) == 5
    assert sum(n.startswith("obj_box") for n in names) == 4


def test_conveyor_boxes_have_the_original_sizes() -> None:
    objects = movable_objects(load_model("conveyor"))
    assert len(objects) == 20
    sizes = [(2 * o.half[0], 2 * o.half[1], o.height) for o in objects]
    for i, (sx, sy, sz) in enumerate(sizes):
        assert 0.7 <= sz <= 1.0
        if i < 2:
            assert 0.6 <= sx <= 0.7 and sy == pytest.approx(0.7)
        else:
            assert 0.4 <= sx <= 0.5 and 0.5 <= sy <= 0.6
    assert sizes == [tuple(pytest.approx(v) for v in s) for s in fixed_scenes.conveyor_box_sizes()]


def test_cameras() -> None:
    for scene in ("kitchen", "conveyor"):
        model = load_model(scene)
        for cam in ("top_down", "perspective"):
            assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, cam) >= 0
        assert model.cam_projection[model.camera("top_down").id] == 1  # orthographic
    assert math.isfinite(float(load_model("kitchen").stat.extent))
