"""The conveyor with the base planner's exact-footprint option (BasePlannerConfig.footprint)."""

from __future__ import annotations

import numpy as np
import pytest

from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.core.scene import object_footprint
from voot.envs.motion.footprint import FootprintConfig, footprint_hits
from voot.envs.motion.planner import BasePlannerConfig
from voot.envs.robot.model import compose2d

OPTION = BasePlannerConfig(footprint=FootprintConfig())


@pytest.fixture(scope="module")
def env() -> ConveyorPackingEnv:
    e = ConveyorPackingEnv(preset="v1", planner=OPTION)
    e.reset(seed=0)
    return e


def test_footprint_parts_are_inside_the_carry_disc(env: ConveyorPackingEnv) -> None:
    for i in range(env.n):
        fp = env.footprint(i)
        assert [p.name for p in fp.parts] == ["base", env.objects[i].name, "arm"]
        assert fp.reach <= env.picks[i].disc.radius


def test_the_footprint_agrees_with_mujoco_on_sampled_poses(env: ConveyorPackingEnv) -> None:
    """At 2,400 random poses (4 boxes carried, 6 boxes placed), the planner's verdict is
    MuJoCo's collision test: never free where MuJoCo collides; conservative (the arm is
    its bounding rectangle, the placed boxes full height) at under 2% of the poses."""
    snap = env.get_state()
    for a in env.solution_actions()[:2]:
        env.transition(a)
    placed = [env.object_box(j) for j in range(env.task.placed)]
    obstacles = [*env.planner.static_obstacles, *placed]
    rng = np.random.default_rng(1)
    ws = env.config.workspace
    unsafe = conservative = total = 0
    for i in (6, 7, 12, 19):
        fp, pick = env.footprint(i), env.picks[i]
        for _ in range(600):
            c = (rng.uniform(ws[0], ws[1]), rng.uniform(ws[2], ws[3]), rng.uniform(-np.pi, np.pi))
            planner_hit = footprint_hits(fp, c, obstacles)  # MuJoCo has no workspace bound
            base = pick.disc.base(np.array(c))[0]
            obj = compose2d(base, pick.rel)
            report = env.collision.check(
                env.data.qpos, base, pick.arm_q, held=i,
                object_poses={i: (obj[0], obj[1], 0.0, obj[2])},
            )  # fmt: skip
            unsafe += (not planner_hit) and (not report.free)
            conservative += planner_hit and report.free
            total += 1
    env.set_state(snap)
    assert unsafe == 0
    assert conservative <= 0.02 * total


def test_default_planner_has_no_footprint_and_base_model_sets_it() -> None:
    assert ConveyorPackingEnv(preset="v1").config.planner.footprint is None
    cfg = ConveyorPackingEnv(preset="v1", base_model="footprint").config
    assert cfg.planner.footprint == FootprintConfig()
    with pytest.raises(ValueError, match="base_model must be one of disc, footprint"):
        ConveyorPackingEnv(preset="v1", base_model="box")


def test_a_root_action_the_disc_refuses_passes_with_the_footprint(env: ConveyorPackingEnv) -> None:
    disc = ConveyorPackingEnv(preset="v1")
    disc.reset(seed=0)
    snap = env.get_state()
    rng = np.random.default_rng(5)
    for _ in range(2000):
        a = rng.uniform(-1.0, 1.0, 9)
        ok, _ = disc.precheck(a)
        if not ok:
            continue
        d_state = disc.get_state()
        _, _, _, d_info = disc.transition(a)
        disc.set_state(d_state)
        if d_info["feasible"]:
            continue
        _, _, _, info = env.transition(a)
        env.set_state(snap)
        if not info["feasible"]:
            continue
        # every waypoint of every box's path is free for that box's footprint
        search = env.planner.footprint_search()
        for k, path in enumerate(info["base_paths"]):
            fp, pick = env.footprint(k), env.picks[k]
            # the boxes placed before it in this action
            others = tuple(
                object_footprint(env.objects[j], *info["placements"][j]) for j in range(k)
            )
            for w in path:
                assert search.is_free(fp, tuple(pick.disc.center(w).tolist()), others)
        assert info["base_path_length"] > 0.0
        return
    pytest.fail("no root action refused by the disc passed with the footprint")


def test_big_box_ban_at_execution_only() -> None:
    """The authors' explicit rule: a big box outside the first room fails when executed
    (not in the pre-check); off by default; the scripted solution still solves."""
    assert ConveyorPackingEnv(preset="v1").config.big_box_ban is False
    ban = ConveyorPackingEnv(preset="v1", big_box_ban=True)
    free = ConveyorPackingEnv(preset="v1")
    for e in (ban, free):
        e.reset(seed=0)
    script = ban.solution_actions()
    # the first action with its first (big) box moved to the west room, as the scripted
    # small boxes are placed there
    a = script[0].copy()
    a[:3] = script[1][:3]
    for e in (ban, free):
        ok, _ = e.precheck(a)
        assert ok
    _, _, _, info = ban.transition(a)
    assert not info["feasible"]
    assert info["reason"].startswith("box 1/3 (obj_00): forbidden room")
    _, _, _, info = free.transition(a)
    assert "forbidden" not in info["reason"]
    ban.reset(seed=0)
    total = 0.0
    for act in script:
        r, _, _, info = ban.transition(act)
        assert info["feasible"]
        total += r
    assert ban.task.done and total > 7.0
    with pytest.raises(ValueError, match="big_box_ban must be a bool"):
        ConveyorPackingEnv(preset="v1", big_box_ban=1)


def test_authors_rooms() -> None:
    """The authors' walls replace voot's; the 1.5 m entrance stops the big boxes' disc."""
    from voot.envs.conveyor.authors_rooms import AUTHORS_WALLS

    env = ConveyorPackingEnv(preset="v1", rooms="authors")
    env.reset(seed=0)
    names = [b.name for b in env.static_boxes]
    assert names == [w[0] for w in AUTHORS_WALLS] + ["belt_frame"]
    gaps = {w[0]: w[1:] for w in AUTHORS_WALLS}
    assert gaps["wall_east_n"][2] - gaps["wall_east_s"][3] == pytest.approx(1.5)  # entrance
    assert gaps["wall_room1_s"][0] - gaps["wall_rooms_mid"][1] == pytest.approx(1.695)  # door
    assert 2 * env.picks[0].disc.radius > 1.5
    _, _, _, info = env.transition(env.solution_actions()[0])
    assert info["reason"] == "box 1/3 (obj_00): no base path"
    assert ConveyorPackingEnv(preset="v1").config.rooms == "voot"
    with pytest.raises(ValueError, match="rooms must be one of voot, authors"):
        ConveyorPackingEnv(preset="v1", rooms="paper")
