"""Greedy one-step lookahead with restarts: a planner for voot, outside voot.

Every simulation is one rollout from the root. At each state the planner draws ``width``
actions uniformly in the state's action box, drops the ones the problem's pre-check (if it
has one) rejects, executes each remaining one and keeps the one with the best immediate
reward; the rollout continues from there until an infeasible action, the end of the
episode or ``horizon`` actions. Rollouts differ by their random draws (restarts), and the
best plan is the best-returning prefix of any rollout.

voot hands it the problem (``snapshot``, ``restore``, ``step``, ``action_bounds``,
optionally ``is_feasible``, and ``discount``), a budget of simulations and a seed, and
measures its simulator calls and CPU time itself. After each rollout it yields a
:class:`voot.planners.Progress`: the best return and the step info at the end of the best
plan (its ``objects_left`` gives the benchmark's objects-left curve); a plain number would
do as well.
"""

from __future__ import annotations

import numpy as np

from voot.planners import Progress

__all__ = ["greedy"]


def greedy(problem, budget, seed, width=4, horizon=20):
    """Greedy one-step lookahead: yield the best return (with the step info at the end of
    the best plan) after each of ``budget`` rollouts, then return the best plan (a list of
    actions)."""
    rng = np.random.default_rng(seed)
    precheck = getattr(problem, "is_feasible", None)
    root = problem.snapshot()
    best, best_plan, best_info = -np.inf, [], {}
    for _ in range(budget):
        problem.restore(root)
        plan, ret, weight = [], 0.0, 1.0
        for _ in range(horizon):
            state = problem.snapshot()
            box = problem.action_bounds()
            draws = [rng.uniform(box.lower, box.upper) for _ in range(width)]
            passed = [a for a in draws if precheck is None or precheck(a)] or draws[-1:]
            choice = None  # (reward, action, result, state after)
            for action in passed:
                problem.restore(state)
                result = problem.step(action)
                if choice is None or result.reward > choice[0]:
                    choice = (result.reward, action, result, problem.snapshot())
            _, action, result, after = choice
            problem.restore(after)
            plan.append(action)
            ret += weight * result.reward
            weight *= problem.discount
            if ret > best:
                best, best_plan, best_info = ret, list(plan), result.info
            if not result.feasible or result.terminal:
                break
        yield Progress(best, best_info)
    return best_plan


#: The settings `voot-bench plan --grid paper` tunes (every combination is a candidate).
greedy.grid = {"width": (2, 4, 8)}
