"""Tests of voot.envs.assets.meshes: the shapes' files, the mesh cache and their MJCF (the shapes
themselves: tests/envs/assets/test_mesh_shapes.py)."""

from __future__ import annotations

import hashlib
import math
import os
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
import trimesh
from mesh_fixtures import SIZES

from voot.envs.assets import mesh_shapes as S
from voot.envs.assets import meshes as M
from voot.envs.assets.meshes import SHAPE_KINDS, ShapeSpec, build_shape
from voot.envs.core.caches import CacheWarning
from voot.envs.core.scene import movable_objects, object_pose

#: Every test gets a fresh mesh cache (never ~/.cache).
pytestmark = pytest.mark.usefixtures("mesh_cache")


def scene_xml(specs: list[ShapeSpec], poses: list[tuple[float, float, float, float]]) -> str:
    """A tiny scene: a floor, the robot, one object per spec (bodies obj_0, obj_1, ...)."""
    return M.objects_scene_xml(specs, poses, "tiny")


# ----- shapes -----------------------------------------------------------------------------


def test_a_mesh_that_is_not_watertight_is_an_error_naming_the_spec(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def open_box(spec: ShapeSpec) -> S._Build:
        box = trimesh.creation.box(spec.size)
        box.update_faces(np.arange(len(box.faces)) != 0)  # one triangle missing
        return S._Build([box], [box.convex_hull])

    monkeypatch.setitem(S._BUILDERS, "box", open_box)
    spec = ShapeSpec("box", (0.1, 0.2, 0.3), 4)
    with pytest.raises(
        ValueError, match=r"the mesh of ShapeSpec\(kind='box'.*variant=4\) is not watertight"
    ):
        build_shape(spec)
    with pytest.raises(ValueError, match="is not watertight"):
        M.compile_scene(scene_xml([spec], [(0.0, 0.0, 0.0, 0.0)]), [spec])


# ----- files and cache --------------------------------------------------------------------
def test_stl_bytes_are_a_binary_stl_of_the_mesh() -> None:
    shape = build_shape(ShapeSpec("bowl", SIZES["bowl"]))
    data = M.stl_bytes(shape.visual, "bowl")
    n = int.from_bytes(data[80:84], "little")
    assert n == len(shape.visual.faces) and len(data) == 84 + 50 * n
    assert data[:80].startswith(b"voot.envs.assets.meshes bowl")
    back = trimesh.load_mesh(trimesh.util.wrap_as_stream(data), file_type="stl")
    assert back.is_watertight
    np.testing.assert_allclose(back.extents, SIZES["bowl"], atol=1e-7)


_DIGEST = """
import hashlib, sys
from voot.envs.assets.meshes import ShapeSpec, mesh_assets

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


def test_the_cache_is_written_once_and_read_back_the_same(mesh_cache: Path) -> None:
    specs = [ShapeSpec("bowl", SIZES["bowl"], 1), ShapeSpec("box", SIZES["box"])]
    cold = M.mesh_assets(specs)
    files = sorted(p.name for p in (mesh_cache / "meshes").iterdir())
    assert files == sorted(f"{s.key}.mesh.npz" for s in specs)
    stamps = {p: p.stat().st_mtime_ns for p in (mesh_cache / "meshes").iterdir()}
    M.clear_memory_cache()
    warm = M.mesh_assets(specs)  # from the disk
    assert warm == cold
    assert {p: p.stat().st_mtime_ns for p in (mesh_cache / "meshes").iterdir()} == stamps
    assert M.mesh_assets(specs) is not None and M._MEMORY  # now from the process


def test_a_corrupt_cache_file_is_rebuilt(mesh_cache: Path) -> None:
    spec = ShapeSpec("plate", SIZES["plate"])
    cold = M.mesh_assets([spec])
    path = mesh_cache / "meshes" / f"{spec.key}.mesh.npz"
    path.write_bytes(b"not a zip file")
    M.clear_memory_cache()
    with pytest.warns(CacheWarning, match=rf"{spec.key}\.mesh\.npz cannot be read"):
        assert M.mesh_assets([spec]) == cold
    assert path.read_bytes()[:2] == b"PK"  # rewritten


def test_a_cache_file_of_another_layout_is_rebuilt(mesh_cache: Path) -> None:
    spec = ShapeSpec("tray", SIZES["tray"])
    cold = M.mesh_assets([spec])
    path = mesh_cache / "meshes" / f"{spec.key}.mesh.npz"
    np.savez(path, visual=np.zeros(3, dtype=np.uint8))  # readable, but not an entry
    M.clear_memory_cache()
    assert M.mesh_assets([spec]) == cold
    with np.load(path) as z:
        assert sorted(z.files) == ["__key__", "__sha256__", "inertial", "sizes", "stl"]


def test_cache_writes_are_atomic(mesh_cache: Path) -> None:
    spec = ShapeSpec("bin", SIZES["bin"])

    def broken(*args: object, **kwargs: object) -> None:
        raise OSError("disk full")

    with pytest.MonkeyPatch.context() as mp:  # undone on leaving; VOOT_CACHE stays
        mp.setattr(os, "replace", broken)
        with pytest.warns(CacheWarning, match="could not write .*disk full"):
            files = M.mesh_assets([spec])  # built, kept in memory, no error
    assert files
    assert list((mesh_cache / "meshes").iterdir()) == []  # no half file, no temporary left
    M.clear_memory_cache()
    M.mesh_assets([spec])
    assert [p.name for p in (mesh_cache / "meshes").iterdir()] == [f"{spec.key}.mesh.npz"]


def test_compile_scene_leaves_no_mesh_in_mujocos_asset_cache(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """MuJoCo keeps every mesh it compiled (the storage rooms' RSS creep, about 0.33 MB a
    new layout, docs/environments.md): a generated scene's compile bypasses that cache and
    restores its capacity; $VOOT_MUJOCO_CACHE_MB sets the capacity instead; the same model
    either way."""
    cache = mujoco.mj_getCache()
    before = mujoco.mj_getCacheCapacity(cache)
    specs = [ShapeSpec("mug", SIZES["mug"], 11)]
    xml = scene_xml(specs, [(0.0, 0.0, 0.5, 0.0)])
    try:
        monkeypatch.delenv("VOOT_MUJOCO_CACHE_MB", raising=False)
        mujoco.mj_setCacheCapacity(cache, 50_000_000)
        mujoco.mj_clearCache(cache)
        bypassed = M.compile_scene(xml, specs)
        assert mujoco.mj_getCacheCapacity(cache) == 50_000_000  # restored
        assert mujoco.mj_getCacheSize(cache) == 0  # nothing kept
        monkeypatch.setenv("VOOT_MUJOCO_CACHE_MB", "50")
        cached = M.compile_scene(xml, specs)
        assert mujoco.mj_getCacheCapacity(cache) == 50_000_000
        assert mujoco.mj_getCacheSize(cache) > 0  # asked for: the meshes are kept
        again = M.compile_scene(xml, specs)  # served from the cache
        for model in (cached, again):
            assert model.nmesh == bypassed.nmesh > 0
            assert np.array_equal(model.mesh_vert, bypassed.mesh_vert)
            assert np.array_equal(model.body_inertia, bypassed.body_inertia)
        monkeypatch.setenv("VOOT_MUJOCO_CACHE_MB", "-3")
        with pytest.raises(ValueError, match="VOOT_MUJOCO_CACHE_MB='-3'"):
            M.compile_scene(xml, specs)
    finally:
        mujoco.mj_setCacheCapacity(cache, before)


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


def test_swapped_or_edited_mesh_files_are_rebuilt_naming_them(mesh_cache: Path) -> None:
    """Before: a file copied over another spec's was served (the kitchen got the wrong
    shapes); now each file is checked against the spec and tag it was made for."""
    mug, bowl = ShapeSpec("mug", SIZES["mug"]), ShapeSpec("bowl", SIZES["bowl"])
    right = M.mesh_assets([mug])
    M.mesh_assets([bowl])
    folder = mesh_cache / "meshes"
    mug_file, bowl_file = folder / f"{mug.key}.mesh.npz", folder / f"{bowl.key}.mesh.npz"
    mug_file.write_bytes(bowl_file.read_bytes())
    M.clear_memory_cache()
    with pytest.warns(CacheWarning, match=rf"{mug.key}\.mesh\.npz holds 'mesh\|bowl"):
        assert M.mesh_assets([mug]) == right
    # an edit inside a file with its key: refused by its digest
    with np.load(mug_file) as z:
        arrays = {k: z[k] for k in z.files}
    arrays["inertial"] = arrays["inertial"] * 2.0
    np.savez(mug_file, **arrays)
    M.clear_memory_cache()
    with pytest.warns(CacheWarning, match="does not match its digest"):
        assert M.mesh_assets([mug]) == right
    # a grasp table's file under a mesh's name: another tag
    from voot.envs.robot.mesh_grasp import grasp_set

    grasp_set(mug)
    mug_file.write_bytes((folder / f"{mug.key}.grasp.npz").read_bytes())
    M.clear_memory_cache()
    with pytest.warns(CacheWarning, match="holds 'grasp"):
        assert M.mesh_assets([mug]) == right


def test_the_memory_caches_are_bounded() -> None:
    assert all(memo.size == M.MEMO_SIZE for memo in M.MEMORY_CACHES)


def test_cached_arrays_come_from_the_disk_when_intact(mesh_cache: Path) -> None:
    spec = ShapeSpec("crate", SIZES["crate"])
    built = {"a": np.arange(3.0), "b": np.array([7], dtype=np.int64)}
    calls = []

    def build() -> dict[str, np.ndarray]:
        calls.append(1)
        return built

    first, from_disk = M.cached_arrays(spec, "probe", build, ("a", "b"))
    assert from_disk is False and len(calls) == 1 and first is built
    again, from_disk = M.cached_arrays(spec, "probe", build, ("a", "b"))
    assert from_disk is True and len(calls) == 1  # read back, not built
    assert sorted(again) == ["a", "b"] and np.array_equal(again["a"], built["a"])
    # a required array missing: rebuilt
    _, from_disk = M.cached_arrays(spec, "probe", build, ("a", "b", "c"))
    assert from_disk is False and len(calls) == 2
    # a file with its key but no digest (or the reverse) is not served
    path = mesh_cache / "meshes" / f"{spec.key}.probe.npz"
    with np.load(path) as z:
        members = {k: z[k] for k in z.files}
    for drop in ("__key__", "__sha256__"):
        np.savez(path, **{k: v for k, v in members.items() if k != drop})
        _, from_disk = M.cached_arrays(spec, "probe", build)
        assert from_disk is False
