"""Tests of voot.envs.pick_place_demo: the tiny MuJoCo pick-and-place demo problem."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mujoco")

from voot.envs.pick_place_demo import GOAL, DemoPickPlace
from voot.tree import PlanningProblem, plan


def test_pick_then_place_on_the_goal() -> None:
    p = DemoPickPlace()
    assert isinstance(p, PlanningProblem)
    assert p.operator == "pick"
    far = p.step(np.array([2.0, 2.0, 0.0]))
    assert not far.feasible and far.reward == -2.0 and far.info["base_pose"] == (2.0, 2.0, 0.0)
    p = DemoPickPlace()
    pick = p.step(np.array([-1.1, -1.0, np.pi]))
    assert pick.feasible and pick.reward == pytest.approx(1.0)
    assert pick.info == {"base_pose": (-1.1, -1.0, np.pi), "next_operator": "place"}
    assert p.operator == "place"
    assert np.allclose(p.data.qpos[:3], [-1.1, -1.0, np.pi])
    assert p.data.qpos[5] == pytest.approx(0.72)  # carried in the hand
    too_far = p.step(np.array([1.0, 1.0, 0.0]))
    assert not too_far.feasible and too_far.info["next_operator"] == "place"
    # Teleport next to the goal, then place on it: terminal, with the bonus apart.
    p = DemoPickPlace()
    p.data.qpos[3:5] = (GOAL[0] - 1.0, GOAL[1])
    p.step(np.array([GOAL[0] - 0.6, GOAL[1], 0.0]))
    done = p.step(np.array([GOAL[0], GOAL[1], 0.5]))
    assert (
        done.feasible and done.terminal and done.bonus == 2.0 and done.reward == pytest.approx(1.0)
    )
    assert np.allclose(p.data.xpos[p.model.body("box").id], [GOAL[0], GOAL[1], 0.1])


def test_snapshots_are_exact_and_search_is_deterministic() -> None:
    p = DemoPickPlace(horizon=4)
    s0 = p.snapshot()
    a = np.array([-1.1, -1.0, 0.3])
    r1 = p.step(a)
    s1 = p.snapshot()
    p.restore(s0)
    r2 = p.step(a)
    assert r1 == r2 and np.array_equal(p.snapshot()[0], s1[0])
    with pytest.raises(ValueError, match="read-only"):
        s0[0][0] = 1.0
    res1 = plan(DemoPickPlace(), "voot", 60, seed=2)
    res2 = plan(DemoPickPlace(), "voot", 60, seed=2)
    assert np.array_equal(res1.best_return_curve, res2.best_return_curve)


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="horizon"):
        DemoPickPlace(horizon=0)
    p = DemoPickPlace()
    with pytest.raises(ValueError, match="3 finite numbers"):
        p.step(np.array([0.0, np.nan, 0.0]))
    with pytest.raises(ValueError, match="3 finite numbers"):
        p.step(np.zeros(2))
