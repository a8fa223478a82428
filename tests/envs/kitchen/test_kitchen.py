"""voot/KitchenClearing-v0 (voot.envs.kitchen.env): the env's step, rewards, snapshots, API checks.

The layers it is built of have their own test modules (test_kitchen_config, _task,
_path, _poses, _screen, _checks); test_kitchen_v1 covers the v1 preset's options.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest
from env_fixtures import (
    assert_horizon_ends,
    assert_restore_is_exact,
    check_gymnasium_api,
    timed_step,
)
from gymnasium.utils.env_checker import data_equivalence
from kitchen_fixtures import place_action
from process_fixtures import run_pickled

import voot  # noqa: F401  (registers the ids)
from voot.envs.kitchen.env import KitchenClearingEnv, KitchenConfig
from voot.envs.kitchen.scripted import kitchen_actions
from voot.envs.robot.model import compose2d, inverse2d


@pytest.fixture(scope="module")
def env() -> KitchenClearingEnv:
    return KitchenClearingEnv()


def test_initial_task(env: KitchenClearingEnv) -> None:
    obs, info = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    assert {k: info[k] for k in ("next_operator", "objects_left", "next_object")} == {
        "next_operator": "pick",
        "objects_left": 7,
        "next_object": "obj_box1",
    }
    # the step's keys with neutral values (a vector env stacks both)
    assert info["operator"] is None and info["feasible"] and not info["parameters_mask"].any()
    names = [env.objects[i].name for i in env.task.on_path]
    assert names == [
        "obj_box1",
        "obj_chair1",
        "obj_box2",
        "obj_chair2",
        "obj_box3",
        "obj_box4",
        "obj_chair3",
    ]
    # the fixed path is the straight segment from the start to the sink pose
    np.testing.assert_allclose(env.path.waypoints[[0, -1], :2], [[-1.5, -1.5], [0.0, 2.5]])
    assert env.action_bounds().dim == 6


def test_scripted_solution_clears_every_obstacle(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    rewards, infos = [], []
    for a in kitchen_actions(env):
        _, r, terminated, truncated, info = env.step(a)
        assert info["feasible"], info["reason"]
        rewards.append(r)
        infos.append(info)
        assert not truncated
    assert terminated and info["objects_left"] == 0 and info["goal_bonus"] == 2.0
    assert all(i["goal_bonus"] == 0.0 for i in infos[:-1])
    # picks: 0 first, then +1 after every clearing place; places: min(1/L, 2)
    assert rewards[0::2] == [0.0] + [1.0] * 6
    for r, i in zip(rewards[1::2], infos[1::2], strict=True):
        assert r == pytest.approx(min(1.0 / i["base_path_length"], 2.0))
        assert len(i["base_path"][0]) == 3  # (x, y, theta) waypoints
    assert [i["objects_left"] for i in infos[1::2]] == [6, 5, 4, 3, 2, 1, 0]
    with pytest.raises(ValueError, match="ended"):
        env.step(np.zeros(6))
    with pytest.raises(ValueError, match="ended"):
        env.precheck(np.zeros(6))


def test_infos_carry_base_poses_and_placements(env: KitchenClearingEnv) -> None:
    """``base_pose`` and ``placement`` (what a recording draws) match the state reached."""
    env.reset(seed=0)
    for a in kitchen_actions(env):
        _, _, _, _, info = env.step(a)
        base = info["base_pose"]
        assert isinstance(base, tuple) and len(base) == 3
        assert all(type(v) is float for v in base)
        np.testing.assert_allclose(base, env.robot.base_pose(env.data), atol=1e-12)
        if info["operator"] == "pick":
            assert info["placement"] is None
            # no base path for picks by default: none reported
            assert info["base_path_length"] == 0.0 and info["base_path"] is None
        else:
            x, y, _, yaw = env.object_pose(env.object_index[info["object"]])
            px, py, pth = info["placement"]
            np.testing.assert_allclose((px, py), (x, y), atol=1e-12)
            assert math.cos(pth - yaw) == pytest.approx(1.0)
            np.testing.assert_allclose(info["parameters"][:3], info["placement"])
            assert info["parameters_mask"].tolist() == [True] * 3 + [False] * 3


def test_infeasible_infos_carry_the_poses(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    rng = np.random.default_rng(1)
    s = env.get_state()
    reasons = set()
    for _ in range(200):  # infeasible picks: the sampled base pose
        a = rng.uniform(-1, 1, 6)
        _, _, _, _, info = env.step(a)
        env.set_state(s)
        expected = env.pick_base_pose(env.task.on_path[0], info["parameters"])
        np.testing.assert_allclose(info["base_pose"], expected, atol=1e-12)
        assert info["placement"] is None
        if not info["feasible"]:
            reasons.add(info["reason"].split(":")[0])
            # the robot did not move: no base path
            assert info["base_path_length"] == 0.0 and info["base_path"] is None
    assert {"collision", "IK failed", "outside region"} <= reasons
    env.step(kitchen_actions(env)[0])
    held_rel = env.task.held_rel
    before = env.get_state()
    for x, y in ((4.0, 2.0), (-1.95, 0.0)):  # a forbidden room; half outside the house
        _, r, _, _, info = env.step(place_action(env, x, y, 0.5))
        env.set_state(before)
        assert not info["feasible"] and r == -2.0
        np.testing.assert_allclose(info["placement"], (x, y, 0.5), atol=1e-12)
        # the base pose follows from the grasp
        np.testing.assert_allclose(
            info["base_pose"][:2], compose2d((x, y, 0.5), inverse2d(held_rel))[:2], atol=1e-12
        )


def test_non_clearing_place_is_penalised(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    acts = kitchen_actions(env)
    env.step(acts[0])
    # put box1 back where it stands (rotated slightly): still on the path
    x, y, _, yaw = env.object_pose(env.task.held)
    _, r, _, _, info = env.step(place_action(env, x, y, (yaw + 0.05) % (2 * math.pi)))
    assert info["feasible"] and info["objects_left"] == 7
    assert r == pytest.approx(max(-info["base_path_length"], -2.0))
    _, r, _, _, info = env.step(acts[0])  # the next pick: no clearing before it
    assert info["operator"] == "pick" and r == 0.0


def test_bad_actions(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    with pytest.raises(ValueError, match="NaN"):
        env.step(np.array([0.0, np.nan, 0, 0, 0, 0]))
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(3))
    with pytest.raises(ValueError, match="numeric"):
        env.step("pick")  # type: ignore[arg-type]


def test_out_of_range_actions_are_clipped(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    s = env.get_state()
    a = kitchen_actions(env)[0]
    wild = a * 1.0
    wild[5] = -7.0  # facing offset far below the range -> clipped to -1
    clipped = np.clip(wild, -1.0, 1.0)
    out_wild = env.step(wild)
    env.set_state(s)
    out_clip = env.step(clipped)
    assert out_wild[4]["action_clipped"] and not out_clip[4]["action_clipped"]
    assert data_equivalence(out_wild[:4], out_clip[:4])


def test_truncation_at_the_horizon() -> None:
    env = KitchenClearingEnv(KitchenConfig(horizon=2))
    env.reset(seed=0)
    bad = place_action(env, 4.0, 2.0, 0.0)  # a pick here: infeasible (IK/collision/region)
    bad[:] = 1.0
    _, _, term, trunc, _ = env.step(bad)
    assert not term and not trunc
    assert_horizon_ends(env, bad)


def test_snapshot_restore_is_bit_identical(env: KitchenClearingEnv) -> None:
    assert_restore_is_exact(env, seed=3, actions=kitchen_actions, before=3)


def test_snapshot_determinism_across_processes(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    acts = kitchen_actions(env)
    for a in acts[:5]:
        env.step(a)
    state = env.get_state()
    rng = np.random.default_rng(7)
    probes = [acts[5]] + [np.clip(rng.normal(0, 0.6, 6), -1, 1) for _ in range(3)]
    local = []
    for a in probes:
        env.set_state(state)
        local.append(env.step(a))
    script = textwrap.dedent(
        """
        import pickle, sys
        from voot.envs.kitchen.env import KitchenClearingEnv
        state, probes = pickle.load(sys.stdin.buffer)
        env = KitchenClearingEnv()
        env.reset(seed=0)
        out = []
        for a in probes:
            env.set_state(state)
            out.append(env.step(a))
        sys.stdout.buffer.write(pickle.dumps(out))
        """
    )
    remote = run_pickled(script, (state, probes))
    assert data_equivalence(local, remote, exact=True)
    assert any(r[4]["feasible"] for r in local)


def test_gymnasium_checks() -> None:
    check_gymnasium_api("voot/KitchenClearing-v0", num_steps=12, seed=1)


def test_render_rgb_array() -> None:
    env = KitchenClearingEnv(render_mode="rgb_array", render_size=(160, 120))
    env.reset(seed=0)
    for cam in ("perspective", "top_down"):
        env.render_camera = cam
        img = env.render()
        assert img is not None and img.shape == (120, 160, 3) and img.dtype == np.uint8
        assert img.std() > 5  # not a blank image
    env.close()
    with pytest.raises(ValueError, match="render_mode"):
        KitchenClearingEnv(render_mode="human")


def test_place_base_pose_follows_the_grasp(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    env.step(kitchen_actions(env)[0])
    rel = env.task.held_rel
    env.step(kitchen_actions(env)[1])
    x, y, _, yaw = env.object_pose(env.object_index["obj_box1"])
    base = env.robot.base_pose(env.data)
    np.testing.assert_allclose(inverse2d(rel)[:2], _relative(base, (x, y, yaw)), atol=1e-9)


def _relative(base: np.ndarray, obj: tuple[float, float, float]) -> np.ndarray:
    """The base's position in the object's frame."""
    c, s = math.cos(obj[2]), math.sin(obj[2])
    d = np.array([base[0] - obj[0], base[1] - obj[1]])
    return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])


def test_place_rewards_reach_their_caps() -> None:
    """min(1/L, cap) for a clearing place and max(-L, -cap) otherwise, with the caps hit."""
    tight = KitchenClearingEnv(KitchenConfig(max_place_reward=0.05, max_place_penalty=0.05))
    loose = KitchenClearingEnv()
    for env in (tight, loose):
        env.reset(seed=0)
        acts = kitchen_actions(env)
        env.step(acts[0])
        state = env.get_state()
        _, r_clear, _, _, info = env.step(acts[1])  # the scripted place clears box1
        assert info["objects_left"] == 6
        length = info["base_path_length"]
        assert r_clear == pytest.approx(min(1.0 / length, env.config.max_place_reward))
        env.set_state(state)
        x, y, _, yaw = env.object_pose(env.task.held)
        _, r_stay, _, _, info = env.step(place_action(env, x, y, (yaw + 0.05) % (2 * math.pi)))
        assert info["feasible"] and info["objects_left"] == 7
        assert r_stay == pytest.approx(
            max(-info["base_path_length"], -env.config.max_place_penalty)
        )
    # the caps bind in the tight config and not in the default one
    assert 1.0 / length > 0.05


def test_a_short_clearing_place_earns_one_over_its_length_below_the_cap(
    env: KitchenClearingEnv,
) -> None:
    """Under 1 m but over 1/cap, a clearing place earns 1/L: more than 1, less than 2."""
    env.reset(seed=0)
    env.step(kitchen_actions(env)[0])
    x, y, _, yaw = env.object_pose(env.task.held)
    # box1 set down 0.7 m east of where it stood: off the path, a 0.7 m drive
    _, r, _, _, info = env.step(place_action(env, x + 0.7, y, yaw))
    assert info["feasible"] and info["objects_left"] == 6  # it cleared box1
    length = info["base_path_length"]
    assert 1.0 / env.config.max_place_reward < length < 1.0
    assert r == pytest.approx(1.0 / length) and 1.0 < r < env.config.max_place_reward


def test_a_pick_path_starts_clear_of_the_objects_the_robot_stands_against() -> None:
    """With a pick base-path disc wider than the base (0.4 m), the robot stands overlapping
    the chair or box it has just set down; that object is left out of the pick's path
    obstacles, so the scripted solution still clears the kitchen."""
    env = KitchenClearingEnv(KitchenConfig(pick_base_path=True, pick_path_radius=0.4))
    env.reset(seed=0)
    touched = []
    for a in kitchen_actions(env):
        if env.task.operator == "pick":
            here = env.robot.base_pose(env.data)
            touched += env.planner.colliding(here, 0.4, env.object_boxes())
        _, _, terminated, _, info = env.step(a)
        assert info["feasible"], info["reason"]
    assert terminated and info["objects_left"] == 0
    assert {"obj_chair1", "obj_box2"} <= set(touched)  # the case did occur


def test_step_timings_are_consistent(env: KitchenClearingEnv) -> None:
    """``last_timing`` (read by ``voot.bench.measure.env_speed``): parts >= 0 that sum to <= total.

    Over feasible picks and places and over infeasible ones stopped at each check.
    """
    env.reset(seed=0)
    acts = kitchen_actions(env)
    rng = np.random.default_rng(3)

    s = env.get_state()
    for _ in range(40):  # infeasible and feasible picks
        timed_step(env, rng.uniform(-1, 1, 6))
        env.set_state(s)
    timed_step(env, acts[0])
    s = env.get_state()
    # places: outside the house, in a forbidden room, feasible
    for x, y in ((-1.95, 0.0), (4.0, 2.0)):
        timed_step(env, place_action(env, x, y, 0.5))
        env.set_state(s)
    timed_step(env, acts[1])
    # a pick with its base path planned (pick_base_path): the planning time is counted
    env = KitchenClearingEnv(KitchenConfig(pick_base_path=True))
    env.reset(seed=0)
    _, _, _, _, info = timed_step(env, kitchen_actions(env)[0])
    assert info["feasible"] and env.last_timing.planning > 0.0


def test_every_step_counts_and_a_place_empties_the_gripper(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    assert env.task.steps == 0
    pick, place = kitchen_actions(env)[:2]
    env.step(pick)
    assert env.task.steps == 1 and env.task.operator == "place" and len(env.task.grasp_q) == 7
    assert env.task.held_rel != (0.0, 0.0, 0.0)
    _, _, _, _, info = env.step(place)
    assert info["feasible"]
    t = env.task
    assert t.steps == 2 and t.operator == "pick" and t.held == -1
    assert t.held_rel == (0.0, 0.0, 0.0) and t.grasp_q == ()
    before = env.get_state()
    env.step(np.full(6, 0.99))  # any step counts, feasible or not
    assert env.task.steps == 3
    env.set_state(before)
