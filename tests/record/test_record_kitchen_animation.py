"""Tests of voot.record.kitchen_animation: a kitchen plan as frames."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("rerun")
pytest.importorskip("mujoco")
pytest.importorskip("matplotlib")

from voot.bench.demos.kitchen_demo import make_problem
from voot.envs.kitchen.scripted import kitchen_actions
from voot.record.kitchen_animation import (
    GENERATED_VIEW_DISTANCE,
    KITCHEN_VIEW,
    kitchen_view,
    plan_animation,
)


def test_plan_animation_follows_the_scripted_solution() -> None:
    problem = make_problem(0)
    env = problem.unwrapped
    # pick and place box1, then chair1 (a planner's place actions are 3-D)
    actions = [a if k % 2 == 0 else a[:3] for k, a in enumerate(kitchen_actions(env)[:4])]
    expected = make_problem(0)
    for a in actions:
        expected.step(a)
    frames = plan_animation(problem, actions, size=(96, 72), label="test")
    assert len(frames) > 2 * len(actions)  # drives and arm motions between the states
    assert all(f.shape == (72, 96, 3) and f.dtype == np.uint8 for f in frames)
    assert frames[0].std() > 5 and not np.array_equal(frames[0], frames[-1])
    # the problem is left at the end of the plan, exactly
    assert problem.snapshot() == expected.snapshot()
    with pytest.raises(ValueError, match="size"):
        plan_animation(problem, [], size=(10, 10))


def test_kitchen_view_fits_a_generated_house() -> None:
    assert kitchen_view(make_problem(0).unwrapped) == KITCHEN_VIEW  # the paper's kitchen
    env = make_problem(
        0, "voot/KitchenClearing-v2", {"layout_seed": 3, "difficulty": "medium"}
    ).unwrapped
    x0, x1, y0, y1 = env.layout.house
    view = kitchen_view(env)
    assert view["lookat"] == pytest.approx((0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0))
    assert view["distance"] == pytest.approx(GENERATED_VIEW_DISTANCE * max(x1 - x0, y1 - y0))
    frame = plan_animation(
        make_problem(0, "voot/KitchenClearing-v2", {"layout_seed": 3, "difficulty": "medium"}),
        [],
        size=(96, 72),
    )[0]
    assert frame.shape == (72, 96, 3) and frame.std() > 5
