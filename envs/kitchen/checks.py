"""The checks of a kitchen pick or place: the step's and the planners' pre-check.

A **pick** is feasible iff the base footprint is inside the house, the base with the arm
tucked collides with nothing, the arm's IK reaches the grasp
(:mod:`voot.envs.robot.arm_ik`), the robot at the grasp collides with nothing (the gripper
may touch the grasped object) and, with ``pick_requires_free_carry``, the carry disc is
free (:meth:`~voot.envs.kitchen.screen.KitchenScreen._carry_blocked`), tested last so the
other reasons stay as without the rule: :meth:`KitchenChecks._pick_kinematics`.
A **place** first checks that the object is inside the house and (in the step) not in
the forbidden rooms, that the robot's base stays in the house and that robot and object
collide with nothing: :meth:`KitchenChecks._place_checks`; the step then plans the base
path (:mod:`voot.envs.kitchen.env`). :meth:`KitchenChecks.precheck` is these checks without
the forbidden rooms and the base paths: stage 1 of the authors' two-stage feasibility
(the v1 ``"kinematic"`` pre-check). Each check records its seconds in ``last_timing``.

:class:`KitchenChecks` is the middle layer of :class:`~voot.envs.kitchen.env.KitchenClearingEnv`
(over :class:`~voot.envs.kitchen.screen.KitchenScreen`), kept apart from the step so that
what makes an action infeasible, and why, reads in one place.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.core.names import Failure, Operator, Reason, reason_code
from voot.envs.core.scene import object_footprint
from voot.envs.core.state import StepTiming, pose_tuple
from voot.envs.core.units import denormalize
from voot.envs.kitchen.poses import pick_base, place_base, relative_pose
from voot.envs.kitchen.screen import KitchenScreen
from voot.envs.motion.rects import rect_inside, rect_overlaps
from voot.envs.robot.grasp import GraspPose, side_grasp
from voot.envs.robot.model import TUCK, base_footprint
from voot.envs.robot.rotations import rot_z

FloatArray = NDArray[np.float64]


def _collision(hits: Any) -> Failure:
    """The failure of a collision check with ``hits`` (the colliding pairs' names)."""
    return Failure(Reason.COLLISION, "collision: " + ", ".join(hits))


class KitchenChecks(KitchenScreen):
    """The pick and place checks of :class:`~voot.envs.kitchen.env.KitchenClearingEnv`.

    A mixin layer (see the module docstring); changes nothing but ``last_timing``.
    """

    def pick_base_pose(self, obj: int, params: ArrayLike) -> FloatArray:
        """The base pose ``(x, y, theta)`` of pick parameters for object ``obj``."""
        return pick_base(self.object_box(obj), params)

    def _grasp_pose(
        self, obj: int, pose: FloatArray, base_heading: float, params: FloatArray
    ) -> tuple[GraspPose | None, str]:
        """The gripper pose of a pick's grasp parameters, or None and why there is none.

        The hook of the grasp step of :meth:`_pick_kinematics`: the kitchen's boxes and
        chairs take the original's :func:`~voot.envs.robot.grasp.side_grasp`, which always
        gives a pose (''); a subclass whose objects are meshes returns its own grasp,
        or None with a reason such as ``"grasp misses the object"`` (an infeasible pick).
        ``pose`` is the object's ``(x, y, z, yaw)``, ``params`` the pick's parameters
        (grasp angle, height and depth fractions first).
        """
        grasp = side_grasp(
            self.objects[obj],
            pose,
            base_heading,
            params[0],
            params[1],
            params[2],
            self.config.grasp_standoff,
        )
        return grasp, ""

    def _pick_kinematics(
        self, params: FloatArray
    ) -> tuple[str, FloatArray, Any, tuple[float, float, float]]:
        """The pick's kinematic checks (its pre-check): why it fails ('' if it passes).

        Also returns the base pose, the IK solution and the object's pose in the base
        frame (None and zeros where the check stopped before them). Changes nothing.
        """
        cfg, t = self.config, self.task
        obj = t.on_path[0]
        ik_time = col_time = 0.0
        no_rel = (0.0, 0.0, 0.0)
        base = self.pick_base_pose(obj, params)
        if not rect_inside(base_footprint(base), cfg.house):
            self.last_timing = StepTiming()
            return (
                Failure(Reason.OUTSIDE_REGION, "outside region: the robot leaves the house"),
                base,
                None,
                no_rel,
            )
        pose = self.object_pose(obj)
        grasp, miss = self._grasp_pose(obj, pose, float(base[2]), params)
        if grasp is None:  # the hook's contract: no grasp pose means the grasp misses
            self.last_timing = StepTiming()
            return Failure(Reason.GRASP_MISSES, miss), base, None, no_rel
        t0 = time.perf_counter()
        base_report = self.collision.check(self.data.qpos, base, TUCK)  # cheap early exit
        col_time = time.perf_counter() - t0
        if not base_report.free:
            self.last_timing = StepTiming(collision=col_time)
            return _collision(base_report.hits), base, None, no_rel
        rb = rot_z(float(base[2]))
        target_p = rb.T @ (grasp.position - np.array([base[0], base[1], 0.0]))
        target_r = rb.T @ grasp.rotation
        t0 = time.perf_counter()
        ik = self.ik.solve(target_p, target_r)
        ik_time = time.perf_counter() - t0
        if not ik.success or ik.q is None:
            self.last_timing = StepTiming(ik=ik_time, collision=col_time)
            return Failure(Reason.IK_FAILED, f"IK failed: {ik.reason}"), base, None, no_rel
        t0 = time.perf_counter()
        report = self.collision.check(self.data.qpos, base, ik.q, held=obj)
        col_time += time.perf_counter() - t0
        self.last_timing = StepTiming(ik=ik_time, collision=col_time)
        if not report.free:
            return _collision(report.hits), base, None, no_rel
        held_rel = relative_pose(base, pose)
        if cfg.pick_requires_free_carry:  # last, so the other reasons stay as without it
            t0 = time.perf_counter()
            carry_reason = self._carry_blocked(obj, held_rel, base)
            col_time += time.perf_counter() - t0
            self.last_timing = StepTiming(ik=ik_time, collision=col_time)
            if carry_reason:
                return carry_reason, base, None, no_rel
        return "", base, ik.q, held_rel

    def _place_checks(
        self, params: FloatArray, forbidden_rooms: bool
    ) -> tuple[str, FloatArray, tuple[float, float, float], float, float]:
        """The place's checks before its base path: why it fails ('' if it passes).

        In the step's order: object in the house, (with ``forbidden_rooms``) not in the
        rooms behind the door, robot in the house, no collision. Without the forbidden
        rooms they are the place's pre-check. Also returns the base pose, the placement,
        the object's height and the seconds spent checking collisions. Changes nothing.
        """
        cfg, t = self.config, self.task
        obj = t.held
        x, y, theta = (float(v) for v in params)
        new_box = object_footprint(self.objects[obj], x, y, theta)
        base = place_base((x, y, theta), t.held_rel)
        placement = (x, y, theta)
        z = float(self.object_pose(obj)[2])
        if not rect_inside(new_box, cfg.house):
            text = "outside region: the object leaves the house"
            return Failure(Reason.OUTSIDE_REGION, text), base, placement, z, 0.0
        if forbidden_rooms and rect_overlaps(new_box, cfg.forbidden):
            text = "forbidden room: the object is in the rooms behind the door"
            return Failure(Reason.FORBIDDEN_ROOM, text), base, placement, z, 0.0
        if not rect_inside(base_footprint(base), cfg.house):
            text = "outside region: the robot leaves the house"
            return Failure(Reason.OUTSIDE_REGION, text), base, placement, z, 0.0
        t0 = time.perf_counter()
        report = self.collision.check(
            self.data.qpos, base, t.grasp_q, held=obj, object_poses={obj: (x, y, z, theta)}
        )
        col_time = time.perf_counter() - t0
        if not report.free:
            return _collision(report.hits), base, placement, z, col_time
        return "", base, placement, z, col_time

    def precheck(self, action: ArrayLike) -> tuple[bool, dict[str, Any]]:
        """The cheap kinematic check of ``action`` in the current state (changes nothing).

        Stage 1 of the authors' two-stage feasibility (:mod:`voot.tree.problem`): a pick
        passes if the robot stays in the house, IK reaches the grasp and nothing collides
        (with ``pick_requires_free_carry``, also the carry disc); a place if object and
        robot stay in the house and nothing collides. The forbidden rooms and the base
        paths are left to :meth:`step`. Returns whether it passes and an info with the
        keys of an infeasible step's info (``feasible``, ``reason``, ``operator``,
        ``object``, ``base_pose``, ``placement``).
        """
        a, _ = self._validate_action(action)
        t = self.task
        if t.done or t.steps >= self.config.horizon:
            raise ValueError("the episode has ended (terminated or truncated); call reset()")
        placement: tuple[float, float, float] | None = None
        if t.operator == Operator.PICK:
            obj = t.on_path[0]
            reason, base, _, _ = self._pick_kinematics(denormalize(a, self.config.pick_ranges))
        else:
            obj = t.held
            reason, base, placement, _, _ = self._place_checks(
                denormalize(a[:3], self.config.place_ranges), forbidden_rooms=False
            )
        return not reason, {
            "operator": t.operator,
            "object": self.objects[obj].name,
            "feasible": not reason,
            "reason": str(reason),
            "reason_code": reason_code(reason),
            "base_pose": pose_tuple(base),
            "placement": placement,
        }
