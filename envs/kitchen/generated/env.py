"""``voot/GeneratedKitchen-v0``: the object-clearing task in kitchens generated from a seed.

``gym.make("voot/GeneratedKitchen-v0", layout_seed=s, difficulty=d)`` builds the kitchen
:func:`~voot.envs.kitchen.generated.layout.generate_kitchen_layout` draws for ``(s, d)``
(a :class:`~voot.envs.core.names.Difficulty`: ``"easy"``, ``"medium"``, ``"hard"``;
:data:`~voot.envs.kitchen.generated.layout.DIFFICULTIES`), writes it as MJCF
(:mod:`voot.envs.kitchen.generated.scene`) and plays the v1 rules in it
(:data:`~voot.envs.kitchen.config.KITCHEN_PRESETS` ``"v1"``: two-stage feasibility, the
non-clearing penalty, the pick's base path) with the layout's start, sink pose, house and
forbidden rooms. Everything else is :class:`~voot.envs.kitchen.env.KitchenClearingEnv`.
Its first name, ``voot/KitchenClearing-v2``, is an alias.

For learners (:class:`~voot.envs.core.family.LayoutFamily`): one observation space for
every layout and level (:data:`MAX_OBJECTS` object slots and their mask), the layout
chosen at ``reset(options={"layout_seed": k})``, and a split mode
(``split="training"`` or ``"heldout"``) that draws each reset's layout from the
protocol's split.

**Every instance is solvable**: a scripted constructive solver
(:mod:`voot.envs.kitchen.generated.witness`) clears it through the env's own ``step``
before it is accepted, and its plan is :meth:`GeneratedKitchenEnv.witness_actions`.
Rejected attempts and the cache of accepted kitchens are
:mod:`voot.envs.kitchen.generated.instance`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.envs.core.family import LayoutFamily
from voot.envs.core.generation import reject_layout_fields, witness_arrays
from voot.envs.core.names import Difficulty
from voot.envs.core.presets import env_config
from voot.envs.kitchen.config import KITCHEN_PRESETS, KitchenConfig
from voot.envs.kitchen.generated.instance import (
    LAYOUT_FIELDS,
    SceneKitchenEnv,
    generated_kitchen,
    kitchen_config,
)
from voot.envs.kitchen.generated.layout import DIFFICULTIES, GENERATOR_VERSION

__all__ = ["MAX_OBJECTS", "GeneratedKitchenEnv"]

FloatArray = NDArray[np.float64]

#: The most objects a generated kitchen holds (obstacles and clutter at their levels' most).
MAX_OBJECTS = max(level.on_path[1] + level.clutter[1] for level in DIFFICULTIES.values())


class GeneratedKitchenEnv(LayoutFamily, SceneKitchenEnv):
    """The kitchen of ``(layout_seed, difficulty)`` under the v1 rules (module docstring).

    Args:
        layout_seed: The layout's seed (an int >= 0; default 0, or the split's first).
        difficulty: The level (:data:`~voot.envs.kitchen.generated.layout.DIFFICULTIES`).
        render_mode: None or ``"rgb_array"``.
        render_camera: ``"perspective"`` or ``"top_down"``.
        render_size: ``(width, height)`` of rendered images.
        split: None (one layout, or the one a reset's options name), ``"training"`` or
            ``"heldout"``: each reset draws a layout of that part of the protocol's split
            (:class:`~voot.envs.core.family.LayoutFamily`).
        **options: ``config``, the settings (a :class:`KitchenConfig`; default: the v1
            preset's; its start, goal, house and forbidden rooms are replaced by the
            layout's), and :class:`KitchenConfig` fields overriding the config's, except
            the layout's (``start``, ``goal``, ``house``, ``forbidden``). The witness and
            the solvability check hold for the v1 rules.
    """

    MAX_OBJECTS = MAX_OBJECTS
    OBJECT_FIELDS = 6
    TAIL = 3
    LEVELS = tuple(DIFFICULTIES)
    GENERATOR_VERSION = GENERATOR_VERSION

    def _take_options(self, options: dict[str, Any]) -> None:
        reject_layout_fields(options, LAYOUT_FIELDS)
        self._config: KitchenConfig | None = options.pop("config", None)
        # the whole config checked now, before any kitchen is generated or cached: the
        # layout's fields, set later, are no option
        env_config(KitchenConfig, KITCHEN_PRESETS, self._config, "v1", options)

    def _load_layout(self, layout_seed: int, difficulty: Difficulty) -> None:
        kitchen = generated_kitchen(layout_seed, difficulty)
        SceneKitchenEnv.__init__(
            self,
            kitchen,
            kitchen_config(kitchen.layout, self._config, **self._options),
            **self._render,
        )

    def solution_actions(self) -> list[FloatArray]:
        """The witness (:meth:`witness_actions`): the known solution of a generated instance."""
        return self.witness_actions()

    def witness_actions(self) -> list[FloatArray]:
        """The constructive solver's plan: normalised actions that clear the path from
        ``reset()`` (proof of solvability; a scripted solution for tests). Named as the
        generated storage rooms' (:mod:`voot.bench.protocol.difficulty` reads either)."""
        return witness_arrays(self.kitchen.witness)
