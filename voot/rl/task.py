r"""One planning problem instance as a reinforcement-learning task (a gymnasium wrapper).

The paper's RL baselines learn on the *same* problem the tree search plans in: one
initial state (the env reset with the run's seed), the same rewards, the same end of a
rollout. :class:`PlanningTask` turns a made env into that task:

* **one initial state**: the env is reset with the run's seed once and snapshotted
  (``unwrapped.get_state()``) with its observation and info; every later ``reset``
  resets the wrapped env with that same seed (so every wrapper's counters, e.g.
  gymnasium's ``TimeLimit`` and ``OrderEnforcing``, start afresh) and then restores the
  snapshot (physics, task progress and the env's generator), and returns the stored
  observation and info. The seed SB3 passes to ``reset`` is ignored: the task has one
  initial state;
* **an infeasible step ends the episode** (``terminated=True``), as it ends a tree
  rollout with its penalty (the voot robot envs report it in ``info["feasible"]`` and,
  unlike the chains, do not end the episode themselves);
* **the agent learns the tree's objective** :math:`r + b` (reward plus goal bonus, what
  the tree backs up), while the **reported return excludes the bonus**
  (:func:`reward_parts`), as the tree's ``best_so_far`` does;
* **it counts env steps** (:attr:`PlanningTask.n_steps`: every ``step`` call is one
  simulator call; resets are not counted) and **keeps the best trajectory** found so
  far: the discounted return :math:`\sum_t \gamma^t r_t` (goal bonus excluded) of every
  *finished* episode (ended by a terminal state, an infeasible step or truncation), its
  ``objects_left`` at the last step, and the step count at which it improved
  (:attr:`PlanningTask.improvements`).

This is the tree's definition (``best_return_over="leaves"``, the default of
:class:`~voot.tree.MCTSConfig`): the maximum over paths from the root to a leaf, and a
tree simulation always runs to a terminal state, an infeasible action or the depth
limit. An episode cut by the end of the training budget is unfinished and does not
count. Before the first episode finishes the best is the empty plan's return, 0.0 (the
tree's root is its only leaf before the first simulation): :data:`EMPTY_PLAN_RETURN`.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import numpy as np

from voot import validation as V

#: The best return before any episode has finished: the empty plan's (the tree's root).
EMPTY_PLAN_RETURN = 0.0
#: Step-info key of the objects still to handle (voot's robot envs).
OBJECTS_KEY = "objects_left"
#: Step-info key of a goal bonus reported *apart from* the reward (voot's robot envs).
GOAL_BONUS_KEY = "goal_bonus"
#: Step-info key of a bonus *included in* the reward (voot's chain envs).
INCLUDED_BONUS_KEY = "bonus"


def reward_parts(reward: float, info: Mapping[str, Any]) -> tuple[float, float]:
    """``(reward without bonus, bonus)`` of one step, by the envs' two conventions.

    The robot envs report the goal bonus apart (``info["goal_bonus"]``, not in the
    reward); the chain envs include their bonus in the reward and say how much it is
    (``info["bonus"]``). Any other env has no bonus.
    """
    bonus = info.get(GOAL_BONUS_KEY)
    if isinstance(bonus, int | float) and not isinstance(bonus, bool):
        return float(reward), float(bonus)
    included = info.get(INCLUDED_BONUS_KEY)
    if isinstance(included, int | float) and not isinstance(included, bool):
        return float(reward) - float(included), float(included)
    return float(reward), 0.0


@dataclass(frozen=True)
class Improvement:
    """The best return improved at env step ``step`` (1-based count of steps so far)."""

    step: int
    best: float
    objects_left: float | None


class PlanningTask(gym.Wrapper[Any, Any, Any, Any]):
    """A made env as one fixed-start RL task (see the module docstring).

    Args:
        env: a made env (``gymnasium.make(...)``) whose unwrapped env has
            ``get_state()``/``set_state()``.
        seed: the run's seed: the env is reset with it (here and at every episode).
        gamma: the problem's discount, for the reported returns.
        max_episode_steps: truncate an episode after this many steps (None: only where
            the env ends it, as the tree's rollouts).

    Raises:
        ValueError: the env cannot be snapshotted, or a bad argument.
    """

    def __init__(
        self,
        env: gym.Env[Any, Any],
        seed: int,
        gamma: float,
        max_episode_steps: int | None = None,
    ) -> None:
        super().__init__(env)
        u: Any = env.unwrapped
        if not (
            callable(getattr(u, "get_state", None)) and callable(getattr(u, "set_state", None))
        ):
            raise ValueError(
                f"{type(u).__name__} has no get_state()/set_state(): an RL task restores one"
                " initial state at every episode"
            )
        self.seed_value = V.integer(seed, "seed", 0)
        self.gamma = V.number(gamma, "gamma", 0.0, 1.0)
        self.max_episode_steps = V.optional_integer(max_episode_steps, "max_episode_steps", 1)
        obs, info = env.reset(seed=self.seed_value)
        self._obs0 = np.array(obs, copy=True)
        self._info0 = copy.deepcopy(dict(info))
        self._state0 = u.get_state()
        left = info.get(OBJECTS_KEY)
        #: Objects to handle at the initial state (None if the env does not say).
        self.objects_initial: float | None = (
            float(left) if isinstance(left, int | float) and math.isfinite(left) else None
        )
        #: Env steps taken (every ``step`` call; resets excluded).
        self.n_steps = 0
        #: Episodes finished.
        self.n_episodes = 0
        #: Best discounted return (goal bonus excluded) of a finished episode.
        self.best_return = EMPTY_PLAN_RETURN
        #: ``objects_left`` at the last step of the best episode (None: not reported yet).
        self.best_objects_left: float | None = None
        #: Every improvement of the best return, in step order.
        self.improvements: list[Improvement] = []
        self._found = False
        self._episode_return = 0.0
        self._discount = 1.0
        self._episode_steps = 0
        self._needs_reset = True

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Any, dict[str, Any]]:
        """Back to the task's one initial state (``seed`` is ignored, see the module)."""
        del seed
        self.env.reset(seed=self.seed_value, options=options)
        self.env.unwrapped.set_state(self._state0)  # type: ignore[attr-defined]
        self._episode_return, self._discount, self._episode_steps = 0.0, 1.0, 0
        self._needs_reset = False
        return self._obs0.copy(), copy.deepcopy(self._info0)

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        """One env step; an infeasible one ends the episode. The reward is :math:`r + b`."""
        if self._needs_reset:
            raise RuntimeError("the episode has ended (or not begun); call reset()")
        obs, reward, terminated, truncated, info = self.env.step(action)
        self.n_steps += 1
        self._episode_steps += 1
        r, bonus = reward_parts(float(reward), info)
        self._episode_return += self._discount * r
        self._discount *= self.gamma
        feasible = bool(info.get("feasible", True))
        terminated = bool(terminated) or not feasible
        truncated = bool(truncated) or (
            self.max_episode_steps is not None and self._episode_steps >= self.max_episode_steps
        )
        if terminated or truncated:
            self._finish(info)
        return obs, r + bonus, terminated, truncated and not terminated, info

    def _finish(self, info: Mapping[str, Any]) -> None:
        self.n_episodes += 1
        self._needs_reset = True
        g = self._episode_return
        if not self._found or g > self.best_return:
            self._found = True
            left = info.get(OBJECTS_KEY)
            objects = float(left) if isinstance(left, int | float) else None
            self.best_return, self.best_objects_left = g, objects
            self.improvements.append(Improvement(self.n_steps, g, objects))

    def best_at(self, step: int) -> tuple[float, float | None]:
        """``(best return, its objects_left)`` over the episodes finished within ``step``
        env steps (the empty plan's before the first)."""
        best, objects = EMPTY_PLAN_RETURN, None
        for imp in self.improvements:
            if imp.step > step:
                break
            best, objects = imp.best, imp.objects_left
        return best, objects
