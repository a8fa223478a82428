"""Tests of voot.envs.motion.swept_volume: which objects meet the robot's swept area."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from voot.envs.motion.planar import Box2D, Pose2D
from voot.envs.motion.planner import BasePlanner
from voot.envs.motion.swept_volume import PathProbe, obstacles_on_path, path_hits, swept_footprint

R = 0.5
STRAIGHT = np.array([[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]])


def test_on_beside_and_touching_a_straight_path() -> None:
    objects = [
        Box2D(2.0, 0.0, 0.2, 0.2, 0.0, "on"),
        Box2D(2.0, 1.5, 0.2, 0.2, 0.0, "beside"),  # 1.3 m from the path
        Box2D(2.0, 0.7, 0.3, 0.2, 0.0, "touching"),  # bottom face exactly at y = r
        Box2D(2.0, -0.7 - 1e-6, 0.3, 0.2, 0.0, "just_clear"),  # a micrometre away
        Box2D(4.7, 0.0, 0.2, 0.2, 0.0, "touching_end_cap"),  # 0.5 beyond the last point
        Box2D(-0.9, 0.0, 0.2, 0.2, 0.0, "before_start"),  # 0.7 before the first point
        Box2D(1.0, 0.0, 0.1, 0.1, 0.7, "rotated_on"),
    ]
    assert obstacles_on_path(STRAIGHT, R, objects) == [
        "on",
        "touching",
        "touching_end_cap",
        "rotated_on",
    ]
    np.testing.assert_array_equal(
        path_hits(STRAIGHT, R, objects), [True, False, True, False, True, False, True]
    )
    # a larger tolerance picks up the micrometre gap
    assert "just_clear" in obstacles_on_path(STRAIGHT, R, objects, tolerance=1e-5)


def test_rotated_box_corner_near_the_path() -> None:
    # a square turned 45 degrees, corner pointing at the path: corner at y = 0.5 + gap
    half = 0.2
    reach = half * math.sqrt(2)
    for gap, expected in ((-0.01, True), (0.01, False)):
        box = Box2D(2.0, R + gap + reach, half, half, math.pi / 4, "diamond")
        assert obstacles_on_path(STRAIGHT, R, [box]) == (["diamond"] if expected else [])


def test_bent_path_and_2d_waypoints() -> None:
    path = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]])
    inner = Box2D(1.2, 0.9, 0.1, 0.1, 0.0, "inner")  # inside the bend, 0.7 from both legs
    # beyond both legs' ends, 0.495 from the bend: only the round join reaches it
    outer_corner = Box2D(2.45, -0.45, 0.1, 0.1, 0.0, "outer")
    assert obstacles_on_path(path, R, [inner, outer_corner]) == ["outer"]
    with_theta = np.column_stack([path, [0.0, 1.0, 2.0]])
    assert obstacles_on_path(with_theta, R, [inner, outer_corner]) == ["outer"]
    assert obstacles_on_path(path, 0.75, [inner, outer_corner]) == ["inner", "outer"]


def test_single_waypoint_is_a_disc() -> None:
    point = np.array([[1.0, 1.0, 0.0]])
    near = Box2D(1.6, 1.0, 0.2, 0.2, 0.0, "near")  # face at 1.4: 0.4 away
    far = Box2D(2.0, 1.0, 0.2, 0.2, 0.0, "far")  # 0.8 away
    assert obstacles_on_path(point, R, [near, far]) == ["near"]
    area = swept_footprint(point, R)
    assert area.area == pytest.approx(math.pi * R * R, rel=0.01)


def test_matches_shapely_distance_on_random_boxes() -> None:
    rng = np.random.default_rng(0)
    path = np.array([[-1.5, -1.5], [-0.2, 0.4], [0.3, 1.9], [0.0, 2.5]])
    line = shapely.LineString(path)
    objects = []
    for i in range(300):
        objects.append(
            Box2D(
                rng.uniform(-3, 2),
                rng.uniform(-3, 4),
                rng.uniform(0.05, 0.4),
                rng.uniform(0.05, 0.4),
                rng.uniform(-math.pi, math.pi),
                f"o{i}",
            )
        )
    dist = np.array([line.distance(shapely.Polygon(o.corners())) for o in objects])
    clear_cut = np.abs(dist - R) > 1e-6
    hits = path_hits(path, R, objects)
    assert clear_cut.sum() > 290
    np.testing.assert_array_equal(hits[clear_cut], (dist <= R)[clear_cut])
    assert 20 < hits.sum() < 280  # the sample has objects on and off the path


def test_swept_footprint_geometry() -> None:
    area = swept_footprint(STRAIGHT, R, quad_segs=64)
    assert isinstance(area, shapely.Polygon)
    assert area.area == pytest.approx(2 * R * 4.0 + math.pi * R * R, rel=1e-3)
    assert area.contains(shapely.Point(2.0, 0.49))
    assert not area.intersects(shapely.Point(2.0, 0.51))
    on = Box2D(2.0, 0.0, 0.2, 0.2, 0.0, "on")
    beside = Box2D(2.0, 1.5, 0.2, 0.2, 0.0, "beside")
    assert area.intersects(shapely.Polygon(on.corners()))
    assert not area.intersects(shapely.Polygon(beside.corners()))


def test_kitchen_like_path_from_the_planner() -> None:
    """The env's use: plan the fixed path to the sink, then list the objects on it."""
    walls = [
        Box2D.from_bounds(-2.0, -1.98, -4.0, 4.0, "wall_w"),
        Box2D.from_bounds(-2.0, 2.8, 3.5, 3.6, "wall_n"),
        Box2D.from_bounds(-1.0, 1.0, 2.97, 3.5, "sink_counter"),
    ]
    planner = BasePlanner((-2.0, 6.0, -4.0, 4.0), walls)
    path = planner.plan(Pose2D(-1.5, -1.5, math.pi / 2), Pose2D(0.0, 2.5, math.pi / 2), 0.45)
    assert path is not None
    objects = [
        Box2D(-0.75, 0.5, 0.2, 0.2, 0.0, "chair_on_path"),
        Box2D(2.0, 0.0, 0.2, 0.2, 0.0, "chair_far"),
        Box2D(-0.2, 2.0, 0.1, 0.1, 0.3, "box_near_sink"),
    ]
    assert obstacles_on_path(path.waypoints, 0.45, objects) == ["chair_on_path", "box_near_sink"]


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: obstacles_on_path(np.zeros((3, 4)), R, []), "shape"),
        (lambda: obstacles_on_path(np.zeros((0, 2)), R, []), "shape"),
        (lambda: obstacles_on_path(np.array([[np.nan, 0.0]]), R, []), "finite"),
        (lambda: obstacles_on_path(STRAIGHT, 0.0, []), "robot_radius"),
        (lambda: obstacles_on_path(STRAIGHT, R, [], tolerance=-1.0), "tolerance"),
        (
            lambda: obstacles_on_path(STRAIGHT, R, [Box2D(0, 0, 1, 1), Box2D(1, 1, 1, 1)]),
            "non-empty, distinct name",
        ),
        (
            lambda: obstacles_on_path(STRAIGHT, R, [Box2D(0, 0, 1, 1, 0, "a")] * 2),
            "distinct",
        ),
        (lambda: swept_footprint(STRAIGHT, R, quad_segs=0), "quad_segs"),
    ],
)
def test_bad_input(call, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        call()


def test_no_objects() -> None:
    assert obstacles_on_path(STRAIGHT, R, []) == []
    assert path_hits(STRAIGHT, R, []).shape == (0,)


def test_path_hits_remembered_answers_are_the_fresh_ones() -> None:
    from voot.envs.motion import swept_volume as sv

    rng = np.random.default_rng(6)
    path = np.array([[-1.5, -1.5], [-1.0, 0.5], [0.0, 2.5]])
    boxes = [
        Box2D(float(x), float(y), 0.2, 0.3, float(t), f"b{k}")
        for k, (x, y, t) in enumerate(rng.uniform((-3, -3, 0), (2, 4, 6), (300, 3)))
    ]
    fresh = sv._path_hits_arrays(path, 0.48 + 1e-9, boxes)
    sv._PATH_HITS.clear()
    first = path_hits(path, 0.48, boxes[:150])
    again = path_hits(path, 0.48, boxes[::-1])  # half remembered, in another order
    assert first.tolist() == fresh[:150]
    assert again.tolist() == fresh[::-1]
    assert 10 < sum(fresh) < 290
    with pytest.raises(ValueError, match="must be a Box2D"):
        path_hits(path, 0.48, [boxes[0], "nope"])  # type: ignore[list-item]


def test_float_and_array_path_tests_agree(monkeypatch: pytest.MonkeyPatch) -> None:
    """The few-box float branch of path_hits gives the array branch's answers."""
    from voot.envs.motion import swept_volume as sv

    rng = np.random.default_rng(8)
    path = np.array([[0.0, 0.0], [2.0, 0.5], [2.5, 2.0], [2.5, 2.0], [0.5, 3.0]])
    boxes = [
        Box2D(*(float(v) for v in rng.uniform(-0.5, 3.0, 2)), *(float(v) for v in rng.uniform(0.05, 0.4, 2)),
              float(rng.uniform(-math.pi, math.pi)), f"b{i}")
        for i in range(400)
    ]  # fmt: skip
    for reach in (0.3, 0.45):
        for xy in (path, path[:1], path[:2]):
            floats = sv._path_hits_arrays(xy, reach, boxes[:1]) + sv._path_hits_arrays(
                xy, reach, boxes[1:2]
            )
            monkeypatch.setattr(sv, "_FLOAT_PAIRS", 10**9)
            all_floats = sv._path_hits_arrays(xy, reach, boxes)
            monkeypatch.setattr(sv, "_FLOAT_PAIRS", 0)
            arrays = sv._path_hits_arrays(xy, reach, boxes)
            monkeypatch.undo()
            assert all_floats == arrays and floats == arrays[:2]
            assert 20 < sum(arrays) < 380


def test_path_probe_is_path_hits() -> None:
    """A probe of a fixed path answers as path_hits, one box or many; bad paths are refused."""
    rng = np.random.default_rng(9)
    path = np.array([[-1.5, -1.5, 0.3], [-1.0, 0.5, 0.0], [0.0, 2.5, 1.0]])
    boxes = [
        Box2D(float(x), float(y), 0.25, 0.15, float(t), f"b{k}")
        for k, (x, y, t) in enumerate(rng.uniform((-3, -3, 0), (2, 4, 6), (200, 3)))
    ]
    probe = PathProbe(path, 0.48)
    expected = path_hits(path, 0.48, boxes).tolist()
    assert probe.hits(boxes) == expected
    assert [probe.hits([b])[0] for b in boxes] == expected
    assert probe.hits([]) == []
    assert 10 < sum(expected) < 190
    path[0, 0] = 99.0  # the probe kept its own copy
    assert probe.hits(boxes) == expected
    for bad, match in (
        (lambda: PathProbe(np.zeros((0, 2)), R), "waypoints"),
        (lambda: PathProbe(STRAIGHT, -1.0), "robot_radius"),
        (lambda: PathProbe(STRAIGHT, R, tolerance=math.nan), "tolerance"),
    ):
        with pytest.raises(ValueError, match=match):
            bad()
