"""Planning problems shared by the tree and sampling-based planners' tests (not a test module)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
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


@dataclass(frozen=True)
class NonFiniteStep:
    """A step that no planner may accept (``reward`` or ``bonus`` not finite), and how the
    planners' error names it (``what``)."""

    reward: float
    bonus: float
    what: str

    def __str__(self) -> str:
        return self.what

    def problem(self, after: int = 0) -> BadReward:
        """A :class:`BadReward` whose steps are this bad one once ``after`` are done."""
        return BadReward(self.reward, self.bonus, after)

    def raises(self) -> Any:
        """``pytest.raises`` of the planners' error for this step: it names the step's
        action and ``what`` and says that rewards and bonuses must be finite."""
        return pytest.raises(
            ValueError,
            match=rf"BadReward\.step\(action=\[.*\]\) returned {self.what}.*must be finite",
        )


#: Every non-finite step (as a test parameter: ``ids=str``).
NON_FINITE_STEPS = [
    NonFiniteStep(math.nan, 0.0, "reward=nan"),
    NonFiniteStep(math.inf, 0.0, "reward=inf"),
    NonFiniteStep(-math.inf, 0.0, "reward=-inf"),
    NonFiniteStep(0.5, math.nan, "goal bonus=nan"),
    NonFiniteStep(0.5, math.inf, "goal bonus=inf"),
    NonFiniteStep(0.5, -math.inf, "goal bonus=-inf"),
]
