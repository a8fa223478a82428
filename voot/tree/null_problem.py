"""A planning problem whose step costs (almost) nothing: for measuring the search's own cost,
and for tests and examples of the tree search.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from voot import validation as V
from voot.optim.base import Bounds, FloatArray
from voot.tree.problem import StepResult


class NullProblem:
    """A stateless problem with a nearly free step: reward :math:`1 - \\|a - c\\|_1 / (2d)`.

    Every action is feasible, nothing is terminal; the reward lies in [0, 1] and has a
    unique optimum 1 at ``c`` (``optimum``), so the samplers behave as on a real problem
    and longer plans are better. Snapshots are None.
    """

    def __init__(self, dim: int = 6, optimum: Sequence[float] | None = None) -> None:
        V.integer(dim, "dim", 1)
        self.dim = dim
        self.bounds = Bounds.cube(-1.0, 1.0, dim)
        c = np.full(dim, 0.3) if optimum is None else np.asarray(optimum, dtype=np.float64)
        self.optimum = self.bounds.check_point(c, "optimum")
        self._scale = 0.5 / dim

    def snapshot(self) -> None:
        return None

    def restore(self, snapshot: object) -> None:
        pass

    def action_bounds(self) -> Bounds:
        return self.bounds

    def step(self, action: FloatArray) -> StepResult:
        return StepResult(1.0 - float(np.abs(action - self.optimum).sum()) * self._scale)
