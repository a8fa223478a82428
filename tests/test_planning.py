"""The benchmark envs as planning problems (voot.envs.planning.EnvProblem)."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import voot  # noqa: F401  (registers the ids)
from voot.envs.conveyor import ConveyorPackingEnv
from voot.envs.kitchen import KitchenClearingEnv
from voot.envs.planning import EnvProblem
from voot.envs.scripted import conveyor_actions, kitchen_actions
from voot.tree.problem import FeasibilityCheck, PlanningProblem, StepResult


@pytest.fixture(scope="module")
def kitchen() -> KitchenClearingEnv:
    return KitchenClearingEnv()


def test_protocols_and_bounds(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(kitchen, seed=0)
    assert isinstance(p, PlanningProblem) and isinstance(p, FeasibilityCheck)
    assert p.action_bounds().dim == 6
    acts = kitchen_actions(kitchen)
    res = p.step(acts[0])
    assert isinstance(res, StepResult) and res.feasible and res.reward == 0.0
    # a place node: a 3-D box, padded to the env's 6-D action
    b = p.action_bounds()
    assert b.dim == 3 and np.all(b.lower == -1.0) and np.all(b.upper == 1.0)
    res = p.step(acts[1][:3])
    assert res.feasible and res.info["operator"] == "place" and res.bonus == 0.0
    with pytest.raises(ValueError, match="6 entries"):
        p.step(np.zeros(3))


def test_goal_bonus_is_separate(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(gym.make("voot/KitchenClearing-v0"), seed=0)
    acts = kitchen_actions(kitchen)
    for k, a in enumerate(acts):
        res = p.step(a if k % 2 == 0 else a[:3])
        assert res.feasible
    assert res.terminal and res.bonus == 2.0 and res.reward < 2.0


def test_snapshot_restore_and_feasibility_cache(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(kitchen, seed=0)
    assert p.last_check is None
    s0 = p.snapshot()
    a = kitchen_actions(kitchen)[0]
    assert p.is_feasible(a)
    assert p.snapshot() == s0  # the check does not advance the state
    check = p.last_check
    assert check is not None and check.feasible and len(check.info["base_pose"]) == 3
    cached = p.step(a)  # reuses the check's result
    assert cached is check
    s1 = p.snapshot()
    p.restore(s0)
    fresh = p.step(a)
    assert fresh.reward == cached.reward and p.snapshot() == s1
    # a different action after a check is stepped for real
    p.restore(s0)
    assert not p.is_feasible(np.full(6, -0.3))
    assert p.last_check is not None and not p.last_check.feasible
    assert p.last_check.info["base_pose"] is not None  # where the rejected pick stood
    assert p.snapshot() == s0
    res = p.step(a)
    assert res.feasible and p.snapshot() == s1


def test_paper_units(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(kitchen, seed=0, units="paper")
    b = p.action_bounds()
    assert b.lower[0] == pytest.approx(math.radians(45)) and b.upper[4] == pytest.approx(
        2 * math.pi
    )
    q = b.lower + 0.5 * (b.upper - b.lower)
    np.testing.assert_allclose(p.to_env_action(q), np.zeros(6), atol=1e-12)
    with pytest.raises(ValueError, match="units"):
        EnvProblem(kitchen, units="furlongs")


def test_conveyor_problem() -> None:
    env = ConveyorPackingEnv()
    p = EnvProblem(env, seed=0)
    assert p.action_bounds().dim == 9
    res = p.step(conveyor_actions(env)[0])
    assert res.feasible and 0.0 < res.reward <= 3.0
    assert EnvProblem(env, units="paper").action_bounds().dim == 9


def test_rejects_other_envs() -> None:
    with pytest.raises(ValueError, match="KitchenClearingEnv or ConveyorPackingEnv"):
        EnvProblem(gym.make("voot/ShekelChain-v0"))
