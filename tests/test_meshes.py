"""Tests of voot.envs.meshes: trimesh object shapes, their MJCF and the mesh cache."""

from __future__ import annotations

import hashlib
import math
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import mujoco
import numpy as np
import pytest
import trimesh
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from voot.envs import meshes as M
from voot.envs.meshes import SHAPE_KINDS, ShapeSpec, build_shape
from voot.envs.scene import movable_objects, object_pose

#: A plausible size per kind (metres).
SIZES: dict[str, tuple[float, float, float]] = {
    "box": (0.1, 0.15, 0.2),
    "crate": (0.4, 0.3, 0.25),
    "tray": (0.4, 0.3, 0.04),
    "bin": (0.3, 0.2, 0.2),
    "bowl": (0.16, 0.16, 0.07),
    "plate": (0.26, 0.26, 0.025),
    "mug": (0.12, 0.085, 0.1),
    "bucket": (0.28, 0.28, 0.3),
    "bottle": (0.07, 0.07, 0.25),
    "jug": (0.16, 0.11, 0.25),
}


@pytest.fixture(autouse=True)
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A fresh cache folder (never ~/.cache) and empty in-process caches."""
    monkeypatch.setenv("VOOT_CACHE", str(tmp_path / "cache"))
    M.clear_memory_cache()
    yield tmp_path / "cache"
    M.clear_memory_cache()


def scene_xml(specs: list[ShapeSpec], poses: list[tuple[float, float, float, float]]) -> str:
    """A tiny scene: a floor, the robot, one object per spec (bodies obj_0, obj_1, ...)."""
    bodies = "".join(
        M.object_body_xml(f"obj_{i}", s, p, "stuff")
        for i, (s, p) in enumerate(zip(specs, poses, strict=True))
    )
    return f"""<mujoco model="tiny">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="0.002"/>
  <asset>
    <material name="stuff" rgba="0.8 0.5 0.3 1"/>
{M.shape_assets_xml(specs)}  </asset>
  <default>
    <default class="scene"><geom contype="2" conaffinity="5" group="0"/></default>
    <default class="object"><geom contype="4" conaffinity="7" group="0" density="100"/></default>
    <default class="decor"><geom contype="0" conaffinity="0" group="1"/></default>
  </default>
  <include file="robot.xml"/>
  <worldbody>
    <geom name="floor" class="scene" type="plane" size="5 5 0.1" pos="0 0 0"/>
{bodies}  </worldbody>
</mujoco>
"""


def inside_hull(hull: trimesh.Trimesh, points: np.ndarray, tol: float) -> np.ndarray:
    """Which ``points`` lie in the convex ``hull`` (within ``tol`` of its faces)."""
    normals = np.asarray(hull.face_normals)
    offsets = np.einsum("ij,ij->i", normals, np.asarray(hull.triangles)[:, 0, :])
    inside: np.ndarray = np.all(points @ normals.T - offsets <= tol, axis=1)
    return inside


# ----- shapes -----------------------------------------------------------------------------
@pytest.mark.parametrize("variant", [0, 1, 7])
@pytest.mark.parametrize("kind", SHAPE_KINDS)
def test_every_kind_is_watertight_convex_parts_and_spans_its_size(kind: str, variant: int) -> None:
    spec = ShapeSpec(kind, SIZES[kind], variant)
    shape = build_shape(spec)
    assert shape.visual.is_watertight and shape.visual.is_winding_consistent
    assert shape.visual.volume > 0
    lo, hi = shape.visual.bounds
    np.testing.assert_allclose(hi - lo, spec.size, rtol=0, atol=1e-12)
    np.testing.assert_allclose(lo, [-spec.size[0] / 2, -spec.size[1] / 2, 0.0], atol=1e-12)
    assert shape.parts and all(p.is_convex and p.volume > 0 for p in shape.parts)
    # the parts cover the shape: every vertex of the visual mesh is in some part
    verts = np.asarray(shape.visual.vertices)
    covered = np.zeros(len(verts), dtype=bool)
    for p in shape.parts:
        covered |= inside_hull(p, verts, 1e-9)
    assert covered.all(), f"{int((~covered).sum())} vertices of {spec} outside every part"


def test_the_hollow_kinds_are_hollow_and_the_solid_ones_solid() -> None:
    # a vessel's volume is a fraction of its hull's; a box fills its bounding box
    for kind in ("crate", "tray", "bin", "bowl", "mug", "bucket"):
        shape = build_shape(ShapeSpec(kind, SIZES[kind]))
        assert shape.visual.volume < 0.5 * shape.visual.convex_hull.volume, kind
    box = build_shape(ShapeSpec("box", (0.1, 0.2, 0.3)))
    assert box.visual.volume == pytest.approx(0.1 * 0.2 * 0.3, rel=1e-12)
    assert box.mass == pytest.approx(0.1 * 0.2 * 0.3 * M.DENSITY["box"], rel=1e-12)


def test_variants_differ_and_a_spec_builds_the_same_mesh_twice() -> None:
    a, b = (
        build_shape(ShapeSpec("bottle", SIZES["bottle"], 1)),
        build_shape(ShapeSpec("bottle", SIZES["bottle"], 2)),
    )
    assert not np.array_equal(a.visual.vertices, b.visual.vertices)
    again = build_shape(ShapeSpec("bottle", SIZES["bottle"], 1))
    assert np.array_equal(a.visual.vertices, again.visual.vertices)
    assert np.array_equal(a.visual.faces, again.visual.faces)


def test_mugs_and_jugs_have_the_handle_on_the_plus_x_side() -> None:
    for kind in ("mug", "jug"):
        shape = build_shape(ShapeSpec(kind, SIZES[kind]))
        assert shape.visual.body_count == 2  # body and handle shells
        # the handle sits at the +x end: the centre of mass is pulled that way, the
        # body's axis is on the -x side of the bounding box's centre
        assert shape.center_of_mass[0] < 0.0


def test_mass_and_inertia_are_trimesh_s_and_positive_definite() -> None:
    for kind in SHAPE_KINDS:
        shape = build_shape(ShapeSpec(kind, SIZES[kind], 3))
        props = shape.visual.mass_properties  # density set by build_shape
        assert shape.visual.density == M.DENSITY[kind]
        assert shape.mass == pytest.approx(shape.visual.volume * M.DENSITY[kind], rel=1e-12)
        assert shape.mass == props["mass"]
        np.testing.assert_array_equal(shape.inertia, props["inertia"])
        np.testing.assert_array_equal(shape.center_of_mass, props["center_mass"])
        np.testing.assert_allclose(shape.inertia, shape.inertia.T, atol=1e-15)
        eig = np.linalg.eigvalsh(shape.inertia)
        assert eig.min() > 0, kind
        # the principal moments of a real body satisfy the triangle inequality
        assert eig[0] + eig[1] >= eig[2] * (1 - 1e-9), kind


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    kind=st.sampled_from(SHAPE_KINDS),
    size=st.tuples(st.floats(0.03, 0.6), st.floats(0.03, 0.6), st.floats(0.02, 0.6)),
    variant=st.integers(0, 1000),
)
def test_any_size_gives_a_watertight_mesh_of_that_size(
    kind: str, size: tuple[float, float, float], variant: int
) -> None:
    spec = ShapeSpec(kind, size, variant)
    shape = build_shape(spec)
    assert shape.visual.is_watertight and shape.visual.volume > 0
    np.testing.assert_allclose(shape.visual.extents, size, rtol=1e-12, atol=1e-15)
    assert all(p.is_convex for p in shape.parts)
    assert shape.mass > 0 and np.linalg.eigvalsh(shape.inertia).min() > 0
    # it stands on its base (not on a handle): the vertices at z = 0 span at least 30 %
    # of the footprint both ways
    verts = np.asarray(shape.visual.vertices)
    base = verts[verts[:, 2] < 1e-12]
    assert np.ptp(base[:, 0]) >= 0.3 * size[0] and np.ptp(base[:, 1]) >= 0.3 * size[1]


# ----- specs ------------------------------------------------------------------------------
def test_specs_are_validated_with_clear_errors() -> None:
    with pytest.raises(ValueError, match=r"kind must be one of box, crate.*got 'teapot'"):
        ShapeSpec("teapot", (0.1, 0.1, 0.1))
    with pytest.raises(ValueError, match=r"size\[1\] must be"):
        ShapeSpec("box", (0.1, -0.1, 0.1))
    with pytest.raises(ValueError, match=r"size\[2\] must be"):
        ShapeSpec("box", (0.1, 0.1, math.nan))
    with pytest.raises(ValueError, match=r"size\[0\] must be"):
        ShapeSpec("box", (math.inf, 0.1, 0.1))
    with pytest.raises(ValueError, match=r"size must be 3 extents"):
        ShapeSpec("box", (0.1, 0.1))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"variant must be an integer >= 0"):
        ShapeSpec("box", (0.1, 0.1, 0.1), -1)
    with pytest.raises(ValueError, match=r"variant must be"):
        ShapeSpec("box", (0.1, 0.1, 0.1), True)  # type: ignore[arg-type]


def test_a_mesh_that_is_not_watertight_is_an_error_naming_the_spec(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def open_box(spec: ShapeSpec) -> M._Build:
        box = trimesh.creation.box(spec.size)
        box.update_faces(np.arange(len(box.faces)) != 0)  # one triangle missing
        return M._Build([box], [box.convex_hull])

    monkeypatch.setitem(M._BUILDERS, "box", open_box)
    spec = ShapeSpec("box", (0.1, 0.2, 0.3), 4)
    with pytest.raises(
        ValueError, match=r"the mesh of ShapeSpec\(kind='box'.*variant=4\) is not watertight"
    ):
        build_shape(spec)
    with pytest.raises(ValueError, match="is not watertight"):
        M.compile_scene(scene_xml([spec], [(0.0, 0.0, 0.0, 0.0)]), [spec])


def test_specs_are_canonical_values_so_equal_specs_share_a_key() -> None:
    a = ShapeSpec("mug", (np.float64(0.1), 0.08, 1), np.int64(2))  # type: ignore[arg-type]
    b = ShapeSpec("mug", (0.1, 0.08, 1.0), 2)
    assert a == b and hash(a) == hash(b) and a.key == b.key
    assert type(a.size[2]) is float and type(a.variant) is int
    assert ShapeSpec("mug", (0.1, 0.08, 1.0), 3).key != b.key
    assert ShapeSpec("bowl", (0.1, 0.08, 1.0), 2).key != b.key


# ----- files and cache --------------------------------------------------------------------
def test_stl_bytes_are_a_binary_stl_of_the_mesh() -> None:
    shape = build_shape(ShapeSpec("bowl", SIZES["bowl"]))
    data = M.stl_bytes(shape.visual, "bowl")
    n = int.from_bytes(data[80:84], "little")
    assert n == len(shape.visual.faces) and len(data) == 84 + 50 * n
    assert data[:80].startswith(b"voot.envs.meshes bowl")
    back = trimesh.load_mesh(trimesh.util.wrap_as_stream(data), file_type="stl")
    assert back.is_watertight
    np.testing.assert_allclose(back.extents, SIZES["bowl"], atol=1e-7)


_DIGEST = """
import hashlib, sys
from voot.envs.meshes import ShapeSpec, mesh_assets
specs = [ShapeSpec("mug", (0.12, 0.085, 0.1), 3), ShapeSpec("crate", (0.4, 0.3, 0.25), 1)]
files = mesh_assets(specs)
h = hashlib.sha256()
for name in sorted(files):
    h.update(name.encode()); h.update(files[name])
print(h.hexdigest())
"""


def test_mesh_bytes_are_the_same_in_another_process(tmp_path: Path) -> None:
    digests = []
    for i in range(2):
        env = {**os.environ, "VOOT_CACHE": str(tmp_path / f"other{i}")}
        out = subprocess.run(
            [sys.executable, "-c", _DIGEST], env=env, capture_output=True, text=True, check=True
        )
        digests.append(out.stdout.strip().splitlines()[-1])
    specs = [ShapeSpec("mug", (0.12, 0.085, 0.1), 3), ShapeSpec("crate", (0.4, 0.3, 0.25), 1)]
    files = M.mesh_assets(specs)
    h = hashlib.sha256()
    for name in sorted(files):
        h.update(name.encode())
        h.update(files[name])
    assert digests == [h.hexdigest(), h.hexdigest()]


def test_the_cache_is_written_once_and_read_back_the_same(cache: Path) -> None:
    specs = [ShapeSpec("bowl", SIZES["bowl"], 1), ShapeSpec("box", SIZES["box"])]
    cold = M.mesh_assets(specs)
    files = sorted(p.name for p in (cache / "meshes").iterdir())
    assert files == sorted(f"{s.key}.mesh.npz" for s in specs)
    stamps = {p: p.stat().st_mtime_ns for p in (cache / "meshes").iterdir()}
    M.clear_memory_cache()
    warm = M.mesh_assets(specs)  # from the disk
    assert warm == cold
    assert {p: p.stat().st_mtime_ns for p in (cache / "meshes").iterdir()} == stamps
    assert M.mesh_assets(specs) is not None and M._MEMORY  # now from the process


def test_a_corrupt_cache_file_is_rebuilt(cache: Path) -> None:
    spec = ShapeSpec("plate", SIZES["plate"])
    cold = M.mesh_assets([spec])
    path = cache / "meshes" / f"{spec.key}.mesh.npz"
    path.write_bytes(b"not a zip file")
    M.clear_memory_cache()
    assert M.mesh_assets([spec]) == cold
    assert path.read_bytes()[:2] == b"PK"  # rewritten


def test_a_cache_file_of_another_layout_is_rebuilt(cache: Path) -> None:
    spec = ShapeSpec("tray", SIZES["tray"])
    cold = M.mesh_assets([spec])
    path = cache / "meshes" / f"{spec.key}.mesh.npz"
    np.savez(path, visual=np.zeros(3, dtype=np.uint8))  # readable, but not an entry
    M.clear_memory_cache()
    assert M.mesh_assets([spec]) == cold
    with np.load(path) as z:
        assert sorted(z.files) == ["inertial", "sizes", "stl"]


def test_cache_writes_are_atomic(cache: Path) -> None:
    spec = ShapeSpec("bin", SIZES["bin"])

    def broken(*args: object, **kwargs: object) -> None:
        raise OSError("disk full")

    with pytest.MonkeyPatch.context() as mp:  # undone on leaving; VOOT_CACHE stays
        mp.setattr(np, "savez", broken)
        with pytest.raises(OSError, match="disk full"):
            M.mesh_assets([spec])
    assert list((cache / "meshes").iterdir()) == []  # no half file, no temporary left
    M.mesh_assets([spec])
    assert [p.name for p in (cache / "meshes").iterdir()] == [f"{spec.key}.mesh.npz"]


def test_the_cache_folder_follows_voot_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("VOOT_CACHE", "/some/where")
    assert M.cache_dir() == Path("/some/where")
    monkeypatch.delenv("VOOT_CACHE")
    assert M.cache_dir() == Path.home() / ".cache" / "voot"


def test_assets_and_asset_xml_are_deduplicated() -> None:
    mug = ShapeSpec("mug", SIZES["mug"])
    box = ShapeSpec("box", SIZES["box"])
    files = M.mesh_assets([mug, box, mug])
    n_mug = len(build_shape(mug).parts)
    assert len(files) == (1 + n_mug) + (1 + 1)
    xml = M.shape_assets_xml([mug, box, mug])
    assert xml.count("<mesh ") == len(files)
    for name in files:
        assert f'file="{name}"' in xml
    with pytest.raises(TypeError, match="ShapeSpec"):
        M.mesh_assets(["mug"])  # type: ignore[list-item]


# ----- MJCF -------------------------------------------------------------------------------
def test_object_body_xml_has_a_free_joint_collision_parts_and_a_visual_mesh() -> None:
    spec = ShapeSpec("bucket", SIZES["bucket"])
    xml = M.object_body_xml("obj_bucket", spec, (1.0, 2.0, 0.5, 0.25), "steel")
    assert xml.lstrip().startswith('<body name="obj_bucket" pos="1.0 2.0 0.5" euler="0 0 0.25">')
    assert '<freejoint name="obj_bucket"/>' in xml
    n = len(build_shape(spec).parts)
    assert xml.count('class="object" type="mesh"') == n
    assert xml.count('class="decor" type="mesh"') == 1
    assert xml.count("<inertial ") == 1 and xml.count('material="steel"') == n + 1
    for bad in ("bucket", "obj_", "box_obj_1"):
        with pytest.raises(ValueError, match="must start with 'obj_'"):
            M.object_body_xml(bad, spec, (0.0, 0.0, 0.0, 0.0), "steel")
    with pytest.raises(ValueError, match=r"pose\[3\] must be"):
        M.object_body_xml("obj_b", spec, (0.0, 0.0, 0.0, math.nan), "steel")
    with pytest.raises(ValueError, match=r"pose must be \(x, y, z, yaw\)"):
        M.object_body_xml("obj_b", spec, (0.0, 0.0, 0.0), "steel")  # type: ignore[arg-type]


def test_a_scene_of_three_mesh_objects_compiles_and_its_objects_are_found() -> None:
    specs = [
        ShapeSpec("mug", SIZES["mug"], 2),
        ShapeSpec("bottle", SIZES["bottle"], 1),
        ShapeSpec("crate", SIZES["crate"]),
    ]
    poses = [(1.0, 0.5, 0.0, 0.3), (1.5, -0.5, 0.0, -1.0), (2.0, 1.0, 0.0, 2.0)]
    model = M.compile_scene(scene_xml(specs, poses), specs)
    objs = movable_objects(model)
    assert [o.name for o in objs] == ["obj_0", "obj_1", "obj_2"]
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    for o, s, p in zip(objs, specs, poses, strict=True):
        shape = build_shape(s)
        # the footprint and height are the spec's (float32 STL vertices)
        np.testing.assert_allclose(o.half, np.array(s.size[:2]) / 2, atol=1e-7)
        np.testing.assert_allclose(o.center, [0.0, 0.0], atol=1e-7)
        assert o.height == pytest.approx(s.size[2], abs=1e-7)
        np.testing.assert_allclose(object_pose(data, o), p, atol=1e-12)
        # the inertial is the mesh's
        assert model.body_mass[o.body] == pytest.approx(shape.mass, rel=1e-12)
        np.testing.assert_allclose(model.body_ipos[o.body], shape.center_of_mass, atol=1e-12)
        np.testing.assert_allclose(
            np.sort(model.body_inertia[o.body]), np.linalg.eigvalsh(shape.inertia), rtol=1e-9
        )
        assert len(o.geoms) == len(shape.parts) + 1
        assert all(model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH for g in o.geoms)


def test_objects_rest_on_the_floor_on_their_collision_parts() -> None:
    specs = [ShapeSpec(k, SIZES[k], v) for k in SHAPE_KINDS for v in (0, 3)]
    poses = [(1.0 + 0.6 * (i % 10), 1.0 + 0.7 * (i // 10), 0.002, 0.1 * i) for i in range(20)]
    model = M.compile_scene(scene_xml(specs, poses), specs)
    data = mujoco.MjData(model)
    objs = movable_objects(model)
    for _ in range(500):  # one second
        mujoco.mj_step(model, data)
    for o, p in zip(objs, poses, strict=True):
        x, y, z, _ = object_pose(data, o)
        assert abs(z) < 0.003, o.name  # settled on the floor, not through it
        assert math.hypot(x - p[0], y - p[1]) < 0.01, o.name
        quat = data.qpos[o.qpos_adr + 3 : o.qpos_adr + 7]
        assert abs(quat[1]) < 0.01 and abs(quat[2]) < 0.01, o.name  # still upright


def test_cached_and_fresh_meshes_compile_to_the_same_model() -> None:
    specs = [ShapeSpec("jug", SIZES["jug"], 4), ShapeSpec("bin", SIZES["bin"], 5)]
    xml = scene_xml(specs, [(1.0, 0.0, 0.0, 0.0), (2.0, 0.0, 0.0, 1.0)])
    fresh = M.compile_scene(xml, specs)
    M.clear_memory_cache()
    cached = M.compile_scene(xml, specs)
    for name in ("mesh_vert", "mesh_face", "geom_pos", "geom_quat", "body_mass", "body_inertia"):
        np.testing.assert_array_equal(getattr(fresh, name), getattr(cached, name), err_msg=name)
