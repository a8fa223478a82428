"""Inverse kinematics of the arm relative to its base: closed-form seeds refined by mink.

:class:`ArmIK` solves the arm's inverse kinematics for a gripper pose given in the base
frame, with `mink <https://github.com/kevinzakka/mink>`_ (its own
:class:`mink.Configuration` and :class:`mujoco.MjData` on an arm-only model, QP solver
``daqp``). The arm is a 7-joint S-R-S chain (spherical shoulder and wrist), so a
closed-form solution exists for every elbow "swivel" angle; we compute the closed-form
candidates with the upper-arm roll at 0 and at pi (elbow down / elbow up) as *seeds*,
and mink's differential IK, which respects the joint limits, refines the best seed.
When a seed is already exact and inside the limits, no QP is solved. Deterministic:
same target, same joints, in any process.

Its settings are :class:`IKConfig` and its answer an :class:`IKResult`. A pick's grasp
pose comes from :mod:`voot.envs.robot.grasp`; whether the robot at the solution is free, from
:mod:`voot.envs.robot.collision`.
"""

from __future__ import annotations

import ctypes
import math
from collections.abc import Iterator
from dataclasses import dataclass

import daqp
import mink
import mujoco
import numpy as np
import qpsolvers
from numpy.typing import ArrayLike, NDArray

from voot import validation as V
from voot.envs.core.scene import model_path
from voot.envs.robot.model import (
    ARM_JOINTS,
    FINGER_JOINTS,
    FOREARM,
    SHOULDER,
    TOOL,
    TUCK,
    UPPER_ARM,
)
from voot.envs.robot.rotations import _wrap, rot_x, rot_y, rot_z, xyx_euler

FloatArray = NDArray[np.float64]

__all__ = ["IK_SOLVERS", "ArmIK", "IKConfig", "IKResult"]

#: QP solvers accepted by :class:`IKConfig` (mink solves through qpsolvers).
IK_SOLVERS = ("daqp", "quadprog", "osqp", "proxqp", "clarabel")


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
        so the step is bit for bit theirs (``tests/envs/robot/test_arm_ik.py`` compares).
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
