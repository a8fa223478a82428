"""Rectangles against axis-aligned regions (voot.envs.motion.rects)."""

from __future__ import annotations

import math

import numpy as np

from voot.envs.motion import rects
from voot.envs.motion.planar import Box2D
from voot.envs.motion.rects import (
    rect_fields_inside,
    rect_fields_overlap,
    rect_inside,
    rect_overlaps,
)


def test_rectangle_region_tests() -> None:
    region = (0.0, 4.0, 0.0, 2.0)
    assert rect_inside(Box2D(1.0, 1.0, 0.5, 0.5), region)
    assert not rect_inside(Box2D(1.0, 1.0, 0.5, 0.5, math.pi / 4), (0.0, 4.0, 0.0, 1.6))
    assert rect_overlaps(Box2D(4.2, 1.0, 0.5, 0.5), region)
    assert not rect_overlaps(Box2D(5.0, 1.0, 0.5, 0.5), region)
    # a rotated box whose bounding box overlaps but which itself does not
    assert not rect_overlaps(Box2D(4.6, 2.6, 0.5, 0.1, -math.pi / 4), region)


# ----- the float shortcuts decide as the corner arrays do ---------------------------------
def _inside_corners(box: Box2D, b: tuple[float, float, float, float]) -> bool:
    c = box.corners()
    return bool(
        (c[:, 0] >= b[0]).all() and (c[:, 0] <= b[1]).all() and (c[:, 1] >= b[2]).all()
        and (c[:, 1] <= b[3]).all()
    )  # fmt: skip


def _random_boxes(n: int, bounds: tuple[float, float, float, float]) -> list[Box2D]:
    """Random rectangles, half of them moved to touch an edge of ``bounds`` within 1e-12."""
    rng = np.random.default_rng(7)
    out = []
    for k in range(n):
        hx, hy = rng.uniform(0.05, 0.6, 2)
        yaw = float(rng.choice([0.0, math.pi / 2, math.pi / 4, rng.uniform(0, 2 * math.pi)]))
        cx, cy = rng.uniform(bounds[0], bounds[1]), rng.uniform(bounds[2], bounds[3])
        box = Box2D(float(cx), float(cy), float(hx), float(hy), yaw, "b")
        if k % 2:  # shift so that the extreme corner lies (almost) on an edge
            c = box.corners()
            edge = int(rng.integers(4))
            delta = float(rng.choice([0.0, 1e-12, -1e-12, 5e-10, -5e-10]))
            if edge == 0:
                cx += bounds[0] - c[:, 0].min() + delta
            elif edge == 1:
                cx += bounds[1] - c[:, 0].max() + delta
            elif edge == 2:
                cy += bounds[2] - c[:, 1].min() + delta
            else:
                cy += bounds[3] - c[:, 1].max() + delta
            box = Box2D(float(cx), float(cy), float(hx), float(hy), yaw, "b")
        out.append(box)
    return out


def test_rect_inside_and_overlaps_agree_with_the_corner_tests() -> None:
    bounds = (-2.0, 6.0, -4.0, 4.0)
    for box in _random_boxes(3000, bounds):
        assert rect_inside(box, bounds) == _inside_corners(box, bounds)
        assert rect_overlaps(box, bounds) == rects._rect_overlaps_sat(box, bounds)


def test_rect_tests_on_fields_match_the_box_tests() -> None:
    """rect_fields_inside / rect_fields_overlap decide as rect_inside / rect_overlaps."""
    rng = np.random.default_rng(4)
    bounds = (-1.0, 2.0, -0.5, 1.5)
    seen = set()
    for k in range(3000):
        hx, hy = (float(v) for v in rng.uniform(0.05, 0.6, 2))
        yaw = float(rng.uniform(-np.pi, np.pi)) if k % 4 else 0.0
        cx, cy = (float(v) for v in rng.uniform(-1.8, 2.8, 2))
        if k % 5 == 0:  # right at an edge, where the corner arrays decide
            cx = bounds[0] + hx
        box = Box2D(cx, cy, hx, hy, yaw, "b")
        inside = rect_fields_inside(cx, cy, hx, hy, yaw, bounds)
        overlap = rect_fields_overlap(cx, cy, hx, hy, yaw, bounds)
        assert inside == rect_inside(box, bounds)
        assert overlap == rect_overlaps(box, bounds)
        seen.add((inside, overlap))
    assert seen == {(True, True), (False, True), (False, False)}


def test_float_separating_axes_agree_with_the_corner_arrays_or_abstain() -> None:
    rng = np.random.default_rng(9)
    bounds = (-1.0, 2.0, -0.5, 1.5)
    told = abstained = 0
    for k in range(4000):
        hx, hy = (float(v) for v in rng.uniform(0.05, 0.6, 2))
        yaw = float(rng.uniform(-np.pi, np.pi))
        cx, cy = (float(v) for v in rng.uniform(-1.8, 2.8, 2))
        box = Box2D(cx, cy, hx, hy, yaw, "b")
        if k % 7 == 0:  # a corner exactly on an edge: the floats must abstain or agree
            c = box.corners()
            cx += bounds[0] - float(c[:, 0].max())
            box = Box2D(cx, cy, hx, hy, yaw, "b")
        sure = rects._rect_overlaps_floats(cx, cy, hx, hy, yaw, bounds)
        if sure is None:
            abstained += 1
        else:
            told += 1
            assert sure == rects._rect_overlaps_sat(box, bounds)
    assert told > 3000 and abstained > 0
