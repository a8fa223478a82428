"""The values an env's state is made of: snapshots, task records, step timings.

:class:`EnvState` is the immutable snapshot :meth:`~voot.envs.core.env.ManipulationEnv.get_state`
returns (physics, task record, generator state, and the :class:`SceneIdentity` of the scene
that produced it); :class:`StepTiming` the seconds a step
spent in its checks. The task records themselves are each env's own frozen dataclasses
(:class:`voot.envs.kitchen.task.KitchenTask`, :class:`voot.envs.conveyor.env.ConveyorTask`);
what they share lives here: :func:`replace`, a cheap copy with changes (the envs replace
their record at every step, and :func:`dataclasses.replace` costs a generic ``__init__``),
and the predicates their validation is written with (:func:`is_count`,
:func:`is_finite_tuple`), which :meth:`~voot.envs.core.env.ManipulationEnv.set_state`
applies through each env's ``_task_error`` before it accepts a snapshot. A step's info
carries poses as :func:`pose_tuple` makes them.

Apart from :mod:`voot.envs.core.env` so that the state's types and their checks can be
read, tested and imported (by planners, benchmarks) without the env machinery.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]

_PLAIN_DATACLASSES: dict[type, tuple[str, ...] | None] = {}


def replace(obj: Any, /, **changes: Any) -> Any:
    """:func:`dataclasses.replace`, minus its generic cost for plain dataclasses.

    A *plain* dataclass (every field an ``__init__`` argument, no ``__post_init__``, no
    slots, such as the task-progress records and :class:`StepTiming`) is copied field
    by field with the changes applied, which is what ``dataclasses.replace`` does through
    ``__init__``; anything else, or an unknown field name, goes to
    ``dataclasses.replace`` itself. The envs replace their task record at every step.
    """
    cls = type(obj)
    names = _PLAIN_DATACLASSES.get(cls, ())
    if names == ():
        names = _plain_fields(cls)
        _PLAIN_DATACLASSES[cls] = names
    state = obj.__dict__
    if names is None or len(state) != len(names) or not changes.keys() <= state.keys():
        return dataclasses.replace(obj, **changes)
    new = object.__new__(cls)
    new.__dict__.update(state)  # exactly the fields (as many, every change one of them)
    new.__dict__.update(changes)
    return new


def _plain_fields(cls: type) -> tuple[str, ...] | None:
    """The field names of a plain dataclass (see :func:`replace`), or None."""
    if not dataclasses.is_dataclass(cls) or hasattr(cls, "__post_init__"):
        return None
    if "__slots__" in cls.__dict__:
        return None
    fields = dataclasses.fields(cls)
    if any(not f.init for f in fields) or len(fields) != len(cls.__dataclass_fields__):
        return None
    return tuple(f.name for f in fields)


_F64 = np.dtype(np.float64)


def is_count(value: object, low: int, high: int) -> bool:
    """Whether ``value`` is an ``int`` (not a bool) in ``low..high``: a task record's count
    or index, as the envs write them."""
    return type(value) is int and low <= value <= high


def is_finite_tuple(value: object, length: int) -> bool:
    """Whether ``value`` is a tuple of ``length`` finite real numbers (not bools).

    What a task record's poses and joint values are (the envs write Python floats).
    """
    if type(value) is not tuple or len(value) != length:
        return False
    for v in value:
        if type(v) is not float and (isinstance(v, bool) or not isinstance(v, int | float)):
            return False
        if not math.isfinite(v):
            return False
    return True


def path_tuple(waypoints: ArrayLike | None) -> tuple[tuple[float, ...], ...] | None:
    """A base path's waypoints ``(k, 3)`` as a tuple of pose tuples (for a step's ``info``;
    None stays None).

    A path's length varies from step to step: as an array it would give the info a shape
    of its own at every step, which gymnasium's vector envs cannot stack.
    """
    if waypoints is None:
        return None
    return tuple(tuple(p) for p in np.asarray(waypoints, dtype=np.float64).tolist())


def pose_tuple(pose: ArrayLike) -> tuple[float, float, float]:
    """An ``(x, y, theta)`` pose as a tuple of Python floats (for a step's ``info``).

    Tuples of floats are immutable, compare exactly and pickle small, which suits the
    step infos a tree search keeps for each of its nodes.
    """
    if type(pose) is np.ndarray and pose.dtype is _F64 and pose.shape == (3,):
        x, y, theta = pose.tolist()
        return x, y, theta
    x, y, theta = (float(v) for v in np.asarray(pose, dtype=np.float64).reshape(3))
    return x, y, theta


TaskT = TypeVar("TaskT")


@dataclass(frozen=True)
class SceneIdentity:
    """What produced a snapshot: the scene a state belongs to (and only to).

    Two envs take each other's states iff their identities are equal: the same family,
    version, layout, level and compiled scene. A state of another layout with as many
    objects has a physics vector of the right size, and would otherwise be accepted.

    Attributes:
        family: The env's family (``"kitchen"``, ``"conveyor"``; its class name if it
            declares none).
        version: The scene's version: a generated family's generator version
            (``"generator-1"``), ``""`` for a fixed scene (its v0 and v1 share it: a
            version's rules change what a step does, not what a state is).
        layout_seed: The generated layout's seed (None: a fixed scene).
        difficulty: The generated layout's level (None: a fixed scene).
        digest: A hash of the compiled scene (:func:`voot.envs.core.scene.model_digest`).
    """

    family: str
    version: str
    layout_seed: int | None
    difficulty: str | None
    digest: str

    def __str__(self) -> str:
        where = (
            "fixed scene"
            if self.layout_seed is None
            else (f"layout_seed={self.layout_seed}, difficulty={self.difficulty}")
        )
        version = f" {self.version}" if self.version else ""
        return f"{self.family}{version} ({where}, scene {self.digest[:12]})"


@dataclass(frozen=True, eq=False)
class EnvState(Generic[TaskT]):
    """An immutable snapshot of a :class:`ManipulationEnv`.

    Attributes:
        physics: The ``mj_getState`` vector (read-only float64 array).
        signature: Its ``mjtState`` signature (``mjSTATE_INTEGRATION``).
        task: The task's progress (an immutable dataclass of the environment).
        rng_state: The env's ``np_random`` bit-generator state.
        scene: The identity of the scene that produced it (:class:`SceneIdentity`);
            ``set_state`` refuses a state of another (None: a state made by hand, which
            no env takes).
    """

    physics: FloatArray
    signature: int
    task: TaskT
    rng_state: Mapping[str, Any]
    scene: SceneIdentity | None = None

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, EnvState)
            and self.signature == other.signature
            and np.array_equal(self.physics, other.physics)
            and self.task == other.task
            and self.rng_state == other.rng_state
            and self.scene == other.scene
        )

    __hash__ = None  # type: ignore[assignment]

    def with_task(self, task: TaskT) -> EnvState[TaskT]:
        """This snapshot with another task record, sharing the physics and generator state.

        What an action that changed only the task progress leads to (an infeasible one);
        built without the dataclass ``__init__`` (the other fields are this snapshot's).
        """
        out: EnvState[TaskT] = object.__new__(EnvState)
        out.__dict__.update(
            physics=self.physics,
            signature=self.signature,
            task=task,
            rng_state=self.rng_state,
            scene=self.scene,
        )
        return out


@dataclass(frozen=True)
class StepTiming:
    """Wall-clock seconds spent in the last step's checks (for :mod:`voot.bench.measure.env_speed`)."""

    ik: float = 0.0
    collision: float = 0.0
    planning: float = 0.0
    total: float = 0.0
