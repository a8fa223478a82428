"""Grasp poses, the arm's IK (mink + closed-form seeds) and MuJoCo collision checks."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from voot.envs.feasibility import (
    ArmIK,
    CollisionChecker,
    IKConfig,
    object_pose,
    rot_x,
    rot_y,
    set_object_pose,
    side_grasp,
    xyx_euler,
)
from voot.envs.robot import TUCK, Robot
from voot.envs.scene import load_model, movable_objects


@pytest.fixture(scope="module")
def ik() -> ArmIK:
    return ArmIK()


def test_xyx_euler_round_trip() -> None:
    rng = np.random.default_rng(0)
    for _ in range(200):
        a, b, c = rng.uniform(-3.0, 3.0, 3)
        r = rot_x(a) @ rot_y(b) @ rot_x(c)
        sols = xyx_euler(r)
        assert 1 <= len(sols) <= 2
        for s in sols:
            np.testing.assert_allclose(rot_x(s[0]) @ rot_y(s[1]) @ rot_x(s[2]), r, atol=1e-9)
    # singular: b = 0
    (s,) = xyx_euler(rot_x(0.3) @ rot_x(0.4))
    np.testing.assert_allclose(rot_x(s[0]) @ rot_y(s[1]) @ rot_x(s[2]), rot_x(0.7), atol=1e-9)


def test_seeds_are_exact_closed_form_solutions(ik: ArmIK) -> None:
    rng = np.random.default_rng(1)
    for _ in range(30):
        q = rng.uniform(ik.lower, ik.upper)
        p, r = ik.forward(q)
        seeds = ik.seeds(p, r)
        assert seeds
        for s in seeds:
            p2, r2 = ik.forward(s)
            np.testing.assert_allclose(p2, p, atol=1e-9)
            np.testing.assert_allclose(r2, r, atol=1e-9)


def test_solve_reaches_reachable_targets(ik: ArmIK) -> None:
    rng = np.random.default_rng(2)
    n_ok = 0
    for _ in range(40):
        q = rng.uniform(ik.lower, ik.upper)
        p, r = ik.forward(q)
        res = ik.solve(p, r)
        if res.success:
            n_ok += 1
            assert res.q is not None
            assert np.all(res.q >= ik.lower - 1e-12) and np.all(res.q <= ik.upper + 1e-12)
            p2, r2 = ik.forward(res.q)
            assert np.linalg.norm(p2 - p) <= ik.config.position_tolerance * 1.01
            assert np.linalg.norm(r2 - r) < 3 * ik.config.orientation_tolerance
    assert n_ok >= 36  # every target is reachable; a few may need more iterations


def test_solve_reports_out_of_reach(ik: ArmIK) -> None:
    res = ik.solve([1.5, 0.0, 0.8], np.eye(3))
    assert not res.success and res.reason == "out of reach" and res.q is None


def test_solve_is_deterministic(ik: ArmIK) -> None:
    r = rot_x(1.2)
    target = np.array([0.55, 0.1, 0.45])
    a, b = ik.solve(target, r), ik.solve(target, r)
    assert a.success and np.array_equal(a.q, b.q) and a.iterations == b.iterations


def test_refinement_uses_mink_when_the_seed_violates_limits(ik: ArmIK) -> None:
    # a close, low target: every closed-form seed breaks a limit, mink finds a solution
    ang = math.pi
    r = np.column_stack(
        [[1, 0, 0], [0, math.cos(ang), math.sin(ang)], [0, -math.sin(ang), math.cos(ang)]]
    )
    res = ik.solve([0.47, 0.0, 0.64], r)
    assert res.success and res.iterations >= 1


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"solver": "cvxopt-ish"}, "daqp"),
        ({"max_iterations": -1}, "max_iterations"),
        ({"position_tolerance": 0.0}, "position_tolerance"),
        ({"orientation_cost": -1.0}, "orientation_cost"),
        ({"damping": True}, "IKConfig.damping must be a finite number > 0, got True"),
        ({"orientation_cost": True}, "IKConfig.orientation_cost"),
    ],
)
def test_ik_config_validation(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        IKConfig(**kwargs)  # type: ignore[arg-type]


def test_side_grasp_faces_the_robot() -> None:
    model = load_model("kitchen")
    box = next(o for o in movable_objects(model) if o.name == "obj_box2")
    pose = (1.0, 2.0, 0.0, 0.0)
    # robot west of the box, heading east: grasps the -x face
    g = side_grasp(box, pose, 0.0, math.pi / 2, 0.75, 0.5)
    assert g.face == "-x"
    assert g.position[0] == pytest.approx(1.0 - box.half[0])
    assert g.position[1] == pytest.approx(2.0)
    assert g.position[2] == pytest.approx(0.75 * box.height)
    np.testing.assert_allclose(g.rotation[:, 0], [1.0, 0.0, 0.0], atol=1e-12)  # approach
    np.testing.assert_allclose(g.rotation.T @ g.rotation, np.eye(3), atol=1e-12)
    assert np.linalg.det(g.rotation) == pytest.approx(1.0)
    # depth fraction moves the point across the face; heading north picks the -y face
    g2 = side_grasp(box, pose, math.pi / 2, math.pi / 2, 0.5, 0.9)
    assert g2.face == "-y" and g2.position[1] == pytest.approx(2.0 - box.half[1])
    assert g2.position[0] == pytest.approx(1.0 + 0.8 * box.half[0])


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


def test_set_and_read_object_pose() -> None:
    model = load_model("kitchen")
    data = mujoco.MjData(model)
    obj = movable_objects(model)[0]
    set_object_pose(data, obj, (1.0, -2.0, 0.0, 2.5))
    np.testing.assert_allclose(object_pose(data, obj), [1.0, -2.0, 0.0, 2.5], atol=1e-12)


# ----- float versions and the filtered collision model match the originals ----------------
def _side_grasp_numpy(obj, obj_pose, base_heading, grasp_angle, hf, df, standoff=0.0):  # type: ignore[no-untyped-def]
    """side_grasp as it was written with numpy vectors (the reference)."""
    x, y, z, yaw = (float(v) for v in np.asarray(obj_pose, dtype=np.float64))
    c, s = math.cos(yaw), math.sin(yaw)
    faces = (
        ("+x", np.array([c, s]), float(obj.half[0]), float(obj.half[1])),
        ("-x", np.array([-c, -s]), float(obj.half[0]), float(obj.half[1])),
        ("+y", np.array([-s, c]), float(obj.half[1]), float(obj.half[0])),
        ("-y", np.array([s, -c]), float(obj.half[1]), float(obj.half[0])),
    )
    heading = np.array([math.cos(base_heading), math.sin(base_heading)])
    k = int(np.argmin([float(n @ heading) for _, n, _, _ in faces]))
    face, n, half_normal, half_across = faces[k]
    tangent = np.array([-n[1], n[0]])
    cx = x + c * obj.center[0] - s * obj.center[1]
    cy = y + s * obj.center[0] + c * obj.center[1]
    p_xy = (
        np.array([cx, cy]) + (half_normal + standoff) * n + (2.0 * df - 1.0) * half_across * tangent
    )
    p = np.array([p_xy[0], p_xy[1], z + hf * obj.height])
    approach = np.array([-n[0], -n[1], 0.0])
    y0 = np.array([tangent[0], tangent[1], 0.0])
    z0 = np.cross(approach, y0)
    ca, sa = math.cos(grasp_angle), math.sin(grasp_angle)
    y_axis = ca * y0 + sa * z0
    z_axis = np.cross(approach, y_axis)
    return p, np.column_stack([approach, y_axis, z_axis]), face


def test_side_grasp_is_bit_identical_to_the_numpy_version() -> None:
    model = load_model("kitchen")
    objects = movable_objects(model)
    rng = np.random.default_rng(5)
    for k in range(800):
        obj = objects[k % len(objects)]
        yaw = float(rng.uniform(-4, 4))
        pose = (*rng.uniform(-3, 3, 3).tolist(), yaw)
        # every 4th heading at 45 degrees to the object: two faces tie
        heading = (
            yaw + math.pi / 4 + math.pi / 2 * int(rng.integers(4))
            if k % 4 == 0
            else float(rng.uniform(-4, 4))
        )
        args = (
            np.float64(rng.uniform(0.7, 3.2)),
            np.float64(rng.uniform(0.5, 1)),
            np.float64(rng.uniform(0.1, 0.9)),
        )
        g = side_grasp(obj, pose, heading, *args, standoff=0.01 * (k % 2))
        p, r, face = _side_grasp_numpy(obj, pose, heading, *args, standoff=0.01 * (k % 2))
        assert g.face == face
        assert g.position.tobytes() == p.tobytes() and g.rotation.tobytes() == r.tobytes()


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


def test_closest_seed_is_the_sorted_violation_choice(ik: ArmIK) -> None:
    """_closest_seed picks what sorting by (_violation, index) picked."""
    rng = np.random.default_rng(4)
    for k in range(400):
        seeds = list(rng.uniform(-3.5, 3.5, (int(rng.integers(1, 9)), 7)))
        if k % 3 == 0:  # inside the limits, and duplicates (exact ties)
            seeds = [np.clip(q, ik.lower, ik.upper) for q in seeds] + [seeds[0]]
        if k % 5 == 0 and len(seeds) > 1:
            seeds[1] = seeds[0].copy()
        viol = [ik._violation(q) for q in seeds]
        order = sorted(range(len(seeds)), key=lambda i: (viol[i], i))
        assert ik._closest_seed(seeds) == (order[0], viol[order[0]] == 0.0)


def test_chosen_seed_is_the_closest_of_all_seeds(ik: ArmIK) -> None:
    """Stopping at the first seed inside the limits picks what choosing among all did."""
    rng = np.random.default_rng(6)
    outcomes = set()
    for _ in range(200):
        # targets of random joint values, some beyond the limits (seeds outside them)
        q = rng.uniform(ik.lower - 0.5, ik.upper + 0.5)
        p, r = ik.forward(q)
        seeds = ik.seeds(p, r)
        chosen = ik._chosen_seed(p, r)
        if not seeds:
            assert chosen is None
            continue
        first, inside = ik._closest_seed(seeds)
        assert chosen is not None
        assert chosen[0].tobytes() == seeds[first].tobytes() and chosen[1] == inside
        outcomes.add((inside, first > 0))
    # stopped early at a later seed, and fell back to choosing among all
    assert (True, True) in outcomes and any(not inside for inside, _ in outcomes)
    assert ik._chosen_seed(np.array([5.0, 0.0, 0.0]), np.eye(3)) is None  # out of reach


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


def test_ik_step_is_minks_solve_ik(ik: ArmIK) -> None:
    """ArmIK's step (its own daqp call) is mink.solve_ik's velocity, bit for bit, with the
    limits inactive and active (joints at a limit, far targets)."""
    import mink

    assert ik._qp_rows is not None  # the daqp path is the one under test
    rng = np.random.default_rng(6)
    at_limit = 0
    for k in range(200):
        q = rng.uniform(ik.lower, ik.upper)
        if k % 2:
            q = np.clip(rng.uniform(ik.lower - 1.0, ik.upper + 1.0), ik.lower, ik.upper)
        spread = 0.15 if k % 3 else 0.8
        target = np.array([0.5, 0.0, 0.5]) + rng.uniform(-spread, spread, 3)
        rotation = rot_x(float(rng.uniform(-3, 3))) @ rot_y(float(rng.uniform(-1.5, 1.5)))
        ik.task.set_target(
            mink.SE3.from_rotation_and_translation(mink.SO3.from_matrix(rotation), target)
        )
        ik.configuration.update(q)
        ours = ik._ik_velocity()
        at_limit += bool(np.any(q == ik.lower) or np.any(q == ik.upper))
        ik.configuration.update(q)
        theirs = mink.solve_ik(
            ik.configuration,
            [ik.task],
            1.0,
            ik.config.solver,
            damping=ik.config.damping,
            limits=ik.limits,
        )
        assert ours.tobytes() == theirs.tobytes()
    assert at_limit > 50
    generic = ArmIK()
    generic._qp_rows = None  # mink.build_ik and qpsolvers, as for another solver
    generic.task.set_target(ik.task.transform_target_to_world)
    generic.configuration.update(q)
    assert generic._ik_velocity().tobytes() == theirs.tobytes()
