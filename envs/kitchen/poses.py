"""The kitchen's pick and place actions decoded into poses.

A kitchen action alternates between two operators (:data:`OPERATORS`). Once its
normalised entries are scaled to the config's ranges
(:func:`voot.envs.core.units.denormalize`):

* a **pick**'s six parameters are the grasp (angle, height and depth fractions) and the
  robot's base pose relative to the object: distance (a fraction of the arm reach),
  angle around the object in the object's frame and heading offset from facing it;
  :func:`pick_base` turns the last three into the base pose ``(x, y, theta)``;
* a **place**'s three are the object's new pose ``(x, y, theta)``; the base follows
  rigidly from the grasp (:func:`place_base`), given the object's pose in the base
  frame at the pick (:func:`relative_pose`).

Apart from the env's checks so that the geometry of an action can be read and tested on
its own; :func:`relative_pose_floats` computes :func:`relative_pose`'s numbers on Python floats, with
the same operations, for the pre-screen (:mod:`voot.envs.kitchen.screen`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.core.names import Operator
from voot.envs.motion.planner import Box2D
from voot.envs.robot.model import ARM_REACH, compose2d, inverse2d

FloatArray = NDArray[np.float64]

#: Operators, in the order actions alternate.
OPERATORS: tuple[Operator, ...] = (Operator.PICK, Operator.PLACE)


def pick_base(box: Box2D, params: ArrayLike) -> FloatArray:
    """The base pose ``(x, y, theta)`` of pick parameters for an object with footprint ``box``.

    The base stands ``params[3] * ARM_REACH`` from the footprint's centre, at the angle
    ``box.yaw + params[4]``, and faces the centre turned by ``params[5]``.
    """
    p = np.asarray(params, dtype=np.float64)
    dist = p[3] * ARM_REACH
    ang = box.yaw + p[4]
    bx, by = box.cx + dist * math.cos(ang), box.cy + dist * math.sin(ang)
    heading = math.atan2(box.cy - by, box.cx - bx) + p[5]
    return np.array([bx, by, heading])


def place_base(
    placement: tuple[float, float, float], held_rel: tuple[float, float, float]
) -> FloatArray:
    """The base pose of placing at ``placement`` an object held at ``held_rel`` (base frame)."""
    return compose2d(placement, inverse2d(held_rel))


def relative_pose_floats(
    bx: float, by: float, bt: float, pose: tuple[float, float, float]
) -> tuple[float, float, float]:
    """:func:`relative_pose` of the base ``(bx, by, bt)`` and the object's ``(x, y, yaw)``:
    ``compose2d(inverse2d(base), pose)``'s operations on the same floats."""
    c, s = math.cos(bt), math.sin(bt)
    ix, iy, it = -c * bx - s * by, s * bx - c * by, -bt
    c, s = math.cos(it), math.sin(it)
    px, py, pt = pose
    return ix + c * px - s * py, iy + s * px + c * py, it + pt


def relative_pose(base: FloatArray, pose: FloatArray) -> tuple[float, float, float]:
    """The object's body pose ``(x, y, yaw)`` in the frame of the base at ``base``.

    ``pose`` is the object's ``(x, y, z, yaw)``; the height is left out.
    """
    bx, by, bt = (float(v) for v in base[:3])
    return relative_pose_floats(bx, by, bt, (float(pose[0]), float(pose[1]), float(pose[3])))
