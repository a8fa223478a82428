"""Tests of voot.tree.chains and voot.envs.chains: the synthetic planning chains."""

from __future__ import annotations

import numpy as np
import pytest

import voot  # noqa: F401  (registers the environment ids)
from voot.functions import get_function
from voot.optim.base import Bounds
from voot.tree import (
    CHAIN_SPECS,
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
