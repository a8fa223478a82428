"""``voot/GeneratedStorage-v0``: the conveyor on generated storage rooms (v1 rules).

``gym.make("voot/GeneratedStorage-v0", layout_seed=s, difficulty=d)`` gives the conveyor
packing task of ``voot/ConveyorPacking-v1`` (the same action, checks, reward, fixed picks
and two-stage feasibility) on the storage rooms generated from ``layout_seed`` at the
level ``difficulty`` (``"easy"``, ``"medium"`` or ``"hard"``;
:data:`voot.envs.conveyor.generated.layout.DIFFICULTIES`): the rooms, their doors, the boxes'
count and sizes are drawn (:mod:`voot.envs.conveyor.generated.layout`), the loading region, the
workspace and ``n_objects`` follow from the layout, and the instance is proven solvable
before it is used (:mod:`voot.envs.conveyor.generated.witness`; its packing is
:meth:`ConveyorFamilyEnv.witness_actions`). Instances are cached per
``(layout_seed, difficulty)`` and generator version (:mod:`voot.envs.conveyor.generated.instance`).
Its first name, ``voot/ConveyorPacking-v2``, is an alias.

For learners (:class:`~voot.envs.core.family.LayoutFamily`): one observation space for
every layout and level (:data:`MAX_OBJECTS` box slots and their mask), the layout chosen
at ``reset(options={"layout_seed": k})``, and a split mode (``split="training"`` or
``"heldout"``) that draws each reset's layout from the protocol's split.

Other keywords are :class:`~voot.envs.conveyor.config.ConveyorConfig` fields, as for v1
(``horizon``, ``precheck``...); the solvability proof holds for the default grasp and
planner settings (changing ``grasp_angle``, ``present_gap``, ``planner``... voids it).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.envs.conveyor.config import conveyor_config
from voot.envs.conveyor.generated.instance import (
    LAYOUT_FIELDS,
    SceneConveyorEnv,
    layout_config,
    storage_instance,
)
from voot.envs.conveyor.generated.layout import DIFFICULTIES, GENERATOR_VERSION, StorageLayout
from voot.envs.conveyor.generated.witness import Witness
from voot.envs.core.family import LayoutFamily
from voot.envs.core.generation import Rejection, reject_layout_fields, witness_arrays
from voot.envs.core.names import Difficulty

__all__ = ["MAX_OBJECTS", "ConveyorFamilyEnv", "witness_return"]

FloatArray = NDArray[np.float64]

#: The most boxes a generated storage layout's belt carries (its levels' most).
MAX_OBJECTS = max(level.boxes[1] for level in DIFFICULTIES.values())


class ConveyorFamilyEnv(LayoutFamily, SceneConveyorEnv):
    """The conveyor packing task on a generated, solvable storage layout (module docstring).

    Args:
        layout_seed: The layout's seed (an integer >= 0; default 0, or the split's first).
        difficulty: ``"easy"``, ``"medium"`` or ``"hard"``
            (:class:`~voot.envs.core.names.Difficulty`).
        render_mode: None or ``"rgb_array"``.
        render_camera: ``"perspective"`` or ``"top_down"`` (framed on the layout).
        render_size: ``(width, height)`` of rendered images.
        split: None (one layout, or the one a reset's options name), ``"training"`` or
            ``"heldout"``: each reset draws a layout of that part of the protocol's split
            (:class:`~voot.envs.core.family.LayoutFamily`).
        **options: :class:`~voot.envs.conveyor.config.ConveyorConfig` fields overriding v1's,
            except those the layout sets (``loading_region``, ``workspace``,
            ``n_objects``).

    Attributes:
        layout: The accepted :class:`~voot.envs.conveyor.generated.layout.StorageLayout`.
        witness: The packing that proves it solvable.
        rejections: Why earlier draws of this seed were rejected (their count is the
            number of rejections).
    """

    MAX_OBJECTS = MAX_OBJECTS
    OBJECT_FIELDS = 5
    TAIL = 2
    LEVELS = tuple(DIFFICULTIES)
    GENERATOR_VERSION = GENERATOR_VERSION

    def _take_options(self, options: dict[str, Any]) -> None:
        for name in ("config", "preset"):
            if name in options:
                raise ValueError(
                    f"voot/GeneratedStorage-v0 takes no {name!r}: its config is v1's on the"
                    " generated layout (pass ConveyorConfig fields as keywords)"
                )
        # every keyword checked now, before any layout is generated or cached (the
        # layout's own fields are no option)
        reject_layout_fields(options, LAYOUT_FIELDS)
        conveyor_config("v1", **options)

    def _load_layout(self, layout_seed: int, difficulty: Difficulty) -> None:
        instance = storage_instance(layout_seed, difficulty)
        config = layout_config(instance.layout, **self._options)
        self.layout: StorageLayout = instance.layout
        self.witness: Witness = instance.witness
        self.rejections: tuple[Rejection, ...] = instance.rejections
        SceneConveyorEnv.__init__(
            self,
            instance.model_copy(),
            config,
            **self._render,
        )

    def solution_actions(self) -> list[FloatArray]:
        """The witness (:meth:`witness_actions`): the known solution of a generated instance."""
        return self.witness_actions()

    def witness_actions(self) -> list[FloatArray]:
        """The witness packing as normalised actions: from a reset, they pack every box
        (with the default grasp and planner settings)."""
        return witness_arrays(self.witness.actions)


def witness_return(env: ConveyorFamilyEnv, gamma: float = 1.0) -> float:
    """The (discounted) return of the witness packing executed from a reset of ``env``."""
    env.reset(seed=0)
    total = 0.0
    for k, a in enumerate(env.witness_actions()):
        _, reward, _, _, _ = env.step(a)
        total += math.pow(gamma, k) * float(reward)
    return total
