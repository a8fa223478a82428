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

Size: the three kinematic checks an action needs (grasp, IK, collisions), with their
float fast paths.
"""

from __future__ import annotations

import copy
import ctypes
import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field

import daqp
import mink
import mujoco
import numpy as np
import qpsolvers
from numpy.typing import ArrayLike, NDArray

from voot import validation as V
from voot.envs.robot import (
    ARM_JOINTS,
    FINGER_JOINTS,
    FINGER_OPEN,
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
            V.positive(getattr(self, name), f"IKConfig.{name}")
        V.positive(self.orientation_cost, "IKConfig.orientation_cost")
        V.integer(self.max_iterations, "IKConfig.max_iterations", 0)
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
        self._lower_l: list[float] = self.lower.tolist()
        self._upper_l: list[float] = self.upper.tolist()
        self._site = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_SITE, "grasp")
        limit = self.limits[0]
        # the QP's constant constraint matrix, as mink stacks it (hinge limits only)
        self._qp_rows: FloatArray | None = None
        if (
            self.config.solver == "daqp"
            and limit.projection_matrix is not None
            and len(limit._ball_qposadr) == 0
            and callable(getattr(self.task, "compute_qp_residual", None))
        ):
            P = limit.projection_matrix
            self._qp_rows = np.vstack([P, -P])

    # ----- closed form ------------------------------------------------------------------
    def seeds(self, position: ArrayLike, rotation: ArrayLike) -> list[FloatArray]:
        """Closed-form solutions (upper-arm roll 0 or pi), any joint limits ignored.

        Ordered: elbow up before elbow down, forward pan before backward, then the two
        wrist solutions. Empty if the wrist centre is out of the arm's reach.
        """
        return list(self._seed_iter(position, rotation))

    def _seed_iter(self, position: ArrayLike, rotation: ArrayLike) -> Iterator[FloatArray]:
        """:meth:`seeds` one at a time, in their order (:meth:`solve` stops at the first
        inside the limits)."""
        p = np.asarray(position, dtype=np.float64)
        r = np.asarray(rotation, dtype=np.float64)
        wrist = p - TOOL * r[:, 0]
        d = wrist - SHOULDER
        dist = float(np.linalg.norm(d))
        if dist > UPPER_ARM + FOREARM or dist < abs(UPPER_ARM - FOREARM):
            return
        cos_alpha = (dist**2 - UPPER_ARM**2 - FOREARM**2) / (2 * UPPER_ARM * FOREARM)
        alpha = math.acos(max(-1.0, min(1.0, cos_alpha)))  # bend between the links
        gamma = math.atan2(FOREARM * math.sin(alpha), UPPER_ARM + FOREARM * math.cos(alpha))
        rho = math.hypot(d[0], d[1])
        for roll in (math.pi, 0.0):  # elbow up, elbow down
            for flip in (False, True):
                pan = math.atan2(d[1], d[0]) + (math.pi if flip else 0.0)
                beta = math.atan2(-d[2], -rho if flip else rho)
                lift = beta - gamma if roll else beta + gamma
                q1, q2, q3, q4 = _wrap(pan), _wrap(lift), roll, -alpha
                r04 = rot_z(q1) @ rot_y(q2) @ rot_x(q3) @ rot_y(q4)
                for q5, q6, q7 in xyx_euler(r04.T @ r):
                    yield np.array([q1, q2, q3, q4, q5, q6, q7])

    def _violation(self, q: FloatArray) -> float:
        return float(np.sum(np.maximum(self.lower - q, 0) + np.maximum(q - self.upper, 0)))

    def _float_violation(self, q: FloatArray) -> float:
        """:meth:`_violation` summed on floats in joint order (zero iff it is zero)."""
        v = 0.0
        for qj, lo, hi in zip(q.tolist(), self._lower_l, self._upper_l, strict=True):
            v += max(lo - qj, 0.0) + max(qj - hi, 0.0)
        return v

    def _chosen_seed(
        self, position: FloatArray, rotation: FloatArray
    ) -> tuple[FloatArray, bool] | None:
        """:meth:`_closest_seed` of :meth:`seeds` (the seed and whether it is inside the
        limits; None if there is none), computing seeds only up to the first inside the
        limits: that one is the choice whatever follows."""
        seeds: list[FloatArray] = []
        for q in self._seed_iter(position, rotation):
            if self._float_violation(q) == 0.0:
                return q, True
            seeds.append(q)
        if not seeds:
            return None
        first, inside = self._closest_seed(seeds)
        return seeds[first], inside

    def _closest_seed(self, seeds: list[FloatArray]) -> tuple[int, bool]:
        """The seed :meth:`solve` refines (least limit violation, first on ties) and
        whether it is inside the limits.

        The violations are summed on floats; only when two nonzero ones come within 1e-9
        (where numpy's summation order could decide) does :meth:`_violation` decide. A
        zero violation is exact either way (every term is zero).
        """
        approx = [self._float_violation(q) for q in seeds]
        m = min(approx)
        if m == 0.0:
            return approx.index(0.0), True
        close = [i for i, v in enumerate(approx) if v - m <= 1e-9]
        if len(close) == 1:
            return close[0], False
        viol = [self._violation(q) for q in seeds]
        k = min(range(len(seeds)), key=lambda i: (viol[i], i))
        return k, viol[k] == 0.0

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
        # the seed closest to the limits (exact seeds inside them first), then in order
        chosen = self._chosen_seed(p, r)
        if chosen is None:
            return IKResult(False, None, 0, reason="out of reach")
        seed, inside = chosen
        best = np.clip(seed, self.lower, self.upper)
        self.task.set_target(mink.SE3.from_rotation_and_translation(mink.SO3.from_matrix(r), p))
        if inside:
            pe, oe = self._errors(best)
            if pe <= cfg.position_tolerance and oe <= cfg.orientation_tolerance:
                return IKResult(True, best, 0, pe, oe)
        self.configuration.update(best)
        pe = oe = math.inf
        for it in range(1, cfg.max_iterations + 1):
            vel = self._ik_velocity()
            self.configuration.integrate_inplace(vel, 1.0)
            err = self.task.compute_error(self.configuration)
            pe, oe = float(np.linalg.norm(err[:3])), float(np.linalg.norm(err[3:]))
            if pe <= cfg.position_tolerance and oe <= cfg.orientation_tolerance:
                q = np.clip(self.configuration.q.copy(), self.lower, self.upper)
                return IKResult(True, q, it, pe, oe)
        q = self.configuration.q.copy()
        return IKResult(False, q, cfg.max_iterations, pe, oe, reason="no convergence")

    def _ik_velocity(self) -> FloatArray:
        """One differential-IK step: ``mink.solve_ik`` (dt 1) without its limit check.

        ``mink.solve_ik`` first checks the configuration against the joint limits and,
        with ``safety_break=False`` (its default, and ours), only logs a warning when it
        is outside them; the rest (``mink.build_ik``, then ``qpsolvers.solve_problem``)
        is what it computes, so the step is the same. The check was a tenth of a step's
        cost, and our iterates start clipped to the limits, which the QP keeps.
        """
        cfg = self.config
        if self._qp_rows is not None:
            return self._daqp_velocity()
        problem = mink.build_ik(self.configuration, [self.task], 1.0, cfg.damping, self.limits)
        result = qpsolvers.solve_problem(problem, solver=cfg.solver)
        if not result.found or result.x is None:
            raise mink.NoSolutionFound(cfg.solver)
        velocity: FloatArray = result.x / 1.0
        return velocity

    def _daqp_velocity(self) -> FloatArray:
        """:meth:`_ik_velocity` with daqp: the QP that ``mink.build_ik`` assembles (one
        frame task, hinge limits) and the call that qpsolvers makes of daqp, without their
        generic machinery (per-task lists, the constant constraint rows rebuilt, a
        ``Problem`` and a ``Solution``): the same arrays, built with the same operations,
        so the step is bit for bit theirs (``tests/test_feasibility.py`` compares).
        """
        conf, limit, rows = self.configuration, self.limits[0], self._qp_rows
        assert rows is not None
        nv = self.model.nv
        # mink.solve_ik._compute_qp_objective for one task with a weighted residual
        weighted_jacobian, weighted_error, mu = self.task.compute_qp_residual(conf)
        w = np.vstack([weighted_jacobian])
        hessian = w.T @ w
        linear = -(np.concatenate([weighted_error]) @ w)
        hessian.flat[:: nv + 1] += self.config.damping + (0.0 + mu)
        # ConfigurationLimit.compute_qp_inequalities: G is constant, h follows q
        q = conf.q
        upper_gap = np.empty((nv,))
        mujoco.mj_differentiatePos(
            m=limit.model, qvel=upper_gap, dt=1.0, qpos1=q, qpos2=limit.upper
        )
        lower_gap = np.empty((nv,))
        mujoco.mj_differentiatePos(
            m=limit.model, qvel=lower_gap, dt=1.0, qpos1=limit.lower, qpos2=q
        )
        bound = np.concatenate(
            [limit.gain * upper_gap[limit.indices], limit.gain * lower_gap[limit.indices]]
        )
        # qpsolvers' daqp_solve_problem for inequalities only
        m = rows.shape[0]
        x, _, exitflag, _ = daqp.solve(
            hessian,
            linear,
            rows,
            bound,
            np.full(m, -1e30),
            np.zeros(m, dtype=ctypes.c_int),
            primal_start=None,
        )
        if exitflag <= 0 or x is None:
            raise mink.NoSolutionFound("daqp")
        velocity: FloatArray = x / 1.0
        return velocity

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


#: A contact pair not looked up yet (the pair memo holds None for "not reported").
_UNKNOWN = object()


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
        self.model, self._held_affinity = _robot_pairs_model(model, robot, objects)
        self.data = mujoco.MjData(self.model)
        # views into the model's and data's buffers, fetched once (each attribute access
        # builds a new array object)
        self._affinity_view = self.model.geom_conaffinity
        self._qpos_view = self.data.qpos
        # (geom, geom, held) -> what the contact reports (a pure function of the three)
        self._pair_hit: dict[tuple[int, int, int], str | None] = {}
        # the last query, ``(held, qpos bytes)``, and its report (see check; None: a hit
        # found by collides, names not built)
        self._last: tuple[tuple[int, bytes], CollisionReport | None] | None = None
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
        # plain lists and slices for check(), whose contacts are few: indexing them from
        # Python is cheaper than numpy masks over a handful of rows
        self._robot_l: list[bool] = self._is_robot.tolist()
        self._gripper_l: list[bool] = self._is_gripper.tolist()
        self._owner_l: list[int] = self._owner.tolist()
        self._base_sl = _as_slice(robot.base_qadr)
        self._arm_sl = _as_slice(robot.arm_qadr)
        self._finger_sl = _as_slice(robot.finger_qadr)
        self._names = []
        for g in range(n):
            owner = int(self._owner[g])
            if owner >= 0:
                self._names.append(objects[owner].name)
            else:
                self._names.append(
                    mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
                )

    def __getstate__(self) -> dict[str, object]:
        """The checker without its two buffer views, for :mod:`pickle` and :mod:`copy`.

        The views alias the buffers of :attr:`model` and :attr:`data`; copied, they would
        be arrays of their own, so a copy's checks would write the configuration where
        MuJoCo never reads it (and report collisions of a stale one). They are fetched
        again from the copy's model and data (:meth:`__setstate__`).
        """
        state = self.__dict__.copy()
        del state["_affinity_view"], state["_qpos_view"]
        return state

    def __setstate__(self, state: dict[str, object]) -> None:
        self.__dict__.update(state)
        self._affinity_view = self.model.geom_conaffinity
        self._qpos_view = self.data.qpos

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
            Treat it as read-only: a query repeating the last one (the same ``held`` and
            the same ``qpos`` once the changes are applied, byte for byte) returns the
            last report itself. The report is a pure function of the two (kinematics and
            contacts depend on the positions alone), so the repeat is exact; it is what a
            pre-screen followed by the full step of the same action asks
            (:meth:`voot.envs.task_env.ManipulationEnv.certainly_infeasible`).
        """
        key = self._configure(qpos, base_pose, arm_q, held, object_poses)
        last = self._last
        if last is not None and last[0] == key and last[1] is not None:
            return last[1]
        self._contacts(held)
        report = self._report(held)
        self._last = (key, report)
        return report

    def collides(
        self,
        qpos: FloatArray,
        base_pose: ArrayLike,
        arm_q: ArrayLike,
        held: int | None = None,
        object_poses: Mapping[int, ArrayLike] | None = None,
    ) -> bool:
        """``not check(...).free`` (the same arguments), without naming what is hit.

        It stops at the first contact that counts, so a pre-screen that only needs the
        verdict pays for no names; a free configuration is remembered as the last query
        (its report is empty), so :meth:`check` of it right after costs nothing.
        """
        key = self._configure(qpos, base_pose, arm_q, held, object_poses)
        last = self._last
        if last is not None and last[0] == key:
            return last[1] is None or not last[1].free
        self._contacts(held)
        d = self.data
        ncon = d.ncon
        if ncon:
            held_i = -2 if held is None else held
            memo = self._pair_hit
            for a, b in d.contact.geom[:ncon].tolist():
                pair = (a, b, held_i)
                name = memo.get(pair, _UNKNOWN)
                if name is _UNKNOWN:
                    name = memo[pair] = self._hit_name(a, b, held_i)
                if name is not None:
                    self._last = (key, None)  # hit; the names are built if check() asks
                    return True
        self._last = (key, CollisionReport())
        return False

    def _configure(
        self,
        qpos: FloatArray,
        base_pose: ArrayLike,
        arm_q: ArrayLike,
        held: int | None,
        object_poses: Mapping[int, ArrayLike] | None,
    ) -> tuple[int, bytes]:
        """Write the configuration into :attr:`data`'s ``qpos``; the query's key.

        The key is ``held`` and the ``qpos`` bytes: what a report is a function of.
        """
        d = self.data
        q = self._qpos_view
        q[:] = qpos
        base_sl, arm_sl, finger_sl = self._base_sl, self._arm_sl, self._finger_sl
        if base_sl is not None and arm_sl is not None and finger_sl is not None:
            q[base_sl] = base_pose
            q[arm_sl] = arm_q
            q[finger_sl] = FINGER_OPEN
        else:  # pragma: no cover - robot.xml keeps each joint group contiguous
            self.robot.set_base(d, base_pose)
            self.robot.set_arm(d, arm_q)
        if object_poses:
            objects = self.objects
            for i, pose in object_poses.items():
                if type(pose) is tuple and len(pose) == 4:
                    # set_object_pose's numbers, written straight into the qpos view
                    x, y, z, yaw = pose
                    adr = objects[i].qpos_adr
                    q[adr : adr + 7] = (x, y, z, math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw))
                else:
                    set_object_pose(d, objects[i], pose)
        return (-2 if held is None else held, q.tobytes())

    def _contacts(self, held: int | None) -> None:
        """Kinematics and contacts of the configuration in :attr:`data` (``held``'s filter)."""
        m, d = self.model, self.data
        mujoco.mj_kinematics(m, d)
        restore = self._held_affinity.get(held) if held is not None else None
        if restore is not None:
            geoms, full, reduced = restore
            affinity = self._affinity_view
            affinity[geoms] = full
            mujoco.mj_collision(m, d)
            affinity[geoms] = reduced
        else:
            mujoco.mj_collision(m, d)

    def _report(self, held: int | None) -> CollisionReport:
        """The report of the contacts in :attr:`data`."""
        d = self.data
        ncon = d.ncon
        if ncon == 0:
            return CollisionReport()
        held_i = -2 if held is None else held
        memo = self._pair_hit
        hits: set[str] = set()
        for a, b in d.contact.geom[:ncon].tolist():
            key = (a, b, held_i)
            if key in memo:
                name = memo[key]
            else:
                name = memo[key] = self._hit_name(a, b, held_i)
            if name is not None:
                hits.add(name)
        if len(memo) > 200_000:  # pragma: no cover - bounded by ngeom^2 x objects
            memo.clear()
        return CollisionReport(sorted(hits))

    def _hit_name(self, a: int, b: int, held_i: int) -> str | None:
        """What a contact between geoms ``a`` and ``b`` reports (None: not reported)."""
        robot, owner, gripper, names = self._robot_l, self._owner_l, self._gripper_l, self._names
        hold_a, hold_b = owner[a] == held_i, owner[b] == held_i
        if not (robot[a] or robot[b] or hold_a or hold_b):
            return None  # between two other parties
        if (gripper[a] and hold_b) or (gripper[b] and hold_a):
            return None  # the grasp itself
        if not (robot[a] or hold_a):
            a, b = b, a  # a is ours (robot or held), b the other party
        who = "robot" if robot[a] else "object"
        return f"{who}-{names[b]}" if not robot[b] else f"{who}-robot"


def _robot_pairs_model(
    model: mujoco.MjModel, robot: Robot, objects: list[ObjectInfo]
) -> tuple[
    mujoco.MjModel, dict[int, tuple[slice | list[int], NDArray[np.int32], NDArray[np.int32]]]
]:
    """A copy of ``model`` whose collision filter keeps only the pairs a check reports.

    :meth:`CollisionChecker.check` reports contacts of the robot and of the held object
    only; MuJoCo would also compute every contact between two other parties (an object
    resting against a wall). In the copy, every non-robot geom's ``conaffinity`` keeps
    only the robot's ``contype`` bits, so such pairs are never tested, and the held
    object's geoms get their own ``conaffinity`` back for the duration of a check. Pairs
    with the robot keep their filter, and a pair of the held object and another geom is
    kept exactly when it was (verified here for every object against every geom;
    otherwise the original filter is used). Contacts are computed per pair, so the ones
    reported are the same. Returns the model and, per object index, its geoms with
    their original and reduced ``conaffinity``.
    """
    contype = model.geom_contype.astype(np.int64)
    affinity = model.geom_conaffinity.astype(np.int64)
    is_robot = np.zeros(model.ngeom, dtype=bool)
    is_robot[list(robot.geoms)] = True
    robot_bits = int(np.bitwise_or.reduce(contype[is_robot])) if is_robot.any() else 0
    if np.any(contype[~is_robot] & robot_bits):  # pragma: no cover - not in the scenes
        return model, {}
    reduced = np.where(is_robot, affinity, affinity & robot_bits)

    def pairs(ct: NDArray[np.int64], af: NDArray[np.int64]) -> NDArray[np.bool_]:
        return ((ct[:, None] & af[None, :]) | (ct[None, :] & af[:, None])) != 0

    original = pairs(contype, affinity)
    held: dict[int, tuple[slice | list[int], NDArray[np.int32], NDArray[np.int32]]] = {}
    for i, obj in enumerate(objects):
        geoms = list(obj.geoms)
        trial = reduced.copy()
        trial[geoms] = affinity[geoms]
        filtered = pairs(contype, trial)
        ours = is_robot.copy()
        ours[geoms] = True
        # every pair with the robot or this object is filtered as before
        if not np.array_equal(filtered[ours], original[ours]):  # pragma: no cover
            return model, {}
        run = _as_slice(np.asarray(geoms, dtype=np.intp))
        held[i] = (
            geoms if run is None else run,
            model.geom_conaffinity[geoms].copy(),
            reduced[geoms].astype(model.geom_conaffinity.dtype),
        )
    copy_ = copy.copy(model)
    copy_.geom_conaffinity[:] = reduced.astype(model.geom_conaffinity.dtype)
    return copy_, held


def _as_slice(index: NDArray[np.intp]) -> slice | None:
    """``index`` as an equivalent slice if it is a run of consecutive addresses."""
    lo = int(index[0])
    if index.tolist() == list(range(lo, lo + len(index))):
        return slice(lo, lo + len(index))
    return None


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
