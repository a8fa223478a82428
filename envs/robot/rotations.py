"""Elementary rotation matrices and the XYX Euler angles of a rotation.

The arm's closed-form inverse kinematics (:mod:`voot.envs.robot.arm_ik`) composes the
shoulder's rotations about z, y and x and solves the spherical wrist, whose three joints
turn about x, y and x, from the remaining rotation (:func:`xyx_euler`); the environments
turn base-frame grasp targets into the world with :func:`rot_z`. Plain ``math`` on Python
floats, so each matrix is the same in every process.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

__all__ = ["rot_x", "rot_y", "rot_z", "xyx_euler"]


def rot_x(a: float) -> FloatArray:
    """The rotation by ``a`` radians about the x axis, ``(3, 3)``."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a: float) -> FloatArray:
    """The rotation by ``a`` radians about the y axis, ``(3, 3)``."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a: float) -> FloatArray:
    """The rotation by ``a`` radians about the z axis, ``(3, 3)``."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _wrap(a: float) -> float:
    """``a`` wrapped to ``[-pi, pi)``."""
    return (a + math.pi) % (2.0 * math.pi) - math.pi


def xyx_euler(r: FloatArray) -> list[tuple[float, float, float]]:
    """Both solutions ``(a, b, c)`` of ``R = Rx(a) Ry(b) Rx(c)`` (one if singular)."""
    b = math.acos(max(-1.0, min(1.0, float(r[0, 0]))))
    if math.sin(b) < 1e-9:
        # b = 0: R = Rx(a + c); b = pi: R = Rx(a - c) Ry(pi). Only a +- c is defined.
        return [(math.atan2(float(r[2, 1]), float(r[1, 1])), b, 0.0)]
    sol1 = (
        math.atan2(float(r[1, 0]), float(-r[2, 0])),
        b,
        math.atan2(float(r[0, 1]), float(r[0, 2])),
    )
    sol2 = (_wrap(sol1[0] + math.pi), -b, _wrap(sol1[2] + math.pi))
    return [sol1, sol2]
