"""The execution loop (paper Algorithm 1's outer loop): plan, execute, re-plan.

At every step a search of ``n_simulations`` runs from the problem's current state, the
recommended root action is executed on the problem, and the loop re-plans from the state
reached, until the problem is terminal, an executed action is infeasible, or
``max_steps`` actions were executed. With ``reuse_subtree`` the next search starts from
the executed action's subtree instead of an empty tree.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from voot import validation as V
from voot.optim.base import FloatArray
from voot.tree.config import MCTSConfig, planner_config
from voot.tree.mcts import MCTS, Callback
from voot.tree.problem import PlanningProblem, StepResult, step_values
from voot.tree.search import PlanResult, check_n_simulations


@dataclass(frozen=True)
class EpisodeResult:
    """What an execution loop did.

    Attributes:
        actions: the executed actions.
        steps: their :class:`StepResult`.
        total_return: :math:`\\sum_t \\gamma^t r_t` of the executed rewards (bonus excluded).
        total_bonus: sum of the executed goal bonuses.
        plans: the search result of every step (``keep_plans=True``), else empty.
        n_steps: simulator steps spent by all searches (executions excluded).
        wall_time: seconds.
    """

    actions: tuple[FloatArray, ...]
    steps: tuple[StepResult, ...]
    total_return: float
    total_bonus: float
    plans: tuple[PlanResult, ...] = field(repr=False)
    n_steps: int
    wall_time: float

    @property
    def rewards(self) -> FloatArray:
        return np.array([s.reward for s in self.steps], dtype=np.float64)


def run_episode(
    problem: PlanningProblem,
    planner: str | MCTSConfig = "voot",
    n_simulations: int = 1000,
    max_steps: int = 100,
    seed: int | None = 0,
    *,
    reuse_subtree: bool = False,
    keep_plans: bool = False,
    callback: Callback | None = None,
    **options: Any,
) -> EpisodeResult:
    """Plan and execute on ``problem`` (which is left in the final state).

    Args:
        problem: the problem, in its initial state.
        planner: a planner name or an :class:`MCTSConfig`.
        n_simulations: simulations per search.
        max_steps: maximum number of executed actions.
        seed: seed of the whole episode (each search gets a seed drawn from it).
        reuse_subtree: start each search from the previous tree's executed subtree.
        keep_plans: keep every search's :class:`PlanResult` (and so every tree).
        callback: passed to every search.
        **options: :class:`MCTSConfig` overrides.
    """
    n_sims = check_n_simulations(n_simulations)
    V.integer(max_steps, "max_steps", 1)
    if isinstance(planner, MCTSConfig):
        config = planner.replace(**options) if options else planner
    else:
        config = planner_config(planner, **options)
    rng = np.random.default_rng(V.seed(seed))
    t0 = time.perf_counter()
    actions: list[FloatArray] = []
    steps: list[StepResult] = []
    plans: list[PlanResult] = []
    total, bonus, discount, n_steps = 0.0, 0.0, 1.0, 0
    mcts: MCTS | None = None
    for _ in range(max_steps):
        if mcts is None:
            mcts = MCTS(problem, config, seed=int(rng.integers(2**63)))
        res = mcts.search(n_sims, callback=callback)
        n_steps += mcts.n_steps
        if keep_plans:
            plans.append(res)
        edge = mcts.recommended_edge()
        if edge < 0:
            break
        action = mcts.root.actions[edge].copy()
        problem.restore(mcts.root.snapshot)
        step = problem.step(action)
        reward, step_bonus = step_values(problem, action, step)
        actions.append(action)
        steps.append(step)
        total += discount * reward
        bonus += step_bonus
        discount *= config.gamma
        if step.terminal or not step.feasible:
            break
        if reuse_subtree and mcts.root.children[edge].expandable:
            mcts.reroot(edge)
            mcts.n_steps = 0
            mcts.n_feasibility_checks = 0
        else:
            mcts = None
    return EpisodeResult(
        actions=tuple(actions),
        steps=tuple(steps),
        total_return=total,
        total_bonus=bonus,
        plans=tuple(plans),
        n_steps=n_steps,
        wall_time=time.perf_counter() - t0,
    )
