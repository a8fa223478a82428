"""The kitchen's task record, what records an episode can reach, and its rewards.

:class:`KitchenTask` is the immutable progress of an episode of
:class:`~voot.envs.kitchen.env.KitchenClearingEnv` (part of every snapshot): steps taken, the
next operator, the held object and its grasp, the obstacles left on the path.
:func:`task_error` says what no episode reaches in a record, which
:meth:`~voot.envs.core.env.ManipulationEnv.set_state` asks before it restores a snapshot
(a wrong index would otherwise fail deep in the next step, or handle the wrong object).
:func:`pick_reward` and :func:`place_reward` are the reference page's rewards.

Apart from the env: the record, its invariants and the rewards are the task's rules,
checked here on plain values (no scene needed).
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass

from voot.envs.core.names import Operator
from voot.envs.core.state import is_count, is_finite_tuple
from voot.envs.kitchen.config import KitchenConfig
from voot.envs.robot.model import ARM_JOINTS


@dataclass(frozen=True)
class KitchenTask:
    """The task's progress (immutable; part of every snapshot).

    Attributes:
        steps: Steps taken in this episode (feasible or not).
        operator: The next operator, ``"pick"`` or ``"place"``.
        held: Index of the object in the gripper, or -1.
        held_rel: The held object's body pose ``(x, y, yaw)`` in the base frame.
        grasp_q: The arm's joint values holding it.
        on_path: Objects on the path, in handling order (the next pick is the first).
        last_place_cleared: Whether the last place reduced the number of obstacles.
        done: The path is clear (terminated).
    """

    steps: int
    operator: Operator
    held: int
    held_rel: tuple[float, float, float]
    grasp_q: tuple[float, ...]
    on_path: tuple[int, ...]
    last_place_cleared: bool
    done: bool


def task_error(
    task: KitchenTask,
    n_objects: int,
    horizon: int,
    order: tuple[int, ...],
    rank: Mapping[int, int],
) -> str | None:
    """What no episode of a kitchen reaches in ``task``, or None.

    An episode alternates pick (nothing held: ``held`` -1, no grasp: ``held_rel``
    ``(0.0, 0.0, 0.0)`` and ``grasp_q`` ``()``) and place (``held`` an object index, its
    pose in the base frame and the arm's 7 joints finite); a place that cleared an
    obstacle (``last_place_cleared``) follows a pick, so comes at step 2 or later; the
    obstacles left are distinct objects in the handling ``order`` (``rank``: each
    object's position in it), and the episode is done exactly when none is left. The
    kitchen has ``n_objects`` objects and truncates after ``horizon`` steps.
    """
    n = n_objects
    if not is_count(task.steps, 0, horizon):
        return f"steps must be an int in 0..{horizon} (the horizon), got {task.steps!r}"
    if task.operator == Operator.PICK:
        if task.held != -1 or type(task.held) is not int:
            return f"held must be -1 before a pick (nothing in the gripper), got {task.held!r}"
        if (
            type(task.held_rel) is not tuple
            or task.held_rel != (0.0, 0.0, 0.0)
            or task.grasp_q != ()
        ):
            # what every pick-time record holds (reset and a place write these values)
            return (
                "held_rel and grasp_q must be (0.0, 0.0, 0.0) and () before a pick (no grasp),"
                f" got {task.held_rel!r} and {task.grasp_q!r}"
            )
    elif task.operator == Operator.PLACE:
        if not is_count(task.held, 0, n - 1):
            return f"held must be an object index in 0..{n - 1} before a place, got {task.held!r}"
        if not is_finite_tuple(task.held_rel, 3):
            return f"held_rel must be 3 finite numbers (x, y, yaw), got {task.held_rel!r}"
        if not is_finite_tuple(task.grasp_q, len(ARM_JOINTS)):
            return (
                f"grasp_q must be {len(ARM_JOINTS)} finite joint values at a place,"
                f" got {task.grasp_q!r}"
            )
    else:
        return f"operator must be 'pick' or 'place', got {task.operator!r}"
    on_path = task.on_path
    if type(on_path) is not tuple or any(type(i) is not int or i not in rank for i in on_path):
        return f"on_path must be a tuple of object indices in 0..{n - 1}, got {on_path!r}"
    if any(rank[a] >= rank[b] for a, b in itertools.pairwise(on_path)):
        return f"on_path must list distinct objects in the handling order {order}, got {on_path!r}"
    if type(task.last_place_cleared) is not bool or type(task.done) is not bool:
        return (
            "last_place_cleared and done must be bools, got"
            f" {task.last_place_cleared!r} and {task.done!r}"
        )
    if task.last_place_cleared and task.steps < 2:
        return f"last_place_cleared can be True only after a pick and a place, at step {task.steps}"
    if task.done != (not on_path):
        return f"done must be {not on_path} when on_path is {on_path!r}, got {task.done!r}"
    return None


def pick_reward(config: KitchenConfig, last_place_cleared: bool) -> float:
    """A feasible pick's reward: ``pick_reward`` after a place that cleared an obstacle, else 0."""
    return config.pick_reward if last_place_cleared else 0.0


def place_reward(config: KitchenConfig, cleared: bool, length: float) -> float:
    """A feasible place's reward from its base path's length ``length`` (``L``).

    ``min(1/L, max_place_reward)`` if the place cleared an obstacle (the cap if the
    robot did not move), else ``max(-L, -max_place_penalty)``.
    """
    if cleared:
        return (
            config.max_place_reward if length <= 0 else min(1.0 / length, config.max_place_reward)
        )
    return max(-length, -config.max_place_penalty)
