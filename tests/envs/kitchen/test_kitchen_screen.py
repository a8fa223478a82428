"""The kitchen's exact pre-screen and carry-disc test (voot.envs.kitchen.screen)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from voot.envs.core.units import denormalize
from voot.envs.kitchen.env import KitchenClearingEnv, KitchenConfig
from voot.envs.kitchen.poses import relative_pose, relative_pose_floats
from voot.envs.kitchen.scripted import kitchen_actions


@pytest.fixture(scope="module")
def env() -> KitchenClearingEnv:
    return KitchenClearingEnv()


def _screen_against_the_step(env: KitchenClearingEnv, actions: np.ndarray) -> dict[str, int]:
    """certainly_infeasible of each action vs the step's verdict; counts of the outcomes."""
    counts = {"screened": 0, "infeasible": 0, "feasible": 0}
    for a in actions:
        before = env.get_state()
        screened = env.certainly_infeasible(a)
        assert env.get_state() == before  # the screen changes nothing
        assert env.certainly_infeasible_values(a.tolist()) is screened  # the float entry
        _, _, _, info = env.transition(a)
        env.set_state(before)
        if info["feasible"]:
            assert not screened, info  # never a feasible action
            counts["feasible"] += 1
        else:
            counts["infeasible"] += 1
            counts["screened"] += screened
    return counts


@pytest.mark.parametrize("carry", [True, False])
def test_certainly_infeasible_is_exact(carry: bool) -> None:
    """The pre-screen never rejects a feasible step, and settles most infeasible ones."""
    env = KitchenClearingEnv(config=KitchenConfig(pick_requires_free_carry=carry))
    env.reset(seed=0)
    rng = np.random.default_rng(11)
    totals = {"pick": [0, 0], "place": [0, 0]}  # screened, infeasible
    for good in kitchen_actions(env)[:4]:
        op = env.task.operator
        dim = 6 if op == "pick" else 3
        props = np.zeros((150, 6))
        props[:, :dim] = rng.uniform(-1, 1, (150, dim))
        c = _screen_against_the_step(env, props)
        totals[op][0] += c["screened"]
        totals[op][1] += c["infeasible"]
        env.transition(good)
    for op, (screened, infeasible) in totals.items():
        assert infeasible > 100 and screened > 0.6 * infeasible, (op, screened, infeasible)


def test_certainly_infeasible_leaves_odd_cases_to_the_step(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    far = np.full(6, 1.0)  # the robot leaves the house
    assert env.certainly_infeasible(far)
    assert not env.certainly_infeasible(far * 3.0)  # to be clipped: the step decides
    assert not env.certainly_infeasible(np.full(6, np.nan))  # the step raises
    assert not env.certainly_infeasible(far[:3])
    env.task = dataclasses.replace(env.task, done=True)
    assert not env.certainly_infeasible(far)  # the step raises: the episode has ended
    env.reset(seed=0)


def test_carry_verdict_on_floats_is_the_carry_test(env: KitchenClearingEnv) -> None:
    """The pick screen's float carry test answers as _carry_blocked, or abstains."""
    env.reset(seed=0)
    rng = np.random.default_rng(12)
    ctx = env._screen_context()
    seen = set()
    for a in rng.uniform(-1, 1, (600, 6)):
        base = env.pick_base_pose(ctx.obj, denormalize(a, ctx.ranges))
        bx, by, heading = base.tolist()
        held_rel = relative_pose_floats(bx, by, heading, ctx.pose_xyyaw)
        assert held_rel == relative_pose(base, ctx.pose)
        verdict = env._carry_verdict(ctx, held_rel, bx, by, heading)
        assert verdict is not None
        assert verdict is bool(env._carry_blocked(ctx.obj, held_rel, base))
        seen.add(verdict)
    assert seen == {True, False}


def test_carry_discs_are_remembered_and_enclose_the_robot(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    assert env.held_disc().radius == env.config.robot_radius  # nothing held
    env.step(kitchen_actions(env)[0])
    t = env.task
    disc = env.held_disc()
    assert disc is env.carry_disc_for(t.held, t.held_rel)  # the same object: remembered
    assert disc.radius >= env.config.robot_radius
    env.reset(seed=0)


def test_certainly_infeasible_is_exact_with_the_footprint() -> None:
    """With ``base_model="footprint"`` the screen asks the exact search where the disc
    fails, so it still never rejects a place the step executes."""
    env = KitchenClearingEnv(
        config=KitchenConfig(pick_requires_free_carry=False, base_model="footprint")
    )
    env.reset(seed=0)
    rng = np.random.default_rng(12)
    good = kitchen_actions(env)
    env.transition(good[0])  # holding the first obstacle: a place node
    props = np.zeros((80, 6))
    props[:, :3] = rng.uniform(-1, 1, (80, 3))
    c = _screen_against_the_step(env, props)
    assert c["feasible"] > 0 and c["infeasible"] > 0 and c["screened"] > 0, c


def test_the_carry_footprint_is_inside_the_carry_disc(env: KitchenClearingEnv) -> None:
    """The footprint's rectangles (base square, held object) lie in the carry disc, so a
    disc path is a footprint path; remembered per object and grasp."""
    env.reset(seed=0)
    env.step(kitchen_actions(env)[0])
    t = env.task
    disc = env.carry_disc_for(t.held, t.held_rel)
    footprint = env.carry_footprint_for(t.held, t.held_rel)
    assert footprint is env.carry_footprint_for(t.held, t.held_rel)
    assert [p.name for p in footprint.parts] == ["base", env.objects[t.held].name]
    assert footprint.reach <= disc.radius + 1e-9
    env.reset(seed=0)
