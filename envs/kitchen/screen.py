"""The kitchen's exact pre-screen and the carry-disc test it shares with the pick step.

The carry disc is the disc enclosing the robot and the object it holds, which the place
step plans the base path with (:meth:`KitchenScreen.carry_disc_for`); with
``pick_requires_free_carry`` a pick is feasible only if that disc is free where the robot
stands (:meth:`KitchenScreen._carry_blocked`, remembered for the step after the screen).

The pre-screen (:meth:`KitchenScreen.certainly_infeasible`, the v0 ``"full_step"``
pre-check's fast path, :meth:`voot.envs.core.env.ManipulationEnv.certainly_infeasible`)
answers whether a step would certainly find an action infeasible, on Python floats with
the step's operations in its order, so that its verdicts are exact. What depends on the
state alone is computed once per state (:class:`ScreenContext`); the carry test on floats
(:meth:`KitchenScreen._carry_verdict`) answers first when it is sure.

:class:`KitchenScreen` is the lowest layer of :class:`~voot.envs.kitchen.env.KitchenClearingEnv`
(then :class:`~voot.envs.kitchen.checks.KitchenChecks`, the step's checks, then the env):
a mixin over :class:`~voot.envs.core.env.ManipulationEnv` whose methods read the env's
state (``self.task``, ``self.data``, ``self.planner`` ...), kept apart because it is the
planners' hot path and mirrors the checks number for number.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.core.env import ManipulationEnv
from voot.envs.core.names import Failure, Operator, Reason
from voot.envs.core.scene import object_footprint
from voot.envs.core.state import replace
from voot.envs.core.units import denormalize_floats
from voot.envs.kitchen.config import KitchenConfig
from voot.envs.kitchen.poses import relative_pose_floats
from voot.envs.kitchen.task import KitchenTask
from voot.envs.motion.footprint import Footprint
from voot.envs.motion.planner import Box2D, DiscProbe
from voot.envs.motion.rects import rect_fields_inside, rect_fields_overlap
from voot.envs.robot.model import (
    ARM_REACH,
    BASE_HALF,
    ROBOT_DISC,
    TUCK,
    CarryDisc,
    carry_disc,
    carry_disc_floats,
    inverse2d,
)

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class ScreenContext:
    """What :meth:`KitchenClearingEnv.certainly_infeasible` needs of one state.

    Built once per state (a task record and the ``qpos`` bytes: every number here is a
    function of the two), so the pre-screen of each proposal at a node computes only
    what depends on the action.

    Attributes:
        task: The task record the numbers are for.
        qpos: The ``qpos`` bytes they are for.
        obj: The object handled (held at a place, first on the path at a pick).
        ranges: The operator's parameter ranges.
        center: The object's footprint centre in its body frame (``ObjectInfo.center``).
        half: The footprint's half extents.
        pose: The object's body pose ``(x, y, z, yaw)`` (``object_pose``).
        pose_xyyaw: Its ``(x, y, yaw)`` as floats.
        box: The object's footprint now (``object_box``).
        inverse: ``inverse2d(held_rel)`` at a place (the base in the object's frame).
        disc: The carry disc at a place (``held_disc``), else None.
        start: The disc's centre pose now at a place (the base path's start), else None.
        movable: The footprints of the other objects (``object_boxes(exclude=(obj,))``).
        probe: The base planner's disc tests among the static obstacles and ``movable``.
    """

    task: KitchenTask
    qpos: bytes
    obj: int
    ranges: tuple[tuple[float, float], ...]
    center: tuple[float, float]
    half: tuple[float, float]
    pose: FloatArray
    pose_xyyaw: tuple[float, float, float]
    box: Box2D
    inverse: tuple[float, float, float]
    disc: CarryDisc | None
    start: FloatArray | None
    movable: tuple[Box2D, ...]
    probe: DiscProbe


class KitchenScreen(ManipulationEnv[KitchenTask]):
    """The carry disc and the exact pre-screen of :class:`~voot.envs.kitchen.env.KitchenClearingEnv`.

    A mixin (see the module docstring): the env sets the attributes declared here in its
    ``__init__``.
    """

    config: KitchenConfig
    #: Carry discs by object and grasp (:meth:`carry_disc_for`).
    _disc_cache: dict[tuple[int, tuple[float, float, float]], CarryDisc]
    #: Carry footprints by object and grasp (:meth:`carry_footprint_for`).
    _footprint_cache: dict[tuple[int, tuple[float, float, float]], Footprint]
    #: The pre-screen's numbers of the last state (:meth:`_screen_context`).
    _screen: ScreenContext | None
    #: The last carry test and its answer (:meth:`_carry_blocked`).
    _last_carry: tuple[tuple[int, bytes, bytes], str] | None

    # ----- the carry disc ------------------------------------------------------------------
    def held_disc(self) -> CarryDisc:
        """The base-motion disc of the robot carrying the held object (robot disc if none)."""
        t = self.task
        if t.held < 0:
            return replace(ROBOT_DISC, radius=self.config.robot_radius)
        return self.carry_disc_for(t.held, t.held_rel)

    def carry_disc_for(self, obj: int, held_rel: tuple[float, float, float]) -> CarryDisc:
        """The base-motion disc of the robot carrying object ``obj`` at ``held_rel``.

        ``held_rel`` is the object's body pose ``(x, y, yaw)`` in the base frame. The disc
        encloses the base square and the object's footprint (:func:`voot.envs.robot.model.carry_disc`),
        with a radius of at least ``robot_radius``; the place step plans with it.
        """
        key = (obj, held_rel)
        disc = self._disc_cache.get(key)
        if disc is None:
            box = object_footprint(self.objects[obj], *held_rel)
            disc = carry_disc(box.corners())
            disc = replace(disc, radius=max(disc.radius, self.config.robot_radius))
            if len(self._disc_cache) > 4096:
                self._disc_cache.clear()
            self._disc_cache[key] = disc
        return disc

    def carry_footprint_for(self, obj: int, held_rel: tuple[float, float, float]) -> Footprint:
        """The exact footprint of what :meth:`carry_disc_for` encloses, in its centre's frame.

        Two rectangles: the base square and the object's footprint at ``held_rel`` (the
        arm between them is not in the kitchen's carry disc either), in the frame of the
        carry disc's centre, so the disc encloses the footprint and a disc path is a
        footprint path. The place step searches it where the disc finds no path
        (``KitchenConfig.base_model="footprint"``).
        """
        cache = self._footprint_cache
        key = (obj, held_rel)
        hit = cache.get(key)
        if hit is None:
            ox, oy = self.carry_disc_for(obj, held_rel).offset
            box = object_footprint(self.objects[obj], *held_rel)
            hit = Footprint(
                (
                    Box2D(-ox, -oy, BASE_HALF, BASE_HALF, 0.0, "base"),
                    Box2D(box.cx - ox, box.cy - oy, box.half_x, box.half_y, box.yaw, box.name),
                )
            )
            if len(cache) > 4096:
                cache.clear()
            cache[key] = hit
        return hit

    def _carry_blocked(
        self, obj: int, held_rel: tuple[float, float, float], base: ArrayLike
    ) -> str:
        """Why the robot could not move carrying ``obj`` from ``base`` ('' if it could).

        The test the place step's base planner makes of its start: the carry disc at
        ``base`` against the house, the static obstacles and the other objects. The last
        answer is remembered (keyed by the numbers, bit for bit, and the ``qpos`` bytes,
        which place the objects), for the step after the pre-screen. At a pick state the
        float test (:meth:`_carry_verdict`) answers first when it is sure the disc is free.
        """
        b = np.asarray(base, dtype=np.float64)
        ctx = self._screen_context()
        if ctx.task.operator == Operator.PICK and ctx.obj == obj:
            bx, by, heading = b.tolist()
            if self._carry_verdict(ctx, held_rel, bx, by, heading) is False:
                return ""
        key = (obj, struct.pack("<3d", *held_rel) + b.tobytes(), self.data.qpos.tobytes())
        last = self._last_carry
        if last is not None and last[0] == key:
            return last[1]
        reason = self._carry_reason(obj, held_rel, base)
        self._last_carry = (key, reason)
        return reason

    def _carry_reason(self, obj: int, held_rel: tuple[float, float, float], base: ArrayLike) -> str:
        """:meth:`_carry_blocked` without its memory of the last query."""
        disc = self.carry_disc_for(obj, held_rel)
        hits = self.planner.colliding(
            disc.center(base), disc.radius, self.object_boxes(exclude=(obj,))
        )
        if not hits:
            return ""
        parts = []
        if hits[0] == "workspace":
            parts.append("leaves the house")
            hits = hits[1:]
        if hits:
            parts.append("collides with " + ", ".join(hits))
        return Failure(Reason.CARRY_FOOTPRINT, "carry footprint " + " and ".join(parts))

    #: Metres within which :meth:`_carry_verdict` defers to the exact carry test: far
    #: above the float difference (~1e-15 m) of :func:`carry_disc_floats`.
    _CARRY_MARGIN = 1e-9

    def _carry_verdict(
        self,
        ctx: ScreenContext,
        held_rel: tuple[float, float, float],
        bx: float,
        by: float,
        heading: float,
    ) -> bool | None:
        """:meth:`_carry_blocked` as a verdict from float tests; None if they cannot tell.

        The carry disc (:func:`carry_disc_floats`) at the base ``(bx, by, heading)``
        against the obstacles of ``ctx`` (:meth:`DiscProbe.verdict`).
        """
        # object_footprint's numbers
        x, y, yaw = held_rel
        c, s = math.cos(yaw), math.sin(yaw)
        fx, fy = ctx.center
        hx, hy = ctx.half
        ox, oy, radius = carry_disc_floats(x + c * fx - s * fy, y + s * fx + c * fy, hx, hy, yaw)
        radius = max(radius, self.config.robot_radius)
        c, s = math.cos(heading), math.sin(heading)
        return ctx.probe.verdict(
            bx + c * ox - s * oy, by + s * ox + c * oy, radius, self._CARRY_MARGIN
        )

    # ----- the pre-screen ------------------------------------------------------------------
    def certainly_infeasible(self, action: ArrayLike) -> bool:
        """The exact pre-screen of :meth:`ManipulationEnv.certainly_infeasible`.

        A place: its checks before the base path, as :meth:`_place_checks` runs them (on
        floats, with what depends on the state alone computed once per state: see
        :class:`ScreenContext`), then the base path itself (the planner remembers its
        last answer, so a place that passes is not planned twice). A pick: the robot in the house, the base at the tucked
        arm free of collisions and, with ``pick_requires_free_carry``, the carry disc
        free; the step tests the carry disc last (after IK and the arm's collisions, so
        that the reasons it gives stay those it gave without the rule), but for the
        verdict alone it can come first and spares the IK of a pick that cannot carry.
        Every number is computed with the step's operations, in its order.
        """
        t = self.task
        if t.done or t.steps >= self.config.horizon:
            return False  # the step raises
        a = self._plain_action(action)
        if a is None:
            return False
        return self.certainly_infeasible_values(a.tolist())

    def certainly_infeasible_values(self, values: list[float]) -> bool:
        """:meth:`certainly_infeasible` of the plain action with entries ``values``."""
        t = self.task
        if t.done or t.steps >= self.config.horizon or len(values) != self.action_dim:
            return False  # the step raises (or the action is not one)
        ctx = self._screen_context()
        if t.operator == Operator.PLACE:
            return self._place_screened(ctx, values)
        return self._pick_screened(ctx, values)

    def _screen_context(self) -> ScreenContext:
        """The pre-screen's per-state numbers (rebuilt when the task or qpos changed)."""
        t, qpos = self.task, self.data.qpos.tobytes()
        ctx = self._screen
        if ctx is not None and ctx.task is t and ctx.qpos == qpos:
            return ctx
        cfg = self.config
        obj = t.held if t.operator == Operator.PLACE else t.on_path[0]
        info = self.objects[obj]
        ox, oy = info.center.tolist()
        hx, hy = info.half.tolist()
        pose = self.object_pose(obj)
        place = t.operator == Operator.PLACE
        inverse = tuple(inverse2d(t.held_rel).tolist()) if place else (0.0, 0.0, 0.0)
        ranges = cfg.place_ranges if place else cfg.pick_ranges
        disc = self.held_disc() if place else None
        movable = tuple(self.object_boxes(exclude=(obj,)))
        ctx = self._screen = ScreenContext(
            task=t,
            qpos=qpos,
            obj=obj,
            ranges=ranges,
            center=(ox, oy),
            half=(hx, hy),
            pose=pose,
            pose_xyyaw=(float(pose[0]), float(pose[1]), float(pose[3])),
            box=self.object_box(obj),
            inverse=(inverse[0], inverse[1], inverse[2]),
            disc=disc,
            start=None if disc is None else disc.center(self.robot.base_pose(self.data)),
            movable=movable,
            probe=self.planner.disc_probe(movable),
        )
        return ctx

    def _place_screened(self, ctx: ScreenContext, a: list[float]) -> bool:
        """Does the place ``a`` fail :meth:`_place_checks` (forbidden rooms on) or its path?"""
        cfg, t = self.config, self.task
        x, y, theta = denormalize_floats(a[:3], ctx.ranges)
        ox, oy = ctx.center
        hx, hy = ctx.half
        # object_footprint's and compose2d's numbers (the same cosine and sine)
        c, s = math.cos(theta), math.sin(theta)
        cx = x + c * ox - s * oy
        cy = y + s * ox + c * oy
        if not rect_fields_inside(cx, cy, hx, hy, theta, cfg.house):
            return True
        if rect_fields_overlap(cx, cy, hx, hy, theta, cfg.forbidden):
            return True
        ix, iy, it = ctx.inverse
        bx = x + c * ix - s * iy
        by = y + s * ix + c * iy
        bt = theta + it
        if not rect_fields_inside(bx, by, BASE_HALF, BASE_HALF, bt, cfg.house):
            return True
        # the base path's goal test first (a disc in collision there has no path): a
        # few float tests that spare the MuJoCo query of most colliding placements
        disc = ctx.disc
        assert disc is not None and ctx.start is not None
        goal = disc.center(np.array([bx, by, bt]))
        gx, gy, _ = goal.tolist()
        exact = cfg.planner.footprint is not None  # a blocked disc can leave a footprint path
        if not exact and ctx.probe.blocked(gx, gy, disc.radius):
            return True
        z = float(ctx.pose[2])
        if self.collision.collides(
            self.data.qpos,
            (bx, by, bt),
            t.grasp_q,
            held=ctx.obj,
            object_poses={ctx.obj: (x, y, z, theta)},
        ):
            return True
        # the step's base path (the planner remembers it for the step that follows)
        if exact:
            footprint = self.carry_footprint_for(ctx.obj, t.held_rel)
            path = self.planner.plan_footprint(ctx.start, goal, disc.radius, footprint, ctx.movable)
            return path is None
        return self.planner.plan(ctx.start, goal, disc.radius, ctx.movable) is None

    def _pick_screened(self, ctx: ScreenContext, a: list[float]) -> bool:
        """Does the pick ``a`` fail the region, tucked-base collision or carry test?"""
        cfg = self.config
        p = denormalize_floats(a, ctx.ranges)
        box = ctx.box
        # pick_base_pose's numbers
        dist = p[3] * ARM_REACH
        ang = box.yaw + p[4]
        bx, by = box.cx + dist * math.cos(ang), box.cy + dist * math.sin(ang)
        heading = math.atan2(box.cy - by, box.cx - bx) + p[5]
        if not rect_fields_inside(bx, by, BASE_HALF, BASE_HALF, heading, cfg.house):
            return True
        if cfg.pick_requires_free_carry:  # float tests, before the MuJoCo query
            held_rel = relative_pose_floats(bx, by, heading, ctx.pose_xyyaw)
            blocked = self._carry_verdict(ctx, held_rel, bx, by, heading)
            if blocked is None:  # too close to tell on floats: the exact (remembered) test
                blocked = bool(self._carry_blocked(ctx.obj, held_rel, np.array([bx, by, heading])))
            if blocked:
                return True
        return self.collision.collides(self.data.qpos, (bx, by, heading), TUCK)
