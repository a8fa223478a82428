"""The planning-problem protocol: the seam between tree search and the worlds it plans in.

A planner needs, from any deterministic world:

* ``snapshot()``: the current state as a cheap immutable value (hashable is not required);
* ``restore(snapshot)``: go back to that state exactly;
* ``step(action)``: apply an action, returning a :class:`StepResult`;
* ``action_bounds()``: the action box in the *current* state (a pick node and a place
  node may differ).

**Two stages of feasibility.** A new action meets the world twice, as in the authors'
code:

1. *Pre-check* (optional, :class:`FeasibilityCheck`): ``is_feasible(action)`` is a test
   that leaves the state unchanged. The search re-draws a new action until it passes,
   at most ``feasibility_retries`` times (the same number for every planner); if all
   fail, the last draw is executed anyway and earns the infeasible reward. A problem
   without the method has no pre-check: every draw is executed.
2. *Execution*: ``step(action)``, which may still find the action infeasible
   (``StepResult.feasible`` False, e.g. reward -2): the child is created and the
   simulation ends there.

What the pre-check covers is the problem's choice: the authors' robot domains check
only cheap kinematics there (IK, collisions, regions) and leave base motion planning and
the forbidden rooms to execution (``voot/KitchenClearing-v1``); a problem may also make
the pre-check the whole step (``voot/KitchenClearing-v0``), which filters every
infeasible draw before it costs a simulation.

Optionally, ``n_simulator_calls`` (:class:`SimulatorCalls`) counts the runs of the
underlying simulator, which a pre-check may also make (v0's full-step pre-check does):
the benchmark's cost measure next to the search's own counts of steps and pre-checks.

Optionally, ``action_metric()`` (:class:`ActionMetric`) gives the distance between
actions *in the current state* that a Voronoi sampler should use (e.g. the authors'
per-operator distance: places compare x, y only), used with
``MCTSConfig.use_problem_metric``.

Determinism contract: ``restore(s); step(a)`` gives bit-identical results every time, in
any process. The search relies on it to cache a child's snapshot on its tree edge and
restore it instead of stepping again.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from voot.optim.base import Bounds
from voot.validation import real_number


@dataclass(frozen=True)
class StepResult:
    """What one step of a planning problem returns.

    Attributes:
        reward: the step's reward, *excluding* any goal bonus (the paper's curves plot
            this sum); infeasible actions carry their penalty here (e.g. -2). It must be
            finite, like ``bonus``: the search raises a ValueError on NaN or +-inf.
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
    """Optional stage 1: pre-check an action without changing the state.

    The test must leave the problem exactly as it was (same snapshot, same next step);
    a False answer makes the search draw another action (see the module docstring).
    """

    def is_feasible(self, action: NDArray[np.float64]) -> bool: ...


#: A distance from many actions to one: ``metric(points (n, d), y (d,)) -> (n,)``.
ActionDistance = Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]


@runtime_checkable
class ActionMetric(Protocol):
    """Optional: the distance between actions in the current state (None: Euclidean).

    Return the *same* object for states that share a metric (e.g. one per operator), so
    that the search can reuse the samplers' configs built from it.
    """

    def action_metric(self) -> ActionDistance | None: ...


@runtime_checkable
class SimulatorCalls(Protocol):
    """Optional: how many times the problem ran its simulator (pre-checks included)."""

    n_simulator_calls: int


# ----- reading the protocol safely (every planner's checks, one wording) -----------------
def check_problem(problem: object) -> None:
    """A TypeError unless ``problem`` has the protocol's four methods."""
    for method in ("snapshot", "restore", "step", "action_bounds"):
        if not callable(getattr(problem, method, None)):
            raise TypeError(
                f"{type(problem).__name__} is not a PlanningProblem: it has no {method}()"
            )


def problem_bounds(problem: PlanningProblem) -> Bounds:
    """``problem.action_bounds()`` as a :class:`Bounds`, or a ValueError saying what is wrong."""
    raw = problem.action_bounds()
    if isinstance(raw, Bounds):
        return raw
    try:
        return Bounds.coerce(raw)
    except ValueError as exc:
        raise ValueError(
            f"{type(problem).__name__}.action_bounds() returned an invalid action box: {exc}"
        ) from None


def non_finite_step_error(
    problem: PlanningProblem, action: NDArray[np.float64], reward: float, bonus: float
) -> ValueError:
    """The error for a step whose reward or goal bonus is not a finite number.

    Rewards and bonuses must be finite. NaN has no order, so a NaN return would
    silently poison every :math:`\\hat Q` above it and the best-return curve (PW-UCT and
    HOOT reported ``best_return=nan``). An infinite reward is refused as well: one
    ``+inf`` makes every path through it the best whatever else it earns, one ``-inf``
    makes every backed-up mean ``-inf`` (and NaN once mixed with a ``+inf``), and
    neither can be told to an action optimiser. A failed action is reported as
    ``feasible=False`` with a finite penalty (the chains and the environments use -2).
    """
    name = "reward" if not math.isfinite(reward) else "goal bonus"
    value = reward if name == "reward" else bonus
    return ValueError(
        f"{type(problem).__name__}.step(action={np.asarray(action).tolist()}) returned"
        f" {name}={value!r} (reward={reward!r}, bonus={bonus!r}); rewards and goal bonuses"
        " must be finite numbers (report a failed action as feasible=False with a finite"
        " penalty)"
    )


def step_values(
    problem: PlanningProblem, action: NDArray[np.float64], res: object
) -> tuple[float, float]:
    """The reward and goal bonus of ``res = problem.step(action)``, as floats.

    A TypeError if ``res`` is not a :class:`StepResult`; the ValueError of
    :func:`non_finite_step_error` if either number is not finite.
    """
    if not isinstance(res, StepResult):
        raise TypeError(
            f"{type(problem).__name__}.step() must return a StepResult, got {type(res).__name__}"
        )
    reward, bonus = res.reward, res.bonus
    if type(reward) is not float or type(bonus) is not float:
        reward, bonus = (
            _real_step_value(problem, action, "reward", reward),
            _real_step_value(problem, action, "goal bonus", bonus),
        )
    if not (math.isfinite(reward) and math.isfinite(bonus)):
        raise non_finite_step_error(problem, action, reward, bonus)
    return reward, bonus


def _real_step_value(
    problem: PlanningProblem, action: NDArray[np.float64], what: str, value: object
) -> float:
    """``value`` (a step's reward or goal bonus) as a float, or a ValueError naming the
    step: a None, a string, a bool or a complex number is not read as some number."""
    try:
        return real_number(value, what)
    except ValueError as exc:
        raise ValueError(
            f"{type(problem).__name__}.step(action={np.asarray(action).tolist()}) returned {exc}"
        ) from None
