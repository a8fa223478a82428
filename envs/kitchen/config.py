"""The kitchen's task rules and named versions: :class:`KitchenConfig` and its presets.

Everything that defines the object-clearing task (:mod:`voot.envs.kitchen.env`) as numbers:
the start and the goal at the sink (the ends of the fixed path), the house the robot and
the objects must stay in, the forbidden rooms behind the door, the ranges the pick and
place parameters are scaled to, the rewards and their caps, the horizon, and the switches
that tell the domain's versions apart (:data:`KITCHEN_PRESETS`: ``v0``, the first release,
and ``v1``, the authors' protocol). A frozen dataclass, validated on construction, so a
bad setting is an error naming the field before any scene is loaded.

Apart from the env so that the rules can be read, built and compared (benchmarks, the
registration of ``voot/KitchenClearing-v1``) without MuJoCo doing anything.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from voot import validation as V
from voot.envs.core.names import Precheck
from voot.envs.core.presets import check_step_rules, preset_config
from voot.envs.kitchen.problems import HORIZON
from voot.envs.motion.base_model import base_model_planner
from voot.envs.motion.planner import BasePlannerConfig
from voot.envs.robot.arm_ik import IKConfig
from voot.envs.robot.model import BASE_HALF, ROBOT_RADIUS

#: Named versions of the domain: :class:`KitchenConfig` overrides. ``v0`` is the first
#: release (every check inside the planners' retries); ``v1`` is the authors' protocol
#: (two-stage feasibility, see the reference page and docs/environments.md).
KITCHEN_PRESETS: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {
        "v0": MappingProxyType({}),
        "v1": MappingProxyType(
            {
                "precheck": Precheck.KINEMATIC,
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
        base_model: ``"disc"`` (default: the place step plans the base path for the
            carry disc, :meth:`KitchenClearingEnv.carry_disc_for`) or ``"footprint"``
            (where the disc finds no path, the exact oriented footprint of what that disc
            encloses, the base square and the held object at its grasp,
            :meth:`KitchenClearingEnv.carry_footprint_for`: sets ``planner.footprint`` to a
            default :class:`~voot.envs.motion.footprint.FootprintConfig` when it is None).
            The fixed path's swept volume (which objects are obstacles) and the pick's
            base path keep their discs: the first defines the task, the second is already
            narrower than the base. Needs ``pick_requires_free_carry=False`` (v1's), since
            that rule tests the disc.
        footprint_heuristic: The ``heuristic`` of the footprint option that
            ``base_model="footprint"`` sets: ``"euclidean"`` (default) or ``"geodesic"``.
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
    horizon: int = HORIZON
    render_overlays: bool = True
    pick_requires_free_carry: bool = True
    precheck: Precheck = Precheck.FULL_STEP
    nonclearing_penalty_infeasible: bool = False
    pick_base_path: bool = False
    pick_path_radius: float = BASE_HALF
    base_model: str = "disc"
    footprint_heuristic: str = "euclidean"
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
        for name in (
            "pick_requires_free_carry",
            "nonclearing_penalty_infeasible",
            "pick_base_path",
        ):
            V.flag(getattr(self, name), f"KitchenConfig.{name}")
        planner = base_model_planner(
            "KitchenConfig", self.base_model, self.footprint_heuristic, self.planner
        )
        object.__setattr__(self, "planner", planner)
        if self.base_model == "footprint" and self.pick_requires_free_carry:
            raise ValueError(
                'KitchenConfig.base_model="footprint" needs pick_requires_free_carry=False'
                " (v1's): that rule tests the carry disc, which the footprint replaces"
            )
        check_step_rules(self)

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
