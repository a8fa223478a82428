"""The cost of the trimesh object meshes (``voot-bench measure mesh-speed``; docs/meshes.md).

Three measurements, each in a temporary cache folder (``VOOT_CACHE``), so nothing of the
user's cache is read or written:

* :func:`time_shapes`: per shape, *cold* (build the mesh, its parts, mass properties, STL
  bytes and the grasp rays, and write both cache files), *disk* (read them back in a
  process that has not seen the spec: the in-process cache cleared) and *memory* (the
  in-process cache);
* :func:`time_scene`: a scene of :data:`SCENE` (ten objects of nine kinds) with the robot:
  the asset XML, the object bodies and MuJoCo's compile, cold, from the disk cache and
  from memory;
* :func:`time_lookup`: the cost per call of :func:`~voot.envs.robot.mesh_grasp.mesh_side_grasp`
  against :func:`~voot.envs.robot.grasp.side_grasp` on the same object.

Every function takes the ``clock`` to read (wall time by default; ``--cpu`` on the
command line: CPU time).
"""

from __future__ import annotations

import contextlib
import os
import statistics
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence

import numpy as np

from voot.envs.assets import meshes as M
from voot.envs.assets.meshes import ShapeSpec
from voot.envs.robot.grasp import side_grasp
from voot.envs.robot.mesh_grasp import grasp_set, mesh_side_grasp

#: A clock in seconds: ``time.perf_counter`` (wall) or ``time.process_time`` (this
#: process's CPU time, which a machine shared with other jobs inflates less).
Clock = Callable[[], float]

#: A plausible size per kind (metres), the shapes :func:`time_shapes` measures.
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

#: The ten objects of the scene :func:`time_scene` compiles.
SCENE: tuple[ShapeSpec, ...] = (
    ShapeSpec("box", (0.1, 0.15, 0.2)),
    ShapeSpec("box", (0.2, 0.2, 0.12), 3),
    ShapeSpec("crate", (0.4, 0.3, 0.25), 1),
    ShapeSpec("bin", (0.3, 0.2, 0.2), 2),
    ShapeSpec("bowl", (0.16, 0.16, 0.07), 1),
    ShapeSpec("plate", (0.26, 0.26, 0.025)),
    ShapeSpec("mug", (0.12, 0.085, 0.1), 4),
    ShapeSpec("bucket", (0.28, 0.28, 0.3)),
    ShapeSpec("bottle", (0.07, 0.07, 0.25), 5),
    ShapeSpec("jug", (0.16, 0.11, 0.25), 6),
)


@contextlib.contextmanager
def temporary_cache() -> Iterator[str]:
    """A fresh ``VOOT_CACHE`` folder for the duration (restored after), caches emptied."""
    old = os.environ.get("VOOT_CACHE")
    with tempfile.TemporaryDirectory(prefix="voot-mesh-speed-") as tmp:
        os.environ["VOOT_CACHE"] = tmp
        M.clear_memory_cache()
        try:
            yield tmp
        finally:
            M.clear_memory_cache()
            if old is None:
                os.environ.pop("VOOT_CACHE", None)
            else:
                os.environ["VOOT_CACHE"] = old


def _load(specs: Sequence[ShapeSpec]) -> None:
    """Everything a scene needs of ``specs``: the STL assets and the grasp tables."""
    M.mesh_assets(specs)
    for s in specs:
        grasp_set(s)


def time_shapes(
    specs: Sequence[ShapeSpec], repeats: int = 3, clock: Clock = time.perf_counter
) -> list[dict[str, float]]:
    """Seconds to get each spec's meshes and grasp table: cold, from disk, from memory.

    Each figure is the median of ``repeats`` (cold: each repeat in a fresh cache folder).
    Also returns the visual mesh's triangles, the number of convex parts and the bytes of
    the STL files.
    """
    if repeats < 1:
        raise ValueError(f"repeats must be >= 1, got {repeats}")
    out = []
    for spec in specs:
        cold, disk, memory = [], [], []
        for _ in range(repeats):
            with temporary_cache():
                t0 = clock()
                _load([spec])
                cold.append(clock() - t0)
                M.clear_memory_cache()
                t0 = clock()
                _load([spec])
                disk.append(clock() - t0)
                t0 = clock()
                _load([spec])
                memory.append(clock() - t0)
                files = M.mesh_assets([spec])
        visual = files[f"{M.mesh_name(spec)}.stl"]
        out.append(
            {
                "cold": statistics.median(cold),
                "disk": statistics.median(disk),
                "memory": statistics.median(memory),
                "triangles": float(int.from_bytes(visual[80:84], "little")),
                "parts": float(len(files) - 1),
                "bytes": float(sum(len(b) for b in files.values())),
            }
        )
    return out


def scene_xml(specs: Sequence[ShapeSpec]) -> str:
    """A scene of the robot, a floor and one body per spec in a row (``obj_0``...)."""
    poses = [(1.0 + 0.5 * i, 1.0, 0.0, 0.3 * i) for i in range(len(specs))]
    return M.objects_scene_xml(specs, poses, "mesh_speed")


def _scene(specs: Sequence[ShapeSpec]) -> None:
    for s in specs:
        grasp_set(s)
    M.compile_scene(scene_xml(specs), specs)


def time_scene(
    specs: Sequence[ShapeSpec] = SCENE, repeats: int = 3, clock: Clock = time.perf_counter
) -> dict[str, float]:
    """Seconds to make a compiled scene of ``specs`` with their grasp tables.

    ``cold``: an empty cache (build, write, compile); ``disk``: a warm disk cache and an
    empty process (read, compile); ``memory``: everything in the process (the XML and
    MuJoCo's compile); ``robot_only``: MuJoCo's compile of the same scene without the
    objects, for scale. Medians of ``repeats``.
    """
    if repeats < 1:
        raise ValueError(f"repeats must be >= 1, got {repeats}")
    cold, disk, memory, bare = [], [], [], []
    for _ in range(repeats):
        with temporary_cache():
            t0 = clock()
            _scene(specs)
            cold.append(clock() - t0)
            M.clear_memory_cache()
            t0 = clock()
            _scene(specs)
            disk.append(clock() - t0)
            t0 = clock()
            _scene(specs)
            memory.append(clock() - t0)
            t0 = clock()
            _scene([])
            bare.append(clock() - t0)
    return {
        "cold": statistics.median(cold),
        "disk": statistics.median(disk),
        "memory": statistics.median(memory),
        "robot_only": statistics.median(bare),
    }


def time_lookup(
    spec: ShapeSpec, calls: int = 20000, clock: Clock = time.perf_counter
) -> dict[str, float]:
    """Microseconds per call of ``mesh_side_grasp`` and of ``side_grasp`` on ``spec``.

    The calls sweep the four faces, heights and offsets (a fixed pseudo-random list), as a
    planner's picks would; ``hit_share`` is the share of them that hit the object.
    """
    if calls < 1:
        raise ValueError(f"calls must be >= 1, got {calls}")
    rng = np.random.default_rng(0)
    with temporary_cache():
        g = grasp_set(spec)
        pose = np.array([1.0, 2.0, 0.4, 0.3])
        args = [
            (float(h), float(a), float(hf), float(df))
            for h, a, hf, df in zip(
                rng.uniform(-np.pi, np.pi, 256),
                rng.uniform(np.pi / 4, np.pi, 256),
                rng.uniform(0.0, 1.0, 256),
                rng.uniform(0.0, 1.0, 256),
                strict=True,
            )
        ]
        info = g._info
        rounds = max(1, calls // len(args))
        hits = sum(mesh_side_grasp(g, pose, *a)[0] is not None for a in args)
        t0 = clock()
        for _ in range(rounds):
            for h, a, hf, df in args:
                mesh_side_grasp(g, pose, h, a, hf, df, 0.01)
        mesh = (clock() - t0) / (rounds * len(args))
        t0 = clock()
        for _ in range(rounds):
            for h, a, hf, df in args:
                side_grasp(info, pose, h, a, hf, df, 0.01)
        plain = (clock() - t0) / (rounds * len(args))
    return {"mesh_us": 1e6 * mesh, "side_us": 1e6 * plain, "hit_share": hits / len(args)}
