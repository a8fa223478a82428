"""Tests of voot.envs.core.names: typed names equal their strings; every failure has a code."""

from __future__ import annotations

import json
import pickle

import gymnasium as gym
import numpy as np
import pytest

import voot  # noqa: F401 - registers the ids
from voot.envs.core.names import (
    Difficulty,
    Failure,
    Operator,
    Precheck,
    Reason,
    Units,
    reason_code,
)
from voot.tree.step_info import StepInfo


def test_members_equal_hash_and_serialise_as_their_strings() -> None:
    for member, text in (
        (Operator.PICK, "pick"),
        (Precheck.KINEMATIC, "kinematic"),
        (Units.PAPER, "paper"),
        (Difficulty.HARD, "hard"),
        (Reason.NO_BASE_PATH, "no base path"),
    ):
        assert member == text and hash(member) == hash(text)
        assert json.dumps(member) == json.dumps(text) and f"{member}" == text
    with pytest.raises(ValueError, match="'sideways' is not a valid Operator"):
        Operator("sideways")


def test_a_failure_is_its_text_with_a_code() -> None:
    f = Failure(Reason.COLLISION, "collision: robot-wall")
    assert f == "collision: robot-wall" and f.code is Reason.COLLISION
    assert reason_code(f) is Reason.COLLISION and reason_code("") is Reason.NONE
    g = pickle.loads(pickle.dumps(f.prefixed("box 1/3 (b): ")))
    assert g == "box 1/3 (b): collision: robot-wall" and g.code is Reason.COLLISION
    with pytest.raises(TypeError, match="must be a Failure"):
        reason_code("collision: robot-wall")


@pytest.mark.parametrize("env_id", ["voot/KitchenClearing-v1", "voot/ConveyorPacking-v1"])
def test_every_infeasible_info_has_the_code_of_its_text(env_id: str) -> None:
    env = gym.make(env_id, disable_env_checker=True)
    env.reset(seed=0)
    u = env.unwrapped
    start = u.get_state()
    rng = np.random.default_rng(0)
    codes = set()
    for _ in range(60):
        a = rng.uniform(-1.0, 1.0, u.action_dim)
        for info in (u.precheck(a)[1], u.step(a)[-1]):
            step = StepInfo.of(info)
            assert bool(step.reason_code) == (not step.feasible)
            if not step.feasible:
                text = step.reason.split("): ", 1)[-1] if "failed_box" in info else step.reason
                assert text.startswith(step.reason_code), (text, step.reason_code)
                assert isinstance(info["reason_code"], Reason)
                codes.add(step.reason_code)
        u.set_state(start)
    assert len(codes) >= 2
