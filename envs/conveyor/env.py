"""``voot/ConveyorPacking-v0``: pack the boxes arriving on a belt into the storage rooms.

The paper's conveyor-belt domain (Figure 1 left; reference page "Conveyor-belt
packing"). Boxes arrive on a belt east of the robot's start pose (0, 1.05, 0). West of
the start, a wide entrance opens into a small first room; its 1.62 m door leads to the
larger rooms. The first two boxes are big: carrying one, the robot's base-motion disc is
too wide for that door, so they must go into the first room, leaving space for the rest.

Picks are fixed (as in the original): each box is taken from the belt with the same
side grasp and presented in front of the robot at the start pose, and every placement's
base path starts there. Each action places the **next three boxes**: 9 numbers, three
object poses ``(x, y, theta)`` in the loading region x in [-7.4, -0.5],
y in [-7.5, 3], theta in [0, 2 pi) (normalised to [-1, 1]). The placements are checked
in sequence (each sees the ones before it): the box must lie in the loading region, the
robot's base footprint in the workspace, robot and box must collide with nothing, and a
base path must exist from the start pose to the placing pose for the robot carrying the
box. If all three are feasible the reward is ``sum_i exp(-0.1 L_i)`` over the three base
paths' lengths ``L_i``; if any is infeasible the action earns -2 and nothing moves.
``info["placement"]`` is the first box's pose ``(x, y, theta)`` and ``info["base_pose"]``
the robot's base pose placing it; ``info["placements"]`` and ``info["base_poses"]`` list
them for every box of the action (also for an infeasible action: they follow from the
action alone).
The episode terminates when every box is placed (no goal bonus in this domain:
``info["goal_bonus"]`` is 0) and is truncated after ``horizon`` steps. When fewer than
three boxes remain, the action's trailing entries are ignored.

Every info, the reset's included, has the same keys, shapes and dtypes whatever the
step (gymnasium's vector envs stack them): ``info["parameters"]`` is ``(3, 3)``, the
placements of the action's boxes in the paper's units with rows of zeros for boxes it does
not place (``info["parameters_mask"]`` says which entries are real), ``info["failed_box"]``
is -1 when no box failed, and the reset's info has the step's keys with neutral values
(no operator, feasible, nothing placed).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, ClassVar

import gymnasium as gym
import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.assets.mjcf import belt_pose
from voot.envs.conveyor.config import CONVEYOR_PRESETS, ConveyorConfig
from voot.envs.conveyor.problems import FAMILY
from voot.envs.core.env import ManipulationEnv
from voot.envs.core.metrics import Distance, place_distance
from voot.envs.core.names import Failure, Operator, Reason, reason_code
from voot.envs.core.presets import env_config
from voot.envs.core.rendering import add_marker_box
from voot.envs.core.scene import object_footprint, set_object_pose
from voot.envs.core.state import StepTiming, is_count, pose_tuple, replace
from voot.envs.core.units import denormalize, padded_parameters
from voot.envs.motion.footprint import Footprint
from voot.envs.motion.planar import Box2D
from voot.envs.motion.planner import BasePath
from voot.envs.motion.rects import rect_inside
from voot.envs.robot.grasp import side_grasp
from voot.envs.robot.model import (
    BASE_HALF,
    ROBOT_RADIUS,
    CarryDisc,
    base_footprint,
    carry_disc,
    compose2d,
    compose_inverse2d,
    compose_inverse_tuple,
)
from voot.envs.robot.rotations import rot_z
from voot.optim.base import Bounds

FloatArray = NDArray[np.float64]

#: Boxes placed by one action.
OBJECTS_PER_ACTION = 3
#: The shape of a step info's ``parameters``: a pose per box of a full action.
_PARAMETERS_SHAPE = (OBJECTS_PER_ACTION, 3)


@dataclass(frozen=True)
class ConveyorTask:
    """The task's progress (immutable; part of every snapshot).

    Attributes:
        steps: Steps taken in this episode (feasible or not).
        placed: Boxes placed so far (they are the first ``placed`` boxes).
        done: Every box is placed (terminated).
    """

    steps: int
    placed: int
    done: bool


@dataclass(frozen=True)
class FixedPick:
    """The fixed grasp of one box: its pose in the base frame, the arm, the motion disc."""

    rel: tuple[float, float, float]
    arm_q: tuple[float, ...]
    disc: CarryDisc


class ConveyorPackingEnv(ManipulationEnv[ConveyorTask]):
    """The conveyor-belt packing domain as a gymnasium environment (module docstring).

    Args:
        config: Settings; defaults to the ``preset``'s :class:`ConveyorConfig`.
        render_mode: None or ``"rgb_array"``.
        render_camera: ``"perspective"`` or ``"top_down"``.
        render_size: ``(width, height)`` of rendered images.
        preset: The domain version when ``config`` is None: ``"v0"`` or ``"v1"``
            (:data:`CONVEYOR_PRESETS`; ``voot/ConveyorPacking-v1`` passes ``"v1"``).
        **options: :class:`ConveyorConfig` fields overriding the config's.

    Raises:
        RuntimeError: If the fixed grasp of some box is infeasible (a broken scene).
    """

    family: ClassVar[str] = FAMILY

    def __init__(
        self,
        config: ConveyorConfig | None = None,
        render_mode: str | None = None,
        render_camera: str = "perspective",
        render_size: tuple[int, int] = (640, 480),
        preset: str = "v0",
        **options: Any,
    ) -> None:
        self.config = env_config(ConveyorConfig, CONVEYOR_PRESETS, config, preset, options)
        cfg = self.config
        super().__init__(
            self._scene_model(),
            cfg.workspace,
            cfg.ik,
            cfg.planner,
            render_mode,
            render_camera,
            render_size,
        )
        if len(self.objects) < cfg.n_objects:  # pragma: no cover - scene drift
            raise ValueError(
                f"the scene has {len(self.objects)} boxes, fewer than n_objects={cfg.n_objects}"
            )
        self.n = cfg.n_objects
        self._reset_physics()
        self.picks = tuple(self._fixed_pick(i) for i in range(self.n))
        self.action_space = gym.spaces.Box(
            -1.0, 1.0, shape=(3 * OBJECTS_PER_ACTION,), dtype=np.float64
        )
        self.observation_space = gym.spaces.Box(
            -50.0, 50.0, shape=(4 + 5 * len(self.objects) + 2,), dtype=np.float64
        )

    # ----- fixed picks ---------------------------------------------------------------------
    def _fixed_pick(self, i: int) -> FixedPick:
        """Grasp box ``i`` presented on the floor in front of the robot at ``start``."""
        cfg = self.config
        obj = self.objects[i]
        depth = float(obj.half[0])
        rel = (
            BASE_HALF + cfg.present_gap + depth - float(obj.center[0]),
            -float(obj.center[1]),
            0.0,
        )
        pose = compose2d(cfg.start, rel)
        grasp = side_grasp(
            obj,
            (pose[0], pose[1], 0.0, pose[2]),
            cfg.start[2],
            cfg.grasp_angle,
            cfg.height_fraction,
            cfg.depth_fraction,
        )
        rb = rot_z(cfg.start[2])
        ik = self.ik.solve(
            rb.T @ (grasp.position - np.array([cfg.start[0], cfg.start[1], 0.0])),
            rb.T @ grasp.rotation,
        )
        if not ik.success or ik.q is None:
            raise RuntimeError(
                f"the fixed grasp of {obj.name} is out of the arm's reach ({ik.reason})"
            )
        report = self.collision.check(
            self.data.qpos,
            cfg.start,
            ik.q,
            held=i,
            object_poses={i: (pose[0], pose[1], 0.0, pose[2])},
        )
        if not report.free:
            raise RuntimeError(f"the fixed grasp of {obj.name} collides: {', '.join(report.hits)}")
        box = object_footprint(obj, *rel)
        disc = carry_disc(box.corners())
        disc = replace(disc, radius=max(disc.radius, ROBOT_RADIUS))
        # the kitchen's pick_requires_free_carry rule, checked once: the robot must be able
        # to move with its load from the start. Placements cannot block it later: the
        # discs (x <= 0.45 + 0.87 m around the start) stay east of the loading region.
        hits = self.planner.colliding(disc.center(cfg.start), disc.radius, ())
        if hits:
            raise RuntimeError(
                f"the carry footprint of {obj.name} at the start collides with {', '.join(hits)}"
            )
        return FixedPick(rel, tuple(float(v) for v in ik.q), disc)

    def footprint(self, i: int) -> Footprint:
        """The exact footprint carrying box ``i`` (frame of its carry disc's centre).

        Three rectangles: the base square, the box at its fixed grasp, and the bounding
        rectangle (in the base frame) of the arm's collision geoms at the fixed grasp's
        joint values, read from MuJoCo. Used by the base planner's exact-footprint option
        (:attr:`BasePlannerConfig.footprint`); the disc of the pick encloses it.
        """
        cache = self.__dict__.setdefault("_footprints", {})
        hit = cache.get(i)
        if hit is None:
            hit = _carry_footprint(self, self.picks[i])
            cache[i] = hit
        return hit  # type: ignore[no-any-return]

    def _scene_model(self) -> str | mujoco.MjModel:
        """The scene to load: ``voot.models``' fixed ``conveyor.xml`` (the paper's instance).

        A subclass with a generated layout returns its compiled model instead; it is
        called once, in ``__init__``, after :attr:`config` is set. ``rooms="authors"``
        gives the authors' walls (:mod:`voot.envs.conveyor.authors_rooms`).
        """
        if self.config.rooms == "authors":
            from voot.envs.conveyor.authors_rooms import authors_rooms_model

            return authors_rooms_model()
        return "conveyor"

    # ----- ManipulationEnv hooks -------------------------------------------------------------
    def _queue_pose(self, i: int, placed: int) -> tuple[float, float, float, float]:
        """Where box ``i`` waits on the belt when ``placed`` boxes are gone."""
        k = i - placed if i < self.n else i
        return belt_pose(k)

    def _reset_physics(self) -> None:
        mujoco.mj_resetData(self.model, self.data)
        self._set_robot(self.config.start)

    def _initial_task(self) -> ConveyorTask:
        return ConveyorTask(steps=0, placed=0, done=False)

    def _task_error(self, task: ConveyorTask) -> str | None:
        """What no episode of this conveyor reaches in ``task`` (see ``set_state``), or None:
        the counts within their bounds, and done exactly when every box is placed."""
        if not is_count(task.steps, 0, self.config.horizon):
            horizon = self.config.horizon
            return f"steps must be an int in 0..{horizon} (the horizon), got {task.steps!r}"
        if not is_count(task.placed, 0, self.n):
            return f"placed must be an int in 0..{self.n} (the boxes), got {task.placed!r}"
        if type(task.done) is not bool or task.done != (task.placed == self.n):
            full = task.placed == self.n
            return f"done must be {full} when placed is {task.placed}, got {task.done!r}"
        return None

    def _observation(self) -> FloatArray:
        t = self.task
        base = self.robot.base_pose(self.data)
        parts = [base[0], base[1], math.cos(base[2]), math.sin(base[2])]
        for i in range(len(self.objects)):
            x, y, _, yaw = self.object_pose(i)
            parts += [x, y, math.cos(yaw), math.sin(yaw), float(i < t.placed)]
        parts += [t.placed / self.n, t.steps / self.config.horizon]
        return np.array(parts, dtype=np.float64)

    def _info_reset(self) -> dict[str, Any]:
        """A step's info keys with no action behind them (the module docstring)."""
        info = _placements_info("", -1, (), ())
        info["operator"] = None
        info["action_clipped"] = False
        info.update(_paths_info([], [], [], False))
        info.update(padded_parameters(np.empty((0, 3)), _PARAMETERS_SHAPE))
        info.update(self._progress_info())
        return info

    def _progress_info(self) -> dict[str, Any]:
        """The info keys on where the episode stands: the next boxes and the counts."""
        t = self.task
        return {
            "next_operator": Operator.PLACE,
            "next_objects": self._next_names(),
            "objects_left": self.n - t.placed,
            "objects_placed": t.placed,
            "goal_bonus": 0.0,
        }

    @property
    def objects_left(self) -> int:
        """Boxes still to place."""
        return self.n - self.task.placed

    def _next_names(self) -> list[str]:
        p = self.task.placed
        return [self.objects[i].name for i in range(p, min(p + OBJECTS_PER_ACTION, self.n))]

    def action_bounds(self) -> Bounds:
        """The 9-D action box in normalised units."""
        return Bounds.cube(-1.0, 1.0, 3 * OBJECTS_PER_ACTION)

    def current_operator(self) -> Operator:
        """Always a place (the boxes come to the robot)."""
        return Operator.PLACE

    def operator_ranges(self, operator: Operator) -> tuple[tuple[float, float], ...]:
        """The placement ranges (x, y, theta) of each of the action's boxes."""
        return tuple(self.config.place_ranges) * OBJECTS_PER_ACTION

    def operator_distance(self, operator: Operator) -> Distance:
        """The authors' place distance over the action's placements."""
        return place_distance(OBJECTS_PER_ACTION)

    def node_label(self, operator: Operator) -> str:
        """``"place (3 boxes)"``: an action places up to three boxes."""
        return f"{operator} ({OBJECTS_PER_ACTION} boxes)"

    def solution_actions(self) -> list[FloatArray]:
        """A packing of every box in this env's rooms (:mod:`voot.envs.conveyor.scripted`):
        the hand-chosen one in voot's, the searched one in the authors' (which needs
        ``base_model="footprint"``)."""
        from voot.envs.conveyor.scripted import conveyor_actions

        return conveyor_actions(self)

    # ----- stepping ------------------------------------------------------------------------
    def place_base_pose(self, i: int, obj_pose: ArrayLike) -> FloatArray:
        """The base pose placing box ``i`` at ``(x, y, theta)`` with its fixed grasp."""
        return compose_inverse2d(obj_pose, self.picks[i].rel)

    def transition(self, action: ArrayLike) -> tuple[float, bool, bool, dict[str, Any]]:
        """One step without its observation (see :meth:`ManipulationEnv.transition`)."""
        a, clipped = self._validate_action(action)
        cfg, t = self.config, self.task
        if t.done or t.steps >= cfg.horizon:
            raise ValueError("the episode has ended (terminated or truncated); call reset()")
        start_time = time.perf_counter()
        m = min(OBJECTS_PER_ACTION, self.n - t.placed)
        params = denormalize(a[: 3 * m], cfg.place_ranges * m).reshape(m, 3)
        names = [self.objects[t.placed + k].name for k in range(m)]
        placements = tuple((x, y, th) for x, y, th in params.tolist())
        bases = tuple(
            compose_inverse_tuple(p, self.picks[t.placed + k].rel) for k, p in enumerate(placements)
        )
        moved: dict[int, tuple[float, float, float, float]] = {}
        lengths: list[float] = []
        paths: list[FloatArray] = []
        col_time = plan_time = 0.0
        reason: str = ""
        failed = -1
        for k in range(m):
            i = t.placed + k
            reason, dt_col, dt_plan = self._check_place(i, params[k], moved, lengths, paths)
            col_time += dt_col
            plan_time += dt_plan
            if reason:
                reason, failed = _of_box(reason, k, m, names[k]), k
                break
        self.last_timing = StepTiming(
            collision=col_time, planning=plan_time, total=time.perf_counter() - start_time
        )
        if reason:
            reward = cfg.infeasible_reward
            self.task = replace(t, steps=t.steps + 1)
            feasible = False
        else:
            for i, pose in moved.items():
                set_object_pose(self.data, self.objects[i], pose)
            placed = t.placed + m
            for i in range(placed, len(self.objects)):
                set_object_pose(self.data, self.objects[i], self._queue_pose(i, placed))
            reward = float(sum(math.exp(-cfg.length_scale * length) for length in lengths))
            self.task = replace(t, steps=t.steps + 1, placed=placed, done=placed == self.n)
            feasible = True
        t = self.task
        terminated = t.done
        truncated = (not terminated) and t.steps >= cfg.horizon
        info = _placements_info(reason, failed, bases, placements)
        info.update(_paths_info(names, lengths, paths, feasible))
        info.update(padded_parameters(params, _PARAMETERS_SHAPE))
        info["action_clipped"] = clipped
        info.update(self._progress_info())
        return float(reward), terminated, truncated, info

    def _check_place(
        self,
        i: int,
        xyt: FloatArray,
        moved: dict[int, tuple[float, float, float, float]],
        lengths: list[float],
        paths: list[FloatArray],
    ) -> tuple[str, float, float]:
        """Check placing box ``i`` at ``xyt`` after the placements in ``moved``.

        On success, records the placement in ``moved`` and its path in ``lengths`` and
        ``paths``. Returns why it is infeasible (``""`` if feasible) and the seconds spent
        in collision checks and base planning.
        """
        cfg = self.config
        plan_time = 0.0
        x, y, theta = (float(v) for v in xyt)
        reason, col_time, base = self._place_kinematics(i, xyt, moved)
        if reason:
            return reason, col_time, plan_time
        assert base is not None  # passed the region checks
        if cfg.big_box_ban and i < cfg.big_boxes:
            rxmin, rxmax, rymin, rymax = cfg.first_room
            if not (rxmin <= x <= rxmax and rymin <= y <= rymax):
                text = "forbidden room: a big box outside the first room"
                return Failure(Reason.FORBIDDEN_ROOM, text), col_time, plan_time
        pick = self.picks[i]
        t0 = time.perf_counter()
        movable = [self.object_box(j) for j in range(self.task.placed)] + [
            object_footprint(self.objects[j], p[0], p[1], p[3]) for j, p in moved.items()
        ]
        disc = pick.disc
        if cfg.planner.footprint is None:
            path = self.planner.plan(
                disc.center(cfg.start), disc.center(base), disc.radius, movable
            )
        else:
            path = self.planner.plan_footprint(
                disc.center(cfg.start), disc.center(base), disc.radius, self.footprint(i), movable
            )
        plan_time = time.perf_counter() - t0
        if path is None:
            return Failure(Reason.NO_BASE_PATH, "no base path"), col_time, plan_time
        base_path = BasePath._from_owned(disc.base(path.waypoints), cfg.planner.rotation_weight)
        moved[i] = (x, y, 0.0, theta)
        lengths.append(float(base_path.length))
        paths.append(base_path.waypoints)
        return "", col_time, plan_time

    def _place_kinematics(
        self,
        i: int,
        xyt: FloatArray,
        moved: dict[int, tuple[float, float, float, float]],
    ) -> tuple[str, float, FloatArray | None]:
        """Region and collision checks of placing box ``i`` at ``xyt`` after ``moved``.

        Returns why it fails (``""`` if it passes), the seconds spent in collision checks
        and the base pose placing the box (None if the box left the region first).
        Changes nothing.
        """
        cfg = self.config
        x, y, theta = (float(v) for v in xyt)
        box = object_footprint(self.objects[i], x, y, theta)
        if not rect_inside(box, cfg.loading_region):
            text = "outside region: the box leaves the loading region"
            return Failure(Reason.OUTSIDE_REGION, text), 0.0, None
        base = self.place_base_pose(i, (x, y, theta))
        if not rect_inside(base_footprint(base), cfg.workspace):
            text = "outside region: the robot leaves the workspace"
            return Failure(Reason.OUTSIDE_REGION, text), 0.0, base
        t0 = time.perf_counter()
        poses = dict(moved)
        poses[i] = (x, y, 0.0, theta)
        report = self.collision.check(
            self.data.qpos, base, self.picks[i].arm_q, held=i, object_poses=poses
        )
        col_time = time.perf_counter() - t0
        if not report.free:
            return Failure(Reason.COLLISION, "collision: " + ", ".join(report.hits)), col_time, base
        return "", col_time, base

    def precheck(self, action: ArrayLike) -> tuple[bool, dict[str, Any]]:
        """The cheap kinematic check of ``action`` in the current state (changes nothing).

        Stage 1 of the authors' two-stage feasibility (:mod:`voot.tree.problem`): the
        placements' region and collision checks in sequence, each seeing the ones before
        it; the first failure rejects the whole action. The base paths are left to
        :meth:`step`. Returns whether it passes and an info with ``feasible``,
        ``reason``, ``placement(s)`` and ``base_pose(s)``.
        """
        a, _ = self._validate_action(action)
        cfg, t = self.config, self.task
        if t.done or t.steps >= cfg.horizon:
            raise ValueError("the episode has ended (terminated or truncated); call reset()")
        m = min(OBJECTS_PER_ACTION, self.n - t.placed)
        params = [denormalize(a[3 * k : 3 * k + 3], cfg.place_ranges) for k in range(m)]
        placements = tuple(pose_tuple(p) for p in params)
        bases = tuple(pose_tuple(self.place_base_pose(t.placed + k, params[k])) for k in range(m))
        moved: dict[int, tuple[float, float, float, float]] = {}
        reason: str = ""
        failed = -1
        for k in range(m):
            i = t.placed + k
            reason, _, _ = self._place_kinematics(i, params[k], moved)
            if reason:
                reason, failed = _of_box(reason, k, m, self.objects[i].name), k
                break
            x, y, theta = placements[k]
            moved[i] = (x, y, 0.0, theta)
        return not reason, _placements_info(reason, failed, bases, placements)

    # ----- rendering -----------------------------------------------------------------------
    def _decorate(self, scene: mujoco.MjvScene) -> None:
        if not self.config.render_overlays:
            return
        xmin, xmax, ymin, ymax = self.config.loading_region
        add_marker_box(
            scene,
            (0.5 * (xmin + xmax), 0.5 * (ymin + ymax), 0.006),
            (0.5 * (xmax - xmin), 0.5 * (ymax - ymin), 0.002),
            0.0,
            (1.0, 0.85, 0.1, 0.10),
        )


def _carry_footprint(env: ConveyorPackingEnv, pick: FixedPick) -> Footprint:
    """:meth:`ConveyorPackingEnv.footprint` of ``pick`` (computed once per box)."""
    model = env.model
    data = mujoco.MjData(model)
    env.robot.set_base(data, (0.0, 0.0, 0.0))
    env.robot.set_arm(data, pick.arm_q)
    mujoco.mj_kinematics(model, data)
    base_body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "base")
    lo = np.array([np.inf, np.inf])
    hi = -lo
    for g in env.robot.geoms:
        if model.geom_bodyid[g] == base_body:
            continue  # the base's own geoms: inside the base square
        if model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0:
            continue  # visual only
        centre, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        signs = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)])
        corners = data.geom_xpos[g] + (centre + signs * half) @ data.geom_xmat[g].reshape(3, 3).T
        lo = np.minimum(lo, corners[:, :2].min(axis=0))
        hi = np.maximum(hi, corners[:, :2].max(axis=0))
    ox, oy = pick.disc.offset
    obj = env.objects[env.picks.index(pick)]
    held = object_footprint(obj, *pick.rel)
    parts = [
        Box2D(-ox, -oy, BASE_HALF, BASE_HALF, 0.0, "base"),
        Box2D(held.cx - ox, held.cy - oy, held.half_x, held.half_y, held.yaw, obj.name),
    ]
    if np.all(np.isfinite(lo)):
        c = 0.5 * (lo + hi)
        h = 0.5 * (hi - lo)
        parts.append(
            Box2D(float(c[0]) - ox, float(c[1]) - oy, float(h[0]), float(h[1]), 0.0, "arm")
        )
    return Footprint(tuple(parts))


def _of_box(reason: str, k: int, m: int, name: str) -> Failure:
    """The failure of box ``k`` (of the action's ``m``, named ``name``): its text names it."""
    assert isinstance(reason, Failure)
    return reason.prefixed(f"box {k + 1}/{m} ({name}): ")


def _paths_info(
    names: list[str], lengths: list[float], paths: list[FloatArray], feasible: bool
) -> dict[str, Any]:
    """The info keys of an action's boxes and base paths (none unless it is feasible)."""
    return {
        "objects": names,
        "base_path_length": float(sum(lengths)) if feasible else 0.0,
        "base_path_lengths": lengths if feasible else [],
        "base_paths": paths if feasible else [],
    }


def _placements_info(
    reason: str,
    failed: int,
    bases: tuple[tuple[float, float, float], ...],
    placements: tuple[tuple[float, float, float], ...],
) -> dict[str, Any]:
    """The info of an action's placements, the keys a step's info and a pre-check's share
    (the step adds its paths, counts and the next boxes): whether it passes, why not
    (``reason``, ``reason_code``, and ``failed_box``, the index in the action of the first
    box that failed, -1 if none), every box's placement and base pose (None for the
    first when there is none)."""
    return {
        "operator": Operator.PLACE,
        "feasible": not reason,
        "reason": str(reason),
        "reason_code": reason_code(reason),
        "failed_box": failed,
        "placement": placements[0] if placements else None,
        "base_pose": bases[0] if bases else None,
        "placements": placements,
        "base_poses": bases,
    }
