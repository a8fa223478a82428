"""Loading the MJCF scenes and reading their floor plan back as 2-D footprints.

The scenes (``voot.models``: ``kitchen.xml``, ``conveyor.xml``, both including
``robot.xml``) are the single source of truth for the geometry. This module turns the
compiled :class:`mujoco.MjModel` into what the task layer needs:

* :func:`static_footprints`: one :class:`~voot.envs.motion.planar.Box2D` per static
  collision geom (walls, counters, furniture) that stands in the robot's height band;
* :class:`ObjectInfo`: each movable object (a body with a free joint named ``obj_*``): its
  free-joint address, its geoms, and its footprint rectangle in its own frame;
* :func:`object_footprint`: that rectangle at the object's current pose;
* :func:`object_pose` and :func:`set_object_pose`: an object's ``(x, y, z, yaw)``
  read from and written to its free joint's ``qpos``;
* :func:`model_digest`: a hash of the compiled scene, part of every snapshot's identity
  (:class:`voot.envs.core.state.SceneIdentity`).

The conventions it reads (collision bits, the ``obj_`` prefix) are the MJCF writers'
(:mod:`voot.envs.assets.mjcf`); tests of a footprint against a region are
:mod:`voot.envs.motion.rects`.

A footprint is the bounding rectangle, in the geom's (or object's) own horizontal frame,
of the geom's axis-aligned bounding box (``model.geom_aabb``): exact for boxes standing
upright, a tight rectangle around cylinders and capsules; for a mesh geom, the rectangle
around its vertices.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.assets.mjcf import OBJECT_BIT, OBJECT_PREFIX, ROBOT_BIT, SCENE_BIT
from voot.envs.motion.planar import Box2D

__all__ = [
    "DIGEST_FIELDS",
    "OBJECT_BIT",
    "OBJECT_PREFIX",
    "ROBOT_BIT",
    "SCENES",
    "SCENE_BIT",
    "ObjectInfo",
    "load_model",
    "model_digest",
    "model_path",
    "movable_objects",
    "object_footprint",
    "object_pose",
    "quat_of_yaw",
    "set_object_pose",
    "static_footprints",
    "yaw_of_quat",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.intp]

#: Scenes shipped in ``voot.models``.
SCENES = ("kitchen", "conveyor", "robot")


def model_path(scene: str) -> Path:
    """Path of the MJCF file of ``scene`` (one of :data:`SCENES`) inside ``voot.models``."""
    if scene not in SCENES:
        raise ValueError(f"unknown scene {scene!r}; valid scenes: {', '.join(SCENES)}")
    path = Path(str(resources.files("voot.models").joinpath(f"{scene}.xml")))
    if not path.is_file():  # pragma: no cover - broken installation
        raise FileNotFoundError(f"scene file {path} is missing from the voot.models package")
    return path


def load_model(scene: str) -> mujoco.MjModel:
    """Compile the scene ``scene`` (one of :data:`SCENES`)."""
    return mujoco.MjModel.from_xml_path(str(model_path(scene)))


#: The compiled model's fields :func:`model_digest` hashes: the sizes, the bodies' tree and
#: placement, the joints, the geoms' shapes and placement, the meshes. Not the collision
#: filters (an env may change them) nor colours and cameras (they change no state).
DIGEST_FIELDS = (
    "body_parentid",
    "body_pos",
    "body_quat",
    "body_mass",
    "jnt_type",
    "jnt_bodyid",
    "geom_type",
    "geom_bodyid",
    "geom_dataid",
    "geom_size",
    "geom_pos",
    "geom_quat",
    "mesh_vert",
    "mesh_face",
)


def model_digest(model: mujoco.MjModel) -> str:
    """A hash (hex BLAKE2b, 128 bits) of a compiled scene's geometry (:data:`DIGEST_FIELDS`).

    Equal for the same scene compiled in any process; different for another layout (its
    walls, objects or meshes). Costs about a millisecond (the meshes' vertices dominate).
    """
    h = hashlib.blake2b(digest_size=16)
    h.update(np.array([model.nq, model.nv, model.na, model.nbody], dtype=np.int64).tobytes())
    for name in DIGEST_FIELDS:
        h.update(name.encode())
        h.update(np.ascontiguousarray(getattr(model, name)).tobytes())
    return h.hexdigest()


def yaw_of_quat(quat: FloatArray) -> float:
    """Heading (rotation about z) of a unit quaternion ``(w, x, y, z)``."""
    w, x, y, z = (float(v) for v in quat)
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def quat_of_yaw(yaw: float) -> FloatArray:
    """The unit quaternion ``(w, x, y, z)`` of a rotation by ``yaw`` about z."""
    return np.array([math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw)])


def _geom_corners_local(model: mujoco.MjModel, geom: int) -> FloatArray:
    """The 8 corners of a geom's bounding box, in the geom's frame, shape ``(8, 3)``."""
    aabb = model.geom_aabb[geom]
    signs = np.array(
        [[sx, sy, sz] for sx in (-1.0, 1.0) for sy in (-1.0, 1.0) for sz in (-1.0, 1.0)]
    )
    corners: FloatArray = aabb[:3] + signs * aabb[3:]
    return corners


def _geom_points_local(model: mujoco.MjModel, geom: int) -> FloatArray:
    """Points whose bounding box is the geom's, in the geom's frame, shape ``(n, 3)``.

    A mesh geom's vertices (MuJoCo places a mesh in its principal inertia frame, so the
    corners of ``geom_aabb`` there, turned back into the body frame, would inflate the
    box); any other geom's 8 bounding-box corners.
    """
    if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_MESH:
        mesh = int(model.geom_dataid[geom])
        adr, n = int(model.mesh_vertadr[mesh]), int(model.mesh_vertnum[mesh])
        verts: FloatArray = model.mesh_vert[adr : adr + n].astype(np.float64)
        return verts
    return _geom_corners_local(model, geom)


def _rect_of_points(xy: FloatArray) -> tuple[float, float, float, float]:
    """Axis-aligned ``(cx, cy, half_x, half_y)`` of 2-D points."""
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    c, h = 0.5 * (lo + hi), 0.5 * (hi - lo)
    return float(c[0]), float(c[1]), float(h[0]), float(h[1])


def static_footprints(
    model: mujoco.MjModel, z_band: tuple[float, float] = (0.02, 1.5)
) -> list[Box2D]:
    """Footprints of the static collision geoms of the world body.

    Args:
        model: A compiled scene.
        z_band: Only geoms whose vertical extent overlaps ``(zmin, zmax)`` count: the
            robot's height band (something flush with the floor, or hanging above the
            robot's head, does not block the base).

    Returns:
        One :class:`Box2D` per geom, named after the geom, in geom order. A geom whose
        local z axis is vertical gives an oriented rectangle (its yaw); any other gives
        the axis-aligned rectangle around its projected bounding box.
    """
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    boxes: list[Box2D] = []
    for g in range(model.ngeom):
        if model.geom_bodyid[g] != 0 or not (model.geom_contype[g] & SCENE_BIT):
            continue
        rot = data.geom_xmat[g].reshape(3, 3)
        pos = data.geom_xpos[g]
        corners = _geom_points_local(model, g) @ rot.T + pos
        if corners[:, 2].max() <= z_band[0] or corners[:, 2].min() >= z_band[1]:
            continue
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
        if abs(abs(rot[2, 2]) - 1.0) < 1e-9:
            yaw = math.atan2(rot[1, 0], rot[0, 0])
            local = _geom_points_local(model, g)[:, :2]
            lcx, lcy, hx, hy = _rect_of_points(local)
            c, s = math.cos(yaw), math.sin(yaw)
            cx = pos[0] + c * lcx - s * lcy
            cy = pos[1] + s * lcx + c * lcy
            boxes.append(Box2D(float(cx), float(cy), hx, hy, yaw, name))
        else:
            cx, cy, hx, hy = _rect_of_points(corners[:, :2])
            boxes.append(Box2D(cx, cy, hx, hy, 0.0, name))
    return boxes


@dataclass(frozen=True)
class ObjectInfo:
    """A movable object of a scene.

    Attributes:
        name: Body name (``obj_*``); also the free joint's name.
        body: Body id.
        qpos_adr: Address of its free joint's 7 qpos entries ``(x, y, z, qw, qx, qy, qz)``.
        geoms: Its geom ids.
        center: Centre of its footprint rectangle in the body frame, ``(2,)``.
        half: Half extents of the footprint rectangle in the body frame, ``(2,)``.
        height: Top of its bounding box above the body origin (the origin is on the
            support surface).
        radius: Circumradius of the footprint rectangle (``hypot(*half)``).
    """

    name: str
    body: int
    qpos_adr: int
    geoms: tuple[int, ...]
    center: FloatArray
    half: FloatArray
    height: float

    @property
    def radius(self) -> float:
        return float(math.hypot(self.half[0], self.half[1]))


def movable_objects(model: mujoco.MjModel) -> list[ObjectInfo]:
    """Every body named ``obj_*`` with a free joint, in body order."""
    out: list[ObjectInfo] = []
    for b in range(model.nbody):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or ""
        if not name.startswith(OBJECT_PREFIX):
            continue
        jnt = int(model.body_jntadr[b])
        if model.body_jntnum[b] != 1 or model.jnt_type[jnt] != mujoco.mjtJoint.mjJNT_FREE:
            raise ValueError(f"object body {name!r} must have exactly one free joint")
        geoms = tuple(int(g) for g in np.flatnonzero(model.geom_bodyid == b))
        if not geoms:
            raise ValueError(f"object body {name!r} has no geoms")
        pts = []
        for g in geoms:
            rot = np.empty(9)
            mujoco.mju_quat2Mat(rot, model.geom_quat[g])
            pts.append(_geom_points_local(model, g) @ rot.reshape(3, 3).T + model.geom_pos[g])
        allp = np.concatenate(pts)
        cx, cy, hx, hy = _rect_of_points(allp[:, :2])
        out.append(
            ObjectInfo(
                name=name,
                body=b,
                qpos_adr=int(model.jnt_qposadr[jnt]),
                geoms=geoms,
                center=np.array([cx, cy]),
                half=np.array([hx, hy]),
                height=float(allp[:, 2].max()),
            )
        )
    return out


def object_footprint(obj: ObjectInfo, x: float, y: float, yaw: float) -> Box2D:
    """The footprint of ``obj`` with its body at ``(x, y)`` and heading ``yaw``."""
    c, s = math.cos(yaw), math.sin(yaw)
    ox, oy = obj.center.tolist()  # the same numbers as numpy scalars, cheaper to multiply
    hx, hy = obj.half.tolist()
    cx = x + c * ox - s * oy
    cy = y + s * ox + c * oy
    return Box2D.fast(cx, cy, hx, hy, yaw, obj.name)


def set_object_pose(data: mujoco.MjData, obj: ObjectInfo, pose: ArrayLike) -> None:
    """Put ``obj``'s body at ``(x, y, z, yaw)`` (free joint qpos)."""
    if type(pose) is tuple and len(pose) == 4:
        x, y, z, yaw = (float(v) for v in pose)
    else:
        x, y, z, yaw = (float(v) for v in np.asarray(pose, dtype=np.float64))
    a = obj.qpos_adr
    data.qpos[a : a + 7] = (x, y, z, math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw))


def object_pose(data: mujoco.MjData, obj: ObjectInfo) -> FloatArray:
    """``(x, y, z, yaw)`` of ``obj``'s body from its free joint."""
    a = obj.qpos_adr
    # floats: the same products and powers (C pow) as on numpy scalars, cheaper
    x, y, z, q0, q1, q2, q3 = data.qpos[a : a + 7].tolist()
    yaw = math.atan2(2.0 * (q0 * q3 + q1 * q2), 1.0 - 2.0 * (q2**2 + q3**2))
    return np.array([x, y, z, yaw])
