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
  IK reaches the grasp (:mod:`voot.envs.feasibility`), the robot at the grasp
  collides with nothing (the gripper may touch the grasped object) and, with
  ``pick_requires_free_carry`` (default), the robot can still move with its load: the
  carry disc the place step plans with is free at the pick pose (otherwise every
  following place fails with "no base path" and the search is in a dead end).
* **place** (3-D): the object's new pose (x, y, theta) in the house box
  x in [-2, 6], y in [-4, 4], theta in [0, 2 pi); the base pose follows from the grasp.
  Feasible iff the object is inside the house and not in the forbidden rooms
  (x >= 2.8), the robot's base footprint is inside the house, robot and object collide
  with nothing, and a base path exists from the pick pose to the new base pose for the
  robot carrying the object (a disc enclosing robot and load, :mod:`voot.envs.robot`;
  ``L`` below is the length of the base's path).

Rewards (reference page): pick +1 if the previous place reduced the number of
obstacles on the path, else 0; place ``min(1/L, 2)`` if it reduced that number, else
``max(-L, -2)``, with ``L`` the base path's length; an infeasible action -2 (the state
does not change). When nothing is left on the path the episode terminates and a goal
bonus of +2 is reported in ``info["goal_bonus"]`` (not added to the reward). Episodes
are truncated after ``horizon`` steps.

Besides the keys every step's info has (``feasible``, ``reason``, ``next_operator`` ...;
see :mod:`voot.envs.task_env`), ``info["base_pose"]`` is the base pose ``(x, y, theta)``
of the action (a pick: the sampled base pose; a place: the base pose at the placement,
which follows from the grasp) and ``info["placement"]`` the placed object's pose
``(x, y, theta)`` (None for a pick), both also for infeasible actions.

The action space is one ``Box(-1, 1, (6,))`` in normalised units for both operators (a
fixed space keeps gymnasium's checkers and vectorised wrappers happy); at a place step
only the first three entries are read and the rest is ignored. ``info["next_operator"]``
and :meth:`KitchenClearingEnv.action_bounds` (6-D at a pick, 3-D at a place) tell which.

Size: one environment, its config with the v0/v1 presets, the pick and place checks
that the step and the pre-check share, and its rendering overlays.
"""

from __future__ import annotations

import itertools
import math
import struct
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import gymnasium as gym
import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V
from voot.envs.base_planner import BasePath, BasePlannerConfig, Box2D, DiscProbe
from voot.envs.feasibility import IKConfig, rot_z, set_object_pose, side_grasp
from voot.envs.robot import (
    ARM_JOINTS,
    ARM_REACH,
    BASE_HALF,
    ROBOT_DISC,
    ROBOT_RADIUS,
    TUCK,
    CarryDisc,
    base_footprint,
    carry_disc,
    carry_disc_floats,
    compose2d,
    inverse2d,
)
from voot.envs.scene import (
    object_footprint,
    rect_fields_inside,
    rect_fields_overlap,
    rect_inside,
    rect_overlaps,
)
from voot.envs.swept_volume import PathProbe, obstacles_on_path
from voot.envs.task_env import (
    ManipulationEnv,
    StepTiming,
    add_marker_box,
    add_marker_segment,
    denormalize,
    denormalize_floats,
    env_config,
    is_count,
    is_finite_tuple,
    pose_tuple,
    preset_config,
    replace,
)
from voot.optim.base import Bounds

FloatArray = NDArray[np.float64]

#: Operators, in the order actions alternate.
OPERATORS = ("pick", "place")
#: What a planner's pre-check of an action covers (:attr:`KitchenConfig.precheck`).
PRECHECKS = ("full_step", "kinematic")
#: Named versions of the domain: :class:`KitchenConfig` overrides. ``v0`` is the first
#: release (every check inside the planners' retries); ``v1`` is the authors' protocol
#: (two-stage feasibility, see the reference page and docs/environments.md).
KITCHEN_PRESETS: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {
        "v0": MappingProxyType({}),
        "v1": MappingProxyType(
            {
                "precheck": "kinematic",
                "nonclearing_penalty_infeasible": True,
                "pick_requires_free_carry": False,
                "pick_base_path": True,
            }
        ),
    }
)


@dataclass(frozen=True)
class KitchenConfig:
    """Settings of :class:`KitchenClearingEnv` (defaults: the paper's / original's values).

    Attributes:
        start: Initial base pose (the original's (-1.5, -1.5, pi/2)).
        goal: Base pose at the sink, end of the fixed path ((0, 2.5, pi/2)).
        house: The house interior ``(xmin, xmax, ymin, ymax)``: the base planner's
            workspace, the region the robot must stay in and the place action's x, y box.
        forbidden: The two large rooms behind the door; placements there are infeasible.
        grasp_angle: Range of the grasp angle (radians; [45, 180] degrees).
        height_fraction: Range of the grasp height as a fraction of the object's height.
        depth_fraction: Range of the grasp position across the face.
        base_distance: Range of the base distance as a fraction of the arm reach.
        base_angle: Range of the base angle around the object (object frame, radians).
        facing_offset: Range of the heading offset from facing the object (radians).
        place_theta: Range of the placed object's heading (radians).
        robot_radius: Disc radius of the robot for base motion and the swept volume.
        grasp_standoff: Distance of the tool point outside the grasped face (metres).
        pick_reward: Reward of a pick after a place that cleared an obstacle.
        infeasible_reward: Reward of an infeasible action.
        max_place_reward: Cap of ``1/L`` for a clearing place.
        max_place_penalty: Cap of ``L`` for a non-clearing place.
        goal_bonus: Bonus reported when the path is clear.
        horizon: Steps after which an episode is truncated.
        render_overlays: Draw the fixed path's swept corridor and the forbidden rooms in
            rendered images.
        pick_requires_free_carry: A pick is feasible only if the carry disc (the disc
            enclosing robot and load that the following place plans the base path with,
            :meth:`KitchenClearingEnv.carry_disc_for`) is collision-free at the pick pose
            (reason ``carry footprint collides with ...``). Not a paper constant: a fix of
            the disc model's dead ends (a pick whose carry disc already overlaps a counter,
            a wall or an object leaves every placement without a base path). True by
            default; False restores the plain IK/collision/region check.
        precheck: What the planners' pre-check of an action covers (stage 1 of
            :mod:`voot.tree.problem`; :meth:`KitchenClearingEnv.precheck`).
            ``"full_step"`` (v0): the whole step, so every infeasible draw is re-drawn
            before it costs a simulation. ``"kinematic"`` (v1, the authors' code): pick
            = region, collision, IK, collision while holding; place = region and
            collision. The forbidden rooms and the base paths are then found only when
            the action is executed, and a failure there ends the simulation with -2.
        nonclearing_penalty_infeasible: A place that clears nothing and whose penalty
            reaches the cap (``max(-L, -2) == -2``, base path ``L >= 2``) is infeasible:
            the state does not change and the simulation ends (the authors' tree tests
            infeasibility as ``reward == -2``). False (v0): it is a feasible step.
        pick_base_path: A pick is executed only if a base path exists from the robot's
            pose to the pick pose for a disc of radius ``pick_path_radius``. The disc
            model is coarser than the robot's collision geometry (which the pre-check
            tests), so the object to pick and the objects the disc already touches
            where the robot stands (the one it just placed) are left out of the
            obstacles. Reason ``no base path to the pick``.
        pick_path_radius: Radius of the pick's base-path disc. Default: the disc
            inscribed in the base square (0.32 m), since after a place the robot stands
            next to furniture and its enclosing disc (``robot_radius``) often overlaps
            it where the real base does not (with the enclosing disc the scripted
            solution has no path to its fifth pick).
            False (v0): the robot reaches every pick pose that passes the checks.
        ik: IK settings.
        planner: Base planner settings.
    """

    start: tuple[float, float, float] = (-1.5, -1.5, math.pi / 2)
    goal: tuple[float, float, float] = (0.0, 2.5, math.pi / 2)
    house: tuple[float, float, float, float] = (-2.0, 6.0, -4.0, 4.0)
    forbidden: tuple[float, float, float, float] = (2.8, 6.0, -4.0, 4.0)
    grasp_angle: tuple[float, float] = (math.radians(45.0), math.pi)
    height_fraction: tuple[float, float] = (0.5, 1.0)
    depth_fraction: tuple[float, float] = (0.1, 0.9)
    base_distance: tuple[float, float] = (0.4, 0.9)
    base_angle: tuple[float, float] = (0.0, 2.0 * math.pi)
    facing_offset: tuple[float, float] = (math.radians(-30.0), math.radians(30.0))
    place_theta: tuple[float, float] = (0.0, 2.0 * math.pi)
    robot_radius: float = ROBOT_RADIUS
    grasp_standoff: float = 0.0
    pick_reward: float = 1.0
    infeasible_reward: float = -2.0
    max_place_reward: float = 2.0
    max_place_penalty: float = 2.0
    goal_bonus: float = 2.0
    horizon: int = 50
    render_overlays: bool = True
    pick_requires_free_carry: bool = True
    precheck: str = "full_step"
    nonclearing_penalty_infeasible: bool = False
    pick_base_path: bool = False
    pick_path_radius: float = BASE_HALF
    ik: IKConfig = field(default_factory=IKConfig)
    planner: BasePlannerConfig = field(default_factory=BasePlannerConfig)

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", V.pose("KitchenConfig.start", self.start))
        object.__setattr__(self, "goal", V.pose("KitchenConfig.goal", self.goal))
        for name in ("house", "forbidden"):
            object.__setattr__(self, name, V.region(f"KitchenConfig.{name}", getattr(self, name)))
        for name in (
            "grasp_angle",
            "height_fraction",
            "depth_fraction",
            "base_distance",
            "base_angle",
            "facing_offset",
            "place_theta",
        ):
            object.__setattr__(
                self, name, V.range_pair(f"KitchenConfig.{name}", getattr(self, name))
            )
        for name in ("robot_radius", "max_place_reward", "max_place_penalty", "pick_path_radius"):
            object.__setattr__(
                self, name, V.positive_number(f"KitchenConfig.{name}", getattr(self, name))
            )
        for name in ("grasp_standoff", "pick_reward", "goal_bonus"):
            object.__setattr__(
                self,
                name,
                V.positive_number(f"KitchenConfig.{name}", getattr(self, name), allow_zero=True),
            )
        r = V.number(
            self.infeasible_reward, "KitchenConfig.infeasible_reward", high=0.0, open_high=True
        )
        object.__setattr__(self, "infeasible_reward", r)
        V.integer(self.horizon, "KitchenConfig.horizon", 1)
        if self.precheck not in PRECHECKS:
            raise ValueError(
                f"KitchenConfig.precheck must be one of {', '.join(PRECHECKS)}, got {self.precheck!r}"
            )
        for name in (
            "pick_requires_free_carry",
            "nonclearing_penalty_infeasible",
            "pick_base_path",
        ):
            V.flag(getattr(self, name), f"KitchenConfig.{name}")
        if not isinstance(self.ik, IKConfig):
            raise ValueError(f"KitchenConfig.ik must be an IKConfig, got {type(self.ik).__name__}")
        if not isinstance(self.planner, BasePlannerConfig):
            raise ValueError(
                f"KitchenConfig.planner must be a BasePlannerConfig, got {type(self.planner).__name__}"
            )

    @property
    def pick_ranges(self) -> tuple[tuple[float, float], ...]:
        """The pick parameters' ranges, in action order."""
        return (
            self.grasp_angle,
            self.height_fraction,
            self.depth_fraction,
            self.base_distance,
            self.base_angle,
            self.facing_offset,
        )

    @property
    def place_ranges(self) -> tuple[tuple[float, float], ...]:
        """The place parameters' ranges (x, y, theta), in action order."""
        return ((self.house[0], self.house[1]), (self.house[2], self.house[3]), self.place_theta)


def kitchen_config(preset: str = "v0", **overrides: Any) -> KitchenConfig:
    """The :class:`KitchenConfig` of a named version (:data:`KITCHEN_PRESETS`).

    >>> kitchen_config("v1").precheck
    'kinematic'
    """
    config: KitchenConfig = preset_config(KitchenConfig, KITCHEN_PRESETS, preset, **overrides)
    return config


@dataclass(frozen=True)
class KitchenTask:
    """The task's progress (immutable; part of every snapshot).

    Attributes:
        steps: Steps taken in this episode (feasible or not).
        operator: The next operator, ``"pick"`` or ``"place"``.
        held: Index of the object in the gripper, or -1.
        held_rel: The held object's body pose ``(x, y, yaw)`` in the base frame.
        grasp_q: The arm's joint values holding it.
        on_path: Objects on the path, in handling order (the next pick is the first).
        last_place_cleared: Whether the last place reduced the number of obstacles.
        done: The path is clear (terminated).
    """

    steps: int
    operator: str
    held: int
    held_rel: tuple[float, float, float]
    grasp_q: tuple[float, ...]
    on_path: tuple[int, ...]
    last_place_cleared: bool
    done: bool


def _held_rel_floats(
    bx: float, by: float, bt: float, pose: tuple[float, float, float]
) -> tuple[float, float, float]:
    """:meth:`KitchenClearingEnv._held_rel` of the base ``(bx, by, bt)`` and the object's
    ``(x, y, yaw)``: ``compose2d(inverse2d(base), pose)``'s operations on the same floats."""
    c, s = math.cos(bt), math.sin(bt)
    ix, iy, it = -c * bx - s * by, s * bx - c * by, -bt
    c, s = math.cos(it), math.sin(it)
    px, py, pt = pose
    return ix + c * px - s * py, iy + s * px + c * py, it + pt


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


class KitchenClearingEnv(ManipulationEnv[KitchenTask]):
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
        self._path: BasePath | None = None
        self._order: tuple[int, ...] = ()
        self._disc_cache: dict[tuple[int, tuple[float, float, float]], CarryDisc] = {}
        self._screen: ScreenContext | None = None
        self._on_path_memo: dict[Box2D, bool] = {}
        self._last_carry: tuple[tuple[int, bytes, bytes], str] | None = None
        super().__init__(
            "kitchen", cfg.house, cfg.ik, cfg.planner, render_mode, render_camera, render_size
        )
        self._reset_physics()
        path = self.planner.plan(cfg.start, cfg.goal, cfg.robot_radius, ())
        if path is None:
            raise ValueError(
                f"no base path from start {cfg.start} to goal {cfg.goal} for radius {cfg.robot_radius}"
            )
        self._path = path
        self._path_probe = PathProbe(path.waypoints, cfg.robot_radius)
        self._order = self._handling_order()
        #: Each object's position in the handling order (for checking task records).
        self._order_rank = {i: k for k, i in enumerate(self._order)}
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
        assert self._path is not None
        return self._path

    def _path_position(self, box: Box2D) -> float:
        """Arc length along the fixed path of the point nearest the box centre."""
        w = self.path.waypoints[:, :2]
        best, best_s, s0 = math.inf, 0.0, 0.0
        p = np.array([box.cx, box.cy])
        for a, b in itertools.pairwise(w):
            d = b - a
            seg = float(np.hypot(*d))
            t = 0.0 if seg == 0 else float(np.clip((p - a) @ d / seg**2, 0.0, 1.0))
            dist = float(np.hypot(*(a + t * d - p)))
            if dist < best:
                best, best_s = dist, s0 + t * seg
            s0 += seg
        return best_s

    def _handling_order(self) -> tuple[int, ...]:
        """Initial obstacles by position along the path, then the other objects."""
        boxes = self.object_boxes()
        on = self._on_path_names(boxes)
        first = sorted(
            (i for i, o in enumerate(self.objects) if o.name in on),
            key=lambda i: (self._path_position(boxes[i]), i),
        )
        rest = [i for i in range(len(self.objects)) if i not in first]
        return tuple(first + rest)

    def _on_path_names(self, boxes: list[Box2D]) -> set[str]:
        if self._path is None:
            return set()
        return set(obstacles_on_path(self._path.waypoints, self.config.robot_radius, boxes))

    def _on_path(self) -> tuple[int, ...]:
        """Objects (not held) on the path now, in handling order.

        Each footprint's answer is a function of the footprint alone (the path and the
        radius are fixed), so it is remembered per footprint: after a place only the
        moved object is new. The answers are :func:`obstacles_on_path`'s (its
        :class:`~voot.envs.swept_volume.PathProbe`'s).
        """
        if self._path is None:
            return ()
        boxes = self.object_boxes()
        memo = self._on_path_memo
        missing = [b for b in boxes if b not in memo]
        if missing:
            if len(memo) > 100_000:
                memo.clear()
            memo.update(zip(missing, self._path_probe.hits(missing), strict=True))
        on = {b.name for b in boxes if memo[b]}
        return tuple(i for i in self._order if self.objects[i].name in on)

    # ----- ManipulationEnv hooks -------------------------------------------------------------
    def _reset_physics(self) -> None:
        mujoco.mj_resetData(self.model, self.data)
        self._set_robot(self.config.start)

    def _initial_task(self) -> KitchenTask:
        return KitchenTask(
            steps=0,
            operator="pick",
            held=-1,
            held_rel=(0.0, 0.0, 0.0),
            grasp_q=(),
            on_path=self._on_path() if self._order else (),
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
            float(t.operator == "place"),
            len(t.on_path) / self.initial_obstacles,
            t.steps / self.config.horizon,
        ]
        return np.array(parts, dtype=np.float64)

    def _info_reset(self) -> dict[str, Any]:
        return {
            "next_operator": self.task.operator,
            "objects_left": len(self.task.on_path),
            "next_object": self.next_object_name,
        }

    def _task_error(self, task: KitchenTask) -> str | None:
        """What no episode of this kitchen reaches in ``task`` (see ``set_state``), or None.

        An episode alternates pick (nothing held: ``held`` -1) and place (``held`` an
        object index, its pose in the base frame and the arm's 7 joints finite); the
        obstacles left are distinct objects in the handling order, and the episode is
        done exactly when none is left.
        """
        n = len(self.objects)
        if not is_count(task.steps, 0, self.config.horizon):
            horizon = self.config.horizon
            return f"steps must be an int in 0..{horizon} (the horizon), got {task.steps!r}"
        if task.operator == "pick":
            if task.held != -1 or type(task.held) is not int:
                return f"held must be -1 before a pick (nothing in the gripper), got {task.held!r}"
        elif task.operator == "place":
            if not is_count(task.held, 0, n - 1):
                return (
                    f"held must be an object index in 0..{n - 1} before a place, got {task.held!r}"
                )
            if not is_finite_tuple(task.held_rel, 3):
                return f"held_rel must be 3 finite numbers (x, y, yaw), got {task.held_rel!r}"
            if not is_finite_tuple(task.grasp_q, len(ARM_JOINTS)):
                return (
                    f"grasp_q must be {len(ARM_JOINTS)} finite joint values at a place,"
                    f" got {task.grasp_q!r}"
                )
        else:
            return f"operator must be 'pick' or 'place', got {task.operator!r}"
        on_path = task.on_path
        rank = self._order_rank
        if type(on_path) is not tuple or any(type(i) is not int or i not in rank for i in on_path):
            return f"on_path must be a tuple of object indices in 0..{n - 1}, got {on_path!r}"
        if any(rank[a] >= rank[b] for a, b in itertools.pairwise(on_path)):
            return (
                f"on_path must list distinct objects in the handling order {self._order},"
                f" got {on_path!r}"
            )
        if type(task.last_place_cleared) is not bool or type(task.done) is not bool:
            return (
                "last_place_cleared and done must be bools, got"
                f" {task.last_place_cleared!r} and {task.done!r}"
            )
        if task.done != (not on_path):
            return f"done must be {not on_path} when on_path is {on_path!r}, got {task.done!r}"
        return None

    @property
    def objects_left(self) -> int:
        """Obstacles still on the path."""
        return len(self.task.on_path)

    @property
    def next_object_name(self) -> str:
        """Name of the object the next action handles ('' when done)."""
        t = self.task
        if t.operator == "place":
            return self.objects[t.held].name
        return self.objects[t.on_path[0]].name if t.on_path else ""

    def action_bounds(self) -> Bounds:
        """The current operator's action box in normalised units (6-D pick, 3-D place)."""
        dim = 6 if self.task.operator == "pick" else 3
        return Bounds.cube(-1.0, 1.0, dim)

    # ----- stepping ------------------------------------------------------------------------
    def transition(self, action: ArrayLike) -> tuple[float, bool, bool, dict[str, Any]]:
        """One step without its observation (see :meth:`ManipulationEnv.transition`)."""
        a, clipped = self._validate_action(action)
        t = self.task
        if t.done or t.steps >= self.config.horizon:
            raise ValueError("the episode has ended (terminated or truncated); call reset()")
        start = time.perf_counter()
        if t.operator == "pick":
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
        info.update(
            parameters=params,
            action_clipped=clipped,
            next_operator=t.operator,
            next_object=self.next_object_name,
            objects_left=len(t.on_path),
            goal_bonus=self.config.goal_bonus if terminated else 0.0,
        )
        return float(reward), terminated, truncated, info

    def _infeasible(
        self,
        operator: str,
        obj: int,
        reason: str,
        base: ArrayLike,
        placement: ArrayLike | None = None,
    ) -> tuple[float, dict[str, Any]]:
        self.task = replace(self.task, steps=self.task.steps + 1)
        return self.config.infeasible_reward, {
            "operator": operator,
            "object": self.objects[obj].name,
            "feasible": False,
            "reason": reason,
            "base_path_length": 0.0,
            "base_path": None,
            "base_pose": pose_tuple(base),
            "placement": None if placement is None else pose_tuple(placement),
        }

    def pick_base_pose(self, obj: int, params: ArrayLike) -> FloatArray:
        """The base pose ``(x, y, theta)`` of pick parameters for object ``obj``."""
        p = np.asarray(params, dtype=np.float64)
        box = self.object_box(obj)
        dist = p[3] * ARM_REACH
        ang = box.yaw + p[4]
        bx, by = box.cx + dist * math.cos(ang), box.cy + dist * math.sin(ang)
        heading = math.atan2(box.cy - by, box.cx - bx) + p[5]
        return np.array([bx, by, heading])

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
            return "outside region: the robot leaves the house", base, None, no_rel
        pose = self.object_pose(obj)
        grasp = side_grasp(
            self.objects[obj],
            pose,
            float(base[2]),
            params[0],
            params[1],
            params[2],
            cfg.grasp_standoff,
        )
        t0 = time.perf_counter()
        base_report = self.collision.check(self.data.qpos, base, TUCK)  # cheap early exit
        col_time = time.perf_counter() - t0
        if not base_report.free:
            self.last_timing = StepTiming(collision=col_time)
            return "collision: " + ", ".join(base_report.hits), base, None, no_rel
        rb = rot_z(float(base[2]))
        target_p = rb.T @ (grasp.position - np.array([base[0], base[1], 0.0]))
        target_r = rb.T @ grasp.rotation
        t0 = time.perf_counter()
        ik = self.ik.solve(target_p, target_r)
        ik_time = time.perf_counter() - t0
        if not ik.success or ik.q is None:
            self.last_timing = StepTiming(ik=ik_time, collision=col_time)
            return f"IK failed: {ik.reason}", base, None, no_rel
        t0 = time.perf_counter()
        report = self.collision.check(self.data.qpos, base, ik.q, held=obj)
        col_time += time.perf_counter() - t0
        self.last_timing = StepTiming(ik=ik_time, collision=col_time)
        if not report.free:
            return "collision: " + ", ".join(report.hits), base, None, no_rel
        held_rel = self._held_rel(base, pose)
        if cfg.pick_requires_free_carry:  # last, so the other reasons stay as without it
            t0 = time.perf_counter()
            carry_reason = self._carry_blocked(obj, held_rel, base)
            col_time += time.perf_counter() - t0
            self.last_timing = StepTiming(ik=ik_time, collision=col_time)
            if carry_reason:
                return carry_reason, base, None, no_rel
        return "", base, ik.q, held_rel

    @staticmethod
    def _held_rel(base: FloatArray, pose: FloatArray) -> tuple[float, float, float]:
        """The object's body pose ``(x, y, yaw)`` in the frame of the base at ``base``."""
        bx, by, bt = (float(v) for v in base[:3])
        return _held_rel_floats(bx, by, bt, (float(pose[0]), float(pose[1]), float(pose[3])))

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
        if t.operator == "place":
            return self._place_screened(ctx, values)
        return self._pick_screened(ctx, values)

    def _screen_context(self) -> ScreenContext:
        """The pre-screen's per-state numbers (rebuilt when the task or qpos changed)."""
        t, qpos = self.task, self.data.qpos.tobytes()
        ctx = self._screen
        if ctx is not None and ctx.task is t and ctx.qpos == qpos:
            return ctx
        cfg = self.config
        obj = t.held if t.operator == "place" else t.on_path[0]
        info = self.objects[obj]
        ox, oy = info.center.tolist()
        hx, hy = info.half.tolist()
        pose = self.object_pose(obj)
        place = t.operator == "place"
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
        if ctx.probe.blocked(gx, gy, disc.radius):
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
            held_rel = _held_rel_floats(bx, by, heading, ctx.pose_xyyaw)
            blocked = self._carry_verdict(ctx, held_rel, bx, by, heading)
            if blocked is None:  # too close to tell on floats: the exact (remembered) test
                blocked = bool(self._carry_blocked(ctx.obj, held_rel, np.array([bx, by, heading])))
            if blocked:
                return True
        return self.collision.collides(self.data.qpos, (bx, by, heading), TUCK)

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

    def _pick(self, params: FloatArray) -> tuple[float, dict[str, Any]]:
        cfg, t = self.config, self.task
        obj = t.on_path[0]
        reason, base, q, held_rel = self._pick_kinematics(params)
        if reason:
            return self._infeasible("pick", obj, reason, base)
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
                return self._infeasible("pick", obj, "no base path to the pick", base)
            path_length, path_points = float(path.length), path.waypoints
        self._set_robot(base, q)
        reward = cfg.pick_reward if t.last_place_cleared else 0.0
        self.task = replace(
            t,
            steps=t.steps + 1,
            operator="place",
            held=obj,
            held_rel=held_rel,
            grasp_q=tuple(float(v) for v in q),
        )
        return reward, {
            "operator": "pick",
            "object": self.objects[obj].name,
            "feasible": True,
            "reason": "",
            "base_path_length": path_length,
            "base_path": path_points,
            "base_pose": pose_tuple(base),
            "placement": None,
        }

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
        base = compose2d((x, y, theta), inverse2d(t.held_rel))
        placement = (x, y, theta)
        z = float(self.object_pose(obj)[2])
        if not rect_inside(new_box, cfg.house):
            return "outside region: the object leaves the house", base, placement, z, 0.0
        if forbidden_rooms and rect_overlaps(new_box, cfg.forbidden):
            reason = "forbidden room: the object is in the rooms behind the door"
            return reason, base, placement, z, 0.0
        if not rect_inside(base_footprint(base), cfg.house):
            return "outside region: the robot leaves the house", base, placement, z, 0.0
        t0 = time.perf_counter()
        report = self.collision.check(
            self.data.qpos, base, t.grasp_q, held=obj, object_poses={obj: (x, y, z, theta)}
        )
        col_time = time.perf_counter() - t0
        if not report.free:
            return "collision: " + ", ".join(report.hits), base, placement, z, col_time
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
        if t.operator == "pick":
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
            "reason": reason,
            "base_pose": pose_tuple(base),
            "placement": placement,
        }

    def held_disc(self) -> CarryDisc:
        """The base-motion disc of the robot carrying the held object (robot disc if none)."""
        t = self.task
        if t.held < 0:
            return replace(ROBOT_DISC, radius=self.config.robot_radius)
        return self.carry_disc_for(t.held, t.held_rel)

    def carry_disc_for(self, obj: int, held_rel: tuple[float, float, float]) -> CarryDisc:
        """The base-motion disc of the robot carrying object ``obj`` at ``held_rel``.

        ``held_rel`` is the object's body pose ``(x, y, yaw)`` in the base frame. The disc
        encloses the base square and the object's footprint (:func:`voot.envs.robot.carry_disc`),
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
        if ctx.task.operator == "pick" and ctx.obj == obj:
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
        return "carry footprint " + " and ".join(parts)

    def _place(self, params: FloatArray) -> tuple[float, dict[str, Any]]:
        cfg, t = self.config, self.task
        obj = t.held
        reason, base, placement, z, col_time = self._place_checks(params, forbidden_rooms=True)
        self.last_timing = StepTiming(collision=col_time)
        if reason:
            return self._infeasible("place", obj, reason, base, placement)
        x, y, theta = placement
        t0 = time.perf_counter()
        disc = self.held_disc()
        path = self.planner.plan(
            disc.center(self.robot.base_pose(self.data)),
            disc.center(base),
            disc.radius,
            self.object_boxes(exclude=(obj,)),
        )
        plan_time = time.perf_counter() - t0
        self.last_timing = StepTiming(collision=col_time, planning=plan_time)
        if path is None:
            return self._infeasible("place", obj, "no base path", base, placement)
        base_path = BasePath._from_owned(disc.base(path.waypoints), cfg.planner.rotation_weight)
        before = self.data.qpos.copy() if cfg.nonclearing_penalty_infeasible else None
        set_object_pose(self.data, self.objects[obj], (x, y, z, theta))
        self._set_robot(base)
        on_path = self._on_path()
        cleared = len(on_path) < len(t.on_path)
        length = float(base_path.length)
        if before is not None and not cleared and length >= cfg.max_place_penalty:
            self.data.qpos[:] = before
            return self._infeasible(
                "place",
                obj,
                f"non-clearing place at the penalty cap (base path {length:.2f} m >="
                f" {cfg.max_place_penalty:g})",
                base,
                placement,
            )
        if cleared:
            reward = (
                cfg.max_place_reward if length <= 0 else min(1.0 / length, cfg.max_place_reward)
            )
        else:
            reward = max(-length, -cfg.max_place_penalty)
        self.task = replace(
            t,
            steps=t.steps + 1,
            operator="pick",
            held=-1,
            held_rel=(0.0, 0.0, 0.0),
            grasp_q=(),
            on_path=on_path,
            last_place_cleared=cleared,
            done=not on_path,
        )
        return reward, {
            "operator": "place",
            "object": self.objects[obj].name,
            "feasible": True,
            "reason": "",
            "base_path_length": length,
            "base_path": base_path.waypoints,
            "base_pose": pose_tuple(base),
            "placement": placement,
        }

    # ----- rendering -----------------------------------------------------------------------
    def _decorate(self, scene: mujoco.MjvScene) -> None:
        if not self.config.render_overlays or self._path is None:
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
