"""Tests of voot.tree.execute: plan, execute, re-plan (Algorithm 1's outer loop)."""

from __future__ import annotations

import numpy as np
import pytest

from voot.optim.base import Bounds
from voot.tree import StepResult, planner_config, run_episode
from voot.tree.null_problem import NullProblem


class Counter:
    """State: depth t; reward a[0] in [0, 1]; terminal with a bonus at ``goal_depth``."""

    def __init__(self, goal_depth: int, bonus: float = 0.0) -> None:
        self.bounds = Bounds.cube(0.0, 1.0, 2)
        self.t = 0
        self.goal_depth = goal_depth
        self.bonus = bonus

    def snapshot(self) -> int:
        return self.t

    def restore(self, snapshot: int) -> None:
        self.t = snapshot

    def action_bounds(self) -> Bounds:
        return self.bounds

    def step(self, action: np.ndarray) -> StepResult:
        self.t += 1
        goal = self.t >= self.goal_depth
        return StepResult(float(action[0]), terminal=goal, bonus=self.bonus if goal else 0.0)


def test_episode_executes_recommended_actions_until_terminal() -> None:
    problem = Counter(goal_depth=3, bonus=2.0)
    ep = run_episode(problem, "voot", n_simulations=30, max_steps=10, seed=0, keep_plans=True)
    assert len(ep.actions) == 3 and ep.steps[-1].terminal
    assert problem.t == 3  # the problem is left in the final state
    assert ep.total_bonus == 2.0
    disc = 0.9 ** np.arange(3)
    assert ep.total_return == pytest.approx(float(disc @ ep.rewards))
    # Each executed action is the recommendation of its search.
    for action, res in zip(ep.actions, ep.plans, strict=True):
        assert res.best_action is not None and np.array_equal(action, res.best_action)
    assert ep.n_steps > 0


def test_episode_stops_at_max_steps_and_is_deterministic() -> None:
    a = run_episode(NullProblem(3), "pw_uct", 20, max_steps=4, seed=5, depth_limit=3)
    b = run_episode(NullProblem(3), "pw_uct", 20, max_steps=4, seed=5, depth_limit=3)
    assert len(a.actions) == 4
    assert all(np.array_equal(x, y) for x, y in zip(a.actions, b.actions, strict=True))


def test_subtree_reuse_keeps_the_executed_branch() -> None:
    cfg = planner_config("voot", depth_limit=3, root_commitment=None)
    problem = Counter(goal_depth=3)
    ep = run_episode(problem, cfg, 40, max_steps=5, seed=1, reuse_subtree=True, keep_plans=True)
    assert len(ep.actions) == 3
    # The reused tree's root is the executed child: its search saw more simulations.
    assert ep.plans[1].mcts is ep.plans[0].mcts
    fresh = run_episode(Counter(goal_depth=3), cfg, 40, max_steps=5, seed=1, reuse_subtree=False)
    assert len(fresh.actions) == 3


def test_bad_arguments() -> None:
    with pytest.raises(ValueError, match="n_simulations"):
        run_episode(NullProblem(2), "voot", 0)
    with pytest.raises(ValueError, match="max_steps"):
        run_episode(NullProblem(2), "voot", 5, max_steps=0)
    with pytest.raises(ValueError, match="unknown planner"):
        run_episode(NullProblem(2), "vot", 5)
