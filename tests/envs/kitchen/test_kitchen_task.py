"""The kitchen's task record, its reachable records and its rewards (voot.envs.kitchen.task)."""

from __future__ import annotations

import dataclasses
import math
import re

import pytest

from voot.envs.kitchen.config import KitchenConfig
from voot.envs.kitchen.task import KitchenTask, pick_reward, place_reward, task_error

#: A kitchen of 4 objects whose handling order is 3, 0, 2, 1.
ORDER = (3, 0, 2, 1)
RANK = {i: k for k, i in enumerate(ORDER)}
PICK = KitchenTask(0, "pick", -1, (0.0, 0.0, 0.0), (), (3, 2), False, False)
PLACE = KitchenTask(1, "place", 3, (0.5, -0.1, 1.2), (0.1,) * 7, (3, 2), False, False)


def _error(task: KitchenTask) -> str | None:
    return task_error(task, 4, 50, ORDER, RANK)


R = dataclasses.replace


def test_records_episodes_reach_pass() -> None:
    assert _error(PICK) is None and _error(PLACE) is None
    done = dataclasses.replace(PICK, steps=50, on_path=(), done=True, last_place_cleared=True)
    assert _error(done) is None
    # the first and the last object index may be held at a place
    assert _error(R(PLACE, held=0)) is None and _error(R(PLACE, held=3)) is None


@pytest.mark.parametrize(
    ("task", "match"),
    [
        (R(PICK, steps=51), r"steps must be an int in 0\.\.50 \(the horizon\), got 51"),
        (R(PICK, steps=True), "steps must be an int"),
        (R(PICK, operator="drop"), "operator must be 'pick' or 'place', got 'drop'"),
        (R(PICK, held=0), r"held must be -1 before a pick"),
        (R(PLACE, held=4), r"held must be an object index in 0\.\.3 before a place, got 4"),
        (R(PLACE, held_rel=(0.0, math.nan, 0.0)), "held_rel must be 3 finite numbers"),
        (R(PLACE, grasp_q=(0.0,) * 6), "grasp_q must be 7 finite joint values"),
        (R(PICK, on_path=(4,)), r"on_path must be a tuple of object indices in 0\.\.3"),
        (R(PICK, on_path=(2, 3)), r"handling order \(3, 0, 2, 1\)"),
        (R(PICK, on_path=(0, 0)), "distinct objects"),
        (R(PICK, done=None), "last_place_cleared and done must be bools"),
        (R(PICK, done=True), "done must be False when on_path is"),
        # a pick-time record holds no grasp (issue 26: any values were taken)
        (R(PICK, held_rel=(0.5, -0.1, 1.2)), r"held_rel and grasp_q must be \(0\.0, 0\.0, 0\.0\)"),
        (R(PICK, grasp_q=(0.1,) * 7), r"and \(\) before a pick \(no grasp\)"),
        (R(PICK, held_rel="xyz"), "held_rel and grasp_q must be"),
        (R(PICK, last_place_cleared=True), "only after a pick and a place, at step 0"),
        (R(PLACE, last_place_cleared=True), "at step 1"),
    ],
)
def test_records_no_episode_reaches_are_named(task: KitchenTask, match: str) -> None:
    error = _error(task)
    assert error is not None
    assert re.search(match, error), error


def test_rewards_follow_the_reference_page() -> None:
    cfg = KitchenConfig()
    assert pick_reward(cfg, True) == 1.0 and pick_reward(cfg, False) == 0.0
    assert place_reward(cfg, True, 0.8) == 1.0 / 0.8  # 1/L below the cap
    assert place_reward(cfg, True, 0.25) == 2.0  # capped
    assert place_reward(cfg, True, 0.0) == 2.0  # the robot did not move
    assert place_reward(cfg, False, 0.5) == -0.5  # -L above the cap
    assert place_reward(cfg, False, 3.0) == -2.0  # capped
    tight = KitchenConfig(pick_reward=0.5, max_place_reward=0.05, max_place_penalty=0.05)
    assert pick_reward(tight, True) == 0.5
    assert place_reward(tight, True, 1.0) == 0.05 and place_reward(tight, False, 1.0) == -0.05
