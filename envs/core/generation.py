"""What the generated task families share: levels, seeds, the rejection loop, the cache.

Both generated families (:mod:`voot.envs.kitchen.generated`,
:mod:`voot.envs.conveyor.generated`) are one pipeline, one module a step: ``layout`` (a
frozen record drawn from ``(layout_seed, difficulty, attempt)``, pure numpy) ->
``scene`` (its MJCF, :mod:`voot.envs.assets.mjcf`, and the compiled model) ->
``witness`` (a planner-independent solution that proves the instance solvable) ->
``instance`` (generation with rejections, the accepted record, its cache) -> ``env``
(the gymnasium env of ``(layout_seed, difficulty)``). This module holds the steps'
common parts:

* :func:`parse_difficulty` and :func:`check_layout_seed`: the two arguments, checked
  the same way in both families (:mod:`voot.envs.core.arguments`, re-exported here);
* :func:`level_table`: a family's levels from a table of each field's value per level;
* :func:`first_accepted`: draw attempts 0, 1, ... of a seed until one is accepted, and
  keep why the others were rejected (:class:`Rejection`);
* :class:`GeneratedInstance`: the accepted instance (layout, compiled model, witness,
  rejections, the MJCF's hash);
* :class:`InstanceCache`: the instances kept in this process (least recently used
  forgotten past a size);
* :func:`reject_layout_fields` and :func:`witness_arrays`: the envs' shared checks;
* :class:`LayoutSplit` and :data:`PROTOCOL_SPLIT` (defined in :mod:`voot.envs.core.splits`,
  light enough for the problem records, and re-exported here): a family's training and
  held-out layout seeds.

No MuJoCo import: layouts use this module and stay pure numpy.
"""

from __future__ import annotations

import copy
from collections import OrderedDict
from collections.abc import Callable, Collection, Hashable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Generic, NamedTuple, TypeVar

import numpy as np
from numpy.typing import NDArray

from voot.envs.core.arguments import check_difficulty, check_layout_seed
from voot.envs.core.names import Difficulty
from voot.envs.core.splits import HELDOUT_LAYOUTS, PROTOCOL_SPLIT, TRAINING_LAYOUTS, LayoutSplit

if TYPE_CHECKING:
    import mujoco

__all__ = [
    "HELDOUT_LAYOUTS",
    "PROTOCOL_SPLIT",
    "TRAINING_LAYOUTS",
    "GeneratedInstance",
    "InstanceCache",
    "LayoutSplit",
    "Rejection",
    "check_layout_seed",
    "first_accepted",
    "level_table",
    "parse_difficulty",
    "reject_layout_fields",
    "witness_arrays",
]

FloatArray = NDArray[np.float64]
LayoutT = TypeVar("LayoutT")
WitnessT = TypeVar("WitnessT")
KeyT = TypeVar("KeyT", bound=Hashable)
ValueT = TypeVar("ValueT")
T = TypeVar("T")


def parse_difficulty(difficulty: object, levels: Collection[Difficulty]) -> Difficulty:
    """``difficulty`` as one of ``levels``: :func:`voot.envs.core.arguments.check_difficulty`.

    Raises:
        ValueError: Not one of ``levels`` by its exact name (the message names them).
    """
    return check_difficulty(difficulty, levels)


def level_table(
    level: Callable[..., T], columns: Mapping[str, Sequence[Any]]
) -> Mapping[Difficulty, T]:
    """A family's difficulty levels from a table: ``level(**fields)`` per :class:`Difficulty`.

    ``columns`` maps each field to its values at every level, easiest first (as the
    families' docstrings tabulate them), so the levels read side by side, field by field;
    a field left out keeps its default. The mapping is read-only, easiest level first.

    Raises:
        ValueError: A field without exactly one value per level.
    """
    levels = tuple(Difficulty)
    for name, values in columns.items():
        if len(values) != len(levels):
            raise ValueError(f"{name}: {len(values)} values for the {len(levels)} levels")
    return MappingProxyType(
        {
            d: level(**{name: values[k] for name, values in columns.items()})
            for k, d in enumerate(levels)
        }
    )


class Rejection(NamedTuple):
    """Why an attempt of a seed was rejected (it compares equal to ``(attempt, reason)``)."""

    attempt: int
    reason: str

    def __str__(self) -> str:
        return f"attempt {self.attempt}: {self.reason}"


def first_accepted(
    attempt: Callable[[int], T | str], max_attempts: int, what: str
) -> tuple[T, tuple[Rejection, ...]]:
    """The first of attempts ``0, 1, ...`` that ``attempt`` accepts, and the rejections.

    ``attempt(k)`` draws, builds and checks attempt ``k`` of a seed and returns what it
    accepted, or the reason (a string) it rejected it; each family's attempt streams are
    derived from the seed, so the outcome is deterministic.

    Raises:
        RuntimeError: None of ``max_attempts`` was accepted (``what`` names the seed).
    """
    rejections: list[Rejection] = []
    for k in range(max_attempts):
        out = attempt(k)
        if isinstance(out, str):
            rejections.append(Rejection(k, out))
            continue
        return out, tuple(rejections)
    raise RuntimeError(
        f"no solvable {what} in {max_attempts} attempts: {'; '.join(map(str, rejections[-3:]))}"
    )


@dataclass(frozen=True, eq=False)
class GeneratedInstance(Generic[LayoutT, WitnessT]):
    """An accepted generated instance.

    Attributes:
        layout: The layout (its ``attempt`` is the accepted draw).
        model: The compiled scene; an env loads a copy (:meth:`model_copy`): it may
            change its model's collision filters.
        witness: The family's proof that the instance is solvable.
        rejections: Why each earlier attempt of the seed was rejected.
        xml_sha256: Hash of the scene's MJCF (:func:`voot.envs.assets.mjcf.mjcf_sha256`).
    """

    layout: LayoutT
    model: mujoco.MjModel
    witness: WitnessT
    rejections: tuple[Rejection, ...]
    xml_sha256: str

    def model_copy(self) -> mujoco.MjModel:
        """A private copy of :attr:`model`."""
        return copy.copy(self.model)


class InstanceCache(Generic[KeyT, ValueT]):
    """The instances made in this process, by key (the least recently used one is
    forgotten past :attr:`size`; ``None``: never)."""

    def __init__(self, size: int | None) -> None:
        self.size = size
        self._items: OrderedDict[KeyT, ValueT] = OrderedDict()

    def __len__(self) -> int:
        return len(self._items)

    def clear(self) -> None:
        """Forget every instance."""
        self._items.clear()

    def get_or_make(self, key: KeyT, make: Callable[[], ValueT]) -> ValueT:
        """The instance kept for ``key``, else ``make()`` (then kept)."""
        hit = self._items.get(key)
        if hit is not None:
            self._items.move_to_end(key)
            return hit
        value = make()
        self._items[key] = value
        while self.size is not None and len(self._items) > self.size:
            self._items.popitem(last=False)
        return value


def reject_layout_fields(options: Mapping[str, Any], fields: Iterable[str]) -> None:
    """A ValueError if ``options`` (an env's keywords) set a field the layout sets."""
    fixed = sorted(set(fields) & set(options))
    if fixed:
        raise ValueError(
            f"{', '.join(fixed)} come from the generated layout; choose another layout_seed"
            " or difficulty instead"
        )


def witness_arrays(actions: Sequence[Sequence[float]]) -> list[FloatArray]:
    """A witness plan's actions as fresh float arrays (what an env's step takes)."""
    return [np.array(a, dtype=np.float64) for a in actions]
