"""The kitchen's pick and place checks (voot.envs.kitchen.checks): reasons, carry, pre-check."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from kitchen_fixtures import place_action

import voot  # noqa: F401  (registers the ids)
from voot.envs.core.units import normalize
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.poses import pick_base
from voot.envs.kitchen.scripted import kitchen_actions


@pytest.fixture(scope="module")
def env() -> KitchenClearingEnv:
    return KitchenClearingEnv()


def test_placements_in_the_large_rooms_are_infeasible(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    env.step(kitchen_actions(env)[0])
    before = env.get_state()
    obs0 = env._observation()
    for x, y in ((4.0, 2.0), (4.5, -2.0), (3.2, 1.0)):
        _, r, _, _, info = env.step(place_action(env, x, y, 0.0))
        assert not info["feasible"] and r == -2.0
        assert info["reason"].startswith("forbidden room")
        env.set_state(before)
    # the robot cannot pass the 0.9 m door at all
    assert env.planner.plan(env.config.start, (4.4, 2.0, 0.0), env.config.robot_radius) is None
    # infeasible actions change nothing but the step counter
    _, _, _, _, info = env.step(place_action(env, 4.0, 2.0, 0.0))
    np.testing.assert_array_equal(env._observation()[:-1], obs0[:-1])


def test_infeasible_pick_reasons(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    reasons = set()
    rng = np.random.default_rng(0)
    for _ in range(300):
        s = env.get_state()
        _, r, _, _, info = env.step(rng.uniform(-1, 1, 6))
        if not info["feasible"]:
            assert r == -2.0
            reasons.add(info["reason"].split(":")[0])
        env.set_state(s)
    assert {"collision", "IK failed", "outside region"} <= reasons


#: A first pick (paper units: radians, fractions) that passes IK, collision and region
#: checks but leaves the carry disc (robot + held box) overlapping the chair next to it.
DEAD_END_PICK = (2.4075, 0.6945, 0.2081, 0.7607, 3.3009, -0.1987)


def test_pick_requires_a_free_carry_disc(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    assert env.config.pick_requires_free_carry  # the default
    s = env.get_state()
    obs0 = env._observation()
    a = normalize(DEAD_END_PICK, env.config.pick_ranges)
    _, r, _, _, info = env.step(a)
    assert not info["feasible"] and r == -2.0
    assert info["reason"] == "carry footprint collides with obj_chair1"
    assert env.task.operator == "pick" and env.task.held == -1
    np.testing.assert_array_equal(env._observation()[:-1], obs0[:-1])
    env.set_state(s)

    # option off (through gym.make's kwargs): the old check accepts the pick, and the
    # place step's planner then starts in collision (every place: "no base path")
    off = gym.make("voot/KitchenClearing-v0", pick_requires_free_carry=False).unwrapped
    assert isinstance(off, KitchenClearingEnv) and not off.config.pick_requires_free_carry
    off.reset(seed=0)
    _, r, _, _, info = off.step(a)
    assert info["feasible"] and info["reason"] == "" and r == 0.0
    disc = off.held_disc()
    base = off.robot.base_pose(off.data)
    boxes = off.object_boxes(exclude=(off.task.held,))
    assert not off.planner.is_free(disc.center(base), disc.radius, boxes)
    assert off.planner.colliding(disc.center(base), disc.radius, boxes) == ["obj_chair1"]
    _, _, _, _, info = off.step(place_action(off, 1.0, -3.0, 0.0))
    assert not info["feasible"] and info["reason"] == "no base path"
    off.close()


def test_precheck_infos_and_the_state_after_a_place(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    acts = kitchen_actions(env)
    ok, info = env.precheck(acts[0])
    assert ok and info["feasible"] and info["reason"] == ""
    assert info["operator"] == "pick" and info["object"] == "obj_box1"
    bad = np.ones(6)
    ok, info = env.precheck(bad)
    assert not ok and not info["feasible"] and info["reason"]
    env.step(acts[0])
    ok, info = env.precheck(place_action(env, -1.95, 0.0, 0.5))  # half outside the house
    assert not ok and not info["feasible"] and info["reason"].startswith("outside region")
    assert info["operator"] == "place" and info["object"] == "obj_box1"
    ok, info = env.precheck(acts[1])
    assert ok and info["feasible"] and info["object"] == "obj_box1"
    env.step(acts[1])
    # after a place the robot holds nothing
    t = env.task
    assert t.operator == "pick" and t.held == -1
    assert t.held_rel == (0.0, 0.0, 0.0) and t.grasp_q == ()


def test_pick_base_pose_is_the_pose_of_the_objects_footprint(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    params = np.array([2.0, 0.7, 0.5, 0.6, 1.0, 0.2])
    for obj in (0, 3):
        base = env.pick_base_pose(obj, params)
        assert base.tobytes() == pick_base(env.object_box(obj), params).tobytes()


class MissingGrasp(KitchenClearingEnv):
    """A kitchen whose grasp hook misses every object (as a mesh grasp may)."""

    def _grasp_pose(self, obj, pose, base_heading, params):  # type: ignore[no-untyped-def]
        return None, "grasp misses the object"


def test_a_grasp_hook_that_misses_makes_the_pick_infeasible() -> None:
    env = KitchenClearingEnv(preset="v1")
    env.reset(seed=0)
    pick = kitchen_actions(env)[0]
    # the v1 hook is the side grasp: the scripted pick is feasible
    grasp, why = env._grasp_pose(0, env.object_pose(0), 0.0, np.array([2.0, 0.8, 0.5]))
    assert grasp is not None and why == ""
    assert env.precheck(pick)[0]
    miss = MissingGrasp(preset="v1")
    miss.reset(seed=0)
    before = miss.get_state()
    ok, info = miss.precheck(pick)
    assert not ok and info["reason"] == "grasp misses the object"
    _, reward, _, _, info = miss.step(pick)
    assert not info["feasible"] and info["reason"] == "grasp misses the object"
    assert reward == miss.config.infeasible_reward
    assert np.array_equal(miss.get_state().physics, before.physics)
