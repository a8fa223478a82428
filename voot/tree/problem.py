"""The planning-problem protocol: the seam between tree search and the worlds it plans in.

A planner needs, from any deterministic world:

* ``snapshot()``: the current state as a cheap immutable value (hashable is not required);
* ``restore(snapshot)``: go back to that state exactly;
* ``step(action)``: apply an action, returning a :class:`StepResult`;
* ``action_bounds()``: the action box in the *current* state (a pick node and a place
  node may differ);
* optionally ``is_feasible(action)``: a feasibility check that does not advance the state.

Determinism contract: ``restore(s); step(a)`` gives bit-identical results every time, in
any process. The search relies on it to cache a child's snapshot on its tree edge and
restore it instead of stepping again.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from voot.optim.base import Bounds


@dataclass(frozen=True)
class StepResult:
    """What one step of a planning problem returns.

    Attributes:
        reward: the step's reward, *excluding* any goal bonus (the paper's curves plot
            this sum); infeasible actions carry their penalty here (e.g. -2).
        feasible: False if the action was infeasible; the rollout stops there.
        terminal: True if the episode ended (goal reached or a horizon hit).
        bonus: a goal bonus added to the search's value but reported separately.
        info: anything else (next operator, why infeasible, objects left ...).
    """

    reward: float
    feasible: bool = True
    terminal: bool = False
    bonus: float = 0.0
    info: Mapping[str, Any] = field(default_factory=dict)


@runtime_checkable
class PlanningProblem(Protocol):
    """Anything a :mod:`voot.tree` planner can search (see the module docstring)."""

    def snapshot(self) -> Any: ...

    def restore(self, snapshot: Any) -> None: ...

    def step(self, action: NDArray[np.float64]) -> StepResult: ...

    def action_bounds(self) -> Bounds: ...


@runtime_checkable
class FeasibilityCheck(Protocol):
    """Optional extension: test an action without advancing the state."""

    def is_feasible(self, action: NDArray[np.float64]) -> bool: ...
