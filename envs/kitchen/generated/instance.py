"""A solvable generated kitchen from ``(layout_seed, difficulty)``, generated once per process.

:func:`generated_kitchen` is what ``voot/GeneratedKitchen-v0`` loads. It draws attempts
0, 1, ... of the seed (:func:`~voot.envs.kitchen.generated.layout.generate_kitchen_layout`),
writes and compiles each one's scene (:mod:`voot.envs.kitchen.generated.scene`), builds the
env on it (:class:`SceneKitchenEnv`) and proves it solvable
(:func:`~voot.envs.kitchen.generated.witness.constructive_solution`). An attempt is
**rejected** when its numbers make no kitchen (a
:class:`~voot.envs.kitchen.generated.layout.LayoutError`), the env refuses it, the env sees
other obstacles on the fixed path than the generator drew, or the solver leaves an
obstacle; the next attempt is drawn (a derived random stream, so the outcome is
deterministic), up to :data:`MAX_ATTEMPTS` (:func:`voot.envs.core.generation.first_accepted`).

Accepted kitchens are kept per ``(layout_seed, difficulty)`` in this process (the last
:data:`KITCHEN_CACHE_SIZE`, :data:`KITCHENS`): the layout, its MJCF, the compiled model and
the witness; an env of a kept kitchen copies the model and costs what a v1 env costs.
"""

from __future__ import annotations

import copy
import time
from dataclasses import dataclass
from typing import Any, Unpack

import mujoco
import numpy as np
from numpy.typing import NDArray

from voot.envs.assets.mjcf import mjcf_sha256
from voot.envs.core.generation import (
    GeneratedInstance,
    InstanceCache,
    check_layout_seed,
    first_accepted,
    parse_difficulty,
    reject_layout_fields,
)
from voot.envs.core.names import Difficulty
from voot.envs.core.presets import env_config
from voot.envs.core.rendering import RenderOptions
from voot.envs.core.state import replace
from voot.envs.kitchen.config import KITCHEN_PRESETS, KitchenConfig
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.generated.layout import (
    DIFFICULTIES,
    KitchenLayout,
    LayoutError,
    generate_kitchen_layout,
)
from voot.envs.kitchen.generated.scene import compile_kitchen, kitchen_layout_xml, shape_spec
from voot.envs.kitchen.generated.witness import constructive_solution
from voot.envs.robot.grasp import GraspPose
from voot.envs.robot.mesh_grasp import MeshGraspSet, grasp_set, mesh_side_grasp

__all__ = [
    "KITCHENS",
    "KITCHEN_CACHE_SIZE",
    "LAYOUT_FIELDS",
    "MAX_ATTEMPTS",
    "GeneratedKitchen",
    "SceneKitchenEnv",
    "clear_kitchen_cache",
    "generate_kitchen",
    "generated_kitchen",
    "kitchen_config",
]

FloatArray = NDArray[np.float64]

#: Attempts of a seed before generation gives up (hard kitchens need about 10 on average,
#: most of them cheap layout draws that leave no room for an obstacle: see the docs).
MAX_ATTEMPTS = 60
#: The config fields a layout sets (an option naming one is an error).
LAYOUT_FIELDS = ("start", "goal", "house", "forbidden")
#: Generated kitchens kept per process (the least recently used one is forgotten past
#: this: a kitchen holds its compiled model, about 3 MB).
KITCHEN_CACHE_SIZE = 64


@dataclass(frozen=True, eq=False)
class GeneratedKitchen(GeneratedInstance[KitchenLayout, tuple[tuple[float, ...], ...]]):
    """An accepted generated kitchen (see the module docstring).

    Attributes (beside :class:`~voot.envs.core.generation.GeneratedInstance`'s, whose
    ``witness`` is here the normalised actions that clear every obstacle from ``reset()``):
        xml: The scene's MJCF.
        seconds: Wall time the generation took (attempts, checks and all).
        tries: Actions the constructive solver stepped for the accepted attempt.
    """

    xml: str
    seconds: float
    tries: int


def kitchen_config(
    layout: KitchenLayout, config: KitchenConfig | None = None, **options: Any
) -> KitchenConfig:
    """The kitchen rules on ``layout``: ``config`` (default: the v1 preset's) with
    ``options`` applied and the layout's start, goal, house and forbidden rooms.

    Raises:
        ValueError: An option is one of :data:`LAYOUT_FIELDS` or no config field.
    """
    reject_layout_fields(options, LAYOUT_FIELDS)
    base = env_config(KitchenConfig, KITCHEN_PRESETS, config, "v1", options)
    return replace(
        base, start=layout.start, goal=layout.goal, house=layout.house, forbidden=layout.forbidden
    )


class SceneKitchenEnv(KitchenClearingEnv):
    """The kitchen rules on a generated kitchen's layout and compiled model: what the
    solvability check steps, and the base of ``voot/GeneratedKitchen-v0``'s env.

    Picks grasp the objects' meshes (:meth:`_grasp_pose`); the scene is a copy of
    ``kitchen.model``.

    Args:
        kitchen: The kitchen (its layout and model; its witness is not read).
        config: Settings (:func:`kitchen_config`).
        **render: The render arguments (:class:`~voot.envs.core.rendering.RenderOptions`).
    """

    def __init__(
        self, kitchen: GeneratedKitchen, config: KitchenConfig, **render: Unpack[RenderOptions]
    ) -> None:
        self.kitchen = kitchen
        #: The objects' grasp tables (from their meshes), in object order.
        self._grasp_sets: tuple[MeshGraspSet, ...] = tuple(
            grasp_set(shape_spec(o)) for o in kitchen.layout.objects
        )
        super().__init__(config=config, **render)

    @property
    def layout(self) -> KitchenLayout:
        """The generated floor plan."""
        return self.kitchen.layout

    def _grasp_pose(
        self, obj: int, pose: FloatArray, base_heading: float, params: FloatArray
    ) -> tuple[GraspPose | None, str]:
        """The grasp on the object's mesh (:func:`~voot.envs.robot.mesh_grasp.mesh_side_grasp`):
        the side grasp's parameters with the tool point on the real surface, or None and
        ``"grasp misses the object"`` where the ray passes beside it (a jug's handle side,
        a bottle's neck)."""
        return mesh_side_grasp(
            self._grasp_sets[obj],
            pose,
            base_heading,
            params[0],
            params[1],
            params[2],
            self.config.grasp_standoff,
        )

    def _scene_model(self) -> str | mujoco.MjModel:
        """A copy of the generated kitchen's compiled model (the env may change its
        collision filters)."""
        return copy.copy(self.kitchen.model)


#: The kitchens made in this process, by ``(layout_seed, difficulty)``.
KITCHENS: InstanceCache[tuple[int, Difficulty], GeneratedKitchen] = InstanceCache(
    KITCHEN_CACHE_SIZE
)


def clear_kitchen_cache() -> None:
    """Forget the generated kitchens kept in this process."""
    KITCHENS.clear()


def generated_kitchen(layout_seed: int, difficulty: str) -> GeneratedKitchen:
    """The accepted kitchen of ``(layout_seed, difficulty)``, generated once per process.

    Raises:
        ValueError: a bad seed or level.
        RuntimeError: no attempt of :data:`MAX_ATTEMPTS` passed.
    """
    seed = check_layout_seed(layout_seed)
    level = parse_difficulty(difficulty, DIFFICULTIES)
    return KITCHENS.get_or_make((seed, level), lambda: generate_kitchen(seed, level))


def generate_kitchen(layout_seed: int, difficulty: str) -> GeneratedKitchen:
    """Generate and prove the kitchen of ``(layout_seed, difficulty)`` (no cache; see the
    module docstring)."""
    t0 = time.perf_counter()

    def attempt(k: int) -> GeneratedKitchen | str:
        try:
            layout = generate_kitchen_layout(layout_seed, difficulty, k)
        except LayoutError as exc:
            return f"layout: {exc}"
        xml = kitchen_layout_xml(layout)
        model = compile_kitchen(xml, layout)
        candidate = GeneratedKitchen(
            layout=layout,
            model=model,
            witness=(),
            rejections=(),
            xml_sha256=mjcf_sha256(xml),
            xml=xml,
            seconds=0.0,
            tries=0,
        )
        try:
            env = SceneKitchenEnv(candidate, kitchen_config(layout))
        except ValueError as exc:
            return f"env: {exc}"
        if env.initial_obstacles != layout.n_on_path:
            return f"{env.initial_obstacles} obstacles on the path, drew {layout.n_on_path}"
        solution = constructive_solution(env)
        env.close()
        if solution is None:
            return "the constructive solver left an obstacle"
        witness, tries = solution
        return replace(candidate, witness=witness, tries=tries)

    what = f"kitchen for layout_seed={layout_seed}, difficulty='{difficulty}'"
    kitchen, rejections = first_accepted(attempt, MAX_ATTEMPTS, what)
    return replace(kitchen, rejections=rejections, seconds=time.perf_counter() - t0)
