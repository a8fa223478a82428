"""Planning problems shared by the tree and sampling-based planners' tests (not a test module)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest

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


class Quadratic(NullProblem):
    """Reward :math:`1 - \\|a - c\\|^2 / s` on :math:`[-1, 1]^d`, the same at every step.

    Stateless, so the optimum is known: every action at ``c`` (``optimum``, default
    ``linspace(-0.5, 0.6, d)``), return :math:`\\sum_{t<H} \\gamma^t`; ``scale`` s
    defaults to d.
    """

    def __init__(
        self, dim: int = 4, optimum: Sequence[float] | None = None, scale: float | None = None
    ) -> None:
        super().__init__(dim, np.linspace(-0.5, 0.6, dim) if optimum is None else optimum)
        self.scale = float(dim if scale is None else scale)

    def step(self, action: np.ndarray) -> StepResult:
        return StepResult(1.0 - float(np.sum((action - self.optimum) ** 2)) / self.scale)


#: ``(reward, bonus, what)``: a step that no planner may accept, and how its error names it.
NON_FINITE_STEPS = [
    (math.nan, 0.0, "reward=nan"),
    (math.inf, 0.0, "reward=inf"),
    (-math.inf, 0.0, "reward=-inf"),
    (0.5, math.nan, "goal bonus=nan"),
    (0.5, math.inf, "goal bonus=inf"),
    (0.5, -math.inf, "goal bonus=-inf"),
]


def raises_non_finite(what: str) -> Any:
    """``pytest.raises`` of the planners' error for a :class:`BadReward` step: it names the
    step's action and ``what`` and says that rewards and bonuses must be finite."""
    return pytest.raises(
        ValueError, match=rf"BadReward\.step\(action=\[.*\]\) returned {what}.*must be finite"
    )
