"""Tests of voot.record.mujoco_scene: MuJoCo geometry and body poses in rerun."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("rerun")
mujoco = pytest.importorskip("mujoco")

import rerun as rr  # noqa: E402

from voot.record.mujoco_scene import (  # noqa: E402
    MujocoScene,
    camera_names,
    find_mujoco,
    log_mujoco_model,
    model_camera_eye,
    vertex_normals,
)
from voot.record.reader import read_recording  # noqa: E402

XML = """
<mujoco>
  <asset>
    <mesh name="tet" vertex="0 0 0  1 0 0  0 1 0  0 0 1"/>
    <hfield name="hf" nrow="2" ncol="2" size="1 1 0.1 0.1"/>
    <material name="blue" rgba="0 0 1 1"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 0.1" rgba="1 1 1 1"/>
    <geom name="terrain" type="hfield" hfield="hf" pos="5 5 0"/>
    <geom name="hidden" type="box" size="1 1 1" group="3"/>
    <geom name="invisible" type="box" size="1 1 1" rgba="1 1 1 0"/>
    <body name="table" pos="1 0 0">
      <geom name="top" type="box" size="0.5 0.4 0.02" pos="0 0 0.7" material="blue"/>
    </body>
    <body name="cart">
      <joint name="slide" type="slide" axis="1 0 0"/>
      <geom name="cyl" type="cylinder" size="0.1 0.3" pos="0 0 0.3"/>
      <geom name="cap" type="capsule" fromto="0 0 0 0 0 1" size="0.05"/>
      <body name="pole" pos="0 0 1">
        <joint name="hinge" type="hinge" axis="0 1 0"/>
        <geom name="ball" type="sphere" size="0.1" pos="0 0 0.5"/>
        <geom name="egg" type="ellipsoid" size="0.1 0.2 0.3"/>
        <geom name="tet" type="mesh" mesh="tet" pos="0.2 0 0"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


@pytest.fixture(scope="module")
def model() -> object:
    return mujoco.MjModel.from_xml_string(XML)


def _record(path: Path, model: object, data: object, steps: int = 3) -> MujocoScene:
    rec = rr.RecordingStream("voot_test")
    rec.set_log_time_enabled(False)
    rec.save(path)
    scene = log_mujoco_model(rec, model)
    for t in range(steps):
        data.qpos[:] = [0.5 * t, 0.3 * t]  # type: ignore[attr-defined]
        rec.set_time("plan", sequence=t)
        scene.log_poses(rec, data)
    rec.flush()
    rec.disconnect()
    return scene


def test_geometry_by_body_and_kind(model: object, tmp_path: Path) -> None:
    data = mujoco.MjData(model)
    path = tmp_path / "scene.rrd"
    scene = _record(path, model, data)
    assert scene.skipped == 1  # the height field
    assert scene.n_geoms == 7  # floor, table top, cylinder, capsule, sphere, ellipsoid, mesh
    assert scene.moving == [model.body("cart").id, model.body("pole").id]  # type: ignore[attr-defined]
    rec = read_recording(path)
    static = {e for e, info in rec.entities.items() if info.is_static}
    assert static == {
        "/scene/bodies/world/boxes",
        "/scene/bodies/table",
        "/scene/bodies/table/boxes",
        "/scene/bodies/cart/cylinders",
        "/scene/bodies/cart/capsules",
        "/scene/bodies/pole/ellipsoids",
        "/scene/bodies/pole/mesh",
    }
    # The infinite plane is a thin slab whose top is the plane; group 3 and alpha 0 are left out.
    floor = rec.latest("scene/bodies/world/boxes", "Boxes3D:half_sizes")
    assert len(floor) == 1
    assert floor[0][0] == 10.0 and floor[0][2] == pytest.approx(0.001)
    assert rec.latest("scene/bodies/world/boxes", "Boxes3D:centers")[0][2] == pytest.approx(-0.001)
    # A material's colour when the geom keeps the default rgba.
    assert rec.latest("scene/bodies/table/boxes", "Boxes3D:colors") == [0x0000FFFF]
    # Sphere and ellipsoid half sizes.
    half = rec.latest("scene/bodies/pole/ellipsoids", "Ellipsoids3D:half_sizes")
    assert np.allclose(half, [[0.1, 0.1, 0.1], [0.1, 0.2, 0.3]])
    # Capsule: rerun's runs from its origin along its +z, MuJoCo's is centred on geom_pos;
    # drawn, it must still span the MJCF's fromto (0, 0, 0) - (0, 0, 1).
    start = np.array(rec.latest("scene/bodies/cart/capsules", "Capsules3D:translations")[0])
    x, y, z, w = rec.latest("scene/bodies/cart/capsules", "Capsules3D:quaternions")[0]
    length = rec.latest("scene/bodies/cart/capsules", "Capsules3D:lengths")[0]
    assert length == pytest.approx(1.0)
    axis = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
    ends = sorted([tuple(np.round(start, 6)), tuple(np.round(start + length * axis, 6))])
    assert np.allclose(ends, [(0, 0, 0), (0, 0, 1)], atol=1e-6)
    # The mesh: vertices moved into the body frame.
    verts = np.array(rec.latest("scene/bodies/pole/mesh", "Mesh3D:vertex_positions"))
    assert verts.shape == (4, 3)
    d = mujoco.MjData(model)
    mujoco.mj_kinematics(model, d)
    gid = model.geom("tet").id  # type: ignore[attr-defined]
    local = np.array(model.mesh_vert[: model.mesh_vertnum[0]])  # type: ignore[attr-defined]
    world = np.array(d.geom_xpos[gid])[:, None] + np.array(d.geom_xmat[gid]).reshape(3, 3) @ local.T
    body_pos = np.array(d.xpos[model.body("pole").id])  # type: ignore[attr-defined]
    # The pole's frame is not rotated at qpos0, so body frame = world frame shifted.
    assert np.allclose(np.sort(verts + body_pos, axis=0), np.sort(world.T, axis=0), atol=1e-5)
    assert len(rec.latest("scene/bodies/pole/mesh", "Mesh3D:triangle_indices")) == 4
    normals = np.array(rec.latest("scene/bodies/pole/mesh", "Mesh3D:vertex_normals"))
    assert normals.shape == (4, 3) and np.allclose(np.linalg.norm(normals, axis=1), 1.0)
    # outward: each vertex's normal points away from the tetrahedron's centre
    assert np.all(np.einsum("ij,ij->i", normals, verts - verts.mean(axis=0)) > 0)


def test_vertex_normals() -> None:
    # a unit cube, faces wound counter-clockwise from outside
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    faces = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))])
    n = vertex_normals(v, faces)
    assert n.dtype == np.float32 and n.shape == (8, 3)
    # a corner's three faces weigh the same: the normal is the corner's diagonal
    assert np.allclose(n, (2 * v - 1) / np.sqrt(3), atol=1e-6)
    # a vertex on no face, and a degenerate face, give zero vectors
    extra = vertex_normals(np.vstack([v, [[5, 5, 5]]]), np.vstack([faces, [[8, 8, 8]]]))
    assert np.allclose(extra[8], 0.0) and np.allclose(extra[:8], n)


def test_poses_per_step_and_fixed_bodies_once(model: object, tmp_path: Path) -> None:
    data = mujoco.MjData(model)
    path = tmp_path / "poses.rrd"
    _record(path, model, data, steps=3)
    rec = read_recording(path)
    assert rec.entity("scene/bodies/cart").rows == {"plan": 3}
    assert rec.entity("scene/bodies/pole").rows == {"plan": 3}
    assert rec.entity("scene/bodies/table").static_rows == 1
    assert rec.latest("scene/bodies/table", "Transform3D:translation") == [[1.0, 0.0, 0.0]]
    cart = rec.column("scene/bodies/cart", "Transform3D:translation", "plan")
    assert [v[0][0] for _, v in cart] == pytest.approx([0.0, 0.5, 1.0])
    # The pole turns about y by qpos[1]: its quaternion (xyzw) says so.
    quat = rec.column("scene/bodies/pole", "Transform3D:quaternion", "plan")[-1][1][0]
    assert np.allclose(quat, [0.0, math.sin(0.3), 0.0, math.cos(0.3)], atol=1e-6)
    # The caller's data was not recomputed (poses come from the scene's own MjData).
    assert np.allclose(data.xpos, 0.0)


def test_group_filter_and_errors(model: object) -> None:
    everything = MujocoScene(model, geom_groups=None)
    assert everything._geoms.size == 9  # all but the alpha-0 box
    with pytest.raises(ValueError, match=r"mujoco\.MjModel"):
        MujocoScene(object())


def test_find_mujoco_follows_wrappers(model: object) -> None:
    data = mujoco.MjData(model)
    env = SimpleNamespace(model=model, data=data)
    wrapped = SimpleNamespace(env=SimpleNamespace(unwrapped=env))
    problem = SimpleNamespace(problem=wrapped)
    for obj in (env, wrapped, problem, (model, data)):
        found = find_mujoco(obj)
        assert found is not None and found[0] is model and found[1] is data
    assert find_mujoco(SimpleNamespace(model="not a model", data=None)) is None
    assert find_mujoco(None) is None


CAMERAS = """
<mujoco>
  <worldbody>
    <camera name="down" pos="1 2 5" xyaxes="1 0 0 0 1 0"/>
    <camera name="slant" pos="0 -4 3" xyaxes="1 0 0 0 0.6 0.8"/>
    <camera name="level" pos="0 0 1" xyaxes="1 0 0 0 0 1"/>
    <camera pos="0 0 1"/>
    <body name="b" pos="0 0 0.1"><geom type="box" size="2 2 0.1"/></body>
  </worldbody>
</mujoco>
"""


def test_model_camera_eye() -> None:
    """The eye at a camera, looking along its axis at the floor (or one extent ahead)."""
    m = mujoco.MjModel.from_xml_string(CAMERAS)
    assert camera_names(m) == ["down", "slant", "level"]  # the unnamed one left out
    down = model_camera_eye(m, "down")
    assert down.position == (1.0, 2.0, 5.0) and down.look_target == pytest.approx((1, 2, 0))
    assert down.up == (0.0, 0.0, 1.0)
    # y axis (0, 0.6, 0.8): the camera looks along -z = (0, 0.8, -0.6), down 3 m to z = 0
    slant = model_camera_eye(m, "slant")
    assert slant.look_target == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    level = model_camera_eye(m, "level")  # looks along +y: one extent ahead
    assert level.look_target == pytest.approx((0.0, float(m.stat.extent), 1.0))
    with pytest.raises(ValueError, match="no camera 'top' in the model; cameras: down, slant"):
        model_camera_eye(m, "top")
    with pytest.raises(ValueError, match=r"must be a mujoco\.MjModel"):
        model_camera_eye(object(), "down")
