"""Tests of a generated kitchen's MJCF (voot.envs.kitchen.generated.scene)."""

from __future__ import annotations

import subprocess
import sys

import mujoco
import numpy as np
import pytest

from voot.envs.assets.mjcf import mjcf_sha256 as scene_digest
from voot.envs.core.scene import movable_objects, object_pose, static_footprints
from voot.envs.kitchen.generated.layout import generate_kitchen_layout
from voot.envs.kitchen.generated.scene import compile_kitchen, kitchen_layout_xml


@pytest.fixture(scope="module")
def layout():  # type: ignore[no-untyped-def]
    return generate_kitchen_layout(1, "medium", 0)


def test_the_xml_is_a_function_of_the_layout_also_in_another_process(layout) -> None:  # type: ignore[no-untyped-def]
    xml = kitchen_layout_xml(layout)
    assert xml == kitchen_layout_xml(generate_kitchen_layout(1, "medium", 0))
    code = (
        "from voot.envs.kitchen.generated.layout import generate_kitchen_layout\n"
        "from voot.envs.assets.mjcf import mjcf_sha256 as scene_digest\n"
        "from voot.envs.kitchen.generated.scene import kitchen_layout_xml\n"
        "print(scene_digest(kitchen_layout_xml(generate_kitchen_layout(1, 'medium', 0))))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], check=True, capture_output=True, text=True, timeout=120
    )
    assert out.stdout.strip() == scene_digest(xml)
    assert scene_digest(kitchen_layout_xml(generate_kitchen_layout(2, "medium", 0))) != (
        scene_digest(xml)
    )


def test_the_compiled_scene_holds_the_layouts_blocks_and_objects(layout) -> None:  # type: ignore[no-untyped-def]
    model = compile_kitchen(kitchen_layout_xml(layout), layout)
    assert isinstance(model, mujoco.MjModel)
    footprints = {b.name: b for b in static_footprints(model)}
    for block in layout.blocks:
        box = footprints[block.name]
        x0, x1, y0, y1 = block.rect
        assert box.cx == pytest.approx(0.5 * (x0 + x1), abs=1e-4)
        assert box.cy == pytest.approx(0.5 * (y0 + y1), abs=1e-4)
        assert box.half_x == pytest.approx(0.5 * (x1 - x0), abs=1e-4)
        assert box.half_y == pytest.approx(0.5 * (y1 - y0), abs=1e-4)
    objects = movable_objects(model)
    assert [o.name for o in objects] == [o.name for o in layout.objects]
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    for info, spec in zip(objects, layout.objects, strict=True):
        x, y, z, yaw = object_pose(data, info)
        assert (x, y, z) == pytest.approx((spec.pose[0], spec.pose[1], 0.0), abs=1e-4)
        assert np.cos(yaw - spec.pose[2]) == pytest.approx(1.0)
        # the mesh spans its catalogue bounding box
        assert 2 * info.half == pytest.approx(spec.size[:2], abs=2e-3)
        assert info.height == pytest.approx(spec.size[2], abs=2e-3)
        # collision parts (class object, mesh) and a visual mesh (decor)
        geoms = [model.geom(g) for g in info.geoms]
        assert all(int(g.type[0]) == mujoco.mjtGeom.mjGEOM_MESH for g in geoms)
        assert sum(int(g.contype[0]) == 4 for g in geoms) >= 1
        assert sum(int(g.contype[0]) == 0 for g in geoms) == 1
    # the robot (robot.xml, an in-memory asset) and both cameras are there
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "base_x") >= 0
    for cam in ("top_down", "perspective"):
        assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, cam) >= 0
