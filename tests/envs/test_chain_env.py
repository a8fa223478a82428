"""Tests of voot.envs.chains: the synthetic chains as gymnasium environments."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import voot  # noqa: F401  (registers the environment ids)
from voot.functions import get_function
from voot.tree import (
    CHAIN_SPECS,
    GymProblem,
    plan,
)


@pytest.mark.filterwarnings("ignore:.*(symmetric and normalized|maximum value is infinity).*")
@pytest.mark.parametrize(
    ("env_id", "name"),
    [
        ("voot/ShekelChain-v0", "shekel"),
        ("voot/GriewankChain-v0", "griewank"),
        ("voot/RastriginChain-v0", "rastrigin"),
    ],
)
def test_registered_envs(env_id: str, name: str) -> None:
    env = gym.make(env_id, dim=3)
    assert env.unwrapped.chain.threshold == CHAIN_SPECS[name].thresholds[3]
    check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=0)
    assert obs.tolist() == [0.0]
    fn = get_function(name, 3)
    a = np.asarray(fn.optimum_x) if fn.optimum_x is not None else env.action_space.sample()
    obs, reward, terminated, _truncated, info = env.step(a)
    assert reward == pytest.approx(
        info["value"] + info["bonus"] if info["feasible"] else info["value"] - 2
    )
    assert terminated == (not info["feasible"])


def test_chain_env_plans_through_the_gym_adapter() -> None:
    env = gym.make("voot/GriewankChain-v0", dim=3, horizon=3)
    problem = GymProblem(env, seed=0)
    res = plan(problem, "voot", 60, seed=0, reevaluations=2)
    # The adapter moves the goal bonus out of the reward: returns are sums of f.
    assert np.all(res.bonuses[np.array(res.feasible)] == 100.0)
    assert res.best_return <= 0.0 + 1e-12 or not all(res.feasible)
