"""Tests of voot.tree.step_info: the typed record of a step's info, and the envs' contract."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import voot  # noqa: F401  (registers the ids)
from voot.tree.step_info import CORE_KEYS, StepInfo


def test_defaults_and_malformed_values() -> None:
    s = StepInfo.of({})
    assert s.feasible and s.reason == "" and s.objects_left is None and s.base_pose is None
    s = StepInfo.of({"base_pose": (1, 2, math.nan), "placement": "xyz", "objects_left": 3.0})
    assert s.base_pose is None and s.placement is None and s.objects_left == 3
    s = StepInfo.of({"placements": [(0, 0, 0), None, (1, 1, 1)], "feasible": False})
    assert s.placements == ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0)) and not s.feasible
    assert set(CORE_KEYS) <= set(StepInfo.KEYS)


@pytest.mark.parametrize(
    "env_id",
    [
        "voot/KitchenClearing-v0",
        "voot/KitchenClearing-v1",
        "voot/ConveyorPacking-v0",
        "voot/ConveyorPacking-v1",
    ],
)
def test_every_robot_env_publishes_the_core_keys(env_id: str) -> None:
    from voot.envs.conveyor.scripted import conveyor_actions
    from voot.envs.kitchen.env import KitchenClearingEnv
    from voot.envs.kitchen.scripted import kitchen_actions

    env = gym.make(env_id).unwrapped
    env.reset(seed=0)
    good = kitchen_actions(env) if isinstance(env, KitchenClearingEnv) else conveyor_actions(env)
    rng = np.random.default_rng(0)
    seen = set()
    for a in [*good[:2], *rng.uniform(-1, 1, (6, env.action_dim))]:
        _, _, term, trunc, info = env.step(a)
        missing = [k for k in CORE_KEYS if k not in info]
        assert not missing, (env_id, missing)
        s = StepInfo.of(info)
        assert s.feasible == info["feasible"] and s.reason == info["reason"]
        assert s.objects_left == info["objects_left"] and s.operator == info["operator"]
        assert s.base_pose == tuple(info["base_pose"])
        seen.add(s.feasible)
        if term or trunc:
            break
    assert seen == {True, False}
