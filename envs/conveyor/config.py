"""The storage rooms' settings: :class:`ConveyorConfig` and its named versions.

Every constant of the conveyor domain (regions, belt, boxes, costs, the base-motion model
and the authors' geometry options) as a validated field at the paper's value, and the
presets ``v0``, ``v1`` and ``v3`` (:data:`CONVEYOR_PRESETS`) that
``voot/ConveyorPacking-v0``, ``-v1`` and ``-v3`` (the authors' domain) pass. Kept apart
from the env (:mod:`voot.envs.conveyor.env`) as the kitchen's settings are
(:mod:`voot.envs.kitchen.config`): one concept per module.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from voot import validation as V
from voot.envs.conveyor.problems import HORIZON
from voot.envs.core.names import Precheck
from voot.envs.core.presets import check_step_rules, preset_config
from voot.envs.motion.base_model import base_model_planner
from voot.envs.motion.planner import BasePlannerConfig
from voot.envs.robot.arm_ik import IKConfig

#: The choices of :attr:`ConveyorConfig.rooms`.
ROOMS = ("voot", "authors")


@dataclass(frozen=True)
class ConveyorConfig:
    """Settings of :class:`ConveyorPackingEnv` (defaults: the paper's / original's values).

    Attributes:
        start: The robot's base pose where every box is presented and every placement's
            base path starts ((0, 1.05, 0): the authors' ``init_base_conf``, where their
            robot is set back after each pick before its path is planned).
        loading_region: Where boxes may be placed ``(xmin, xmax, ymin, ymax)``; also the
            x, y ranges of the action.
        workspace: Where the robot's base may go (the base planner's workspace).
        place_theta: Range of a placed box's heading (radians).
        n_objects: Boxes to pack, the first ``n_objects`` of the belt (1..20).
        grasp_angle: The fixed grasp's roll about the approach axis (radians).
        height_fraction: The fixed grasp's height as a fraction of the box height.
        depth_fraction: The fixed grasp's position across the grasped face.
        present_gap: Gap between the base's front and the presented box (metres).
        length_scale: ``c`` in the placement reward ``exp(-c L)``.
        infeasible_reward: Reward of an infeasible action.
        horizon: Steps after which an episode is truncated.
        render_overlays: Draw the loading region in rendered images.
        precheck: What the planners' pre-check of an action covers (stage 1 of
            :mod:`voot.tree.problem`; :meth:`ConveyorPackingEnv.precheck`).
            ``"full_step"`` (v0): the whole step. ``"kinematic"`` (v1, the authors'
            code): the three placements' region and collision checks, in sequence; the
            base paths (through the door, which the big boxes' carry disc cannot pass)
            are found only when the action is executed.
        rooms: ``"voot"`` (v0, v1): voot's storage rooms (``models/conveyor.xml``: a
            2.6 m entrance, a 3.3 x 4 m first room with a 1.62 m door mid-wall, a 3.5 m
            south-west opening). ``"authors"``: the walls of the authors'
            ``convbelt_env_diffcult_shapes_two_rooms.xml`` (a 1.5 m entrance, a 3.3 x 3.0 m
            first room with a 1.7 m door against its west wall, a 2.0 m south-west
            opening: :mod:`voot.envs.conveyor.authors_rooms`). Their scripted solution
            is :data:`~voot.envs.conveyor.scripted.AUTHORS_SOLUTION` (voot's does not fit
            them); it needs ``base_model="footprint"``.
        base_model: ``"disc"`` (v0, v1): the base planner's config as given (the disc,
            unless its ``footprint`` is set) or ``"footprint"`` (the exact oriented footprint where the disc
            finds no path: sets ``planner.footprint`` to a default
            :class:`~voot.envs.motion.footprint.FootprintConfig` when it is None; a
            keyword ``gymnasium.make`` and ``voot-bench plan --env-kwargs`` can pass).
        footprint_heuristic: The ``heuristic`` of the
            :class:`~voot.envs.motion.footprint.FootprintConfig` that
            ``base_model="footprint"`` sets: ``"euclidean"`` (default) or ``"geodesic"``
            (the same "a path exists" answers, other paths of about the same length,
            6 times less CPU on a VOOT search's exact queries in the authors' rooms:
            docs/motion-planning.md). A keyword
            ``--env-kwargs`` can pass; another value than the default needs
            ``base_model="footprint"`` and no ``planner.footprint`` of the caller's.
        big_box_ban: The authors' explicit rule at execution (``problem_environments/
            conveyor_belt_env.py`` in beomjoonkim/voot): the big boxes may not be placed in
            the big rooms. False (v0, v1): voot lets the base planner's disc and the door
            width keep them out (the carry disc of a big box cannot pass the 1.62 m door).
            True: executing a placement of one of the first ``big_boxes`` boxes whose
            centre lies outside ``first_room`` fails ("forbidden room"); the pre-check
            does not test it (as in the authors' code).
        big_boxes: How many of the first boxes are big (2: the original's
            ``create_objects`` and :func:`voot.envs.assets.fixed_scenes.conveyor_box_sizes`).
        first_room: The region the big boxes must stay in under ``big_box_ban``: voot's
            first room x in [-4, -0.7], y in [-1, 3] (``models/conveyor.xml``).
        ik: IK settings.
        planner: Base planner settings. Its ``footprint`` option
            (:class:`~voot.envs.motion.footprint.FootprintConfig`) plans the exact footprint
            of robot, arm and box (:meth:`ConveyorPackingEnv.footprint`) where the disc
            finds no path.
    """

    start: tuple[float, float, float] = (0.0, 1.05, 0.0)
    loading_region: tuple[float, float, float, float] = (-7.4, -0.5, -7.5, 3.0)
    workspace: tuple[float, float, float, float] = (-7.4, 1.5, -7.5, 3.0)
    place_theta: tuple[float, float] = (0.0, 2.0 * math.pi)
    n_objects: int = 20
    grasp_angle: float = math.pi / 2
    height_fraction: float = 0.75
    depth_fraction: float = 0.5
    present_gap: float = 0.2
    length_scale: float = 0.1
    infeasible_reward: float = -2.0
    horizon: int = HORIZON
    render_overlays: bool = True
    precheck: Precheck = Precheck.FULL_STEP
    rooms: str = "voot"
    base_model: str = "disc"
    footprint_heuristic: str = "euclidean"
    big_box_ban: bool = False
    big_boxes: int = 2
    first_room: tuple[float, float, float, float] = (-4.0, -0.7, -1.0, 3.0)
    ik: IKConfig = field(default_factory=IKConfig)
    planner: BasePlannerConfig = field(default_factory=BasePlannerConfig)

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", V.pose("ConveyorConfig.start", self.start))
        if self.rooms not in ROOMS:
            raise ValueError(
                f"ConveyorConfig.rooms must be one of {', '.join(ROOMS)}, got {self.rooms!r}"
            )
        planner = base_model_planner(
            "ConveyorConfig", self.base_model, self.footprint_heuristic, self.planner
        )
        object.__setattr__(self, "planner", planner)
        if type(self.big_box_ban) is not bool:
            raise ValueError(f"ConveyorConfig.big_box_ban must be a bool, got {self.big_box_ban!r}")
        V.integer(self.big_boxes, "ConveyorConfig.big_boxes", 0, 20)
        for name in ("loading_region", "workspace", "first_room"):
            object.__setattr__(self, name, V.region(f"ConveyorConfig.{name}", getattr(self, name)))
        object.__setattr__(
            self, "place_theta", V.range_pair("ConveyorConfig.place_theta", self.place_theta)
        )
        V.integer(self.n_objects, "ConveyorConfig.n_objects", 1, 20)
        for name in ("grasp_angle", "present_gap", "length_scale"):
            object.__setattr__(
                self, name, V.positive_number(f"ConveyorConfig.{name}", getattr(self, name))
            )
        for name in ("height_fraction", "depth_fraction"):
            v = V.number(getattr(self, name), f"ConveyorConfig.{name}", 0.0, 1.0)
            object.__setattr__(self, name, v)
        check_step_rules(self)

    @property
    def place_ranges(self) -> tuple[tuple[float, float], ...]:
        """Ranges of one placement's parameters (x, y, theta)."""
        r = self.loading_region
        return ((r[0], r[1]), (r[2], r[3]), self.place_theta)


#: Named versions of the domain: :class:`ConveyorConfig` overrides (see
#: :data:`voot.envs.kitchen.config.KITCHEN_PRESETS`).
#: ``v3`` is v1 on the authors' domain: the exact footprint (with the geodesic
#: heuristic), their rooms and their big-box ban (``voot/ConveyorPacking-v3``).
CONVEYOR_PRESETS: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {
        "v0": MappingProxyType({}),
        "v1": MappingProxyType({"precheck": Precheck.KINEMATIC}),
        "v3": MappingProxyType(
            {
                "precheck": Precheck.KINEMATIC,
                "base_model": "footprint",
                "footprint_heuristic": "geodesic",
                "big_box_ban": True,
                "rooms": "authors",
            }
        ),
    }
)


def conveyor_config(preset: str = "v0", **overrides: Any) -> ConveyorConfig:
    """The :class:`ConveyorConfig` of a named version (:data:`CONVEYOR_PRESETS`)."""
    config: ConveyorConfig = preset_config(ConveyorConfig, CONVEYOR_PRESETS, preset, **overrides)
    return config
