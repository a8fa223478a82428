"""Tests of voot.envs.motion.planner: validity, optimality, doors, determinism, inputs."""

from __future__ import annotations

import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from floor_plans import (
    WORKSPACE,
    assert_path_clear,
    door_scene,
    house_movable,
    house_static,
    path_length_arrays,
    random_free_poses,
    wall,
)
from scipy import ndimage

from voot.envs.motion.disc_geometry import (
    BoxArrays,
    points_hit_boxes,
    points_inside,
)
from voot.envs.motion.planar import Box2D, Pose2D, path_length, wrap_angle
from voot.envs.motion.planner import BasePlanner, BasePlannerConfig


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"rotation_weight": -1.0}, "rotation_weight"),
        ({"clearance": -0.1}, "clearance"),
        ({"clearance": True}, "clearance must be a finite number, got True"),
        ({"rotation_weight": "1"}, "rotation_weight must be a finite number"),
        ({"corner_segments": 0}, "corner_segments"),
        ({"corner_segments": 2.0}, "corner_segments"),
        ({"vertex_margin": 0.0}, "vertex_margin"),
        ({"contact_tolerance": 1e-5}, "contact_tolerance"),
        ({"radius_step": 0.1}, "radius_step"),
        ({"static_cache_size": 0}, "static_cache_size"),
        ({"graph_cache_size": -1}, "graph_cache_size"),
    ],
)
def test_config_validation(kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        BasePlannerConfig(**kwargs)


def test_planner_input_validation() -> None:
    with pytest.raises(ValueError, match="xmin < xmax"):
        BasePlanner((1.0, 0.0, 0.0, 1.0), [])
    with pytest.raises(ValueError, match="4 finite numbers"):
        BasePlanner((0.0, 1.0, 0.0), [])  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="must be a Box2D"):
        BasePlanner(WORKSPACE, ["wall"])  # type: ignore[list-item]
    planner = BasePlanner(WORKSPACE, house_static())
    s, g = Pose2D(-1.0, -2.0, 0.0), Pose2D(0.0, -2.5, 0.0)
    with pytest.raises(ValueError, match="robot_radius must be > 0"):
        planner.plan(s, g, 0.0)
    with pytest.raises(ValueError, match="robot_radius"):
        planner.plan(s, g, float("nan"))
    with pytest.raises(ValueError, match=r"movable\[0\] must be a Box2D"):
        planner.plan(s, g, 0.3, movable=[(0, 0, 1, 1)])  # type: ignore[list-item]
    with pytest.raises(ValueError, match=r"Pose2D\.theta"):
        planner.plan(s, (0.0, 0.0, float("nan")), 0.3)


def test_path_length_formula() -> None:
    planner = BasePlanner(WORKSPACE, house_static(), BasePlannerConfig(rotation_weight=0.7))
    s = Pose2D(-0.5, -2.5, 3.0)
    g = Pose2D(3.4, 1.2, -2.9)  # behind the kitchen door: a multi-segment path
    path = planner.plan(s, g, 0.4)
    assert path is not None and len(path.waypoints) > 2
    w = path.waypoints
    trans = sum(math.hypot(*(w[i + 1, :2] - w[i, :2])) for i in range(len(w) - 1))
    rot = sum(
        abs((w[i + 1, 2] - w[i, 2] + math.pi) % (2 * math.pi) - math.pi) for i in range(len(w) - 1)
    )
    assert path.length == pytest.approx(trans + 0.7 * rot, rel=1e-12)
    # headings turn the short way (0.383 rad), not the long way round
    assert rot == pytest.approx(2 * math.pi - 5.9, abs=1e-9)
    assert path.translation_length == pytest.approx(trans)
    assert path.length == pytest.approx(path_length(w, 0.7))
    np.testing.assert_array_equal(w[0], s.as_array())
    np.testing.assert_array_equal(w[-1], g.as_array())


def test_turn_in_place_length() -> None:
    planner = BasePlanner(WORKSPACE, [])
    path = planner.plan(Pose2D(0, 0, 0.5), Pose2D(0, 0, -0.5), 0.3)
    assert path is not None
    assert path.length == pytest.approx(1.0)
    assert path.translation_length == 0.0


@pytest.mark.parametrize("radius", [0.3, 0.45])
def test_paths_avoid_obstacles(radius: float) -> None:
    static, movable = house_static(), house_movable()
    planner = BasePlanner(WORKSPACE, static)
    starts = random_free_poses(planner, radius, movable, 25, seed=1)
    goals = random_free_poses(planner, radius, movable, 25, seed=2)
    found = 0
    for s, g in zip(starts, goals, strict=True):
        path = planner.plan(s, g, radius, movable)
        if path is None:
            continue
        found += 1
        assert_path_clear(path, radius, static + movable)
        assert planner.path_is_free(path.waypoints, radius, movable)
        assert path.translation_length >= math.hypot(g.x - s.x, g.y - s.y) - 1e-12
    assert found >= 8  # the scene is cluttered, but many queries have paths


def test_detour_around_wall_is_near_optimal() -> None:
    """Around one thin wall the exact shortest disc path is known in closed form."""
    r = 0.5
    wall_box = wall(-0.05, 0.05, -1.0, 1.0, "wall")
    planner = BasePlanner((-5.0, 5.0, -5.0, 5.0), [wall_box])
    s, g = Pose2D(-2.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0)
    path = planner.plan(s, g, r)
    assert path is not None
    assert_path_clear(path, r, [wall_box], (-5.0, 5.0, -5.0, 5.0))
    # exact: tangents from the ends to the two corner discs (radius r at (+-0.05, 1)) and
    # the arc between them, plus the straight bit over the wall's top
    c = np.array([-0.05, 1.0])
    d = math.hypot(*(c - [-2.0, 0.0]))
    tangent = math.sqrt(d * d - r * r)
    to_start = math.atan2(0.0 - 1.0, -2.0 + 0.05)
    touch = float(wrap_angle(to_start - math.acos(r / d)))  # tangent point, seen from c
    arc = touch - math.pi / 2  # from the tangent point round to the top of the disc
    assert 0.0 < arc < math.pi / 2
    exact = 2 * tangent + 2 * r * arc + 0.1
    assert exact <= path.length <= exact / math.cos(math.pi / 8)
    finer = BasePlanner((-5.0, 5.0, -5.0, 5.0), [wall_box], BasePlannerConfig(corner_segments=6))
    fine_path = finer.plan(s, g, r)
    assert fine_path is not None
    assert exact <= fine_path.length <= path.length
    assert fine_path.length <= exact * 1.01


def test_path_existence_matches_grid_connectivity() -> None:
    """Where a fine occupancy grid says start and goal are connected, a path exists."""
    static, movable = house_static(), house_movable()
    planner = BasePlanner(WORKSPACE, static)
    res = 0.02
    xs = np.arange(WORKSPACE[0], WORKSPACE[1] + 1e-9, res)
    ys = np.arange(WORKSPACE[2], WORKSPACE[3] + 1e-9, res)
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    boxes = BoxArrays.from_boxes(static + movable)
    checked = 0
    for radius in (0.35, 0.5):
        free = np.concatenate(
            [
                ~points_hit_boxes(chunk, boxes, radius).any(axis=1)
                for chunk in np.array_split(pts, 16)
            ]
        )
        free &= points_inside(pts, WORKSPACE, radius)
        labels, _ = ndimage.label(free.reshape(gx.shape))
        # poses with a margin, so that grid rounding cannot matter
        starts = random_free_poses(planner, radius + 0.05, movable, 20, seed=5)
        goals = random_free_poses(planner, radius + 0.05, movable, 20, seed=6)
        for s, g in zip(starts, goals, strict=True):
            ls = labels[round((s.x - xs[0]) / res), round((s.y - ys[0]) / res)]
            lg = labels[round((g.x - xs[0]) / res), round((g.y - ys[0]) / res)]
            assert ls > 0 and lg > 0
            path = planner.plan(s, g, radius, movable)
            assert (path is not None) == (ls == lg), (s, g, radius)
            checked += 1
    assert checked == 40


@pytest.mark.parametrize(
    ("width", "radius", "passes"),
    [
        (0.99, 0.5, False),
        (1.01, 0.5, True),
        (1.0, 0.45, True),  # the robot alone
        (1.0, 0.55, False),  # the robot carrying a big box
        (1.0 - 2e-6, 0.5, False),
    ],
)
def test_door_passes_iff_wider_than_diameter(width: float, radius: float, passes: bool) -> None:
    planner = BasePlanner((-5.0, 5.0, -5.0, 5.0), door_scene(width))
    s, g = Pose2D(-2.0, 3.0, 0.0), Pose2D(2.0, -3.0, math.pi)
    path = planner.plan(s, g, radius)
    assert (path is not None) == passes
    if path is not None:
        assert_path_clear(path, radius, door_scene(width), (-5.0, 5.0, -5.0, 5.0))
        # it crosses x = 0 inside the door
        w = path.waypoints
        k = int(np.flatnonzero(np.diff(np.sign(w[:, 0])) != 0)[0])
        a, b = w[k, :2], w[k + 1, :2]
        y0 = a[1] + (b[1] - a[1]) * (0 - a[0]) / (b[0] - a[0])
        assert abs(y0) <= width / 2 - radius + 1e-6


def test_clearance_narrows_doors() -> None:
    planner = BasePlanner(
        (-5.0, 5.0, -5.0, 5.0), door_scene(1.1), BasePlannerConfig(clearance=0.06)
    )
    s, g = Pose2D(-2.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0)
    assert planner.plan(s, g, 0.5) is None
    assert planner.plan(s, g, 0.48) is not None


def test_radius_step_rounds_up_and_shares_caches() -> None:
    planner = BasePlanner(
        (-5.0, 5.0, -5.0, 5.0), door_scene(0.995), BasePlannerConfig(radius_step=0.01)
    )
    exact = BasePlanner((-5.0, 5.0, -5.0, 5.0), door_scene(0.995))
    s, g = Pose2D(-2.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0)
    assert planner.plan(s, g, 0.48) is not None  # 0.48 is a multiple: kept
    assert exact.plan(s, g, 0.4951) is not None
    assert planner.plan(s, g, 0.4951) is None  # rounded up to 0.50: the door blocks
    s2, g2 = Pose2D(-2.0, 2.0, 0.0), Pose2D(2.0, -2.0, 0.0)  # a detour: uses the graph
    reference = planner.plan(s2, g2, 0.48)
    assert reference is not None and len(reference.waypoints) > 2
    for r in (0.471, 0.475, 0.4799):
        assert planner.plan(s2, g2, r) == reference
    assert [radius for radius, _ in planner._graph_cache] == [0.5, 0.48]


def test_movable_box_can_close_a_door() -> None:
    planner = BasePlanner((-5.0, 5.0, -5.0, 5.0), door_scene(1.5))
    s, g = Pose2D(-2.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0)
    assert planner.plan(s, g, 0.4) is not None
    blocker = Box2D(0.0, 0.0, 0.2, 0.2, 0.0, "blocker")
    assert planner.plan(s, g, 0.4, [blocker]) is None
    assert planner.plan(s, g, 0.2, [blocker]) is not None


def test_start_or_goal_in_collision_gives_none() -> None:
    static, movable = house_static(), house_movable()
    planner = BasePlanner(WORKSPACE, static)
    free = Pose2D(-0.5, -2.0, 0.0)
    assert planner.is_free(free, 0.3, movable)
    in_table = Pose2D(1.3, 0.3, 0.0)
    near_chair = Pose2D(-1.2, -0.1, 0.0)  # 0.18 m from chair_a's face
    outside = Pose2D(5.9, 0.0, 0.0)  # the disc leaves the workspace
    for bad in (in_table, near_chair, outside):
        assert not planner.is_free(bad, 0.3, movable)
        assert planner.plan(free, bad, 0.3, movable) is None
        assert planner.plan(bad, free, 0.3, movable) is None
    assert planner.colliding(in_table, 0.3, movable) == ["table"]
    assert planner.colliding(near_chair, 0.3, movable) == ["chair_a"]
    assert planner.colliding(outside, 0.3, movable) == ["workspace", "wall_e"]
    assert planner.colliding(free, 0.3, movable) == []


def test_enclosed_goal_gives_none() -> None:
    pen = [
        wall(-1.0, 1.0, -1.0, -0.9, "s"),
        wall(-1.0, 1.0, 0.9, 1.0, "n"),
        wall(-1.0, -0.9, -1.0, 1.0, "w"),
        wall(0.9, 1.0, -1.0, 1.0, "e"),
    ]
    planner = BasePlanner((-5.0, 5.0, -5.0, 5.0), pen)
    assert planner.is_free((0.0, 0.0, 0.0), 0.5, [])
    assert planner.plan((3.0, 3.0, 0.0), (0.0, 0.0, 0.0), 0.5) is None


def test_straight_line_when_clear() -> None:
    planner = BasePlanner(WORKSPACE, house_static())
    s, g = Pose2D(-1.0, -2.0, 0.3), Pose2D(2.0, -2.5, 1.0)
    path = planner.plan(s, g, 0.4)
    assert path is not None and path.waypoints.shape == (2, 3)
    assert path.length == pytest.approx(math.hypot(3.0, 0.5) + 0.7)


def _query() -> tuple[Pose2D, Pose2D, float]:
    return Pose2D(-0.6, -1.6, 0.3), Pose2D(3.4, 1.2, -2.0), 0.45


def test_same_inputs_same_path_regardless_of_history() -> None:
    static, movable = house_static(), house_movable()[-4:]
    s, g, r = _query()
    fresh = BasePlanner(WORKSPACE, static).plan(s, g, r, movable)
    assert fresh is not None and len(fresh.waypoints) > 2
    busy = BasePlanner(WORKSPACE, static, BasePlannerConfig(graph_cache_size=2))
    for p in random_free_poses(busy, r, movable, 10, seed=7):
        busy.plan(p, g, r, movable)
        busy.plan(s, p, r, movable[:2])
    again = busy.plan(s, g, r, movable)
    uncached = BasePlanner(WORKSPACE, static, BasePlannerConfig(graph_cache_size=0))
    for other in (again, uncached.plan(s, g, r, movable), uncached.plan(s, g, r, movable)):
        assert other is not None
        assert np.array_equal(other.waypoints, fresh.waypoints)
        assert other.length == fresh.length
    busy.clear_caches()
    assert busy.plan(s, g, r, movable) == fresh


def test_same_path_in_another_process() -> None:
    here = Path(__file__).resolve()
    code = (
        f"import sys; sys.path[:0] = [{str(here.parent)!r}, {str(here.parents[2])!r}];"
        "from test_base_planner import BasePlanner, WORKSPACE, house_static, house_movable, _query;"
        "s, g, r = _query();"
        "p = BasePlanner(WORKSPACE, house_static()).plan(s, g, r, house_movable()[-4:]);"
        "print(p.waypoints.tobytes().hex(), repr(p.length))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    s, g, r = _query()
    p = BasePlanner(WORKSPACE, house_static()).plan(s, g, r, house_movable()[-4:])
    assert p is not None
    assert out == [p.waypoints.tobytes().hex(), repr(p.length)]


@pytest.mark.slow
def test_plan_speed_report() -> None:
    """Median plan time in the kitchen-sized house, first and repeated queries per state."""
    planner = BasePlanner(WORKSPACE, house_static())
    rng = np.random.default_rng(0)
    first: list[float] = []
    repeat: list[float] = []
    by_outcome: dict[str, list[float]] = {"direct": [], "detour": [], "none": []}
    for state in range(60):
        movable = [
            Box2D(
                b.cx + rng.normal(0, 0.05),
                b.cy + rng.normal(0, 0.05),
                b.half_x,
                b.half_y,
                b.yaw + rng.normal(0, 0.1),
                b.name,
            )
            for b in house_movable()
        ]
        radius = (0.4, 0.5)[state % 2]
        start = random_free_poses(planner, radius, movable, 1, seed=1000 + state)[0]
        for k, goal in enumerate(random_free_poses(planner, radius, movable, 20, seed=state)):
            t0 = time.process_time()
            path = planner.plan(start, goal, radius, movable)
            dt = time.process_time() - t0
            (first if k == 0 else repeat).append(dt)
            if path is None:
                by_outcome["none"].append(dt)
            else:
                by_outcome["direct" if len(path.waypoints) == 2 else "detour"].append(dt)
    f, r = np.array(first) * 1e3, np.array(repeat) * 1e3
    print(
        f"\nfirst query per state: median {np.median(f):.2f} ms, p90 {np.percentile(f, 90):.2f}"
        f"\nrepeated queries:      median {np.median(r):.2f} ms, p90 {np.percentile(r, 90):.2f}"
        f"\nall {len(f) + len(r)} queries:       median {np.median(np.r_[f, r]):.2f} ms"
    )
    for name, ts in by_outcome.items():
        print(f"{name:>7}: {len(ts):4d} queries, median {np.median(ts) * 1e3:.2f} ms")
    assert np.median(r) < 5.0


def test_colliding_names_as_the_array_test() -> None:
    static, movable = house_static(), house_movable()
    planner = BasePlanner(WORKSPACE, static)
    boxes = BoxArrays.from_boxes(static + movable)
    rng = np.random.default_rng(9)
    seen = 0
    for x, y, r in rng.uniform((-2.5, -4.5, 0.3), (6.5, 4.5, 0.9), (1500, 3)):
        got = planner.colliding((x, y, 0.0), r, movable)
        r_hit = r - planner.config.contact_tolerance
        hits = np.flatnonzero(points_hit_boxes(np.array([[x, y]]), boxes, r_hit)[0])
        ref = [boxes.names[k] for k in hits]
        if not planner._inside_xy(x, y, r_hit):
            ref.insert(0, "workspace")
        assert got == ref
        seen += bool(got)
        # the same with the scene cached (a planning query made it)
        planner.plan((0.0, 0.0, 0.0), (x, y, 0.0), r, movable)
        assert planner.colliding((x, y, 0.0), r, movable) == ref
    assert 100 < seen < 1400
    assert planner.colliding((0.0, 0.0, 0.0), 0.4) == []


def test_the_last_plan_is_remembered_exactly() -> None:
    """A repeated query returns the last answer; any other query is planned afresh."""
    static, movable = house_static(), house_movable()[-4:]
    planner = BasePlanner(WORKSPACE, static)
    s, g, r = _query()
    first = planner.plan(s, g, r, movable)
    assert first is not None
    assert planner.plan(s, g, r, list(movable)) is first  # the same boxes, as a list
    assert planner.plan((s.x, s.y, s.theta), g, r, movable) is first  # the same numbers
    # equal boxes that are other objects, another radius, a signed zero: planned afresh
    copies = [Box2D(b.cx, b.cy, b.half_x, b.half_y, b.yaw, b.name) for b in movable]
    again = planner.plan(s, g, r, copies)
    assert again is not first and again == first
    assert planner.plan(s, g, r + 0.01, copies) is not again
    g0 = Pose2D(g.x, g.y, 0.0)
    zero = planner.plan(s, g0, r, movable)
    assert planner.plan(s, Pose2D(g.x, g.y, -0.0), r, movable) is not zero
    # a query that finds no path is remembered as such
    blocked = Pose2D(-1.9, 0.0, 0.0)  # in the west wall
    assert planner.plan(s, blocked, r, movable) is None
    assert planner.plan(s, blocked, r, movable) is None
    planner.clear_caches()
    assert planner._last_plan is None
    assert planner.plan(s, g, r, movable) == first


def test_disc_probe_blocked_is_the_planners_end_point_test() -> None:
    planner = BasePlanner(WORKSPACE, house_static())
    movable = house_movable()
    probe = planner.disc_probe(movable)
    rng = np.random.default_rng(3)
    free = blocked = 0
    for _ in range(3000):
        x, y = rng.uniform(-2.2, 6.2), rng.uniform(-4.2, 4.2)
        r = float(rng.uniform(0.2, 0.6))
        expect = bool(planner.colliding((x, y, 0.0), r, movable))
        assert probe.blocked(x, y, r) is expect
        if expect:
            blocked += 1
            # a goal whose disc is blocked has no path, whatever the start
            assert planner.plan((0.0, 0.0, 0.0), (x, y, 0.0), r, movable) is None
        else:
            free += 1
    assert free > 300 and blocked > 300


def test_disc_probe_verdict_agrees_or_abstains_near_contact() -> None:
    planner = BasePlanner(WORKSPACE, house_static())
    movable = house_movable()
    probe = planner.disc_probe(movable)
    rng = np.random.default_rng(4)
    margin = 1e-9
    told = 0
    for _ in range(3000):
        x, y = rng.uniform(-2.2, 6.2), rng.uniform(-4.2, 4.2)
        r = float(rng.uniform(0.2, 0.6))
        verdict = probe.verdict(x, y, r, margin)
        # the probe's memory of the last deciding box changes no answer
        fresh = planner.disc_probe(movable)
        assert verdict is fresh.verdict(x, y, r, margin)
        assert probe.blocked(x, y, r) is planner.disc_probe(movable).blocked(x, y, r)
        if verdict is not None:
            told += 1
            assert verdict is probe.blocked(x, y, r)
            # the answer holds for every disc within the margin
            for dx, dy, dr in ((margin, 0, 0), (0, -margin, 0), (0, 0, margin), (0, 0, -margin)):
                assert probe.blocked(x + 0.9 * dx, y + 0.9 * dy, r + 0.9 * dr) is verdict
    assert told > 2990
    # a disc touching the wall x = -1.9 within the margin: too close to tell
    r = 0.3
    x_touch = -1.9 + r + planner.config.clearance - planner.config.contact_tolerance
    assert probe.verdict(x_touch, 0.0, r, margin) is None
    assert probe.verdict(x_touch + 10 * margin, 0.0, r, margin) is False
    assert probe.verdict(x_touch - 10 * margin, 0.0, r, margin) is True
    # rounded radii (radius_step) are not continuous: no verdict
    stepped = BasePlanner(WORKSPACE, house_static(), BasePlannerConfig(radius_step=0.01))
    assert stepped.disc_probe(movable).verdict(0.0, 0.0, 0.3, margin) is None


def test_straight_paths_keep_their_ends() -> None:
    rng = np.random.default_rng(8)
    rng.uniform(-7, 7, (2000, 2, 3))  # the draws of the path-length half
    planner = BasePlanner(WORKSPACE, [])
    for s, g in rng.uniform(-1.0, 1.0, (200, 2, 3)):
        path = planner.plan(s, g, 0.4)
        assert path is not None and path.waypoints.shape == (2, 3)
        # what _make_path computed for two points: the ends with their own headings
        assert path.waypoints.tobytes() == np.array([s, g]).tobytes()
        assert path.length == path_length_arrays(np.array([s, g]), 1.0)
