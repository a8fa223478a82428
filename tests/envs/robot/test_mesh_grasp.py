"""Tests of voot.envs.robot.mesh_grasp: ray-cast grasp tables and the lookup on them."""

from __future__ import annotations

import hashlib
import math
import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from voot.envs.assets import meshes as M
from voot.envs.assets.meshes import ShapeSpec, build_shape
from voot.envs.core.scene import movable_objects
from voot.envs.robot import mesh_grasp as MG
from voot.envs.robot.grasp import side_grasp
from voot.envs.robot.mesh_grasp import (
    COLS,
    FACES,
    MISS,
    ROWS,
    MeshGraspSet,
    cast_grasp_rays,
    grasp_set,
    mesh_side_grasp,
)

#: Every test gets a fresh mesh cache (never ~/.cache).
pytestmark = pytest.mark.usefixtures("mesh_cache")


BOX = ShapeSpec("box", (0.1, 0.16, 0.22))
BOTTLE = ShapeSpec("bottle", (0.07, 0.07, 0.25))
MUG = ShapeSpec("mug", (0.12, 0.085, 0.1))


@pytest.fixture(scope="module")
def box_info(tmp_path_factory: pytest.TempPathFactory):  # type: ignore[no-untyped-def]
    """The box as movable_objects reads it from a compiled scene (MuJoCo's numbers)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("VOOT_CACHE", str(tmp_path_factory.mktemp("box_cache")))
        M.clear_memory_cache()
        info = movable_objects(M.compile_scene(_box_scene(), [BOX]))[0]
        M.clear_memory_cache()
    return info


def _box_scene() -> str:
    xml = f"""<mujoco><compiler angle="radian"/>
  <asset>{M.shape_assets_xml([BOX])}</asset>
  <default><default class="object"><geom contype="4" conaffinity="7"/></default>
  <default class="decor"><geom contype="0" conaffinity="0" group="1"/></default></default>
  <include file="robot.xml"/>
  <worldbody>{M.object_body_xml("obj_box", BOX, (0.0, 0.0, 0.0, 0.0), "")}</worldbody>
</mujoco>"""
    return xml.replace(' material=""', "")


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


def test_grasp_sets_pickle_and_are_cached_beside_the_meshes(mesh_cache: Path) -> None:
    g = grasp_set(BOTTLE)
    assert (mesh_cache / "meshes" / f"{BOTTLE.key}.grasp.npz").is_file()
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


@pytest.mark.parametrize("kind", M.SHAPE_KINDS)
def test_the_rays_hit_what_trimesh_s_ray_mesh_intersector_hits(kind: str) -> None:
    # the reference: trimesh's own ray casting (r-tree broad phase), nearest hit per ray
    sizes = {"plate": (0.26, 0.26, 0.025), "tray": (0.4, 0.3, 0.04), "mug": (0.12, 0.085, 0.1)}
    for variant in (0, 2):
        mesh = build_shape(ShapeSpec(kind, sizes.get(kind, (0.2, 0.14, 0.25)), variant)).visual
        depth, normal = cast_grasp_rays(mesh)
        org, dirv, _ = MG._grid(mesh, ROWS, COLS)
        tri, ray, loc = trimesh.ray.ray_triangle.RayMeshIntersector(mesh).intersects_id(
            org, dirv, multiple_hits=True, return_locations=True
        )
        want = np.full(len(org), np.nan)
        want_n = np.full((len(org), 3), np.nan)
        dist = np.einsum("ij,ij->i", loc - org[ray], dirv[ray])
        for r in np.unique(ray):
            mine = np.flatnonzero(ray == r)
            best = mine[np.lexsort((tri[mine], dist[mine]))[0]]
            want[r] = np.round(dist[best] - MG._MARGIN, 9) + 0.0
            want_n[r] = mesh.face_normals[tri[best]]
        np.testing.assert_array_equal(depth.reshape(-1), want)
        np.testing.assert_array_equal(normal.reshape(-1, 3), want_n)


_NO_RTREE = """
import sys
sys.modules["rtree"] = None  # importing it fails: the library must not need it
from voot.envs.robot.mesh_grasp import grasp_set, mesh_side_grasp
from voot.envs.assets.meshes import ShapeSpec, compile_scene, mesh_assets
g = grasp_set(ShapeSpec("mug", (0.12, 0.085, 0.1), 1))
mesh_assets([ShapeSpec("bowl", (0.16, 0.16, 0.07))])
print(round(g.hit_fraction, 6))
"""


_TABLE_DIGEST = """
import hashlib
from voot.envs.robot.mesh_grasp import grasp_set
from voot.envs.assets.meshes import ShapeSpec

g = grasp_set(ShapeSpec("jug", (0.16, 0.11, 0.25), 2))
print(hashlib.sha256(g.depth.tobytes() + g.normal.tobytes()).hexdigest())
"""


def test_grasp_tables_are_the_same_in_another_process(tmp_path: Path) -> None:
    env = {**os.environ, "VOOT_CACHE": str(tmp_path / "other")}
    out = subprocess.run(
        [sys.executable, "-c", _TABLE_DIGEST], env=env, capture_output=True, text=True, check=True
    )
    g = grasp_set(ShapeSpec("jug", (0.16, 0.11, 0.25), 2))
    here = hashlib.sha256(g.depth.tobytes() + g.normal.tobytes()).hexdigest()
    assert out.stdout.strip().splitlines()[-1] == here


def test_the_library_needs_no_rtree(tmp_path: Path) -> None:
    env = {**os.environ, "VOOT_CACHE": str(tmp_path / "cache")}
    out = subprocess.run(
        [sys.executable, "-c", _NO_RTREE], env=env, capture_output=True, text=True, check=True
    )
    assert 0.5 < float(out.stdout.strip().splitlines()[-1]) < 1.0


def test_cast_grasp_rays_takes_the_nearest_hit() -> None:
    # two boxes one behind the other along x: the +x rays stop at the nearer one
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


def _reference_depth(table: np.ndarray, hf: float, df: float) -> float:
    """The lookup rule written plainly: nearest node decides, bilinear if 4 neighbours hit."""
    rows, cols = table.shape
    i = min(rows - 1, max(0, math.floor(hf * rows)))
    j = min(cols - 1, max(0, math.floor(df * cols)))
    if np.isnan(table[i, j]):
        return math.nan
    ci, cj = hf * rows - 0.5, df * cols - 0.5
    i0 = min(rows - 2, max(0, math.floor(ci)))
    j0 = min(cols - 2, max(0, math.floor(cj)))
    wi, wj = min(1.0, max(0.0, ci - i0)), min(1.0, max(0.0, cj - j0))
    q = table[i0 : i0 + 2, j0 : j0 + 2]
    if np.isnan(q).any():
        return float(table[i, j])
    return float(
        (1 - wi) * ((1 - wj) * q[0, 0] + wj * q[0, 1]) + wi * ((1 - wj) * q[1, 0] + wj * q[1, 1])
    )


def test_the_lookup_is_nearest_for_hits_and_bilinear_for_depth() -> None:
    table = np.array([[0.0, 1.0, np.nan], [2.0, 3.0, 4.0], [np.nan, 5.0, 6.0]])
    rows = table.tolist()
    # node centres: the node's own value
    assert MG._surface_depth(rows, 0.5 / 3, 0.5 / 3) == 0.0
    assert MG._surface_depth(rows, 1.5 / 3, 2.5 / 3) == 4.0
    # halfway between four hitting nodes: their mean
    assert MG._surface_depth(rows, 1.0 / 3, 1.0 / 3) == pytest.approx(1.5)
    # next to a missing node: the nearest node's value; on a missing node: NaN
    assert MG._surface_depth(rows, 0.9 / 3, 1.9 / 3) == 1.0
    assert math.isnan(MG._surface_depth(rows, 0.2 / 3, 2.9 / 3))
    # out of [0, 1]: clamped to the border
    assert MG._surface_depth(rows, -0.5, 0.0) == 0.0 and MG._surface_depth(rows, 2.0, 2.0) == 6.0
    bottle = grasp_set(BOTTLE).depth[0]
    rng = np.random.default_rng(3)
    for hf, df in rng.uniform(-0.2, 1.2, (2000, 2)):
        got = MG._surface_depth(bottle.tolist(), float(hf), float(df))
        want = _reference_depth(bottle, float(hf), float(df))
        assert got == want or (math.isnan(got) and math.isnan(want))
