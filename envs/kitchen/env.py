"""``voot/KitchenClearing-v0``: clear the obstacles from the robot's path to the sink.

The paper's object-clearing domain (Figure 1 right; reference page "Object clearing").
The robot stands at ``start`` = (-1.5, -1.5, pi/2); a fixed base path leads to the sink
pose ``goal`` = (0, 2.5, pi/2). The obstacles are the objects whose footprint meets the
swept volume of the robot's disc along that path (7 at the start: boxes and chairs).
The robot clears them one at a time, in a fixed order (the first object on the path in
the handling order, which sorts the initial obstacles by their position along the path),
alternating pick and place actions:

* **pick** (6-D): grasp angle in [45, 180] deg, grasp height fraction in [0.5, 1], grasp
  depth fraction in [0.1, 0.9], base distance in [0.4, 0.9] x arm reach (0.92 m), base
  angle around the object (object frame) in [0, 2 pi), heading offset from facing the
  object in [-30, 30] deg. Feasible iff the base footprint is inside the house, the arm's
  IK reaches the grasp (:mod:`voot.envs.robot.arm_ik`), the robot at the grasp
  collides with nothing (the gripper may touch the grasped object) and, with
  ``pick_requires_free_carry`` (default), the robot can still move with its load: the
  carry disc the place step plans with is free at the pick pose (otherwise every
  following place fails with "no base path" and the search is in a dead end).
* **place** (3-D): the object's new pose (x, y, theta) in the house box
  x in [-2, 6], y in [-4, 4], theta in [0, 2 pi); the base pose follows from the grasp.
  Feasible iff the object is inside the house and not in the forbidden rooms
  (x >= 2.8), the robot's base footprint is inside the house, robot and object collide
  with nothing, and a base path exists from the pick pose to the new base pose for the
  robot carrying the object (a disc enclosing robot and load, :mod:`voot.envs.robot.model`;
  ``L`` below is the length of the base's path).

Rewards (reference page): pick +1 if the previous place reduced the number of
obstacles on the path, else 0; place ``min(1/L, 2)`` if it reduced that number, else
``max(-L, -2)``, with ``L`` the base path's length; an infeasible action -2 (the state
does not change). When nothing is left on the path the episode terminates and a goal
bonus of +2 is reported in ``info["goal_bonus"]`` (not added to the reward). Episodes
are truncated after ``horizon`` steps.

Besides the keys every step's info has (``feasible``, ``reason``, ``next_operator`` ...;
see :mod:`voot.envs.core.env`), ``info["base_pose"]`` is the base pose ``(x, y, theta)``
of the action (a pick: the sampled base pose; a place: the base pose at the placement,
which follows from the grasp) and ``info["placement"]`` the placed object's pose
``(x, y, theta)`` (None for a pick), both also for infeasible actions.

The action space is one ``Box(-1, 1, (6,))`` in normalised units for both operators (a
fixed space keeps gymnasium's checkers and vectorised wrappers happy); at a place step
only the first three entries are read and the rest is ignored. ``info["next_operator"]``
and :meth:`KitchenClearingEnv.action_bounds` (6-D at a pick, 3-D at a place) tell which.

Every info, the reset's included, has the same keys, shapes and dtypes whatever the node
(gymnasium's vector envs stack them): ``info["parameters"]`` is the action's parameters
in the paper's units padded with zeros to the pick's 6 (a place fills the first 3;
``info["parameters_mask"]`` says which), ``info["base_path"]`` a tuple of ``(x, y,
theta)`` waypoints or None, and the reset's info has the step's keys with neutral values
(no operator, no object, feasible, no parameters).

The env is built in layers, one concept a module: the task's rules and versions
(:mod:`voot.envs.kitchen.config`), its record, reachable records and rewards
(:mod:`voot.envs.kitchen.task`), the fixed path and the obstacles on it
(:mod:`voot.envs.kitchen.path`), the actions decoded into poses
(:mod:`voot.envs.kitchen.poses`), the carry disc and the exact pre-screen
(:mod:`voot.envs.kitchen.screen`) and the pick and place checks
(:mod:`voot.envs.kitchen.checks`). This module holds the environment itself: its
construction, observation and step (the transition, rewards applied, the base paths
planned) and its rendering overlays.
"""

from __future__ import annotations

import itertools
import math
import time
from typing import Any, ClassVar

import gymnasium as gym
import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.core.metrics import Distance, pick_distance, place_distance
from voot.envs.core.names import Failure, Operator, Reason, reason_code
from voot.envs.core.presets import env_config
from voot.envs.core.rendering import add_marker_box, add_marker_segment
from voot.envs.core.scene import set_object_pose
from voot.envs.core.state import StepTiming, path_tuple, pose_tuple, replace
from voot.envs.core.units import denormalize, padded_parameters
from voot.envs.kitchen.checks import KitchenChecks
from voot.envs.kitchen.config import KITCHEN_PRESETS, KitchenConfig, kitchen_config
from voot.envs.kitchen.path import ClearingPath
from voot.envs.kitchen.problems import FAMILY
from voot.envs.kitchen.task import KitchenTask, pick_reward, place_reward, task_error
from voot.envs.motion.planner import BasePath
from voot.optim.base import Bounds

__all__ = ["KITCHEN_PRESETS", "KitchenClearingEnv", "KitchenConfig", "kitchen_config"]

FloatArray = NDArray[np.float64]
#: The shape of a step info's ``parameters``: the pick's 6 (a place's 3 padded).
_PARAMETERS_SHAPE = (6,)


class KitchenClearingEnv(KitchenChecks):
    """The object-clearing domain as a gymnasium environment (see the module docstring).

    Args:
        config: Settings; defaults to the ``preset``'s :class:`KitchenConfig`.
        render_mode: None or ``"rgb_array"``.
        render_camera: ``"perspective"`` or ``"top_down"``.
        render_size: ``(width, height)`` of rendered images.
        preset: The domain version when ``config`` is None: ``"v0"`` or ``"v1"``
            (:data:`KITCHEN_PRESETS`; ``voot/KitchenClearing-v1`` passes ``"v1"``).
        **options: :class:`KitchenConfig` fields overriding the config's (so that
            ``gym.make("voot/KitchenClearing-v1", pick_requires_free_carry=True)`` works).
    """

    family: ClassVar[str] = FAMILY

    def __init__(
        self,
        config: KitchenConfig | None = None,
        render_mode: str | None = None,
        render_camera: str = "perspective",
        render_size: tuple[int, int] = (640, 480),
        preset: str = "v0",
        **options: Any,
    ) -> None:
        self.config = env_config(KitchenConfig, KITCHEN_PRESETS, config, preset, options)
        cfg = self.config
        # the fixed path and handling order are needed by _initial_task (called by super)
        self._clearing: ClearingPath | None = None
        self._disc_cache = {}
        self._footprint_cache = {}
        self._screen = None
        self._last_carry = None
        super().__init__(
            self._scene_model(),
            cfg.house,
            cfg.ik,
            cfg.planner,
            render_mode,
            render_camera,
            render_size,
        )
        self._reset_physics()
        path = self.planner.plan(cfg.start, cfg.goal, cfg.robot_radius, ())
        if path is None:
            raise ValueError(
                f"no base path from start {cfg.start} to goal {cfg.goal} for radius {cfg.robot_radius}"
            )
        names = [o.name for o in self.objects]
        self._clearing = ClearingPath(path, cfg.robot_radius, names, self.object_boxes())
        self.task = self._initial_task()
        if not self.task.on_path:
            raise ValueError("no object is on the path at the start: nothing to clear")
        self.initial_obstacles = len(self.task.on_path)
        n = len(self.objects)
        self.action_space = gym.spaces.Box(-1.0, 1.0, shape=(6,), dtype=np.float64)
        self.observation_space = gym.spaces.Box(
            -50.0, 50.0, shape=(4 + 6 * n + 3,), dtype=np.float64
        )

    # ----- the fixed path ------------------------------------------------------------------
    @property
    def path(self) -> BasePath:
        """The fixed base path from ``start`` to ``goal`` (static obstacles only)."""
        assert self._clearing is not None
        return self._clearing.path

    def _on_path(self) -> tuple[int, ...]:
        """Objects on the path now, in handling order (:meth:`ClearingPath.on_path`)."""
        if self._clearing is None:
            return ()
        return self._clearing.on_path(self.object_boxes())

    def _scene_model(self) -> str | mujoco.MjModel:
        """The scene to load: ``voot.models``' fixed ``kitchen.xml`` (the paper's instance).

        A subclass with a generated layout returns its compiled model instead; it is
        called once, in ``__init__``, after :attr:`config` is set.
        """
        return "kitchen"

    # ----- ManipulationEnv hooks -------------------------------------------------------------
    def _reset_physics(self) -> None:
        mujoco.mj_resetData(self.model, self.data)
        self._set_robot(self.config.start)

    def _initial_task(self) -> KitchenTask:
        return KitchenTask(
            steps=0,
            operator=Operator.PICK,
            held=-1,
            held_rel=(0.0, 0.0, 0.0),
            grasp_q=(),
            on_path=self._on_path(),
            last_place_cleared=False,
            done=False,
        )

    def _observation(self) -> FloatArray:
        t = self.task
        base = self.robot.base_pose(self.data)
        parts = [base[0], base[1], math.cos(base[2]), math.sin(base[2])]
        on = set(t.on_path)
        for i in range(len(self.objects)):
            x, y, _, yaw = self.object_pose(i)
            parts += [x, y, math.cos(yaw), math.sin(yaw), float(i in on), float(i == t.held)]
        parts += [
            float(t.operator == Operator.PLACE),
            len(t.on_path) / self.initial_obstacles,
            t.steps / self.config.horizon,
        ]
        return np.array(parts, dtype=np.float64)

    def _info_reset(self) -> dict[str, Any]:
        """A step's info keys with no action behind them (the module docstring)."""
        info: dict[str, Any] = {
            "operator": None,
            "object": "",
            "feasible": True,
            "reason": "",
            "reason_code": reason_code(""),
            "base_path_length": 0.0,
            "base_path": None,
            "base_pose": None,
            "placement": None,
            "action_clipped": False,
        }
        info.update(padded_parameters(np.empty(0), _PARAMETERS_SHAPE))
        info.update(self._progress_info(terminated=False))
        return info

    def _progress_info(self, terminated: bool) -> dict[str, Any]:
        """The info keys on where the episode stands: the next operator and object, the
        obstacles left, the goal bonus (earned when it terminates)."""
        t = self.task
        return {
            "next_operator": t.operator,
            "next_object": self.next_object_name,
            "objects_left": len(t.on_path),
            "goal_bonus": self.config.goal_bonus if terminated else 0.0,
        }

    def _task_error(self, task: KitchenTask) -> str | None:
        """What no episode of this kitchen reaches in ``task`` (see ``set_state``), or None.

        :func:`voot.envs.kitchen.task.task_error` with this kitchen's objects, horizon and
        handling order.
        """
        clearing = self._clearing
        assert clearing is not None
        n = len(self.objects)
        return task_error(task, n, self.config.horizon, clearing.order, clearing.rank)

    @property
    def objects_left(self) -> int:
        """Obstacles still on the path."""
        return len(self.task.on_path)

    @property
    def next_object_name(self) -> str:
        """Name of the object the next action handles ('' when done)."""
        t = self.task
        if t.operator == Operator.PLACE:
            return self.objects[t.held].name
        return self.objects[t.on_path[0]].name if t.on_path else ""

    def current_operator(self) -> Operator:
        """The operator of the current node (the task record's)."""
        return self.task.operator

    def operator_ranges(self, operator: Operator) -> tuple[tuple[float, float], ...]:
        """The pick's 6 parameter ranges, or the place's 3 (x, y, theta)."""
        cfg = self.config
        return cfg.pick_ranges if operator == Operator.PICK else cfg.place_ranges

    def operator_distance(self, operator: Operator) -> Distance:
        """The authors' pick distance (grasp, base with the planner's rotation weight) or
        place distance (:mod:`voot.envs.core.metrics`)."""
        if operator == Operator.PICK:
            return pick_distance(self.config.planner.rotation_weight)
        return place_distance()

    def solution_actions(self) -> list[FloatArray]:
        """The hand-chosen solution of the paper's kitchen (:mod:`voot.envs.kitchen.scripted`)."""
        from voot.envs.kitchen.scripted import kitchen_actions

        return kitchen_actions(self)

    def action_bounds(self) -> Bounds:
        """The current operator's action box in normalised units (6-D pick, 3-D place)."""
        dim = 6 if self.task.operator == Operator.PICK else 3
        return Bounds.cube(-1.0, 1.0, dim)

    # ----- stepping ------------------------------------------------------------------------
    def transition(self, action: ArrayLike) -> tuple[float, bool, bool, dict[str, Any]]:
        """One step without its observation (see :meth:`ManipulationEnv.transition`)."""
        a, clipped = self._validate_action(action)
        t = self.task
        if t.done or t.steps >= self.config.horizon:
            raise ValueError("the episode has ended (terminated or truncated); call reset()")
        start = time.perf_counter()
        if t.operator == Operator.PICK:
            params = denormalize(a, self.config.pick_ranges)
            reward, info = self._pick(params)
        else:
            params = denormalize(a[:3], self.config.place_ranges)
            reward, info = self._place(params)
        timing = self.last_timing
        self.last_timing = replace(timing, total=time.perf_counter() - start)
        t = self.task
        terminated = t.done
        truncated = (not terminated) and t.steps >= self.config.horizon
        info.update(padded_parameters(params, _PARAMETERS_SHAPE))
        info["action_clipped"] = clipped
        info.update(self._progress_info(terminated))
        return float(reward), terminated, truncated, info

    def _infeasible(
        self,
        operator: Operator,
        obj: int,
        reason: str,
        base: ArrayLike,
        placement: ArrayLike | None = None,
    ) -> tuple[float, dict[str, Any]]:
        """The reward and info of an infeasible pick or place (``reason``: a check's
        :class:`~voot.envs.core.names.Failure`); only the step count moves on."""
        self.task = replace(self.task, steps=self.task.steps + 1)
        return self.config.infeasible_reward, self._action_info(
            operator, obj, reason, base, None if placement is None else pose_tuple(placement)
        )

    def _action_info(
        self,
        operator: Operator,
        obj: int,
        reason: str,
        base: ArrayLike,
        placement: tuple[float, float, float] | None,
        path_length: float = 0.0,
        path: Any = None,
    ) -> dict[str, Any]:
        """The step info of a pick or place (every step's info is built here; the step
        adds what follows it: the parameters, the next operator and the counts)."""
        return {
            "operator": operator,
            "object": self.objects[obj].name,
            "feasible": not reason,
            "reason": str(reason),
            "reason_code": reason_code(reason),
            "base_path_length": path_length,
            "base_path": path_tuple(path),
            "base_pose": pose_tuple(base),
            "placement": placement,
        }

    def _pick(self, params: FloatArray) -> tuple[float, dict[str, Any]]:
        cfg, t = self.config, self.task
        obj = t.on_path[0]
        reason, base, q, held_rel = self._pick_kinematics(params)
        if reason:
            return self._infeasible(Operator.PICK, obj, reason, base)
        assert q is not None
        path_length, path_points = 0.0, None
        if cfg.pick_base_path:
            t0 = time.perf_counter()
            here = self.robot.base_pose(self.data)
            # the disc is coarser than the robot: the object just placed can overlap it
            # where the robot stands, so objects touching the start are left out too
            radius = cfg.pick_path_radius
            touching = self.planner.colliding(here, radius, self.object_boxes())
            skip = {obj} | {self.object_index[n] for n in touching if n in self.object_index}
            path = self.planner.plan(here, base, radius, self.object_boxes(exclude=tuple(skip)))
            timing = self.last_timing
            self.last_timing = replace(timing, planning=time.perf_counter() - t0)
            if path is None:
                failure = Failure(Reason.NO_BASE_PATH_TO_PICK, "no base path to the pick")
                return self._infeasible(Operator.PICK, obj, failure, base)
            path_length, path_points = float(path.length), path.waypoints
        self._set_robot(base, q)
        reward = pick_reward(cfg, t.last_place_cleared)
        self.task = replace(
            t,
            steps=t.steps + 1,
            operator=Operator.PLACE,
            held=obj,
            held_rel=held_rel,
            grasp_q=tuple(float(v) for v in q),
        )
        return reward, self._action_info(
            Operator.PICK, obj, "", base, None, path_length, path_points
        )

    def _place(self, params: FloatArray) -> tuple[float, dict[str, Any]]:
        cfg, t = self.config, self.task
        obj = t.held
        reason, base, placement, z, col_time = self._place_checks(params, forbidden_rooms=True)
        self.last_timing = StepTiming(collision=col_time)
        if reason:
            return self._infeasible(Operator.PLACE, obj, reason, base, placement)
        x, y, theta = placement
        t0 = time.perf_counter()
        disc = self.held_disc()
        start, goal = disc.center(self.robot.base_pose(self.data)), disc.center(base)
        movable = self.object_boxes(exclude=(obj,))
        if cfg.planner.footprint is None:
            path = self.planner.plan(start, goal, disc.radius, movable)
        else:
            footprint = self.carry_footprint_for(obj, t.held_rel)
            path = self.planner.plan_footprint(start, goal, disc.radius, footprint, movable)
        plan_time = time.perf_counter() - t0
        self.last_timing = StepTiming(collision=col_time, planning=plan_time)
        if path is None:
            failure = Failure(Reason.NO_BASE_PATH, "no base path")
            return self._infeasible(Operator.PLACE, obj, failure, base, placement)
        base_path = BasePath._from_owned(disc.base(path.waypoints), cfg.planner.rotation_weight)
        before = self.data.qpos.copy() if cfg.nonclearing_penalty_infeasible else None
        set_object_pose(self.data, self.objects[obj], (x, y, z, theta))
        self._set_robot(base)
        on_path = self._on_path()
        cleared = len(on_path) < len(t.on_path)
        length = float(base_path.length)
        if before is not None and not cleared and length >= cfg.max_place_penalty:
            self.data.qpos[:] = before
            failure = Failure(
                Reason.PENALTY_CAP,
                f"non-clearing place at the penalty cap (base path {length:.2f} m >="
                f" {cfg.max_place_penalty:g})",
            )
            return self._infeasible(Operator.PLACE, obj, failure, base, placement)
        reward = place_reward(cfg, cleared, length)
        self.task = replace(
            t,
            steps=t.steps + 1,
            operator=Operator.PICK,
            held=-1,
            held_rel=(0.0, 0.0, 0.0),
            grasp_q=(),
            on_path=on_path,
            last_place_cleared=cleared,
            done=not on_path,
        )
        return reward, self._action_info(
            Operator.PLACE, obj, "", base, placement, length, base_path.waypoints
        )

    # ----- rendering -----------------------------------------------------------------------
    def _decorate(self, scene: mujoco.MjvScene) -> None:
        if not self.config.render_overlays or self._clearing is None:
            return
        w = self.path.waypoints
        r = self.config.robot_radius
        for a, b in itertools.pairwise(w):
            add_marker_segment(
                scene, (a[0], a[1], 0.01), (b[0], b[1], 0.01), 2 * r, (0.2, 0.55, 1.0, 0.3)
            )
        xmin, xmax, ymin, ymax = self.config.forbidden
        add_marker_box(
            scene,
            (0.5 * (xmin + xmax), 0.5 * (ymin + ymax), 0.01),
            (0.5 * (xmax - xmin), 0.5 * (ymax - ymin), 0.002),
            0.0,
            (1.0, 0.1, 0.1, 0.12),
        )
