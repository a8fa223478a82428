"""Tests of voot.envs.mesh_grasp: ray-cast grasp tables and the lookup on them."""

from __future__ import annotations

import math
import pickle
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from voot.envs import meshes as M
from voot.envs.grasp import side_grasp
from voot.envs.mesh_grasp import (
    COLS,
    FACES,
    MISS,
    ROWS,
    MeshGraspSet,
    cast_grasp_rays,
    grasp_set,
    mesh_side_grasp,
)
from voot.envs.meshes import ShapeSpec, build_shape
from voot.envs.scene import movable_objects

BOX = ShapeSpec("box", (0.1, 0.16, 0.22))
BOTTLE = ShapeSpec("bottle", (0.07, 0.07, 0.25))
MUG = ShapeSpec("mug", (0.12, 0.085, 0.1))


@pytest.fixture(autouse=True)
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A fresh cache folder (never ~/.cache) and empty in-process caches."""
    monkeypatch.setenv("VOOT_CACHE", str(tmp_path / "cache"))
    M.clear_memory_cache()
    yield tmp_path / "cache"
    M.clear_memory_cache()


@pytest.fixture(scope="module")
def box_info():  # type: ignore[no-untyped-def]
    """The box as movable_objects reads it from a compiled scene (MuJoCo's numbers)."""
    xml = f"""<mujoco><compiler angle="radian"/>
  <asset>{M.shape_assets_xml([BOX])}</asset>
  <default><default class="object"><geom contype="4" conaffinity="7"/></default>
  <default class="decor"><geom contype="0" conaffinity="0" group="1"/></default></default>
  <include file="robot.xml"/>
  <worldbody>{M.object_body_xml("obj_box", BOX, (0.0, 0.0, 0.0, 0.0), "")}</worldbody>
</mujoco>"""
    xml = xml.replace(' material=""', "")
    return movable_objects(M.compile_scene(xml, [BOX]))[0]


def test_a_box_is_hit_everywhere_on_its_faces() -> None:
    g = grasp_set(BOX)
    assert g.depth.shape == (4, ROWS, COLS) and g.normal.shape == (4, ROWS, COLS, 3)
    assert g.hit_fraction == 1.0
    np.testing.assert_array_equal(g.depth, 0.0)  # the faces are the bounding box's
    for k, (n0, n1) in enumerate(((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0))):
        np.testing.assert_allclose(g.normal[k].reshape(-1, 3), [[n0, n1, 0.0]] * ROWS * COLS)
    assert g.half == (0.05, 0.08) and g.height == pytest.approx(0.22, abs=1e-15)


@settings(max_examples=60, deadline=None)
@given(
    x=st.floats(-3, 3),
    y=st.floats(-3, 3),
    yaw=st.floats(-math.pi, math.pi),
    heading=st.floats(-math.pi, math.pi),
    angle=st.floats(math.pi / 4, math.pi),
    hf=st.floats(0.0, 1.0),
    df=st.floats(0.0, 1.0),
    standoff=st.floats(0.0, 0.05),
)
def test_on_a_box_the_grasp_is_side_grasp_s(
    box_info, x, y, yaw, heading, angle, hf, df, standoff
) -> None:  # type: ignore[no-untyped-def]
    M.clear_memory_cache()  # hypothesis reuses the function-scoped cache folder
    pose = np.array([x, y, 0.4, yaw])
    got, reason = mesh_side_grasp(grasp_set(BOX), pose, heading, angle, hf, df, standoff)
    want = side_grasp(box_info, pose, heading, angle, hf, df, standoff)
    assert got is not None and reason == ""
    assert got.face == want.face
    # MuJoCo's footprint is the float32 STL's: equal up to float32 rounding
    np.testing.assert_allclose(got.position, want.position, atol=1e-7)
    np.testing.assert_allclose(got.rotation, want.rotation, atol=1e-12)


def test_on_a_box_the_grasp_is_bit_identical_to_side_grasp_on_the_same_footprint() -> None:
    g = grasp_set(BOX)
    pose = (0.3, -0.2, 0.1, 0.7)
    for hf, df in ((0.5, 0.5), (1.0, 0.0), (0.73, 0.99), (0.0, 1.0)):
        got, _ = mesh_side_grasp(g, pose, 2.5, 1.2, hf, df, 0.02)
        want = side_grasp(g._info, pose, 2.5, 1.2, hf, df, 0.02)
        assert got is not None
        assert np.array_equal(got.position, want.position)
        assert np.array_equal(got.rotation, want.rotation)


def test_beside_a_bottle_s_neck_the_grasp_misses() -> None:
    g = grasp_set(BOTTLE)
    assert 0.5 < g.hit_fraction < 1.0
    pose = (1.0, 2.0, 0.0, 0.0)
    # the neck is about a third as wide as the body: at 95 % of the height, 10 % across
    # is beside it; at the middle it is on it; low down the body spans the whole width
    assert mesh_side_grasp(g, pose, 0.0, 1.0, 0.95, 0.1) == (None, MISS)
    assert mesh_side_grasp(g, pose, 0.0, 1.0, 0.95, 0.9) == (None, MISS)
    on_neck, reason = mesh_side_grasp(g, pose, 0.0, 1.0, 0.95, 0.5)
    assert on_neck is not None and reason == ""
    body, _ = mesh_side_grasp(g, pose, 0.0, 1.0, 0.3, 0.15)
    assert body is not None


def test_the_tool_point_is_on_the_bottle_s_surface() -> None:
    g = grasp_set(BOTTLE)
    shape = build_shape(BOTTLE)
    pose = (1.0, 2.0, 0.05, 0.4)
    for heading in (0.0, 1.0, 2.5, -2.0):
        for hf, df in ((0.3, 0.5), (0.3, 0.2), (0.4, 0.75), (0.95, 0.5), (0.9, 0.45)):
            got, _ = mesh_side_grasp(g, pose, heading, 1.0, hf, df)
            assert got is not None
            # back to the body frame: on the mesh's surface within the facets' sag
            c, s = math.cos(-pose[3]), math.sin(-pose[3])
            dx, dy = got.position[0] - pose[0], got.position[1] - pose[1]
            local = np.array([c * dx - s * dy, s * dx + c * dy, got.position[2] - pose[2]])
            dist = abs(float(shape.visual.nearest.signed_distance(local[None])[0]))
            assert dist < 1e-3, (heading, hf, df, dist)
            assert local[2] == pytest.approx(hf * 0.25, abs=1e-12)


def test_the_standoff_moves_the_point_out_along_the_face_normal() -> None:
    g = grasp_set(BOTTLE)
    pose = (0.0, 0.0, 0.0, 0.0)
    near, _ = mesh_side_grasp(g, pose, math.pi, 1.0, 0.3, 0.5)  # heading -x: the +x face
    far, _ = mesh_side_grasp(g, pose, math.pi, 1.0, 0.3, 0.5, standoff=0.03)
    assert near is not None and far is not None and near.face == "+x"
    np.testing.assert_allclose(far.position - near.position, [0.03, 0.0, 0.0], atol=1e-12)
    assert near.position[0] == pytest.approx(0.035, abs=1e-3)  # the body's radius


def test_the_mug_s_handle_is_what_the_plus_x_face_hits() -> None:
    g = grasp_set(MUG)
    plus_x = FACES.index("+x")
    mid = COLS // 2
    # at the handle's height the +x ray hits the handle, at the bounding box's face
    rows_hit = np.flatnonzero(g.depth[plus_x, :, mid] < 0.005)
    assert len(rows_hit) > 0
    z = (rows_hit + 0.5) / ROWS
    assert 0.2 < z.min() and z.max() < 0.9
    # the -x side is the body's wall, slightly tapered: at the bounding box's face at the
    # rim, a few millimetres behind it lower down, never deeper
    wall = g.depth[FACES.index("-x"), :, mid]
    assert np.all(np.diff(wall) <= 1e-12) and wall[-1] < 0.1 * wall[0] and wall[0] < 0.005


def test_normals_face_the_rays_and_are_unit_vectors() -> None:
    g = grasp_set(MUG)
    hit = np.isfinite(g.depth)
    np.testing.assert_array_equal(np.isfinite(g.normal).all(axis=-1), hit)
    for k, (n0, n1) in enumerate(((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0))):
        n = g.normal[k][hit[k]]
        np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-12)
        assert np.all(n[:, 0] * n0 + n[:, 1] * n1 > 0.0)  # against the ray (-n)


def test_grasp_sets_pickle_and_are_cached_beside_the_meshes(cache: Path) -> None:
    g = grasp_set(BOTTLE)
    assert (cache / "meshes" / f"{BOTTLE.key}.grasp.npz").is_file()
    back = pickle.loads(pickle.dumps(g))
    assert isinstance(back, MeshGraspSet) and back.spec == BOTTLE
    np.testing.assert_array_equal(back.depth, g.depth)
    pose = (0.5, 0.5, 0.0, 1.0)
    a, _ = mesh_side_grasp(g, pose, 0.3, 1.0, 0.4, 0.3, 0.01)
    b, _ = mesh_side_grasp(back, pose, 0.3, 1.0, 0.4, 0.3, 0.01)
    assert a is not None and b is not None and np.array_equal(a.position, b.position)
    M.clear_memory_cache()
    disk = grasp_set(BOTTLE)  # read back
    assert disk is not g
    np.testing.assert_array_equal(disk.depth, g.depth)
    np.testing.assert_array_equal(disk.normal, g.normal)
    assert grasp_set(BOTTLE) is disk  # then kept in the process


def test_cast_grasp_rays_takes_the_nearest_hit() -> None:
    # two boxes one behind the other along x: the +x rays stop at the nearer one
    import trimesh

    a = trimesh.creation.box((0.1, 0.1, 0.1))
    b = trimesh.creation.box((0.1, 0.1, 0.1))
    b.apply_translation((0.2, 0.0, 0.0))
    both = trimesh.util.concatenate([a, b])
    both.apply_translation(-np.array([both.bounds[0][0] + 0.15, 0.0, -0.05]))
    depth, _ = cast_grasp_rays(both, 4, 4)
    plus_x, minus_x = FACES.index("+x"), FACES.index("-x")
    np.testing.assert_allclose(depth[plus_x][np.isfinite(depth[plus_x])], 0.0, atol=1e-9)
    np.testing.assert_allclose(depth[minus_x][np.isfinite(depth[minus_x])], 0.0, atol=1e-9)
    # along y the rays at the gap's offsets miss
    plus_y = FACES.index("+y")
    assert np.isnan(depth[plus_y]).any() and np.isfinite(depth[plus_y]).any()


def test_grasp_set_arrays_are_checked() -> None:
    with pytest.raises(ValueError, match=r"depth must be \(4, rows, cols\)"):
        MeshGraspSet(BOX, (0.05, 0.08), 0.22, np.zeros((3, 2, 2)), np.zeros((3, 2, 2, 3)))
