"""Rectangles against axis-aligned regions: is a footprint inside a region, does it overlap one?

The task checks ask these of an object's footprint (a :class:`~voot.envs.motion.planar.Box2D`,
an oriented rectangle) and a region ``(xmin, xmax, ymin, ymax)``: the loading region, the
house, a forbidden room. :func:`rect_inside` and :func:`rect_overlaps` take a box;
:func:`rect_fields_inside` and :func:`rect_fields_overlap` the box's fields as floats (for
a caller that has the numbers and no box). Each decides with plain floats when the answer
is clear by more than 1e-9 m and falls back to the exact corner-array test otherwise, so
the answer is always the corner test's.
"""

from __future__ import annotations

import math

import numpy as np

from voot.envs.motion.planar import Box2D

__all__ = ["rect_fields_inside", "rect_fields_overlap", "rect_inside", "rect_overlaps"]

#: Margin (metres) of the float shortcuts of :func:`rect_inside` and :func:`rect_overlaps`:
#: far above the rounding difference (~1e-14 m) between them and the corner arrays.
_SURE = 1e-9


def _aabb(
    cx: float, cy: float, half_x: float, half_y: float, yaw: float
) -> tuple[float, float, float, float]:
    """``(xmin, xmax, ymin, ymax)`` of the axis-aligned box around the rectangle."""
    c, s = abs(math.cos(yaw)), abs(math.sin(yaw))
    ex, ey = half_x * c + half_y * s, half_x * s + half_y * c
    return cx - ex, cx + ex, cy - ey, cy + ey


def rect_inside(box: Box2D, bounds: tuple[float, float, float, float]) -> bool:
    """Is the rectangle ``box`` inside the axis-aligned ``(xmin, xmax, ymin, ymax)``?

    Decided from the rectangle's extent with plain floats when it is inside or outside by
    more than 1e-9 m; only a rectangle within that of an edge is tested with its corner
    array (as before), so the answer is always the corner test's.
    """
    return rect_fields_inside(box.cx, box.cy, box.half_x, box.half_y, box.yaw, bounds)


def rect_fields_inside(
    cx: float,
    cy: float,
    half_x: float,
    half_y: float,
    yaw: float,
    bounds: tuple[float, float, float, float],
) -> bool:
    """:func:`rect_inside` of the rectangle with these :class:`Box2D` fields (floats).

    For a caller that has the numbers and no box: the box is built only for a rectangle
    within 1e-9 m of an edge.
    """
    xmin, xmax, ymin, ymax = bounds
    lo_x, hi_x, lo_y, hi_y = _aabb(cx, cy, half_x, half_y, yaw)
    if (
        lo_x >= xmin + _SURE
        and hi_x <= xmax - _SURE
        and lo_y >= ymin + _SURE
        and hi_y <= ymax - _SURE
    ):
        return True
    if lo_x < xmin - _SURE or hi_x > xmax + _SURE or lo_y < ymin - _SURE or hi_y > ymax + _SURE:
        return False
    return _rect_inside_corners(Box2D.fast(cx, cy, half_x, half_y, yaw, "rect"), bounds)


def _rect_inside_corners(box: Box2D, bounds: tuple[float, float, float, float]) -> bool:
    c = box.corners()
    xmin, xmax, ymin, ymax = bounds
    return bool(
        np.all(c[:, 0] >= xmin)
        and np.all(c[:, 0] <= xmax)
        and np.all(c[:, 1] >= ymin)
        and np.all(c[:, 1] <= ymax)
    )


def rect_overlaps(box: Box2D, bounds: tuple[float, float, float, float]) -> bool:
    """Does the rectangle ``box`` overlap the open axis-aligned ``(xmin, xmax, ymin, ymax)``?

    Separating-axis test between the oriented rectangle and the axis-aligned one. A
    rectangle clearly apart from the region (by more than 1e-9 m along x or y) or
    clearly inside it is decided with plain floats; the others run the test on arrays,
    as before.
    """
    return rect_fields_overlap(box.cx, box.cy, box.half_x, box.half_y, box.yaw, bounds)


def rect_fields_overlap(
    cx: float,
    cy: float,
    half_x: float,
    half_y: float,
    yaw: float,
    bounds: tuple[float, float, float, float],
) -> bool:
    """:func:`rect_overlaps` of the rectangle with these :class:`Box2D` fields (floats)."""
    xmin, xmax, ymin, ymax = bounds
    lo_x, hi_x, lo_y, hi_y = _aabb(cx, cy, half_x, half_y, yaw)
    if hi_x < xmin - _SURE or lo_x > xmax + _SURE or hi_y < ymin - _SURE or lo_y > ymax + _SURE:
        return False
    if lo_x > xmin + _SURE and hi_x < xmax - _SURE and lo_y > ymin + _SURE and hi_y < ymax - _SURE:
        return True
    sure = _rect_overlaps_floats(cx, cy, half_x, half_y, yaw, bounds)
    if sure is not None:
        return sure
    return _rect_overlaps_sat(Box2D.fast(cx, cy, half_x, half_y, yaw, "rect"), bounds)


def _rect_overlaps_floats(
    cx: float,
    cy: float,
    half_x: float,
    half_y: float,
    yaw: float,
    bounds: tuple[float, float, float, float],
) -> bool | None:
    """:func:`_rect_overlaps_sat` on floats where every test clears it by 1e-9 m; else None.

    The same separating-axis tests on corners rotated with scalar products (the array
    code's matrix products may round differently in the last bits): an answer is given
    only when no comparison is within the margin of flipping.
    """
    c, s = math.cos(yaw), math.sin(yaw)
    xs, ys = [], []
    for lx, ly in ((half_x, half_y), (-half_x, half_y), (-half_x, -half_y), (half_x, -half_y)):
        xs.append(lx * c - ly * s + cx)
        ys.append(lx * s + ly * c + cy)
    xmin, xmax, ymin, ymax = bounds
    unsure = False
    # each test is "separated if a <= b"
    tests = [(max(xs), xmin), (xmax, min(xs)), (max(ys), ymin), (ymax, min(ys))]
    corners = ((xmin, ymin), (xmax, ymin), (xmax, ymax), (xmin, ymax))
    for ux, uy in ((c, s), (-s, c)):
        pa = [x * ux + y * uy for x, y in corners]
        pb = [x * ux + y * uy for x, y in zip(xs, ys, strict=True)]
        tests.append((max(pa), min(pb)))
        tests.append((max(pb), min(pa)))
    for a, b in tests:
        if a < b - _SURE:
            return False
        if a <= b + _SURE:
            unsure = True
    return None if unsure else True


def _rect_overlaps_sat(box: Box2D, bounds: tuple[float, float, float, float]) -> bool:
    xmin, xmax, ymin, ymax = bounds
    c = box.corners()
    if c[:, 0].max() <= xmin or c[:, 0].min() >= xmax:
        return False
    if c[:, 1].max() <= ymin or c[:, 1].min() >= ymax:
        return False
    aabb = np.array([[xmin, ymin], [xmax, ymin], [xmax, ymax], [xmin, ymax]])
    for axis in (
        np.array([math.cos(box.yaw), math.sin(box.yaw)]),
        np.array([-math.sin(box.yaw), math.cos(box.yaw)]),
    ):
        pa, pb = aabb @ axis, c @ axis
        if pa.max() <= pb.min() or pb.max() <= pa.min():
            return False
    return True
