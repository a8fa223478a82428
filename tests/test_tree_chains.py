"""Tests of voot.tree.chains and voot.tree.chain_env: the synthetic planning chains."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import voot  # noqa: F401  (registers the environment ids)
from voot.functions import get_function
from voot.optim.base import Bounds
from voot.tree import (
    CHAIN_SPECS,
    GymProblem,
    SyntheticChain,
    chain_planner_options,
    make_chain,
    plan,
    planner_config,
)


def _sphere_chain(**kwargs: object) -> SyntheticChain:
    return SyntheticChain(
        lambda a: 1.0 - float(np.sum(a**2)),
        Bounds.cube(-1.0, 1.0, 2),
        0.5,
        3.0,
        **kwargs,  # type: ignore[arg-type]
    )


def test_feasible_steps_earn_f_and_the_bonus_infeasible_ones_f_minus_2() -> None:
    chain = _sphere_chain()
    good = chain.step(np.array([0.1, 0.0]))
    assert good.feasible and good.reward == pytest.approx(0.99) and good.bonus == 3.0
    assert chain.snapshot() == 1
    bad = chain.step(np.array([1.0, 1.0]))
    assert not bad.feasible and bad.reward == pytest.approx(-1.0 - 2.0) and bad.bonus == 0.0
    assert chain.snapshot() == 1  # an infeasible action does not advance
    assert chain.meets_threshold(np.array([0.0, 0.0])) and not chain.meets_threshold(
        np.array([1.0, 0.0])
    )
    chain.restore(0)
    assert chain.t == 0


def test_bonus_in_reward_and_horizon() -> None:
    chain = _sphere_chain(bonus_in_reward=True, horizon=2)
    r = chain.step(np.zeros(2))
    assert r.reward == pytest.approx(4.0) and r.bonus == 0.0 and not r.terminal
    assert chain.step(np.zeros(2)).terminal


def test_chain_argument_errors() -> None:
    with pytest.raises(ValueError, match="shape"):
        _sphere_chain().step(np.zeros(3))
    with pytest.raises(ValueError, match="horizon"):
        _sphere_chain(horizon=0)
    with pytest.raises(ValueError, match="threshold"):
        SyntheticChain(lambda a: 0.0, Bounds.cube(0, 1, 1), float("nan"))
    with pytest.raises(ValueError, match="unknown chain 'sphere'; valid chains are"):
        make_chain("sphere", 3)
    with pytest.raises(ValueError, match="no reference threshold"):
        make_chain("shekel", 5)


@pytest.mark.parametrize("name", sorted(CHAIN_SPECS))
@pytest.mark.parametrize("dim", [3, 10, 20])
def test_reference_chains(name: str, dim: int) -> None:
    chain = make_chain(name, dim)
    spec = CHAIN_SPECS[name]
    assert chain.threshold == spec.thresholds[dim] and chain.bonus == spec.bonus
    fn = get_function(name, dim)
    assert chain.bounds == fn.bounds
    # The function's optimum is feasible in every chain.
    if fn.optimum_x is not None:
        assert chain.meets_threshold(np.asarray(fn.optimum_x))
    opts = chain_planner_options(name, dim)
    assert opts["root_commitment"] == spec.root_commitment[dim]
    assert opts["reevaluations"] == 100


def test_voot_plans_feasible_steps_on_griewank_3d() -> None:
    chain = make_chain("griewank", 3, feasibility_precheck=True)
    cfg = planner_config("voot", **{**chain_planner_options("griewank", 3), "reevaluations": 5})
    res = plan(chain, cfg, 150, seed=0)
    assert res.feasible[0] and res.rewards[0] >= chain.threshold
    assert res.bonuses[0] == 100.0
    assert res.n_feasibility_checks > res.n_steps


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
