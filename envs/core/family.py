"""A generated family as one environment a learner trains across: layouts chosen at reset.

A generated family's env (:mod:`voot.envs.kitchen.generated.env`,
:mod:`voot.envs.conveyor.generated.env`) is made on one layout, ``(layout_seed,
difficulty)``; :class:`LayoutFamily`, mixed in before the family's scene env, adds what a
learner needs to span the family with one env (or one vector env):

* **one observation space per family**: the fixed envs' observation (the robot base, a
  block of numbers per object, a few task numbers) with the objects padded to the
  family's most (:attr:`LayoutFamily.MAX_OBJECTS`) and a mask, one entry per object slot
  (1.0: the slot holds an object of this layout), at the end. The same ``Box`` for every
  layout and level, so a flat-vector policy (SB3's ``MlpPolicy``) and gymnasium's vector
  envs take it as it is; a ``Dict`` space would say the same with names but needs a
  policy that reads dictionaries, for no information the flat layout lacks
  (:meth:`LayoutFamily.observation_layout` names the slices);
* **the layout chosen at reset**: ``reset(seed=s, options={"layout_seed": k})`` (and
  ``"difficulty"``) rebuilds the env on layout ``k``, bit-identical to an env made with
  ``layout_seed=k`` and reset with ``seed=s``;
* **a split mode**: made with ``split="training"`` or ``split="heldout"``, every reset
  without a ``layout_seed`` option draws a layout of that part of the family's split
  (:data:`voot.envs.core.generation.PROTOCOL_SPLIT`: the protocol's training layouts
  1000-1019, held-out 0-19), deterministically from the reset's seed (a stream of its
  own: the env's ``np_random`` is untouched, so the episode is the one of an env made
  on that layout); an explicit ``layout_seed`` must be one of the split's;
* **the layout in every info**: ``info["layout_seed"]`` and ``info["difficulty"]``, the
  reset's and every step's (the keys of every info stay the same).

Generation stays off the step's hot path: a new layout is generated (or loaded) at the
reset that asks for it, never in ``step``, and kept by the family's instance cache, so a
later reset onto it only rebuilds the env on the cached model (docs/environments.md has
the measured costs).
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V
from voot.envs.core.arguments import (
    check_difficulty,
    check_layout_seed,
    check_render,
    check_split,
)
from voot.envs.core.caches import mujoco_cache_bytes
from voot.envs.core.names import Difficulty, Split
from voot.envs.core.rendering import RenderOptions
from voot.envs.core.scene import model_digest
from voot.envs.core.splits import PROTOCOL_SPLIT, LayoutSplit
from voot.envs.core.state import SceneIdentity

__all__ = ["RESET_OPTIONS", "LayoutFamily"]

FloatArray = NDArray[np.float64]

#: The options a generated family's ``reset`` takes.
RESET_OPTIONS = ("layout_seed", "difficulty")
#: Tag of the split's random stream (ASCII "splt"): apart from every other seeded draw.
_SPLIT_STREAM = 0x73706C74


class LayoutFamily:
    """Mixin of a generated family's env (see the module docstring).

    The env class lists it first (``class GeneratedKitchenEnv(LayoutFamily,
    SceneKitchenEnv)``), sets the class attributes below, and implements
    :meth:`_load_layout`, which (re)builds the env on a layout, and, if it checks its
    keywords, :meth:`_take_options`; the mixin's ``__init__`` is the env's.
    """

    #: The most objects a layout of the family holds: the observation's object slots.
    MAX_OBJECTS: ClassVar[int]
    #: Observation entries per object (the fixed env's block).
    OBJECT_FIELDS: ClassVar[int]
    #: Observation entries before the objects (the robot base).
    HEAD: ClassVar[int] = 4
    #: Observation entries after the objects (the task's numbers).
    TAIL: ClassVar[int]
    #: The family's difficulty levels (its levels' table's keys).
    LEVELS: ClassVar[Collection[Difficulty]]
    #: The family's split of layout seeds (the protocol's).
    LAYOUT_SPLIT: ClassVar[LayoutSplit] = PROTOCOL_SPLIT
    #: The version of the family's generator (part of every state's identity).
    GENERATOR_VERSION: ClassVar[int]

    # set by the scene env this is mixed into
    family: ClassVar[str]
    model: Any
    objects: Any
    observation_space: Any
    action_space: Any
    layout: Any
    np_random: np.random.Generator

    def __init__(
        self,
        layout_seed: int | None = None,
        difficulty: str = "easy",
        render_mode: str | None = None,
        render_camera: str = "perspective",
        render_size: tuple[int, int] = (640, 480),
        split: str | None = None,
        **options: Any,
    ) -> None:
        """Check every argument, then build the env on its first layout: ``layout_seed``
        (default: 0, or the split's first layout in split mode). ``options`` (the env's
        config keywords, checked by :meth:`_take_options`) and the render arguments are
        kept for every layout the env is built on.

        Every argument is checked (:mod:`voot.envs.core.arguments`) before any layout is
        generated, looked up in a cache or written to one: a refused call changes nothing.
        """
        options = dict(options)
        level = check_difficulty(difficulty, self.LEVELS)
        self.split: Split | None = check_split(split)
        self._split_seeds: tuple[int, ...] = (
            () if self.split is None else self.LAYOUT_SPLIT.seeds(self.split)
        )
        if layout_seed is None:
            seed = self._split_seeds[0] if self._split_seeds else 0
        else:
            seed = self._split_layout(layout_seed)
        mode, camera, size = check_render(render_mode, render_camera, render_size)
        mujoco_cache_bytes()  # a bad $VOOT_MUJOCO_CACHE_MB, refused before any generation
        self._take_options(options)  # before the (costly, cached) generation
        self._options: dict[str, Any] = options
        self._render = RenderOptions(render_mode=mode, render_camera=camera, render_size=size)
        self._split_rng: np.random.Generator | None = None
        self._build(seed, level)

    # ----- to implement --------------------------------------------------------------------
    def _take_options(self, options: dict[str, Any]) -> None:
        """Check the env's keywords (a ValueError names a refused one) and take out those
        the family reads itself; the rest are config fields. Called before any layout is
        generated: it must check every keyword without one (a config built without the
        layout's fields)."""

    def _load_layout(self, layout_seed: int, difficulty: Difficulty) -> None:
        """(Re)build the env on the accepted instance of ``(layout_seed, difficulty)``, as
        the family's ``__init__`` builds it (with ``self._options`` and ``self._render``)."""
        raise NotImplementedError

    def _scene_identity(self) -> SceneIdentity:
        """The scene env's identity with the layout's seed and level and the generator's
        version: a state of another layout is refused even where its sizes fit."""
        return SceneIdentity(
            family=self.family or type(self).__name__,
            version=f"generator-{self.GENERATOR_VERSION}",
            layout_seed=int(self.layout.layout_seed),
            difficulty=str(self.layout.difficulty),
            digest=model_digest(self.model),
        )

    def _split_layout(self, layout_seed: object) -> int:
        """``layout_seed`` checked (and, in split mode, one of the split's)."""
        seed = check_layout_seed(layout_seed)
        if self._split_seeds and seed not in self._split_seeds:
            raise ValueError(
                f"layout_seed {seed} is not a {self.split} layout of this env's split"
                f" ({self._split_seeds[0]}..{self._split_seeds[-1]}, {len(self._split_seeds)}"
                " layouts); make the env without split= to use any layout"
            )
        return seed

    def _build(self, layout_seed: int, difficulty: Difficulty) -> None:
        kept_action = getattr(self, "action_space", None)
        kept_observation = getattr(self, "observation_space", None)
        self._load_layout(layout_seed, difficulty)
        if kept_action is not None and kept_action == self.action_space:
            # the same space on every layout: keep the object, and with it a generator
            # the user seeded (env.action_space.seed(...)) across layout changes
            self.action_space = kept_action
        n = len(self.objects)
        if n > self.MAX_OBJECTS:  # pragma: no cover - the levels' tables bound it
            raise RuntimeError(f"{n} objects, more than the family's {self.MAX_OBJECTS}")
        head, fields, tail, most = self.HEAD, self.OBJECT_FIELDS, self.TAIL, self.MAX_OBJECTS
        size = head + most * fields + tail + most
        #: Where the fixed env's observation entries go in the padded one.
        self._obs_index = np.concatenate(
            [
                np.arange(head + n * fields),
                np.arange(head + most * fields, head + most * fields + tail),
            ]
        )
        template = np.zeros(size)
        template[size - most : size - most + n] = 1.0
        self._obs_template = template
        space = gym.spaces.Box(-50.0, 50.0, shape=(size,), dtype=np.float64)
        same = kept_observation is not None and kept_observation == space
        self.observation_space = kept_observation if same else space
        self._layout_info = {
            "layout_seed": int(self.layout.layout_seed),
            "difficulty": str(self.layout.difficulty),
        }

    def observation_layout(self) -> dict[str, slice]:
        """The padded observation's parts by name: ``base`` (x, y, cos, sin of the robot
        base), ``objects`` (:attr:`MAX_OBJECTS` blocks of :attr:`OBJECT_FIELDS`, the fixed
        env's per-object numbers, zeros in an empty slot), ``task`` (the fixed env's last
        numbers) and ``mask`` (1.0 per slot that holds an object)."""
        head, fields, tail, most = self.HEAD, self.OBJECT_FIELDS, self.TAIL, self.MAX_OBJECTS
        objects_end = head + most * fields
        return {
            "base": slice(0, head),
            "objects": slice(head, objects_end),
            "task": slice(objects_end, objects_end + tail),
            "mask": slice(objects_end + tail, objects_end + tail + most),
        }

    # ----- the layout ----------------------------------------------------------------------
    @property
    def layout_seed(self) -> int:
        """The current layout's seed."""
        return int(self.layout.layout_seed)

    @property
    def difficulty(self) -> Difficulty:
        """The current layout's level."""
        return Difficulty(self.layout.difficulty)

    def _next_layout(self, seed: int | None, options: Mapping[str, Any]) -> tuple[int, Difficulty]:
        """The layout a reset with ``seed`` and ``options`` goes to (module docstring)."""
        unknown = sorted(set(options) - set(RESET_OPTIONS))
        if unknown:
            raise ValueError(
                f"reset takes the options {', '.join(RESET_OPTIONS)}; got {', '.join(unknown)}"
            )
        level = check_difficulty(options.get("difficulty", self.difficulty), self.LEVELS)
        if "layout_seed" in options:
            return self._split_layout(options["layout_seed"]), level
        if not self._split_seeds:
            return self.layout_seed, level
        if seed is not None:
            self._split_rng = np.random.default_rng([_SPLIT_STREAM, seed])
        elif self._split_rng is None:
            self._split_rng = np.random.default_rng()
        pick = int(self._split_rng.integers(len(self._split_seeds)))
        return self._split_seeds[pick], level

    # ----- gymnasium API -------------------------------------------------------------------
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[FloatArray, dict[str, Any]]:
        """Back to a layout's initial configuration: the current one, the one ``options``
        name (``layout_seed``, ``difficulty``) or, in split mode, one drawn from the
        split by ``seed`` (module docstring). Checked before anything changes."""
        if options is not None and not isinstance(options, Mapping):
            raise ValueError(f"reset options must be a mapping or None, got {options!r}")
        seed = V.optional_integer(seed, "seed", low=0)
        target = self._next_layout(seed, options or {})
        if target != (self.layout_seed, self.difficulty):
            self.close()  # type: ignore[attr-defined]  # the renderer holds the old model
            self._build(*target)
        return super().reset(seed=seed)  # type: ignore[misc, no-any-return]

    def _observation(self) -> FloatArray:
        """The fixed env's observation with the objects padded and the mask (module
        docstring)."""
        out = self._obs_template.copy()
        out[self._obs_index] = super()._observation()  # type: ignore[misc]
        return out

    def _info_reset(self) -> dict[str, Any]:
        info: dict[str, Any] = super()._info_reset()  # type: ignore[misc]
        info.update(self._layout_info)
        return info

    def transition(self, action: ArrayLike) -> tuple[float, bool, bool, dict[str, Any]]:
        """The scene env's transition, the layout added to its info."""
        reward, terminated, truncated, info = super().transition(action)  # type: ignore[misc]
        info.update(self._layout_info)
        return reward, terminated, truncated, info
