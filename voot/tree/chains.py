"""Synthetic planning chains: the authors' sequential test problems, without any simulator.

A chain is stateless: at every depth the action space is the same box and the same
function :math:`f` (maximisation form) scores the action. An action with
:math:`f(a) \\ge \\tau` (the threshold) is feasible and earns :math:`f(a)` plus a bonus;
otherwise it earns :math:`f(a) - 2`, is infeasible, and ends the rollout. The best plan
is therefore a sequence of near-optimal actions, found one depth at a time by each
node's optimiser: a planning problem whose every node is a black-box optimisation.

Here the reward is :math:`f(a)` and the bonus travels in :attr:`StepResult.bonus`, so it
counts in :math:`\\hat Q` but not in the reported returns (``bonus_in_reward=True`` puts
it in the reward, as the authors' plots did). Reference values (the reference page):

========  =====================  ======  =================
function  threshold 3 / 10 / 20-D  bonus  root commitment
========  =====================  ======  =================
Shekel    3.0 / 2.0 / 1.0          1      5 / 5 / 3
Rastrigin -10 / -50 / -100         100    5 / 5 / 3
Griewank  -2 / -50 / -50           100    5 / 5 / 3
========  =====================  ======  =================

The authors ran 10,000 simulations, ``w = 100`` re-evaluations, VOO in
``centered_uniform`` mode, no depth limit, :math:`\\gamma = 0.9`:
:func:`chain_planner_options` returns those settings.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from voot import validation as V
from voot.optim.base import Bounds, FloatArray
from voot.tree.problem import StepResult


@dataclass(frozen=True)
class ChainSpec:
    """Reference settings of one chain function: per-dimension thresholds and the bonus."""

    thresholds: Mapping[int, float]
    bonus: float
    root_commitment: Mapping[int, int]


#: The authors' settings (reference page, "Synthetic planning chains").
CHAIN_SPECS: Mapping[str, ChainSpec] = {
    "shekel": ChainSpec({3: 3.0, 10: 2.0, 20: 1.0}, 1.0, {3: 5, 10: 5, 20: 3}),
    "rastrigin": ChainSpec({3: -10.0, 10: -50.0, 20: -100.0}, 100.0, {3: 5, 10: 5, 20: 3}),
    "griewank": ChainSpec({3: -2.0, 10: -50.0, 20: -50.0}, 100.0, {3: 5, 10: 5, 20: 3}),
}

#: The authors' budget on the chains.
CHAIN_SIMULATIONS = 10_000


class SyntheticChain:
    """A chain over ``function`` on ``bounds`` (a :class:`~voot.tree.problem.PlanningProblem`).

    Args:
        function: :math:`f`, maximised; called with one action vector.
        bounds: the action box (the same at every depth).
        threshold: :math:`\\tau`: actions with :math:`f(a) \\ge \\tau` are feasible.
        bonus: added to :math:`\\hat Q` for every feasible action.
        infeasible_penalty: added to :math:`f(a)` for an infeasible action (-2).
        horizon: the episode ends after this many feasible actions (None: never).
        bonus_in_reward: count the bonus in the reward (the authors' plotted sums).
        feasibility_precheck: offer ``is_feasible`` to the planner, so it retries new
            actions below the threshold before executing one. Off by default, as in the
            authors' code (a dummy checker passed every action; infeasibility was only
            found by executing it, and its value :math:`f(a) - 2` reached the node's
            optimiser).

    The state is the number of feasible actions taken so far (an int snapshot).
    """

    def __init__(
        self,
        function: Callable[[FloatArray], float],
        bounds: Bounds | ArrayLike,
        threshold: float,
        bonus: float = 0.0,
        infeasible_penalty: float = -2.0,
        horizon: int | None = None,
        bonus_in_reward: bool = False,
        feasibility_precheck: bool = False,
    ) -> None:
        if not callable(function):
            raise ValueError("function must be callable f(action) -> float")
        self.function = function
        self.bounds = Bounds.coerce(bounds)
        for name, v in (
            ("threshold", threshold),
            ("bonus", bonus),
            ("infeasible_penalty", infeasible_penalty),
        ):
            V.number(v, name)
        V.optional_integer(horizon, "horizon", 1)
        self.threshold = float(threshold)
        self.bonus = float(bonus)
        self.infeasible_penalty = float(infeasible_penalty)
        self.horizon = horizon
        self.bonus_in_reward = bool(bonus_in_reward)
        self.t = 0
        #: The planner's feasibility pre-check (see ``feasibility_precheck``), or None.
        self.is_feasible: Callable[[FloatArray], bool] | None = (
            self.meets_threshold if feasibility_precheck else None
        )

    def snapshot(self) -> int:
        return self.t

    def restore(self, snapshot: int) -> None:
        self.t = int(snapshot)

    def action_bounds(self) -> Bounds:
        return self.bounds

    def value(self, action: FloatArray) -> float:
        """:math:`f(a)`, after checking the action's shape."""
        a = np.asarray(action, dtype=np.float64)
        if a.shape != (self.bounds.dim,):
            raise ValueError(f"action must have shape ({self.bounds.dim},), got {a.shape}")
        return float(self.function(a))

    def meets_threshold(self, action: FloatArray) -> bool:
        """Is ``action`` feasible, i.e. :math:`f(a) \\ge \\tau`? (Does not advance the state.)"""
        return self.value(action) >= self.threshold

    def step(self, action: FloatArray) -> StepResult:
        f = self.value(action)
        if f < self.threshold:
            return StepResult(
                f + self.infeasible_penalty, feasible=False, terminal=False, info={"value": f}
            )
        self.t += 1
        terminal = self.horizon is not None and self.t >= self.horizon
        if self.bonus_in_reward:
            return StepResult(f + self.bonus, terminal=terminal, info={"value": f})
        return StepResult(f, terminal=terminal, bonus=self.bonus, info={"value": f})


def make_chain(
    name: str,
    dim: int,
    *,
    threshold: float | None = None,
    bonus: float | None = None,
    **kwargs: Any,
) -> SyntheticChain:
    """The authors' chain over ``voot.functions.get_function(name, dim)``.

    ``threshold`` and ``bonus`` default to :data:`CHAIN_SPECS` (which has values for 3,
    10 and 20 dimensions; other dimensions need an explicit ``threshold``).
    """
    key = str(name).strip().lower()
    if key not in CHAIN_SPECS:
        raise ValueError(
            f"unknown chain {name!r}; valid chains are: {', '.join(sorted(CHAIN_SPECS))}"
        )
    spec = CHAIN_SPECS[key]
    if threshold is None:
        if dim not in spec.thresholds:
            raise ValueError(
                f"no reference threshold for the {key} chain in {dim}-D (reference:"
                f" {sorted(spec.thresholds)}); pass threshold="
            )
        threshold = spec.thresholds[dim]
    from voot.functions import get_function

    fn = get_function(key, dim)
    return SyntheticChain(
        fn, fn.bounds, threshold, spec.bonus if bonus is None else bonus, **kwargs
    )


def chain_planner_options(name: str, dim: int) -> dict[str, Any]:
    """:class:`~voot.tree.MCTSConfig` overrides the authors used on a chain (any planner).

    ``reevaluations=100``, ``kappa_r=1.0`` (their decay was off), no depth limit,
    ``gamma=0.9``, root commitment 5 / 5 / 3 (3 / 10 / 20-D; 5 otherwise), and the
    authors' "uniform until a reward above -2" rule for VOO (see the code comment). For VOO
    samplers add ``sampler_options={"sampler": "centered_uniform"}`` (VOO's default).
    """
    key = str(name).strip().lower()
    if key not in CHAIN_SPECS:
        raise ValueError(
            f"unknown chain {name!r}; valid chains are: {', '.join(sorted(CHAIN_SPECS))}"
        )
    return {
        "reevaluations": 100,
        "kappa_r": 1.0,
        "depth_limit": None,
        "gamma": 0.9,
        "root_commitment": CHAIN_SPECS[key].root_commitment.get(dim, 5),
        # The authors' VOO sampled uniformly until a node had an action whose best reward
        # exceeded -2. An infeasible chain action earns f(a) - 2, which exceeds -2 exactly
        # when f(a) > 0: always for Shekel (a sum of positive terms), never for the
        # negated Rastrigin and Griewank. So Shekel nodes exploit from their second action.
        "voo_uniform_until_feasible": key != "shekel",
    }
