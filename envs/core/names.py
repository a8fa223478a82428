"""Typed names at the env seam: the values that were plain strings between an env and its
callers (difficulty levels, layout splits, operators, pre-check kinds, action units, why an action is
infeasible).

Each is a :class:`enum.StrEnum`, so a member equals, hashes and serialises (JSON) as its
string value: stores, hashes and keyword arguments written with the strings keep working,
and a string from a caller is checked by calling the enum (``Precheck("kinematic")``; a
bad one is a ValueError naming it). This module imports nothing heavy (no MuJoCo):
problem records use it at ``import voot``.
"""

from __future__ import annotations

from enum import StrEnum


def choices(kind: type[StrEnum]) -> str:
    """The values of ``kind``, for an error message (``"normalized, paper"``)."""
    return ", ".join(m.value for m in kind)


class Difficulty(StrEnum):
    """A level of a generated task family, from the easiest."""

    EASY = "easy"
    MEDIUM = "medium"
    HARD = "hard"


class Split(StrEnum):
    """A part of a generated family's layouts: those a learner or a tuner trains on, or
    the held-out ones it is evaluated on (never trained on)."""

    TRAINING = "training"
    HELDOUT = "heldout"


class Operator(StrEnum):
    """The operator of an action: what the node of the task tree asks the robot to do."""

    PICK = "pick"
    PLACE = "place"


class Precheck(StrEnum):
    """What a planner's pre-check of an action covers (a config's ``precheck``).

    ``FULL_STEP`` (v0): the whole step, so an infeasible draw is re-drawn before it costs a
    simulation; ``KINEMATIC`` (v1, the authors' two-stage protocol): the cheap kinematic
    checks only, the rest is found by the step.
    """

    FULL_STEP = "full_step"
    KINEMATIC = "kinematic"


class Units(StrEnum):
    """The units of a planner's actions: ``[-1, 1]`` boxes, or the parameters' own ranges."""

    NORMALIZED = "normalized"
    PAPER = "paper"


class Reason(StrEnum):
    """Why an action is infeasible: the code beside a step info's ``reason`` text.

    A step's info has ``reason`` (a sentence for a reader, with the objects' names) and
    ``reason_code`` (one of these; ``NONE`` for a feasible action), so that callers count
    and compare failures by code, never by parsing the text. Each value is the head of its
    texts (``"collision: robot-wall"`` has code ``"collision"``).
    """

    NONE = ""
    OUTSIDE_REGION = "outside region"
    COLLISION = "collision"
    IK_FAILED = "IK failed"
    CARRY_FOOTPRINT = "carry footprint"
    FORBIDDEN_ROOM = "forbidden room"
    NO_BASE_PATH = "no base path"
    NO_BASE_PATH_TO_PICK = "no base path to the pick"
    PENALTY_CAP = "non-clearing place at the penalty cap"
    GRASP_MISSES = "grasp misses the object"


class Failure(str):
    """Why an action is infeasible: the text a reader sees (the ``str`` value), with its
    :class:`Reason` code (:attr:`code`).

    The checks return one where they find the failure (``""`` when the action passes), so
    the step info's ``reason`` and ``reason_code`` come from the same place and no code
    is ever read back out of the text.
    """

    code: Reason

    def __new__(cls, code: Reason, text: str) -> Failure:
        self = super().__new__(cls, text)
        self.code = Reason(code)
        return self

    def __reduce__(self) -> tuple[type[Failure], tuple[Reason, str]]:
        return (Failure, (self.code, str(self)))

    def prefixed(self, prefix: str) -> Failure:
        """The same failure with ``prefix`` before its text (which box of an action ...)."""
        return Failure(self.code, prefix + str(self))


def reason_code(reason: str) -> Reason:
    """The code of a check's answer: ``Reason.NONE`` for ``""`` (it passes), else the
    :class:`Failure`'s code.

    Raises:
        TypeError: a non-empty reason that is not a :class:`Failure` (a check that lost
            its code).
    """
    if not reason:
        return Reason.NONE
    if not isinstance(reason, Failure):
        raise TypeError(f"an infeasible action's reason must be a Failure, got {reason!r}")
    return reason.code
