"""The mobile manipulator (``voot.models/robot.xml``): named access and its 2-D footprint.

The robot is a PR2-class holonomic base (0.64 m square) with one 7-joint arm and a
parallel gripper. This module gives named access to its joints and geoms inside a
compiled scene (:class:`Robot`), its kinematic constants (used by the analytic IK seed in
:mod:`voot.envs.robot.arm_ik`), and the disc model used for base motion planning.

Base motion model (:class:`CarryDisc`): the robot is a disc of radius
:data:`ROBOT_RADIUS` = 0.48 m centred at the base (the 0.64 m square's circumradius is
0.4525 m; the tucked arm stays inside the square). Carrying an object, the disc is the
one enclosing the base square and the object's footprint at its held pose, centred at
the centre of their bounding box in the base frame (:func:`carry_disc`); the planner
plans the path of that centre, and since the disc holds the robot and its load whatever
the heading, the base may turn freely along the path. A door of width ``w`` lets the
disc through iff ``w > 2 r``: the kitchen's 0.9 m door stops the robot (0.96 m needed);
the storage rooms' door passes the robot carrying any small box and stops it carrying
one of the two big ones (see :mod:`voot.envs.conveyor.env`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.motion.planar import Box2D

FloatArray = NDArray[np.float64]

#: Planar base joints (x slide, y slide, yaw hinge).
BASE_JOINTS = ("base_x", "base_y", "base_yaw")
#: The arm's revolute joints, shoulder to wrist.
ARM_JOINTS = (
    "shoulder_pan",
    "shoulder_lift",
    "upper_arm_roll",
    "elbow_flex",
    "forearm_roll",
    "wrist_flex",
    "wrist_roll",
)
#: The gripper's two finger slides (0 closed, 0.04 m open each).
FINGER_JOINTS = ("finger_left", "finger_right")
#: Finger opening used throughout (the planner is kinematic: fingers stay open).
FINGER_OPEN = 0.04
#: Tucked arm configuration: the whole arm inside the base footprint (max x 0.28 m).
TUCK = np.array([0.0, 1.1, 0.0, -2.6, 0.0, -0.6, 0.0])
TUCK.setflags(write=False)

#: Shoulder centre in the base frame (all three shoulder axes meet here).
SHOULDER = np.array([0.02, 0.0, 0.80])
SHOULDER.setflags(write=False)
#: Shoulder to elbow, elbow to wrist centre, wrist centre to grasp site (metres).
UPPER_ARM = 0.40
FOREARM = 0.35
TOOL = 0.17
#: Reach from the shoulder to the grasp site with the arm straight (the original's
#: PR2_ARM_LENGTH was 0.9844 m); base distances of pick actions are fractions of it.
ARM_REACH = UPPER_ARM + FOREARM + TOOL
#: Half side of the square base footprint.
BASE_HALF = 0.32
#: Radius of the disc standing for the robot (without a carried object) in base motion.
ROBOT_RADIUS = 0.48

#: Names of the robot's gripper bodies (their geoms may touch the grasped object).
GRIPPER_BODIES = ("gripper_link", "finger_left_link", "finger_right_link")


def _subtree(model: mujoco.MjModel, root: int) -> list[int]:
    """Bodies in the kinematic subtree of ``root`` (including it)."""
    out = [root]
    for b in range(root + 1, model.nbody):
        parent = int(model.body_parentid[b])
        if parent in out:
            out.append(b)
    return out


class Robot:
    """Named access to the robot's joints and geoms inside a compiled scene.

    Args:
        model: A scene that includes ``robot.xml``.
    """

    def __init__(self, model: mujoco.MjModel) -> None:
        self.model = model

        def qadr(name: str) -> int:
            jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
            if jid < 0:
                raise ValueError(f"the model has no joint {name!r}; is robot.xml included?")
            return int(model.jnt_qposadr[jid])

        self.base_qadr = np.array([qadr(n) for n in BASE_JOINTS], dtype=np.intp)
        self.arm_qadr = np.array([qadr(n) for n in ARM_JOINTS], dtype=np.intp)
        self.finger_qadr = np.array([qadr(n) for n in FINGER_JOINTS], dtype=np.intp)
        base = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "base")
        bodies = _subtree(model, base)
        self.bodies = tuple(bodies)
        self.geoms = tuple(int(g) for g in np.flatnonzero(np.isin(model.geom_bodyid, bodies)))
        grip = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, n) for n in GRIPPER_BODIES]
        self.gripper_geoms = tuple(int(g) for g in np.flatnonzero(np.isin(model.geom_bodyid, grip)))
        self.grasp_site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "grasp")
        self.arm_range = np.array(
            [
                model.jnt_range[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, n)]
                for n in ARM_JOINTS
            ]
        )

    def set_base(self, data: mujoco.MjData, pose: ArrayLike) -> None:
        """Put the base at ``(x, y, theta)``."""
        data.qpos[self.base_qadr] = np.asarray(pose, dtype=np.float64)

    def base_pose(self, data: mujoco.MjData) -> FloatArray:
        """The base pose ``(x, y, theta)`` (a copy)."""
        out: FloatArray = data.qpos[self.base_qadr].copy()
        return out

    def set_arm(self, data: mujoco.MjData, q: ArrayLike) -> None:
        """Set the 7 arm joints (and open the fingers)."""
        data.qpos[self.arm_qadr] = np.asarray(q, dtype=np.float64)
        data.qpos[self.finger_qadr] = FINGER_OPEN

    def arm(self, data: mujoco.MjData) -> FloatArray:
        """The 7 arm joint values (a copy)."""
        out: FloatArray = data.qpos[self.arm_qadr].copy()
        return out


def base_footprint(pose: ArrayLike, name: str = "robot") -> Box2D:
    """The base's square footprint at ``pose`` ``(x, y, theta)``."""
    x, y, th = _xyt(pose)
    return Box2D.fast(x, y, BASE_HALF, BASE_HALF, th, name)


@dataclass(frozen=True)
class CarryDisc:
    """The disc standing for the robot (and what it carries) in base motion planning.

    Attributes:
        offset: Centre of the disc in the base frame ``(x, y)``; the base planner plans
            the path of this point, and the base follows at ``-offset`` (rotated).
        radius: The disc's radius.
    """

    offset: tuple[float, float]
    radius: float

    def center(self, base_pose: ArrayLike) -> FloatArray:
        """The disc's centre pose ``(x, y, theta)`` for the base at ``base_pose``."""
        return compose2d(base_pose, (float(self.offset[0]), float(self.offset[1]), 0.0))

    def base(self, center_poses: ArrayLike) -> FloatArray:
        """Base poses ``(k, 3)`` for disc-centre poses ``(k, 3)``."""
        c = np.array(center_poses, dtype=np.float64).reshape(-1, 3)
        cos, sin = np.cos(c[:, 2]), np.sin(c[:, 2])
        c[:, 0] -= cos * self.offset[0] - sin * self.offset[1]
        c[:, 1] -= sin * self.offset[0] + cos * self.offset[1]
        return c


#: The robot alone: a disc of :data:`ROBOT_RADIUS` centred at the base.
ROBOT_DISC = CarryDisc((0.0, 0.0), ROBOT_RADIUS)


def carry_disc(held_corners_in_base: ArrayLike) -> CarryDisc:
    """The disc holding the robot's base square and a carried object's footprint.

    Its centre is the centre of the bounding box (base frame) of the square's and the
    object's corners, its radius the largest distance from there to a corner plus the
    robot's margin ``ROBOT_RADIUS - sqrt(2) BASE_HALF`` (2.75 cm). Rotating the robot
    about that centre keeps robot and object inside the disc, so a path planned for the
    disc (any headings along it) is collision-free for the carried assembly.

    Args:
        held_corners_in_base: Corners ``(k, 2)`` of the carried object's footprint in the
            base frame.
    """
    square = BASE_HALF * np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])
    pts = np.concatenate(
        [square, np.asarray(held_corners_in_base, dtype=np.float64).reshape(-1, 2)]
    )
    centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
    far = float(np.max(np.hypot(pts[:, 0] - centre[0], pts[:, 1] - centre[1])))
    margin = ROBOT_RADIUS - math.sqrt(2.0) * BASE_HALF
    return CarryDisc((float(centre[0]), float(centre[1])), max(ROBOT_RADIUS, far + margin))


def carry_disc_floats(
    cx: float, cy: float, half_x: float, half_y: float, yaw: float
) -> tuple[float, float, float]:
    """:func:`carry_disc` of a footprint ``(cx, cy, half_x, half_y, yaw)`` on Python floats.

    Returns the centre ``(x, y)`` and radius. The corners are rotated with scalar
    products where :meth:`Box2D.corners` uses a matrix product (whose rounding may differ
    in the last bits), so the numbers agree with :func:`carry_disc` to about 1e-15 m, not
    bit for bit: for screens that decide with a margin and defer to the exact disc when
    the margin does not settle the answer.
    """
    c, s = math.cos(yaw), math.sin(yaw)
    xs = [BASE_HALF, -BASE_HALF, -BASE_HALF, BASE_HALF]
    ys = [BASE_HALF, BASE_HALF, -BASE_HALF, -BASE_HALF]
    for lx, ly in ((half_x, half_y), (-half_x, half_y), (-half_x, -half_y), (half_x, -half_y)):
        xs.append(lx * c - ly * s + cx)
        ys.append(lx * s + ly * c + cy)
    ox = 0.5 * (min(xs) + max(xs))
    oy = 0.5 * (min(ys) + max(ys))
    far = max([math.hypot(px - ox, py - oy) for px, py in zip(xs, ys, strict=True)])
    margin = ROBOT_RADIUS - math.sqrt(2.0) * BASE_HALF
    return ox, oy, max(ROBOT_RADIUS, far + margin)


_F64 = np.dtype(np.float64)


def _xyt(pose: ArrayLike) -> list[float] | tuple[float, ...]:
    """A pose's three numbers as Python floats (the same values numpy holds)."""
    kind = type(pose)
    if kind is np.ndarray and pose.dtype is _F64:  # type: ignore[union-attr]
        if pose.ndim == 1:  # type: ignore[union-attr]
            return pose.tolist()  # type: ignore[no-any-return,union-attr]
        return pose.reshape(-1).tolist()  # type: ignore[no-any-return,union-attr]
    if kind is tuple and all(type(v) is float for v in pose):  # type: ignore[union-attr]
        return pose  # type: ignore[return-value]
    return np.asarray(pose, dtype=np.float64).reshape(-1).tolist()  # type: ignore[no-any-return]


def compose2d(a: ArrayLike, b: ArrayLike) -> FloatArray:
    """SE(2) composition ``a * b`` of ``(x, y, theta)`` poses.

    Computed on Python floats (the same IEEE operations, in the same order, as on numpy
    scalars), which is several times cheaper for three numbers.
    """
    ax, ay, at = _xyt(a)
    bx, by, bt = _xyt(b)
    c, s = math.cos(at), math.sin(at)
    return np.array([ax + c * bx - s * by, ay + s * bx + c * by, at + bt])


def inverse2d(a: ArrayLike) -> FloatArray:
    """SE(2) inverse of ``(x, y, theta)`` (on Python floats, as :func:`compose2d`).

    Inverses of tuples (the envs' grasp poses, asked for at every check) are remembered.
    """
    key = a if type(a) is tuple else None
    hit = _INVERSES.get(key) if key is not None else None
    if hit is None:
        ax, ay, at = _xyt(a)
        c, s = math.cos(at), math.sin(at)
        hit = (-c * ax - s * ay, s * ax - c * ay, -at)
        if key is not None and all(type(v) is float for v in key):
            if len(_INVERSES) >= 4096:
                _INVERSES.clear()
            _INVERSES[key] = hit
    return np.array(hit)


_INVERSES: dict[Any, tuple[float, float, float]] = {}


def compose_inverse2d(a: ArrayLike, b: tuple[float, float, float]) -> FloatArray:
    """``compose2d(a, inverse2d(b))`` for a tuple ``b`` (a grasp pose), the same numbers.

    The envs turn an object pose into the base pose holding it this way at every check;
    ``b``'s inverse is remembered and nothing goes through a temporary array.
    """
    inv = _INVERSES.get(b)
    if inv is None:
        inv = tuple(inverse2d(b).tolist())  # type: ignore[assignment]
        assert inv is not None
    return np.array(_compose_inverse(_xyt(a), inv))


def compose_inverse_tuple(
    a: tuple[float, float, float] | list[float], b: tuple[float, float, float]
) -> tuple[float, float, float]:
    """:func:`compose_inverse2d` for a pose of floats, as a tuple (what ``pose_tuple`` of
    the array gives)."""
    inv = _INVERSES.get(b)
    if inv is None:
        inv = tuple(inverse2d(b).tolist())  # type: ignore[assignment]
        assert inv is not None
    return _compose_inverse(a, inv)


def _compose_inverse(
    a: tuple[float, ...] | list[float], inv: tuple[float, float, float]
) -> tuple[float, float, float]:
    bx, by, bt = inv
    ax, ay, at = a
    c, s = math.cos(at), math.sin(at)
    return (ax + c * bx - s * by, ay + s * bx + c * by, at + bt)
