"""Object meshes as MuJoCo assets: STL files, a disk cache, MJCF bodies, compiled scenes.

The shapes themselves (:class:`ShapeSpec`, :func:`build_shape`: the trimesh mesh, its
convex parts and its mass) are :mod:`voot.envs.assets.mesh_shapes`, re-exported here. This
module turns them into what MuJoCo loads: :func:`object_body_xml` writes the MJCF body (a
free joint, the collision geoms of class ``object``, a visual geom of class ``decor``,
the inertial), :func:`shape_assets_xml` the ``<mesh>`` entries of the ``<asset>``
section, :func:`mesh_assets` the binary STL files for ``mujoco.MjModel.from_xml_string``
and :func:`compile_scene` compiles a scene that includes ``robot.xml`` with them.

Cost: building a shape (sweep, hulls, mass properties, STL bytes and the grasp rays of
:mod:`voot.envs.robot.mesh_grasp`) takes 14-45 ms of CPU; each spec's result is cached on disk
(:func:`cache_dir`: ``$VOOT_CACHE`` or ``~/.cache/voot``, under ``meshes/``, keyed by a
hash of the spec and :data:`GENERATOR_VERSION`, written atomically, each file checked
against the spec it was made for and its digest before it is served:
:mod:`voot.envs.core.caches`) and in the process (the last :data:`MEMO_SIZE` shapes).
The measured figures are in docs/meshes.md (``voot-bench mesh-speed``).
"""

from __future__ import annotations

import io
import struct
import zipfile
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import mujoco
import numpy as np
import trimesh
from numpy.typing import NDArray

from voot import validation as V
from voot.envs.assets.mesh_shapes import (
    DENSITY,
    GENERATOR_VERSION,
    SHAPE_KINDS,
    MeshShape,
    ShapeSpec,
    build_shape,
    built_shape,
)
from voot.envs.assets.mjcf import OBJECT_PREFIX, ROBOT_INCLUDE, collision_defaults
from voot.envs.core.caches import (
    LRUMemo,
    cache_dir,
    generated_compile,
    sha256,
    warn_rebuilt,
    write_atomic,
)

FloatArray = NDArray[np.float64]

__all__ = [
    "DENSITY",
    "GENERATOR_VERSION",
    "MEMORY_CACHES",
    "MEMO_SIZE",
    "SHAPE_KINDS",
    "MeshShape",
    "ShapeSpec",
    "build_shape",
    "built_shape",
    "cache_dir",
    "cached_arrays",
    "clear_memory_cache",
    "compile_scene",
    "mesh_assets",
    "mesh_name",
    "object_body_xml",
    "objects_scene_xml",
    "shape_assets_xml",
    "stl_bytes",
]


# ----- files ------------------------------------------------------------------------------
def stl_bytes(mesh: trimesh.Trimesh, label: str = "") -> bytes:
    """``mesh`` as a binary STL (float32), deterministic: same mesh, same bytes.

    The 80-byte header says ``voot.envs.assets.meshes`` and ``label``; no date, no version.
    """
    tri = np.asarray(mesh.triangles, dtype="<f4")
    rec = np.zeros(len(tri), dtype=[("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"] = np.asarray(mesh.face_normals, dtype="<f4")
    rec["v"] = tri
    header = f"voot.envs.assets.meshes {label}".encode()[:80].ljust(80, b" ")
    return header + struct.pack("<I", len(tri)) + rec.tobytes()


def mesh_name(spec: ShapeSpec) -> str:
    """Name of ``spec``'s visual mesh asset (its collision parts: ``<name>_c<i>``)."""
    return f"voot_{spec.kind}_{spec.key}"


@dataclass(frozen=True)
class _Entry:
    """What the MJCF needs of one spec: the STL files and the inertial."""

    files: dict[str, bytes]
    n_parts: int
    mass: float
    center_of_mass: FloatArray
    inertia: FloatArray


def _mesh_dir() -> Path:
    return cache_dir() / "meshes"


def _arrays_digest(arrays: Mapping[str, np.ndarray]) -> str:
    """SHA-256 of ``arrays``: each one's name, dtype, shape and bytes, by name."""
    parts: list[bytes] = []
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        parts += [name.encode(), a.dtype.str.encode(), repr(a.shape).encode(), a.tobytes()]
    return sha256(*parts)


def _cache_key(spec: ShapeSpec, tag: str) -> str:
    """What a cache file holds, written in it and checked on reading: the spec (every
    number exactly), the tag and the generator's version."""
    size = ",".join(v.hex() for v in spec.size)
    return f"{tag}|{spec.kind}|{size}|{spec.variant}|g{GENERATOR_VERSION}"


def _write_npz(path: Path, arrays: dict[str, np.ndarray], key: str) -> None:
    """Write ``arrays`` to ``path`` with their key and digest, atomically
    (:func:`voot.envs.core.caches.write_atomic`); nothing if the cache is unusable."""
    stored = dict(arrays)
    stored[_KEY] = np.frombuffer(key.encode(), dtype=np.uint8)
    stored[_DIGEST] = np.frombuffer(_arrays_digest(arrays).encode(), dtype=np.uint8)
    buffer = io.BytesIO()
    np.savez(buffer, **stored)  # type: ignore[arg-type]
    write_atomic(path, buffer.getvalue())


def _read_npz(path: Path, key: str) -> dict[str, np.ndarray] | None:
    """The arrays of ``path`` if it holds those of ``key``, intact; else None.

    A missing file is None silently (it is built); a file that cannot be read, that was
    made for another key (swapped or copied in) or whose arrays do not match their
    digest (edited) is None with a :class:`~voot.envs.core.caches.CacheWarning` naming
    it (it is rebuilt and replaced). A file of the format before keys (no key inside) is
    rebuilt silently.
    """
    if not path.is_file():
        return None
    try:
        with np.load(path, allow_pickle=False) as z:
            got = {k: z[k] for k in z.files}
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
        warn_rebuilt(path, f"cannot be read ({type(exc).__name__})")
        return None
    stored_key = got.pop(_KEY, None)
    stored_digest = got.pop(_DIGEST, None)
    if stored_key is None or stored_digest is None:
        return None  # written before files carried their key: rebuilt
    if stored_key.tobytes() != key.encode():
        warn_rebuilt(path, f"holds {stored_key.tobytes().decode(errors='replace')!r}, not {key!r}")
        return None
    if stored_digest.tobytes() != _arrays_digest(got).encode():
        warn_rebuilt(path, "does not match its digest (edited)")
        return None
    return got


#: The names of a cache file's key and digest members.
_KEY, _DIGEST = "__key__", "__sha256__"


def cached_arrays(
    spec: ShapeSpec,
    tag: str,
    build: Callable[[], dict[str, np.ndarray]],
    required: Iterable[str] = (),
) -> tuple[dict[str, np.ndarray], bool]:
    """The arrays ``build`` makes for ``spec``, from the disk cache if there.

    Stored as ``meshes/<key>.<tag>.npz`` under :func:`cache_dir` (written atomically),
    with the spec and tag they were made for and their digest. A file that cannot be
    read, was made for another spec or tag, was edited, or lacks one of the ``required``
    arrays is rebuilt and replaced (with a warning naming it). If the cache folder is
    unusable the arrays are built and not written (one warning names ``VOOT_CACHE``).
    Returns the arrays and whether they came from the disk.
    """
    path = _mesh_dir() / f"{spec.key}.{tag}.npz"
    key = _cache_key(spec, tag)
    got = _read_npz(path, key)
    if got is not None and all(k in got for k in required):
        return got, True
    arrays = build()
    _write_npz(path, arrays, key)
    return arrays, False


#: The most shapes whose files and inertials this process keeps (each is tens of kB; a
#: generated layout brings new shapes, so the memo is bounded).
MEMO_SIZE = 512

_MEMORY: LRUMemo[ShapeSpec, _Entry] = LRUMemo(MEMO_SIZE)
#: Every in-process cache of per-spec results (this module's and the grasp sets' of
#: :mod:`voot.envs.robot.mesh_grasp`, which adds its own): :func:`clear_memory_cache` empties them.
MEMORY_CACHES: list[LRUMemo[ShapeSpec, Any]] = [_MEMORY]


def clear_memory_cache() -> None:
    """Forget the in-process caches (the disk cache stays): the next use reads the disk."""
    for cache in MEMORY_CACHES:
        cache.clear()
    built_shape.cache_clear()


#: The arrays of a mesh cache entry (:func:`_build_arrays`).
_MESH_ARRAYS = ("stl", "sizes", "inertial")


def _build_arrays(spec: ShapeSpec) -> dict[str, np.ndarray]:
    """A spec's cache entry: its STL files end to end, their sizes, and the inertial.

    Three arrays (``stl``, ``sizes``: the visual mesh's then each part's, ``inertial``:
    mass, centre of mass, inertia tensor), so that reading it back is three zip members
    whatever the number of parts.
    """
    shape = built_shape(spec)
    name = mesh_name(spec)
    blobs = [stl_bytes(shape.visual, name)]
    blobs += [stl_bytes(p, f"{name}_c{i}") for i, p in enumerate(shape.parts)]
    inertial = np.concatenate(
        [[shape.mass], shape.center_of_mass, shape.inertia.reshape(-1)]
    ).astype(np.float64)
    return {
        "stl": np.frombuffer(b"".join(blobs), dtype=np.uint8),
        "sizes": np.array([len(b) for b in blobs], dtype=np.int64),
        "inertial": inertial,
    }


def _entry(spec: ShapeSpec) -> _Entry:
    """The spec's files and inertial: from the process, else the disk, else built."""
    got = _MEMORY.get(spec)
    if got is not None:
        return got
    arrays, _ = cached_arrays(spec, "mesh", lambda: _build_arrays(spec), _MESH_ARRAYS)
    name = mesh_name(spec)
    data = arrays["stl"].tobytes()
    ends = np.cumsum(arrays["sizes"]).tolist()
    starts = [0, *ends[:-1]]
    names = [f"{name}.stl"] + [f"{name}_c{i}.stl" for i in range(len(ends) - 1)]
    files = {n: data[a:b] for n, a, b in zip(names, starts, ends, strict=True)}
    inertial = np.asarray(arrays["inertial"], dtype=np.float64)
    entry = _Entry(
        files=files,
        n_parts=len(ends) - 1,
        mass=float(inertial[0]),
        center_of_mass=inertial[1:4].copy(),
        inertia=inertial[4:13].reshape(3, 3).copy(),
    )
    _MEMORY[spec] = entry
    return entry


def _unique(specs: Iterable[ShapeSpec]) -> list[ShapeSpec]:
    out: list[ShapeSpec] = []
    for s in specs:
        if not isinstance(s, ShapeSpec):
            raise TypeError(f"expected ShapeSpec items, got {s!r}")
        if s not in out:
            out.append(s)
    return out


def mesh_assets(specs: Iterable[ShapeSpec]) -> dict[str, bytes]:
    """File name -> STL bytes of every spec's meshes (deduplicated), for MuJoCo's ``assets``.

    Built on first use and cached (see :func:`cache_dir`), then served from the process.
    """
    files: dict[str, bytes] = {}
    for s in _unique(specs):
        files.update(_entry(s).files)
    return files


def shape_assets_xml(specs: Iterable[ShapeSpec]) -> str:
    """The ``<mesh name=... file=.../>`` lines of the specs (deduplicated) for ``<asset>``."""
    lines = []
    for s in _unique(specs):
        name = mesh_name(s)
        lines.append(f'    <mesh name="{name}" file="{name}.stl"/>\n')
        for i in range(_entry(s).n_parts):
            lines.append(f'    <mesh name="{name}_c{i}" file="{name}_c{i}.stl"/>\n')
    return "".join(lines)


def _f(v: float) -> str:
    """A float as MJCF text: the shortest repr that reads back to the same double."""
    return repr(float(v))


def object_body_xml(
    name: str, spec: ShapeSpec, pose: tuple[float, float, float, float], material: str
) -> str:
    """The MJCF ``<body>`` of a movable object of shape ``spec``.

    ``<body name=name pos="x y z" euler="0 0 yaw">`` (the scene's compiler must use
    ``angle="radian"``, as :func:`voot.envs.assets.mjcf.header`'s does) with a ``<freejoint>`` of the
    same name, the ``<inertial>`` from the mesh, one collision geom (class ``object``,
    ``type="mesh"``, group 3, hidden in the viewer) per convex part and the visual mesh
    (class ``decor``). ``pose`` is ``(x, y, z, yaw)`` with ``z`` the support height (the
    body origin is the bottom centre).

    Raises:
        ValueError: If ``name`` does not start with ``obj_`` (what
            :func:`voot.envs.core.scene.movable_objects` looks for) or ``pose`` is not 4 finite
            numbers.
    """
    if not name.startswith(OBJECT_PREFIX) or not name[len(OBJECT_PREFIX) :]:
        raise ValueError(f"object body names must start with {OBJECT_PREFIX!r}, got {name!r}")
    if len(tuple(pose)) != 4:
        raise ValueError(f"pose must be (x, y, z, yaw), got {pose!r}")
    x, y, z, yaw = (V.number(v, f"pose[{i}]") for i, v in enumerate(pose))
    e = _entry(spec)
    mesh = mesh_name(spec)
    i = e.inertia
    lines = [
        f'    <body name="{name}" pos="{_f(x)} {_f(y)} {_f(z)}" euler="0 0 {_f(yaw)}">\n',
        f'      <freejoint name="{name}"/>\n',
        f'      <inertial pos="{" ".join(_f(c) for c in e.center_of_mass)}" mass="{_f(e.mass)}" '
        f'fullinertia="{_f(i[0, 0])} {_f(i[1, 1])} {_f(i[2, 2])} '
        f'{_f(i[0, 1])} {_f(i[0, 2])} {_f(i[1, 2])}"/>\n',
    ]
    for k in range(e.n_parts):
        lines.append(
            f'      <geom name="{name}_c{k}" class="object" type="mesh" mesh="{mesh}_c{k}" '
            f'material="{material}" group="3"/>\n'
        )
    lines.append(
        f'      <geom name="{name}_visual" class="decor" type="mesh" mesh="{mesh}" '
        f'material="{material}"/>\n'
    )
    lines.append("    </body>\n")
    return "".join(lines)


def objects_scene_xml(
    specs: Sequence[ShapeSpec],
    poses: Sequence[tuple[float, float, float, float]],
    model: str = "objects",
) -> str:
    """A minimal scene of the robot, a floor and one object per spec (bodies ``obj_0``,
    ``obj_1``... at ``poses``): for measuring and testing the meshes outside a domain."""
    if len(specs) != len(poses):
        raise ValueError(f"got {len(specs)} specs but {len(poses)} poses")
    bodies = "".join(
        object_body_xml(f"obj_{i}", s, p, "stuff")
        for i, (s, p) in enumerate(zip(specs, poses, strict=True))
    )
    return f"""<mujoco model="{model}">
  <compiler angle="radian" autolimits="true"/>
  <asset>
    <material name="stuff" rgba="0.8 0.5 0.3 1"/>
{shape_assets_xml(specs)}  </asset>
  <default>
{collision_defaults(one_line=True)}  </default>
  <include file="{ROBOT_INCLUDE}"/>
  <worldbody>
    <geom name="floor" class="scene" type="plane" size="8 8 0.1"/>
{bodies}  </worldbody>
</mujoco>
"""


def compile_scene(xml: str, specs: Iterable[ShapeSpec]) -> mujoco.MjModel:
    """Compile a scene ``xml`` that includes ``robot.xml`` and uses the meshes of ``specs``.

    The assets handed to MuJoCo are ``robot.xml`` from ``voot.models`` and
    :func:`mesh_assets` of the specs. The compile bypasses MuJoCo's asset cache, or gives
    it the capacity of ``$VOOT_MUJOCO_CACHE_MB`` if set
    (:func:`voot.envs.core.caches.generated_compile`).
    """
    robot = resources.files("voot.models").joinpath(ROBOT_INCLUDE).read_bytes()
    assets = {ROBOT_INCLUDE: robot, **mesh_assets(specs)}
    with generated_compile():
        return mujoco.MjModel.from_xml_string(xml, assets=assets)
