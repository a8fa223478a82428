"""Tests of voot.envs.motion.disc_geometry: the exact disc tests, and the float shortcuts answer as
the array kernels."""

from __future__ import annotations

import numpy as np
from floor_plans import WORKSPACE, house_movable, house_static

from voot.envs.motion.disc_geometry import (
    BoxArrays,
    _point_hits_any,
    _segment_hits_any,
    points_hit_boxes,
    points_inside,
    segments_hit_any,
    segments_hit_boxes,
)
from voot.envs.motion.planar import Box2D


def test_single_segment_and_point_tests_match_the_arrays() -> None:
    boxes = house_static() + house_movable()
    arrays = BoxArrays.from_boxes(boxes)
    lists = arrays.lists()
    rng = np.random.default_rng(11)
    pts = rng.uniform((-2.5, -4.5), (6.5, 4.5), (4000, 2))
    # and segments that graze a box corner at exactly the radius
    for k in range(0, 4000, 4):
        b = boxes[k % len(boxes)]
        pts[k] = b.corners()[k % 4] + 0.5 * np.array([1.0, 0.0])
    hint = [0]
    for k in range(0, len(pts) - 1, 2):
        p, q = pts[k], pts[k + 1]
        r = [0.3, 0.48, 0.5, 0.9][k % 4]
        ref = bool(segments_hit_any(p[None], q[None], arrays, r)[0])
        got = _segment_hits_any(float(p[0]), float(p[1]), float(q[0]), float(q[1]), lists, r, hint)
        assert got == ref
        ref_pt = bool(points_hit_boxes(p[None], arrays, r).any())
        assert _point_hits_any(float(p[0]), float(p[1]), lists, r) == ref_pt
        # whichever box the hint names first (the last hit, or any other)
        start = [k % (len(boxes) + 3)]
        assert _point_hits_any(float(p[0]), float(p[1]), lists, r, start) == ref_pt
        if ref_pt:  # the hint now names a box the point hits
            assert bool(points_hit_boxes(p[None], arrays, r)[0, start[0]])


def test_points_inside_keeps_the_disc_in_the_workspace() -> None:
    # WORKSPACE (-2, 6, -4, 4) with radius 0.5: x in [-1.5, 5.5], y in [-3.5, 3.5]
    pts = np.array([[0.0, 0.0], [-1.5, 0.0], [-1.6, 0.0], [5.5, 3.5], [5.5, 3.6], [0.0, -3.6]])
    assert points_inside(pts, WORKSPACE, 0.5).tolist() == [True, True, False, True, False, False]


def test_segments_hit_boxes_lists_the_pairs_within_the_radius() -> None:
    boxes = BoxArrays.from_boxes(
        [Box2D(0.0, 0.0, 1.0, 1.0, 0.0, "a"), Box2D(5.0, 0.0, 0.5, 0.5, 0.3, "b")]
    )
    p = np.array([[-3.0, 1.4], [-3.0, 1.4], [1.3, 1.3]])
    q = np.array([[3.0, 1.4], [6.0, 0.0], [2.0, 2.0]])
    # 0 passes 0.4 above a; 1 crosses both; 2 starts 0.424 from a's corner (a corner disc)
    seg, box = segments_hit_boxes(p, q, boxes, 0.5)
    assert seg.tolist() == [0, 1, 1, 2] and box.tolist() == [0, 0, 1, 0]
    seg, box = segments_hit_boxes(p, q, boxes, 0.3)
    assert seg.tolist() == [1, 1] and box.tolist() == [0, 1]
    assert segments_hit_any(p, q, boxes, 0.3).tolist() == [False, True, False]
    empty = BoxArrays.from_boxes([])
    assert segments_hit_boxes(p, q, empty, 0.5)[0].size == 0
    assert points_hit_boxes(p, empty, 0.5).shape == (3, 0)
