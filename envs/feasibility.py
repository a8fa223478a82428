"""Feasibility checks of pick and place actions: grasp poses, arm IK, collision checks.

Three building blocks, each deterministic (same inputs, same answer, in any process):

* :func:`side_grasp` turns the original's grasp parameters (grasp angle, height and depth
  fractions) into a gripper pose on the side of a box-shaped footprint facing the robot.
* :class:`ArmIK` solves the arm's inverse kinematics for a gripper pose given in the base
  frame, with `mink <https://github.com/kevinzakka/mink>`_ (its own
  :class:`mink.Configuration` and :class:`mujoco.MjData` on an arm-only model, QP solver
  ``daqp``). The arm is a 7-joint S-R-S chain (spherical shoulder and wrist), so a
  closed-form solution exists for every elbow "swivel" angle; we compute the closed-form
  candidates with the upper-arm roll at 0 and at pi (elbow down / elbow up) as *seeds*,
  and mink's differential IK, which respects the joint limits, refines the best seed.
  When a seed is already exact and inside the limits, no QP is solved.
* :class:`CollisionChecker` poses the robot (and the object it holds) in a scratch copy
  of the scene and runs MuJoCo's collision detection (``mj_kinematics`` +
  ``mj_collision``), reporting which scene geoms or objects are hit. Contacts between the
  gripper and the object being grasped are allowed (the grasp touches it).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import mink
import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.robot import (
    ARM_JOINTS,
    FINGER_JOINTS,
    FOREARM,
    SHOULDER,
    TOOL,
    TUCK,
    UPPER_ARM,
    Robot,
)
from voot.envs.scene import ObjectInfo, model_path

FloatArray = NDArray[np.float64]

#: QP solvers accepted by :class:`IKConfig` (mink solves through qpsolvers).
IK_SOLVERS = ("daqp", "quadprog", "osqp", "proxqp", "clarabel")


# ----------------------------------------------------------------------------------------
# Rotations
# ----------------------------------------------------------------------------------------
def rot_x(a: float) -> FloatArray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a: float) -> FloatArray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a: float) -> FloatArray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _wrap(a: float) -> float:
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


# ----------------------------------------------------------------------------------------
# Grasps
# ----------------------------------------------------------------------------------------
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
    x, y, z, yaw = (float(v) for v in np.asarray(obj_pose, dtype=np.float64))
    c, s = math.cos(yaw), math.sin(yaw)
    # outward normals of the four faces, world frame, with the face's half extents
    faces = (
        ("+x", np.array([c, s]), float(obj.half[0]), float(obj.half[1])),
        ("-x", np.array([-c, -s]), float(obj.half[0]), float(obj.half[1])),
        ("+y", np.array([-s, c]), float(obj.half[1]), float(obj.half[0])),
        ("-y", np.array([s, -c]), float(obj.half[1]), float(obj.half[0])),
    )
    heading = np.array([math.cos(base_heading), math.sin(base_heading)])
    scores = [float(n @ heading) for _, n, _, _ in faces]
    k = int(np.argmin(scores))  # most opposite to the heading; ties: first
    face, n, half_normal, half_across = faces[k]
    tangent = np.array([-n[1], n[0]])  # horizontal, along the face
    cx = x + c * obj.center[0] - s * obj.center[1]
    cy = y + s * obj.center[0] + c * obj.center[1]
    p_xy = (
        np.array([cx, cy])
        + (half_normal + standoff) * n
        + (2.0 * depth_fraction - 1.0) * half_across * tangent
    )
    p = np.array([p_xy[0], p_xy[1], z + height_fraction * obj.height])
    approach = np.array([-n[0], -n[1], 0.0])
    y0 = np.array([tangent[0], tangent[1], 0.0])
    z0 = np.cross(approach, y0)
    ca, sa = math.cos(grasp_angle), math.sin(grasp_angle)
    y_axis = ca * y0 + sa * z0
    z_axis = np.cross(approach, y_axis)
    rot = np.column_stack([approach, y_axis, z_axis])
    return GraspPose(p, rot, face)


# ----------------------------------------------------------------------------------------
# Inverse kinematics
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class IKConfig:
    """Settings of :class:`ArmIK`.

    Attributes:
        position_tolerance: Success threshold on the tool point's error (metres).
        orientation_tolerance: Success threshold on the tool frame's rotation error (rad).
        max_iterations: mink iterations (one QP each) refining the best closed-form seed.
        solver: QP solver passed to :func:`mink.solve_ik` (the project uses ``daqp``).
        damping: Levenberg-Marquardt damping of :func:`mink.solve_ik`.
        orientation_cost: Weight of the orientation error against the position error.
    """

    position_tolerance: float = 1e-3
    orientation_tolerance: float = 1e-2
    max_iterations: int = 10
    solver: str = "daqp"
    damping: float = 1e-6
    orientation_cost: float = 0.5

    def __post_init__(self) -> None:
        for name in ("position_tolerance", "orientation_tolerance", "damping"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise ValueError(f"IKConfig.{name} must be a finite number > 0, got {v!r}")
        if not (isinstance(self.orientation_cost, int | float) and self.orientation_cost > 0):
            raise ValueError(
                f"IKConfig.orientation_cost must be > 0, got {self.orientation_cost!r}"
            )
        if isinstance(self.max_iterations, bool) or not isinstance(self.max_iterations, int):
            raise ValueError(
                f"IKConfig.max_iterations must be an int >= 0, got {self.max_iterations!r}"
            )
        if self.max_iterations < 0:
            raise ValueError(f"IKConfig.max_iterations must be >= 0, got {self.max_iterations}")
        if self.solver not in IK_SOLVERS:
            raise ValueError(
                f"IKConfig.solver must be one of {', '.join(IK_SOLVERS)}; got {self.solver!r}"
            )


@dataclass(frozen=True)
class IKResult:
    """Outcome of :meth:`ArmIK.solve`.

    Attributes:
        success: A configuration inside the joint limits reaches the target.
        q: The 7 arm joint values (the best found, even on failure; None if out of reach).
        iterations: mink iterations (QPs) used.
        position_error, orientation_error: Remaining errors of ``q`` (metres, radians).
        reason: Empty on success; otherwise ``"out of reach"`` or ``"no convergence"``.
    """

    success: bool
    q: FloatArray | None
    iterations: int
    position_error: float = math.inf
    orientation_error: float = math.inf
    reason: str = ""


class ArmIK:
    """Inverse kinematics of the arm relative to its base (mink + closed-form seeds).

    The arm-only model is ``robot.xml`` with the base and finger joints removed, so the
    base frame is the world frame of the IK model and targets are given in it.

    Args:
        config: Settings; defaults to :class:`IKConfig`.
    """

    def __init__(self, config: IKConfig | None = None) -> None:
        self.config = config if config is not None else IKConfig()
        spec = mujoco.MjSpec.from_file(str(model_path("robot")))
        for name in ("base_x", "base_y", "base_yaw", *FINGER_JOINTS):
            spec.delete(spec.joint(name))
        self.model = spec.compile()
        if self.model.nq != len(ARM_JOINTS):  # pragma: no cover - model drift
            raise RuntimeError(f"arm-only model has nq={self.model.nq}, expected 7")
        self.configuration = mink.Configuration(self.model)
        self.task = mink.FrameTask(
            "grasp", "site", position_cost=1.0, orientation_cost=self.config.orientation_cost
        )
        self.limits = [mink.ConfigurationLimit(self.model)]
        self.lower = self.model.jnt_range[:, 0].copy()
        self.upper = self.model.jnt_range[:, 1].copy()
        self._site = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_SITE, "grasp")

    # ----- closed form ------------------------------------------------------------------
    def seeds(self, position: ArrayLike, rotation: ArrayLike) -> list[FloatArray]:
        """Closed-form solutions (upper-arm roll 0 or pi), any joint limits ignored.

        Ordered: elbow up before elbow down, forward pan before backward, then the two
        wrist solutions. Empty if the wrist centre is out of the arm's reach.
        """
        p = np.asarray(position, dtype=np.float64)
        r = np.asarray(rotation, dtype=np.float64)
        wrist = p - TOOL * r[:, 0]
        d = wrist - SHOULDER
        dist = float(np.linalg.norm(d))
        if dist > UPPER_ARM + FOREARM or dist < abs(UPPER_ARM - FOREARM):
            return []
        cos_alpha = (dist**2 - UPPER_ARM**2 - FOREARM**2) / (2 * UPPER_ARM * FOREARM)
        alpha = math.acos(max(-1.0, min(1.0, cos_alpha)))  # bend between the links
        gamma = math.atan2(FOREARM * math.sin(alpha), UPPER_ARM + FOREARM * math.cos(alpha))
        rho = math.hypot(d[0], d[1])
        out: list[FloatArray] = []
        for roll in (math.pi, 0.0):  # elbow up, elbow down
            for flip in (False, True):
                pan = math.atan2(d[1], d[0]) + (math.pi if flip else 0.0)
                beta = math.atan2(-d[2], -rho if flip else rho)
                lift = beta - gamma if roll else beta + gamma
                q1, q2, q3, q4 = _wrap(pan), _wrap(lift), roll, -alpha
                r04 = rot_z(q1) @ rot_y(q2) @ rot_x(q3) @ rot_y(q4)
                for q5, q6, q7 in xyx_euler(r04.T @ r):
                    out.append(np.array([q1, q2, q3, q4, q5, q6, q7]))
        return out

    def _violation(self, q: FloatArray) -> float:
        return float(np.sum(np.maximum(self.lower - q, 0) + np.maximum(q - self.upper, 0)))

    def _errors(self, q: FloatArray) -> tuple[float, float]:
        self.configuration.update(q)
        err = self.task.compute_error(self.configuration)
        return float(np.linalg.norm(err[:3])), float(np.linalg.norm(err[3:]))

    def solve(self, position: ArrayLike, rotation: ArrayLike) -> IKResult:
        """Joint values putting the grasp site at ``position`` with frame ``rotation``.

        Args:
            position: Target tool point ``(3,)`` in the base frame.
            rotation: Target tool frame ``(3, 3)`` (columns: approach, fingers, normal).
        """
        cfg = self.config
        p = np.asarray(position, dtype=np.float64)
        r = np.asarray(rotation, dtype=np.float64)
        seeds = self.seeds(p, r)
        if not seeds:
            return IKResult(False, None, 0, reason="out of reach")
        # the seed closest to the limits (exact seeds inside them first), then in order
        viol = [self._violation(q) for q in seeds]
        order = sorted(range(len(seeds)), key=lambda i: (viol[i], i))
        best = np.clip(seeds[order[0]], self.lower, self.upper)
        self.task.set_target(mink.SE3.from_rotation_and_translation(mink.SO3.from_matrix(r), p))
        if viol[order[0]] == 0.0:
            pe, oe = self._errors(best)
            if pe <= cfg.position_tolerance and oe <= cfg.orientation_tolerance:
                return IKResult(True, best, 0, pe, oe)
        self.configuration.update(best)
        pe = oe = math.inf
        for it in range(1, cfg.max_iterations + 1):
            vel = mink.solve_ik(
                self.configuration,
                [self.task],
                1.0,
                cfg.solver,
                damping=cfg.damping,
                limits=self.limits,
            )
            self.configuration.integrate_inplace(vel, 1.0)
            err = self.task.compute_error(self.configuration)
            pe, oe = float(np.linalg.norm(err[:3])), float(np.linalg.norm(err[3:]))
            if pe <= cfg.position_tolerance and oe <= cfg.orientation_tolerance:
                q = np.clip(self.configuration.q.copy(), self.lower, self.upper)
                return IKResult(True, q, it, pe, oe)
        q = self.configuration.q.copy()
        return IKResult(False, q, cfg.max_iterations, pe, oe, reason="no convergence")

    def forward(self, q: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Grasp-site position and frame in the base frame for arm joints ``q``."""
        self.configuration.update(np.asarray(q, dtype=np.float64))
        data = self.configuration.data
        return data.site_xpos[self._site].copy(), data.site_xmat[self._site].reshape(3, 3).copy()

    @property
    def tuck(self) -> FloatArray:
        return TUCK.copy()


# ----------------------------------------------------------------------------------------
# Collision checks
# ----------------------------------------------------------------------------------------
@dataclass
class CollisionReport:
    """What a configuration of robot and held object collides with (names, sorted)."""

    hits: list[str] = field(default_factory=list)

    @property
    def free(self) -> bool:
        return not self.hits


class CollisionChecker:
    """MuJoCo collision queries for the robot and the object it holds.

    Works on its own :class:`mujoco.MjData`: :meth:`check` copies the given ``qpos``,
    applies the changes, runs ``mj_kinematics`` and ``mj_collision`` and inspects the
    contacts. A contact counts if one of its geoms belongs to the robot or to the
    ``held`` object, except contacts between the gripper and ``held`` (the grasp itself).
    Contacts among other bodies (objects resting against each other) are ignored.

    Args:
        model: The scene.
        robot: Named access to the robot in ``model``.
        objects: The scene's movable objects.
    """

    def __init__(self, model: mujoco.MjModel, robot: Robot, objects: list[ObjectInfo]) -> None:
        self.model = model
        self.data = mujoco.MjData(model)
        self.robot = robot
        self.objects = objects
        n = model.ngeom
        self._is_robot = np.zeros(n, dtype=bool)
        self._is_robot[list(robot.geoms)] = True
        self._is_gripper = np.zeros(n, dtype=bool)
        self._is_gripper[list(robot.gripper_geoms)] = True
        self._owner = np.full(n, -1, dtype=np.intp)  # object index, or -1
        for i, o in enumerate(objects):
            self._owner[list(o.geoms)] = i
        self._names = []
        for g in range(n):
            owner = int(self._owner[g])
            if owner >= 0:
                self._names.append(objects[owner].name)
            else:
                self._names.append(
                    mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
                )

    def check(
        self,
        qpos: FloatArray,
        base_pose: ArrayLike,
        arm_q: ArrayLike,
        held: int | None = None,
        object_poses: Mapping[int, ArrayLike] | None = None,
    ) -> CollisionReport:
        """Collisions of the robot (and ``held``) in a hypothetical configuration.

        Args:
            qpos: The scene's current ``qpos`` (copied, not modified).
            base_pose: Base ``(x, y, theta)``.
            arm_q: The 7 arm joints.
            held: Index (into ``objects``) of the object in the gripper, if any; its
                contacts with the gripper are allowed and its other contacts count.
            object_poses: Object index -> ``(x, y, z, yaw)`` overrides (e.g. the held
                object at its placement, or objects placed earlier in the same action).

        Returns:
            The names of what is hit (scene geom names; object body names), sorted,
            without duplicates; prefixed ``"robot-"`` or ``"object-"`` by the party hit.
        """
        m, d = self.model, self.data
        d.qpos[:] = qpos
        self.robot.set_base(d, base_pose)
        self.robot.set_arm(d, arm_q)
        if object_poses:
            for i, pose in object_poses.items():
                set_object_pose(d, self.objects[i], pose)
        mujoco.mj_kinematics(m, d)
        mujoco.mj_collision(m, d)
        ncon = d.ncon
        if ncon == 0:
            return CollisionReport()
        geom = d.contact.geom[:ncon]
        g1, g2 = geom[:, 0], geom[:, 1]
        held_i = -2 if held is None else held
        own1, own2 = self._owner[g1], self._owner[g2]
        rob1, rob2 = self._is_robot[g1], self._is_robot[g2]
        hold1, hold2 = own1 == held_i, own2 == held_i
        relevant = rob1 | rob2 | hold1 | hold2
        grasp_contact = (self._is_gripper[g1] & hold2) | (self._is_gripper[g2] & hold1)
        keep = np.flatnonzero(relevant & ~grasp_contact)
        hits = set()
        for k in keep:
            a, b = int(g1[k]), int(g2[k])
            if not (self._is_robot[a] or self._owner[a] == held_i):
                a, b = b, a  # a is ours (robot or held), b the other party
            who = "robot" if self._is_robot[a] else "object"
            hits.add(f"{who}-{self._names[b]}" if not self._is_robot[b] else f"{who}-robot")
        return CollisionReport(sorted(hits))


def set_object_pose(data: mujoco.MjData, obj: ObjectInfo, pose: ArrayLike) -> None:
    """Put ``obj``'s body at ``(x, y, z, yaw)`` (free joint qpos)."""
    x, y, z, yaw = (float(v) for v in np.asarray(pose, dtype=np.float64))
    a = obj.qpos_adr
    data.qpos[a : a + 3] = (x, y, z)
    data.qpos[a + 3 : a + 7] = (math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw))


def object_pose(data: mujoco.MjData, obj: ObjectInfo) -> FloatArray:
    """``(x, y, z, yaw)`` of ``obj``'s body from its free joint."""
    a = obj.qpos_adr
    q = data.qpos[a + 3 : a + 7]
    yaw = math.atan2(2.0 * (q[0] * q[3] + q[1] * q[2]), 1.0 - 2.0 * (q[2] ** 2 + q[3] ** 2))
    return np.array([data.qpos[a], data.qpos[a + 1], data.qpos[a + 2], yaw])
