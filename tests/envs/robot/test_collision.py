"""Tests of voot.envs.robot.collision: MuJoCo collision checks of the robot and what it holds."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from voot.envs.core.scene import load_model, movable_objects, object_pose
from voot.envs.robot.collision import CollisionChecker
from voot.envs.robot.model import TUCK, Robot


@pytest.fixture(scope="module")
def kitchen_checker() -> tuple[CollisionChecker, mujoco.MjModel]:
    model = load_model("kitchen")
    robot = Robot(model)
    objects = movable_objects(model)
    return CollisionChecker(model, robot, objects), model


def test_collision_free_and_hits(kitchen_checker: tuple[CollisionChecker, mujoco.MjModel]) -> None:
    checker, model = kitchen_checker
    qpos = model.qpos0.copy()
    assert checker.check(qpos, (-1.5, -1.5, math.pi / 2), TUCK).free
    hits = checker.check(qpos, (-1.9, -1.5, 0.0), TUCK).hits
    assert hits == ["robot-wall_west"]
    # the robot standing on a box: the box is reported by its body name
    i = next(k for k, o in enumerate(checker.objects) if o.name == "obj_box1")
    data = mujoco.MjData(model)
    x, y, _, _ = object_pose(data, checker.objects[i])
    assert "robot-obj_box1" in checker.check(qpos, (x, y, 0.0), TUCK).hits


def test_held_object_and_overrides(
    kitchen_checker: tuple[CollisionChecker, mujoco.MjModel],
) -> None:
    checker, model = kitchen_checker
    qpos = model.qpos0.copy()
    i = next(k for k, o in enumerate(checker.objects) if o.name == "obj_box1")
    # the held object moved into the counter collides; moved into free space it does not
    base = (0.8, -2.5, 0.0)
    assert (
        "object-counter_north"
        in checker.check(qpos, base, TUCK, held=i, object_poses={i: (0.0, 3.6, 0.0, 0.0)}).hits
    )
    assert checker.check(qpos, base, TUCK, held=i, object_poses={i: (1.8, -2.5, 0.0, 0.0)}).free
    # the input qpos is not modified
    np.testing.assert_array_equal(qpos, model.qpos0)


def test_collision_model_filter_reports_the_same_contacts() -> None:
    """The checker's filtered copy reports what the full model reports (robot/held pairs)."""
    model = load_model("kitchen")
    robot = Robot(model)
    objects = movable_objects(model)
    checker = CollisionChecker(model, robot, objects)
    assert checker.model is not model and checker._held_affinity  # the filter is in use
    plain = CollisionChecker(model, robot, objects)
    plain.model, plain._held_affinity = model, {}  # the unfiltered reference
    plain.data = mujoco.MjData(model)
    plain._affinity_view, plain._qpos_view = model.geom_conaffinity, plain.data.qpos
    data = mujoco.MjData(model)
    rng = np.random.default_rng(2)
    seen_hits = 0
    for k in range(600):
        base = (float(rng.uniform(-2, 6)), float(rng.uniform(-4, 4)), float(rng.uniform(-3, 3)))
        held = None if k % 3 == 0 else int(rng.integers(len(objects)))
        arm = TUCK if k % 2 else rng.uniform(-1.5, 1.5, 7)
        poses = None
        if held is not None:
            poses = {held: (base[0] + 0.6, base[1], 0.0, float(rng.uniform(-3, 3)))}
        a = checker.check(data.qpos, base, arm, held=held, object_poses=poses)
        b = plain.check(data.qpos, base, arm, held=held, object_poses=poses)
        assert a.hits == b.hits
        seen_hits += bool(a.hits)
    assert 50 < seen_hits < 590  # both outcomes were exercised
    assert np.array_equal(
        checker.model.geom_conaffinity[list(objects[0].geoms)], [1] * len(objects[0].geoms)
    )


def test_collides_is_not_free_and_the_last_query_is_remembered() -> None:
    """collides() == not check().free; a repeated query is answered from memory, exactly."""
    model = load_model("kitchen")
    robot = Robot(model)
    objects = movable_objects(model)
    checker = CollisionChecker(model, robot, objects)
    fresh = CollisionChecker(model, robot, objects)  # asked once per configuration
    data = mujoco.MjData(model)
    rng = np.random.default_rng(5)
    outcomes = set()
    for k in range(300):
        base = (float(rng.uniform(-2, 6)), float(rng.uniform(-4, 4)), float(rng.uniform(-3, 3)))
        held = None if k % 3 == 0 else int(rng.integers(len(objects)))
        poses = None if held is None else {held: (base[0] + 0.6, base[1], 0.0, 0.3)}
        ref = fresh.check(data.qpos, base, TUCK, held=held, object_poses=poses)
        fresh._last = None  # the reference never answers from memory
        hit = checker.collides(data.qpos, base, TUCK, held=held, object_poses=poses)
        assert hit == (not ref.free)
        outcomes.add(hit)
        # the same query again, through check(): the full names (a hit was not named yet)
        report = checker.check(data.qpos, base, TUCK, held=held, object_poses=poses)
        assert report.hits == ref.hits
        assert checker.check(data.qpos, base, TUCK, held=held, object_poses=poses) is report
        assert checker.collides(data.qpos, base, TUCK, held=held, object_poses=poses) == hit
    assert outcomes == {True, False}


def test_the_collision_memory_is_keyed_by_the_configuration() -> None:
    """Any change of qpos, of the overrides or of the held object is a new query."""
    model = load_model("kitchen")
    checker = CollisionChecker(model, Robot(model), movable_objects(model))
    qpos = model.qpos0.copy()
    free = checker.check(qpos, (-1.5, -1.5, math.pi / 2), TUCK)
    assert free.free and checker.check(qpos, (-1.5, -1.5, math.pi / 2), TUCK) is free
    # the scene's state moved: the robot now stands on the west wall
    assert checker.check(qpos, (-1.9, -1.5, 0.0), TUCK).hits == ["robot-wall_west"]
    moved = qpos.copy()
    i = next(k for k, o in enumerate(checker.objects) if o.name == "obj_box1")
    data = mujoco.MjData(model)
    x, y, _, _ = object_pose(data, checker.objects[i])
    a = checker.check(qpos, (x, y, 0.0), TUCK)
    adr = checker.objects[i].qpos_adr
    moved[adr : adr + 2] = (1.8, -2.5)  # the box is carried away: the same base is free now
    b = checker.check(moved, (x, y, 0.0), TUCK)
    assert "robot-obj_box1" in a.hits and "robot-obj_box1" not in b.hits
    # held or not changes the key: a new report, not the remembered one
    r1 = checker.check(qpos, (x, y, 0.0), TUCK)
    assert checker.check(qpos, (x, y, 0.0), TUCK) is r1
    assert checker.check(qpos, (x, y, 0.0), TUCK, held=i) is not r1


def test_the_first_object_is_named_by_its_body() -> None:
    """Object 0 too is reported by its body's name, not its geoms' (the chair's geoms
    are ``obj_chair1_seat``, ``obj_chair1_back``, ...)."""
    model = load_model("kitchen")
    objects = movable_objects(model)
    chair = next(o for o in objects if o.name == "obj_chair1")
    checker = CollisionChecker(
        model, Robot(model), [chair, *(o for o in objects if o is not chair)]
    )
    x, y, _, _ = object_pose(mujoco.MjData(model), chair)
    hits = checker.check(model.qpos0.copy(), (x, y, 0.0), TUCK).hits
    assert "robot-obj_chair1" in hits and not any("seat" in h or "leg" in h for h in hits)


def test_the_grasp_contacts_are_allowed() -> None:
    """The held object against the fingers: MuJoCo reports contacts, none of which
    counts, and collides() says so on the first query (the pair's verdict is computed,
    then remembered) and on a repeat."""
    model = load_model("kitchen")
    checker = CollisionChecker(model, Robot(model), movable_objects(model))
    qpos = mujoco.MjData(model).qpos
    base = (0.061980687802519974, -2.1775353804947084, -0.2894935179703122)
    arm = np.array([0.0, 1.1, 0.0, -2.6, 0.0, -0.6, 0.0])
    poses = {1: (0.4630080683842436, -2.1954088594082175, 0.4809857907939308, 0.3)}
    for _ in range(2):
        checker._last = None
        assert not checker.collides(qpos, base, arm, held=1, object_poses=poses)
        assert checker.data.ncon > 0
    assert checker.check(qpos, base, arm, held=1, object_poses=poses).free


def test_a_copied_or_pickled_checker_checks_its_own_configuration() -> None:
    import copy
    import pickle

    model = load_model("kitchen")
    checker = CollisionChecker(model, Robot(model), movable_objects(model))
    qpos = model.qpos0.copy()
    for twin in (copy.deepcopy(checker), pickle.loads(pickle.dumps(checker))):
        assert twin._qpos_view is twin.data.qpos and twin.data is not checker.data
        assert twin._affinity_view is twin.model.geom_conaffinity
        assert twin.check(qpos, (-1.9, -1.5, 0.0), TUCK).hits == ["robot-wall_west"]
        assert twin.check(qpos, (-1.5, -1.5, math.pi / 2), TUCK).free


def test_a_tuple_pose_writes_set_object_poses_numbers() -> None:
    """The fast path for ``(x, y, z, yaw)`` tuples writes what set_object_pose writes."""
    model = load_model("kitchen")
    checker = CollisionChecker(model, Robot(model), movable_objects(model))
    qpos = model.qpos0.copy()
    for yaw in (0.0, 0.3, -2.0, math.pi):
        pose = (1.8, -2.5, 0.1, yaw)
        fast = checker._configure(qpos, (0.0, 0.0, 0.0), TUCK, 2, {2: pose})
        slow = checker._configure(qpos, (0.0, 0.0, 0.0), TUCK, 2, {2: np.array(pose)})
        assert fast == slow


def test_the_memory_tells_held_objects_apart() -> None:
    model = load_model("kitchen")
    checker = CollisionChecker(model, Robot(model), movable_objects(model))
    qpos = model.qpos0.copy()
    base = (-1.5, -1.5, math.pi / 2)
    r1 = checker.check(qpos, base, TUCK, held=1)
    r2 = checker.check(qpos, base, TUCK, held=2)
    assert r2 is not r1 and checker.check(qpos, base, TUCK, held=2) is r2
    r0 = checker.check(qpos, base, TUCK)
    assert r0 is not r2 and checker.check(qpos, base, TUCK) is r0


def test_a_check_is_of_the_robot_with_open_fingers() -> None:
    """Whatever the fingers are in the scene's qpos, the configuration checked (the
    query's key) has them open, at the base and arm asked for."""
    from voot.envs.robot.model import FINGER_OPEN

    model = load_model("kitchen")
    robot = Robot(model)
    checker = CollisionChecker(model, robot, movable_objects(model))
    qpos = model.qpos0.copy()
    qpos[list(robot.finger_qadr)] = 0.0
    _, key = checker._configure(qpos, (0.5, -1.0, 0.3), TUCK, None, None)
    q = np.frombuffer(key)
    assert q[list(robot.finger_qadr)].tolist() == [FINGER_OPEN] * len(robot.finger_qadr)
    assert q[list(robot.base_qadr)].tolist() == [0.5, -1.0, 0.3]
    assert q[list(robot.arm_qadr)].tolist() == list(TUCK)
