"""voot/ConveyorPacking-v0: doors and box sizes, scripted packing, rewards, snapshots, checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
from env_fixtures import (
    assert_horizon_ends,
    assert_restore_is_exact,
    check_gymnasium_api,
    timed_step,
)
from gymnasium.utils.env_checker import data_equivalence

import voot  # noqa: F401  (registers the ids)
from voot.envs.conveyor.config import ConveyorConfig
from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.scripted import CONVEYOR_SOLUTION, conveyor_actions
from voot.envs.core.units import normalize

DOOR = 1.62  # the first room's door (models/generate_scenes.py)


@pytest.fixture(scope="module")
def env() -> ConveyorPackingEnv:
    return ConveyorPackingEnv()


def _action(env: ConveyorPackingEnv, poses: list[tuple[float, float, float]]) -> np.ndarray:
    a = np.zeros(9)
    for k, (x, y, th) in enumerate(poses):
        a[3 * k : 3 * k + 3] = normalize([x, y, math.radians(th)], env.config.place_ranges)
    return a


def test_fixed_picks_and_door_rule(env: ConveyorPackingEnv) -> None:
    radii = [p.disc.radius for p in env.picks]
    # the two big boxes make the disc too wide for the door, the small ones do not
    assert min(radii[:2]) > DOOR / 2
    assert max(radii[2:]) < DOOR / 2
    for p in env.picks:
        assert len(p.arm_q) == 7 and p.rel[2] == 0.0


def test_carry_discs_are_free_at_the_start_and_cannot_be_blocked(
    env: ConveyorPackingEnv,
) -> None:
    # the kitchen's pick_requires_free_carry rule holds for every fixed pick, and no
    # placement can break it: each disc stays east of the loading region
    cfg = env.config
    for pick in env.picks:
        c = pick.disc.center(cfg.start)
        assert env.planner.is_free(c, pick.disc.radius)
        assert c[0] - pick.disc.radius > cfg.loading_region[1]


def test_scripted_solution_packs_every_box(env: ConveyorPackingEnv) -> None:
    env.reset(seed=0)
    total = 0.0
    for a in conveyor_actions(env):
        _, r, terminated, truncated, info = env.step(a)
        assert info["feasible"], info["reason"]
        assert r == pytest.approx(
            sum(math.exp(-0.1 * length) for length in info["base_path_lengths"])
        )
        assert len(info["base_paths"]) == len(info["objects"])
        total += r
        assert not truncated
    assert terminated and info["objects_placed"] == 20 and info["objects_left"] == 0
    assert info["goal_bonus"] == 0.0
    with pytest.raises(ValueError, match="ended"):
        env.step(np.zeros(9))
    with pytest.raises(ValueError, match="ended"):
        env.precheck(np.zeros(9))
    assert total > 5.0
    # every box is where the solution put it
    for i, (x, y, th) in enumerate(CONVEYOR_SOLUTION):
        px, py, pz, yaw = env.object_pose(i)
        assert (px, py, pz) == pytest.approx((x, y, 0.0))
        assert math.cos(yaw - math.radians(th)) == pytest.approx(1.0)


def test_infos_carry_base_poses_and_placements(env: ConveyorPackingEnv) -> None:
    """``placement``/``base_pose`` are the first box's; ``placements``/``base_poses`` all."""
    env.reset(seed=0)
    start = 0
    for a in conveyor_actions(env)[:3]:
        _, _, _, _, info = env.step(a)
        m = len(info["objects"])
        assert len(info["placements"]) == len(info["base_poses"]) == m
        assert info["placement"] == info["placements"][0]
        assert info["base_pose"] == info["base_poses"][0]
        for k in range(m):
            x, y, _, yaw = env.object_pose(start + k)
            px, py, pth = info["placements"][k]
            assert (px, py) == pytest.approx((x, y), abs=1e-12)
            assert math.cos(pth - yaw) == pytest.approx(1.0)
            expected = env.place_base_pose(start + k, info["placements"][k])
            np.testing.assert_allclose(info["base_poses"][k], expected, atol=1e-12)
        start += m
    # infeasible (the first box sticks out of the loading region): the poses are given
    env.reset(seed=0)
    _, r, _, _, info = env.step(
        _action(env, [(-0.6, 1.0, 0), (-3.5, -0.05, 180), (-6.55, 2.55, 90)])
    )
    assert r == -2.0 and info["reason"].startswith("box 1/3 (obj_00): outside region")
    np.testing.assert_allclose(info["placement"], (-0.6, 1.0, 0.0), atol=1e-12)
    np.testing.assert_allclose(info["placements"], info["parameters"], atol=0)
    assert len(info["base_poses"]) == 3
    np.testing.assert_allclose(info["base_pose"], env.place_base_pose(0, (-0.6, 1.0, 0.0)))


def test_big_box_cannot_pass_the_door(env: ConveyorPackingEnv) -> None:
    env.reset(seed=0)
    s = env.get_state()
    obs0 = env._observation()
    # obj_00 (big) into the west room, behind the door: no base path
    _, r, _, _, info = env.step(
        _action(env, [(-6.55, 2.55, 90), (-3.5, -0.05, 180), (-5.45, 2.55, 90)])
    )
    assert not info["feasible"] and r == -2.0
    assert info["reason"] == "box 1/3 (obj_00): no base path"
    np.testing.assert_array_equal(env._observation()[:-1], obs0[:-1])  # nothing moved
    # the two big boxes in the first room, then a small box through the same door
    env.set_state(s)
    _, _, _, _, info = env.step(
        _action(env, [(-3.5, 2.1, 180), (-3.5, -0.05, 180), (-6.55, 2.55, 90)])
    )
    assert info["feasible"], info["reason"]


def test_one_bad_placement_voids_the_action(env: ConveyorPackingEnv) -> None:
    env.reset(seed=0)
    obs0 = env._observation()
    # the third box on top of the first: a collision with the box placed just before
    _, r, _, _, info = env.step(
        _action(env, [(-3.5, 2.1, 180), (-3.5, -0.05, 180), (-3.5, 2.1, 180)])
    )
    assert r == -2.0 and info["reason"].startswith("box 3/3 (obj_02): collision")
    assert "obj_00" in info["reason"]
    np.testing.assert_array_equal(env._observation()[:-1], obs0[:-1])
    _, r, _, _, info = env.step(
        _action(env, [(1.0, 1.0, 0), (-3.5, -0.05, 180), (-6.55, 2.55, 90)])
    )
    assert info["reason"].startswith("box 1/3 (obj_00): outside region")


def test_a_box_placed_earlier_in_the_action_blocks_the_later_base_paths(
    env: ConveyorPackingEnv,
) -> None:
    """The base paths of an action's later boxes go around the boxes it placed before,
    where it placed them."""
    env.reset(seed=0)
    s = env.get_state()
    corner, west = (-3.5, 2.1, 180), (-6.55, 2.55, 90)
    # obj_00 (big) in the middle of the first room: the robot carrying obj_01 (also big)
    # cannot get past it to the room's north-west corner
    _, r, _, _, info = env.step(_action(env, [(-2.0, 1.1, 0), corner, (-3.51, 1.05, 180)]))
    assert r == -2.0 and info["reason"] == "box 2/3 (obj_01): no base path"
    # obj_00 against the room's south wall instead: the same corner is reachable
    env.set_state(s)
    _, _, _, _, info = env.step(_action(env, [(-3.5, -0.05, 180), corner, west]))
    assert info["feasible"], info["reason"]
    # obj_00 in the first room's door (x in [-2.98, -1.36] at y = -1): the robot carrying
    # obj_02 can no longer reach the larger rooms through it
    env.set_state(s)
    far = (-5.5, -3.0, 90)
    _, r, _, _, info = env.step(_action(env, [(-2.17, -0.6, 270), corner, far]))
    assert r == -2.0 and info["reason"] == "box 3/3 (obj_02): no base path"
    env.set_state(s)
    _, _, _, _, info = env.step(_action(env, [(-3.5, -0.05, 180), corner, far]))
    assert info["feasible"], info["reason"]


def test_a_box_set_down_on_an_earlier_box_collides_with_it(env: ConveyorPackingEnv) -> None:
    """The placed box itself is checked at floor height: set partly onto the box placed
    just before it (the robot touching nothing), it collides with that box."""
    env.reset(seed=0)
    s = env.get_state()
    _, r, _, _, info = env.step(
        _action(env, [(-3.5, 2.1, 180), (-3.25, 2.1, 180), (-6.55, 2.55, 90)])
    )
    assert r == -2.0 and info["reason"] == "box 2/3 (obj_01): collision: object-obj_00"
    env.set_state(s)
    ok, pre = env.precheck(_action(env, [(-3.5, 2.1, 180), (-3.25, 2.1, 180), (-6.55, 2.55, 90)]))
    assert not ok and pre["reason"] == info["reason"]


def test_fewer_boxes_and_trailing_entries_ignored() -> None:
    env = ConveyorPackingEnv(ConveyorConfig(n_objects=4))
    env.reset(seed=0)
    acts = conveyor_actions(env)
    assert len(acts) == 2
    env.step(acts[0])
    last = acts[1].copy()
    last[3:] = 0.123  # only one box is left: ignored
    _, _, terminated, _, info = env.step(last)
    assert terminated and info["objects"] == ["obj_03"] and len(info["base_path_lengths"]) == 1


def test_bad_actions_and_clipping(env: ConveyorPackingEnv) -> None:
    env.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(6))
    with pytest.raises(ValueError, match="infinite"):
        env.step(np.full(9, np.inf))
    s = env.get_state()
    a = conveyor_actions(env)[0]
    wild = a.copy()
    wild[2] = 5.0  # theta beyond the range -> clipped to 2 pi (== 0)
    out1 = env.step(wild)
    env.set_state(s)
    wild[2] = 1.0
    out2 = env.step(wild)
    assert out1[4]["action_clipped"] and not out2[4]["action_clipped"]
    assert data_equivalence(out1[:4], out2[:4], exact=True)


def test_snapshot_restore_is_bit_identical(env: ConveyorPackingEnv) -> None:
    assert_restore_is_exact(env, seed=0, actions=conveyor_actions, before=1)


def test_config_validation() -> None:
    with pytest.raises(ValueError, match="n_objects"):
        ConveyorConfig(n_objects=21)
    with pytest.raises(ValueError, match="height_fraction"):
        ConveyorConfig(height_fraction=1.5)
    with pytest.raises(ValueError, match=r"ConveyorConfig\.depth_fraction must be a finite number"):
        ConveyorConfig(depth_fraction=True)
    with pytest.raises(
        ValueError, match=r"ConveyorConfig\.height_fraction must be a finite number"
    ):
        ConveyorConfig(height_fraction="half")
    with pytest.raises(ValueError, match="loading_region"):
        ConveyorConfig(loading_region=(1.0, 0.0, 0.0, 1.0))


def test_gymnasium_checks() -> None:
    check_gymnasium_api("voot/ConveyorPacking-v0", num_steps=8, seed=2)


def test_render_rgb_array() -> None:
    env = ConveyorPackingEnv(
        render_mode="rgb_array", render_camera="top_down", render_size=(160, 120)
    )
    env.reset(seed=0)
    img = env.render()
    assert img is not None and img.shape == (120, 160, 3) and img.std() > 5
    env.close()


def test_truncation_at_the_horizon_and_step_timings() -> None:
    """A truncated episode has ended; ``last_timing``'s parts are >= 0 and sum to <= total."""
    env = ConveyorPackingEnv(ConveyorConfig(horizon=3))
    env.reset(seed=0)

    # the third box on top of the first: infeasible after two feasible checks
    bad = _action(env, [(-3.5, 2.1, 180), (-3.5, -0.05, 180), (-3.5, 2.1, 180)])
    _, _, term, trunc, info = timed_step(env, bad)
    assert not info["feasible"] and not term and not trunc
    # boxes 1 and 2 passed before box 3 failed: no path is reported for a void action
    assert info["base_path_length"] == 0.0
    assert info["base_path_lengths"] == [] and info["base_paths"] == []
    _, _, term, trunc, info = timed_step(
        env, _action(env, [(1.0, 1.0, 0), (-3.5, -0.05, 180), (-6.55, 2.55, 90)])
    )
    assert info["reason"].startswith("box 1/3 (obj_00): outside region")
    assert not term and not trunc
    s = env.get_state()
    _, _, term, trunc, info = timed_step(env, conveyor_actions(env)[0])
    assert info["feasible"] and not term and trunc
    env.set_state(s)
    assert_horizon_ends(env, bad)


def test_precheck_agrees_with_the_step(env: ConveyorPackingEnv) -> None:
    """The pre-check's verdict, reason, placements and base poses are the step's."""
    env.reset(seed=0)
    actions = [
        conveyor_actions(env)[0],  # feasible
        _action(env, [(-3.5, 2.1, 180), (-3.5, -0.05, 180), (-3.5, 2.1, 180)]),  # box 3 on 1
        _action(env, [(1.0, 1.0, 0), (-3.5, -0.05, 180), (-6.55, 2.55, 90)]),  # box 1 outside
    ]
    s = env.get_state()
    for a in actions:
        ok, pre = env.precheck(a)
        _, _, _, _, info = env.step(a)
        env.set_state(s)
        assert ok == pre["feasible"] == info["feasible"]
        assert pre["reason"] == info["reason"]
        assert pre["placements"] == info["placements"] and pre["placement"] == info["placement"]
        np.testing.assert_allclose(pre["base_poses"], info["base_poses"], atol=1e-12)
        np.testing.assert_allclose(pre["base_pose"], info["base_pose"], atol=1e-12)
    assert pre["placement"] != pre["placements"][1]
