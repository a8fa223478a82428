"""Grasps on the real shape of a mesh object: ray-cast grasp tables and their lookup.

The v1 pick (:func:`voot.envs.robot.grasp.side_grasp`) puts the tool point on a side of the
object's footprint rectangle, which is the surface only for a box. For the mesh objects
of :mod:`voot.envs.assets.meshes` the surface is found once, when the shape is built: from each
of the four horizontal approach directions of the body frame (faces ``+x``, ``-x``,
``+y``, ``-y``, as :func:`side_grasp` names them), a grid of :data:`ROWS` heights x
:data:`COLS` offsets across the silhouette casts rays horizontally inwards (trimesh's
ray-triangle test, :func:`cast_grasp_rays`) and records the first surface hit, as its depth behind the
bounding-box face, and the surface normal there (:class:`MeshGraspSet`, cached on disk
beside the meshes). Grid nodes sit at the cell centres, ``(i + 1/2) / ROWS`` of the
height and ``(j + 1/2) / COLS`` across, so no ray grazes the bounding box.

:func:`mesh_side_grasp` takes the pick's parameters with :func:`side_grasp`'s meaning
(the face the robot faces, the height fraction, the depth fraction across the face, the
grasp angle, the standoff) and looks the surface up, without casting a ray:

* whether the grasp **hits** is the nearest grid node's answer (a ray beside a bottle's
  neck misses: ``(None, "grasp misses the object")``);
* the surface **depth** ``e`` is interpolated bilinearly between the four nodes around
  the point when all four hit, else the nearest node's;
* the tool point is then :func:`side_grasp`'s (on the bounding box's face, ``standoff``
  outside it) moved ``e`` along the approach axis, i.e. on the surface at exactly the
  requested height and offset, ``standoff`` outside it, with :func:`side_grasp`'s
  rotation. On a box ``e = 0`` everywhere and the pose is :func:`side_grasp`'s, bit for
  bit.

A lookup costs about 7 us of CPU time per call on the project's 2-core machine
(``voot-bench mesh-speed --cpu``: 6.3-7.8 us over the ten kinds, :func:`side_grasp` alone
about 5 us; the table lookup itself about 1 us), within the 20 us target; docs/meshes.md has
the figures.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from voot.envs.assets.meshes import (
    MEMO_SIZE,
    MEMORY_CACHES,
    ShapeSpec,
    built_shape,
    cached_arrays,
)
from voot.envs.core.caches import LRUMemo
from voot.envs.core.scene import ObjectInfo
from voot.envs.robot.grasp import GraspPose, side_grasp

FloatArray = NDArray[np.float64]

__all__ = ["COLS", "FACES", "MISS", "ROWS", "MeshGraspSet", "grasp_set", "mesh_side_grasp"]

#: The approach faces, in :func:`side_grasp`'s order, and their outward normals (body frame).
FACES: tuple[str, ...] = ("+x", "-x", "+y", "-y")
_NORMALS = ((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0))
#: Grid rows (heights) and columns (offsets across) per face.
ROWS = 32
COLS = 32
#: The reason :func:`mesh_side_grasp` gives when the ray misses the object.
MISS = "grasp misses the object"
#: Distance outside the bounding box the rays start from (metres).
_MARGIN = 0.05


@dataclass(frozen=True)
class MeshGraspSet:
    """The ray-cast grasp table of one shape (:func:`grasp_set`); pickles.

    Attributes:
        spec: The shape.
        half: Half extents ``(x, y)`` of its footprint (the bounding box), body frame; the
            footprint is centred on the body origin.
        height: Its height.
        depth: ``(4, ROWS, COLS)``: per face (:data:`FACES`), height row and column
            across, how far behind the bounding-box face the first surface hit lies
            (metres, >= 0); NaN where the ray misses.
        normal: ``(4, ROWS, COLS, 3)``: the outward surface normal at the hit, body frame;
            NaN where the ray misses.
    """

    spec: ShapeSpec
    half: tuple[float, float]
    height: float
    depth: FloatArray
    normal: FloatArray
    _info: ObjectInfo = field(init=False, repr=False, compare=False)
    _tables: tuple[list[list[float]], ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        rows, cols = self.depth.shape[1:]
        if self.depth.shape != (4, rows, cols) or self.normal.shape != (4, rows, cols, 3):
            raise ValueError(
                f"depth must be (4, rows, cols) and normal (4, rows, cols, 3), got "
                f"{self.depth.shape} and {self.normal.shape}"
            )
        info = ObjectInfo(
            name=f"mesh:{self.spec.kind}",
            body=-1,
            qpos_adr=-1,
            geoms=(),
            center=np.zeros(2),
            half=np.array(self.half, dtype=np.float64),
            height=float(self.height),
        )
        object.__setattr__(self, "_info", info)
        # nested lists: a Python float per lookup without numpy's scalar indexing
        object.__setattr__(self, "_tables", tuple(t.tolist() for t in self.depth))

    def __reduce__(self) -> tuple[type[MeshGraspSet], tuple[object, ...]]:
        """Pickle the fields only (the lookup tables are rebuilt)."""
        return (MeshGraspSet, (self.spec, self.half, self.height, self.depth, self.normal))

    @property
    def hit_fraction(self) -> float:
        """Share of the grid's rays that hit the object (1 for a box)."""
        return float(np.mean(np.isfinite(self.depth)))


def _grid(
    mesh: trimesh.Trimesh, rows: int, cols: int
) -> tuple[FloatArray, FloatArray, list[tuple[FloatArray, FloatArray, FloatArray]]]:
    """The rays' origins and directions ``(4 * rows * cols, 3)``, and per face its grid.

    Per face: the across coordinates ``b`` of the columns, the heights ``z`` of the rows
    and the face's ``(n0, n1, t0, t1)`` (outward normal and the direction of ``b``).
    """
    (lx, ly, _), (ux, uy, hz) = mesh.bounds
    hx, hy = 0.5 * (ux - lx), 0.5 * (uy - ly)
    zs = (np.arange(rows) + 0.5) / rows * hz
    us = (np.arange(cols) + 0.5) / cols
    origins, dirs, grids = [], [], []
    for n0, n1 in _NORMALS:
        half_normal, half_across = (hx, hy) if n0 != 0.0 else (hy, hx)
        t0, t1 = -n1, n0
        b = (2.0 * us - 1.0) * half_across
        zz, bb = np.meshgrid(zs, b, indexing="ij")
        a = half_normal + _MARGIN
        origins.append(np.stack([a * n0 + bb * t0, a * n1 + bb * t1, zz], axis=-1).reshape(-1, 3))
        dirs.append(np.tile([-n0, -n1, 0.0], (rows * cols, 1)))
        grids.append((b, zs, np.array([n0, n1, t0, t1])))
    return np.concatenate(origins), np.concatenate(dirs), grids


def _candidates(
    tri: FloatArray, grids: list[tuple[FloatArray, FloatArray, FloatArray]]
) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Broad phase: the (triangle, ray) pairs whose ray passes the triangle's box.

    A ray of face ``k`` is a point ``(b, z)`` in the face's plane; a triangle can be hit
    only by the rays inside its projection's bounding rectangle there (widened by 1e-9 m),
    i.e. by a block of rows and columns, enumerated here with array arithmetic (what
    trimesh's r-tree query does one ray at a time).
    """
    tris, rays = [], []
    offset = 0
    eps = 1e-9
    for b, zs, (_, _, t0, t1) in grids:
        rows, cols = len(zs), len(b)
        across = tri[:, :, 0] * t0 + tri[:, :, 1] * t1  # (F, 3)
        z = tri[:, :, 2]
        j0 = np.searchsorted(b, across.min(axis=1) - eps, side="left")
        j1 = np.searchsorted(b, across.max(axis=1) + eps, side="right")
        i0 = np.searchsorted(zs, z.min(axis=1) - eps, side="left")
        i1 = np.searchsorted(zs, z.max(axis=1) + eps, side="right")
        nj = np.maximum(j1 - j0, 0)
        count = np.maximum(i1 - i0, 0) * nj
        t = np.repeat(np.arange(len(tri)), count)
        r = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
        step = nj[t]
        i = i0[t] + r // step
        j = j0[t] + r % step
        tris.append(t)
        rays.append(offset + i * cols + j)
        offset += rows * cols
    return np.concatenate(tris).astype(np.int64), np.concatenate(rays).astype(np.int64)


def cast_grasp_rays(
    mesh: trimesh.Trimesh, rows: int = ROWS, cols: int = COLS
) -> tuple[FloatArray, FloatArray]:
    """Cast the grid of horizontal rays at ``mesh`` (body frame, footprint centred).

    Returns ``(depth, normal)`` as :class:`MeshGraspSet` holds them. The narrow phase is
    trimesh's ray-triangle test (``trimesh.ray.ray_triangle.ray_triangle_id``'s: the
    ray's line against each candidate triangle's plane, ``trimesh.intersections
    .planes_lines``, then barycentric coordinates, ``trimesh.triangles
    .points_to_barycentric``, inside within trimesh's ``tol.zero``, and forward of the
    origin); the broad phase (:func:`_candidates`) uses the rays' grid instead of
    trimesh's r-tree, 4096 queries in a few array operations. The first hit of a ray is
    its nearest intersection (ties: the lowest triangle index); depths are rounded to
    1e-9 m so that a flat face gives exactly 0.
    """
    org, dirv, grids = _grid(mesh, rows, cols)
    tri_all = np.asarray(mesh.triangles, dtype=np.float64)
    face_normals = np.asarray(mesh.face_normals, dtype=np.float64)
    cand_tri, cand_ray = _candidates(tri_all, grids)
    n_rays = len(org)
    depth = np.full(n_rays, np.nan)
    normal = np.full((n_rays, 3), np.nan)
    if len(cand_tri):
        tri = tri_all[cand_tri]
        location, valid = trimesh.intersections.planes_lines(
            plane_origins=tri[:, 0, :],
            plane_normals=face_normals[cand_tri],
            line_origins=org[cand_ray],
            line_directions=dirv[cand_ray],
        )
        bary = trimesh.triangles.points_to_barycentric(tri[valid], location)
        zero = trimesh.constants.tol.zero
        inside = (bary > -zero).all(axis=1) & (bary < 1.0 + zero).all(axis=1)
        tri_id = cand_tri[valid][inside]
        ray = cand_ray[valid][inside]
        dist = np.einsum("ij,ij->i", location[inside] - org[ray], dirv[ray])
        forward = dist > -1e-6
        tri_id, ray, dist = tri_id[forward], ray[forward], dist[forward]
        if len(ray):
            order = np.lexsort((tri_id, dist, ray))  # by ray, then distance, then triangle
            first = order[np.r_[True, ray[order][1:] != ray[order][:-1]]]
            r = ray[first]
            depth[r] = np.round(dist[first] - _MARGIN, 9) + 0.0
            normal[r] = face_normals[tri_id[first]]
    return depth.reshape(4, rows, cols), normal.reshape(4, rows, cols, 3)


def _build_arrays(spec: ShapeSpec) -> dict[str, np.ndarray]:
    mesh = built_shape(spec).visual
    depth, normal = cast_grasp_rays(mesh)
    return {"depth": depth, "normal": normal, "box": np.array(mesh.extents, dtype=np.float64)}


_MEMORY: LRUMemo[ShapeSpec, MeshGraspSet] = LRUMemo(MEMO_SIZE)
MEMORY_CACHES.append(_MEMORY)


def grasp_set(spec: ShapeSpec) -> MeshGraspSet:
    """The grasp table of ``spec``'s shape: from the process, else the disk cache, else cast."""
    got = _MEMORY.get(spec)
    if got is not None:
        return got
    arrays, _ = cached_arrays(
        spec, "grasp", lambda: _build_arrays(spec), ("depth", "normal", "box")
    )
    ext = arrays["box"]
    out = MeshGraspSet(
        spec=spec,
        half=(0.5 * float(ext[0]), 0.5 * float(ext[1])),
        height=float(ext[2]),
        depth=np.asarray(arrays["depth"], dtype=np.float64),
        normal=np.asarray(arrays["normal"], dtype=np.float64),
    )
    _MEMORY[spec] = out
    return out


def _surface_depth(table: list[list[float]], hf: float, df: float) -> float:
    """Depth at height fraction ``hf`` and fraction across ``df`` of one face's table.

    NaN when the nearest node misses; the bilinear value when the four surrounding nodes
    hit; else the nearest node's.
    """
    rows, cols = len(table), len(table[0])
    fi, fj = hf * rows, df * cols
    # int() truncates towards 0, floor() down: they differ only below 0, clamped to 0 anyway
    i = int(fi) if fi < rows else rows - 1
    j = int(fj) if fj < cols else cols - 1
    i = i if i > 0 else 0
    j = j if j > 0 else 0
    near = table[i][j]
    if near != near:  # NaN: the ray misses
        return near
    ci, cj = fi - 0.5, fj - 0.5  # in node coordinates
    i0 = int(ci) if ci < rows - 2 else rows - 2
    j0 = int(cj) if cj < cols - 2 else cols - 2
    i0 = i0 if i0 > 0 else 0
    j0 = j0 if j0 > 0 else 0
    wi, wj = ci - i0, cj - j0
    wi = 0.0 if wi < 0.0 else (1.0 if wi > 1.0 else wi)
    wj = 0.0 if wj < 0.0 else (1.0 if wj > 1.0 else wj)
    r0, r1 = table[i0], table[i0 + 1]
    d00, d01, d10, d11 = r0[j0], r0[j0 + 1], r1[j0], r1[j0 + 1]
    total = d00 + d01 + d10 + d11
    if total != total:  # a neighbour misses
        return near
    return (1.0 - wi) * ((1.0 - wj) * d00 + wj * d01) + wi * ((1.0 - wj) * d10 + wj * d11)


_FACE_INDEX = {f: k for k, f in enumerate(FACES)}


def mesh_side_grasp(
    grasps: MeshGraspSet,
    obj_pose: ArrayLike,
    base_heading: float,
    grasp_angle: float,
    height_fraction: float,
    depth_fraction: float,
    standoff: float = 0.0,
) -> tuple[GraspPose | None, str]:
    """:func:`side_grasp` on the object's surface (see the module docstring).

    Args:
        grasps: The object's grasp table (:func:`grasp_set`).
        obj_pose: ``(x, y, z, yaw)`` of its body (z: its support height).
        base_heading: Heading of the robot's base (radians): the grasped face is the one
            whose outward normal is most opposite to it.
        grasp_angle: Roll of the gripper about the approach axis (radians).
        height_fraction: Height of the grasp point as a fraction of the object's height.
        depth_fraction: Position across the face's silhouette, in [0, 1].
        standoff: Distance of the tool point outside the surface, along the face normal.

    Returns:
        ``(pose, "")``, or ``(None, "grasp misses the object")`` when the ray at that
        height and offset passes beside the object.
    """
    pose = side_grasp(
        grasps._info,
        obj_pose,
        base_heading,
        grasp_angle,
        height_fraction,
        depth_fraction,
        standoff,
    )
    table = grasps._tables[_FACE_INDEX[pose.face]]
    e = _surface_depth(table, float(height_fraction), float(depth_fraction))
    if e != e:
        return None, MISS
    if e == 0.0:
        return pose, ""
    # e metres further along the approach axis (the rotation's first column, -n)
    r = pose.rotation
    p0, p1, p2 = pose.position.tolist()
    position = np.array([p0 + e * float(r[0, 0]), p1 + e * float(r[1, 0]), p2])
    return GraspPose(position, r, pose.face), ""
