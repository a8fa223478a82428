"""Planning problems shared by the tree and sampling-based planners' tests (not a test module)."""

from __future__ import annotations

import numpy as np

from voot.tree.null_problem import NullProblem
from voot.tree.problem import StepResult


class BadReward(NullProblem):
    """A problem whose step earns ``reward`` (and ``bonus``) once ``after`` steps are done."""

    def __init__(self, reward: float, bonus: float = 0.0, after: int = 0) -> None:
        super().__init__(2)
        self.bad_reward, self.bad_bonus, self.after, self.calls = reward, bonus, after, 0

    def step(self, action: np.ndarray) -> StepResult:
        self.calls += 1
        if self.calls > self.after:
            return StepResult(self.bad_reward, bonus=self.bad_bonus)
        return super().step(action)
