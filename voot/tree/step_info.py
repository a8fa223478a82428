"""The step info at the seam between environments and what reads them, as one typed record.

A :class:`~voot.tree.problem.StepResult` carries the environment's ``info`` mapping
(gymnasium wants a dict). The keys that the recorder, the benchmark and the demo read are
the contract of voot's environments with them; :class:`StepInfo` names that contract
once, with types, and reads it from any info (:meth:`StepInfo.of`): a key an environment
does not publish is None or empty, never a ``KeyError`` far from its cause. voot's robot
environments publish every key of :data:`CORE_KEYS` in every step's info (a test checks
each of them); ``object`` and ``base_path`` are the kitchen's, ``base_poses`` and
``placements`` the conveyor's.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import numpy as np

#: An ``(x, y, theta)`` pose.
Pose = tuple[float, float, float]


def pose(value: Any) -> Pose | None:
    """``value`` (three finite numbers, in any shape) as an ``(x, y, theta)`` tuple, or None."""
    if value is None:
        return None
    try:
        a = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        return None
    if a.size != 3 or not np.all(np.isfinite(a)):
        return None
    return (float(a[0]), float(a[1]), float(a[2]))


def _poses(value: Any) -> tuple[Pose, ...]:
    if not isinstance(value, Sequence) or isinstance(value, str):
        return ()
    out = tuple(pose(v) for v in value)
    return tuple(p for p in out if p is not None)


@dataclass(frozen=True)
class StepInfo:
    """What one action did, as the readers of a step's info see it.

    Attributes:
        feasible: whether the action was feasible (default True when not published).
        reason: why it was infeasible (``""`` if feasible), a sentence for a reader.
        reason_code: the code of that reason (``""`` if feasible; voot's envs publish a
            :class:`voot.envs.core.names.Reason`, equal to its string): what a caller
            counts or compares, instead of parsing the text.
        operator: the operator of the action (``"pick"``, ``"place"``), or None.
        object: the object it handled (a kitchen action), or None.
        next_operator: the operator of the next action, or None.
        objects_left: objects still to handle after it, or None.
        goal_bonus: the goal bonus it earned (0 if none).
        base_pose: the robot base of the action ``(x, y, theta)``, or None.
        placement: the placed object's pose, or None (a pick).
        base_poses, placements: the same for every object of the action (conveyor).
        base_path: the base path's waypoints ``(k, 3)`` if one was planned, else None.
    """

    feasible: bool = True
    reason: str = ""
    reason_code: str = ""
    operator: str | None = None
    object: str | None = None
    next_operator: str | None = None
    objects_left: int | None = None
    goal_bonus: float = 0.0
    base_pose: Pose | None = None
    placement: Pose | None = None
    base_poses: tuple[Pose, ...] = ()
    placements: tuple[Pose, ...] = ()
    base_path: Any = None

    #: The info keys of the contract (the field names).
    KEYS: ClassVar[tuple[str, ...]]

    @classmethod
    def of(cls, info: Mapping[str, Any]) -> StepInfo:
        """The record of ``info`` (missing or malformed keys take their defaults)."""
        left = info.get("objects_left")
        return cls(
            feasible=bool(info.get("feasible", True)),
            reason=str(info.get("reason") or ""),
            reason_code=info.get("reason_code") or "",
            operator=_text(info.get("operator")),
            object=_text(info.get("object")),
            next_operator=_text(info.get("next_operator")),
            objects_left=int(left)
            if isinstance(left, int | float) and math.isfinite(left)
            else None,
            goal_bonus=float(info.get("goal_bonus") or 0.0),
            base_pose=pose(info.get("base_pose")),
            placement=pose(info.get("placement")),
            base_poses=_poses(info.get("base_poses")),
            placements=_poses(info.get("placements")),
            base_path=info.get("base_path"),
        )


StepInfo.KEYS = tuple(f.name for f in fields(StepInfo))
#: The keys every robot environment's step info has.
CORE_KEYS: tuple[str, ...] = (
    "feasible",
    "reason",
    "reason_code",
    "operator",
    "next_operator",
    "objects_left",
    "goal_bonus",
    "base_pose",
    "placement",
)


def _text(value: Any) -> str | None:
    return None if value is None else str(value)
