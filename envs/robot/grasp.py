"""Grasp poses: the original's side grasp of a box-shaped object for a parallel gripper.

The action parameters of a pick (grasp angle, height and depth fractions, as in the
authors' code) become a gripper pose in the world (:class:`GraspPose`) on the vertical
side of the object's footprint that the robot faces (:func:`side_grasp`); the arm's
inverse kinematics (:mod:`voot.envs.robot.arm_ik`) then decides whether the arm reaches it,
and the collision check (:mod:`voot.envs.robot.collision`) whether the robot there is free. A
grasp pose is pure geometry (no MuJoCo), computed on Python floats with the operations
numpy used before, so it is bit-identical to the array version at a fifth of its cost.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.core.scene import ObjectInfo

FloatArray = NDArray[np.float64]

__all__ = ["GraspPose", "side_grasp"]


@dataclass(frozen=True)
class GraspPose:
    """A gripper pose in the world: tool point ``position`` and frame ``rotation``.

    ``rotation``'s columns are the tool frame's axes: x the approach direction (into the
    grasped face), y the finger-opening direction. ``face`` names the grasped side of the
    footprint (``+x``, ``-x``, ``+y`` or ``-y`` in the object's frame).
    """

    position: FloatArray
    rotation: FloatArray
    face: str


def side_grasp(
    obj: ObjectInfo,
    obj_pose: ArrayLike,
    base_heading: float,
    grasp_angle: float,
    height_fraction: float,
    depth_fraction: float,
    standoff: float = 0.0,
) -> GraspPose:
    """The side grasp of the original's parameterisation, for a single parallel gripper.

    The grasped face is the vertical side of the object's footprint rectangle that the
    robot faces: the one whose outward normal ``n`` is most opposite to the base heading
    (the original likewise chose among the four sides by the robot's heading). On it:

    * the tool point is at ``depth_fraction`` across the face (0 one edge, 1 the other;
      the original's grasp "depth" along the face) and at ``height_fraction`` of the
      object's height above its support (the original's range [0.5, 1] spans centre to
      top), ``standoff`` metres outside the face;
    * the approach axis (tool x) is ``-n``; the fingers open along the horizontal face
      tangent rotated by ``grasp_angle`` about the approach axis (the original's grasp
      angle theta in [45, 180] degrees).

    Args:
        obj: The object.
        obj_pose: ``(x, y, z, yaw)`` of its body (z: its support height).
        base_heading: Heading of the robot's base (radians).
        grasp_angle: Roll of the gripper about the approach axis (radians).
        height_fraction: Height of the grasp point as a fraction of the object's height.
        depth_fraction: Position across the face, in [0, 1].
        standoff: Distance of the tool point outside the face (metres).
    """
    # Plain floats instead of 2- and 3-vectors: every product, sum and cross product is
    # the one numpy computed elementwise, in the same order, so the pose is bit-identical
    # to the array version's, at a fifth of its cost.
    if type(obj_pose) is np.ndarray and obj_pose.shape == (4,):
        x, y, z, yaw = obj_pose.astype(np.float64, copy=False).tolist()
    else:
        x, y, z, yaw = (float(v) for v in np.asarray(obj_pose, dtype=np.float64))
    c, s = math.cos(yaw), math.sin(yaw)
    hx, hy = obj.half.tolist()
    # outward normals of the four faces, world frame, with the face's half extents
    faces = (
        ("+x", c, s, hx, hy),
        ("-x", -c, -s, hx, hy),
        ("+y", -s, c, hy, hx),
        ("-y", s, -c, hy, hx),
    )
    k = _facing_face(faces, base_heading)
    face, n0, n1, half_normal, half_across = faces[k]
    t0, t1 = -n1, n0  # horizontal, along the face
    ox, oy = obj.center.tolist()
    cx = x + c * ox - s * oy
    cy = y + s * ox + c * oy
    a = half_normal + standoff
    b = float((2.0 * depth_fraction - 1.0) * half_across)
    p = np.array([cx + a * n0 + b * t0, cy + a * n1 + b * t1, z + height_fraction * obj.height])
    # approach = (-n0, -n1, 0), y0 = (t0, t1, 0); z0 = approach x y0 as np.cross computes it
    a0, a1, a2 = -n0, -n1, 0.0
    z00 = a1 * 0.0 - a2 * t1
    z01 = a2 * t0 - a0 * 0.0
    z02 = a0 * t1 - a1 * t0
    ca, sa = math.cos(grasp_angle), math.sin(grasp_angle)
    y00, y01, y02 = ca * t0 + sa * z00, ca * t1 + sa * z01, ca * 0.0 + sa * z02
    z10 = a1 * y02 - a2 * y01
    z11 = a2 * y00 - a0 * y02
    z12 = a0 * y01 - a1 * y00
    rot = np.array([[a0, y00, z10], [a1, y01, z11], [a2, y02, z12]])
    return GraspPose(p, rot, face)


def _facing_face(faces: tuple[tuple[str, float, float, float, float], ...], heading: float) -> int:
    """Index of the face whose normal is most opposite to ``heading`` (first on ties).

    The scores are computed with plain floats; only when two of them are within 1e-12
    (where the rounding of numpy's dot product could decide) are they recomputed with
    numpy as before, so the choice is always numpy's.
    """
    hx, hy = math.cos(heading), math.sin(heading)
    scores = [n0 * hx + n1 * hy for _, n0, n1, _, _ in faces]
    k = min(range(len(scores)), key=scores.__getitem__)
    if any(j != k and scores[j] - scores[k] < 1e-12 for j in range(len(scores))):
        h = np.array([hx, hy])
        exact = [float(np.array([n0, n1]) @ h) for _, n0, n1, _, _ in faces]
        k = int(np.argmin(exact))
    return k
