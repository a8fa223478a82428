"""Exact collision tests of a disc against oriented boxes, as arrays and on floats.

The base planner (:mod:`voot.envs.motion.planner`) and the swept-volume test
(:mod:`voot.envs.motion.swept_volume`) model the robot as a disc, so every collision question
is "does a disc of radius ``r`` at a point, or swept along a segment, come closer than
``r`` to an oriented rectangle?". This module answers it exactly (no polygonal
approximation of the disc):

* a point collides with a box iff its distance to the rectangle (0 inside) is below
  ``r`` (:func:`points_hit_boxes`);
* a segment collides iff it meets the box grown by ``r`` (a rounded rectangle): the union
  of the box grown along each of its axes (a slab test) and the four discs at its corners
  (point-to-segment distances), after a bounding-circle prefilter
  (:func:`segments_hit_boxes`, :func:`segments_hit_any`).

Two implementations of each test live side by side on purpose. The array kernels, over
:class:`BoxArrays`, answer many (point or segment, box) pairs at once (graph
construction). The float versions (:func:`_point_hits_any`, :func:`_segment_hits_any`,
:func:`_point_hit_indices`) answer one point or segment against the boxes as Python
lists: every quantity is the array kernel's elementwise expression, evaluated in the same
order with the same IEEE operations, so the answer is bit-identical, and for one query
against a few dozen boxes they are several times cheaper than the arrays' fixed costs (a
tree search asks one start, one goal and one straight segment per simulated place
action). Keeping each float shortcut next to the kernel it mirrors is what lets a reader
check that they agree (``tests/envs/motion/test_disc_geometry.py`` compares them).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from voot.envs.motion.planar import Box2D

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.intp]
BoolArray = NDArray[np.bool_]

__all__ = [
    "BoxArrays",
    "points_hit_boxes",
    "points_inside",
    "segments_hit_any",
    "segments_hit_boxes",
]


@dataclass(frozen=True, eq=False)
class BoxArrays:
    """A set of :class:`Box2D` as arrays, for vectorised tests.

    Attributes:
        center: ``(m, 2)`` centres.
        cos: ``(m,)`` cosine of the yaw.
        sin: ``(m,)`` sine of the yaw.
        half: ``(m, 2)`` half extents.
        reach: ``(m,)`` circumradius ``hypot(half_x, half_y)`` (for prefilters).
        names: The boxes' names.
    """

    center: FloatArray
    cos: FloatArray
    sin: FloatArray
    half: FloatArray
    reach: FloatArray
    names: tuple[str, ...]

    @classmethod
    def from_boxes(cls, boxes: Sequence[Box2D]) -> BoxArrays:
        for i, b in enumerate(boxes):
            if not isinstance(b, Box2D):
                raise ValueError(f"obstacle {i} must be a Box2D, got {type(b).__name__}")
        n = len(boxes)
        center = np.array([[b.cx, b.cy] for b in boxes], dtype=np.float64).reshape(n, 2)
        yaw = np.array([b.yaw for b in boxes], dtype=np.float64)
        half = np.array([[b.half_x, b.half_y] for b in boxes], dtype=np.float64).reshape(n, 2)
        return cls(
            center, np.cos(yaw), np.sin(yaw), half, np.hypot(half[:, 0], half[:, 1]),
            tuple(b.name for b in boxes),
        )  # fmt: skip

    def __len__(self) -> int:
        return len(self.names)

    @cached_property
    def corners_and_extents(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Corner ``x`` and ``y`` (``(4 m,)``, box-major, counter-clockwise from
        ``(+, +)`` as :meth:`VisibilityGraphs._polygon_nodes` orders them) and the half extents
        of each box's axis-aligned bounding box (``(m,)`` each), for prefilters only."""
        c, s = self.cos[:, None], self.sin[:, None]
        lx = _CORNER_SIGNS[:, 0] * self.half[:, 0:1]
        ly = _CORNER_SIGNS[:, 1] * self.half[:, 1:2]
        kx = self.center[:, 0:1] + c * lx - s * ly
        ky = self.center[:, 1:2] + s * lx + c * ly
        ac, as_ = np.abs(self.cos), np.abs(self.sin)
        ax = ac * self.half[:, 0] + as_ * self.half[:, 1]
        ay = as_ * self.half[:, 0] + ac * self.half[:, 1]
        return kx.ravel(), ky.ravel(), ax, ay

    def lists(self) -> tuple[list[float], ...]:
        """The columns as lists of Python floats, in the order the float tests read them:
        centre x, centre y, cos, sin, half x, half y, reach."""
        return (
            self.center[:, 0].tolist(), self.center[:, 1].tolist(), self.cos.tolist(),
            self.sin.tolist(), self.half[:, 0].tolist(), self.half[:, 1].tolist(),
            self.reach.tolist(),
        )  # fmt: skip

    def concat(self, other: BoxArrays) -> BoxArrays:
        return BoxArrays(
            np.concatenate([self.center, other.center]),
            np.concatenate([self.cos, other.cos]),
            np.concatenate([self.sin, other.sin]),
            np.concatenate([self.half, other.half]),
            np.concatenate([self.reach, other.reach]),
            self.names + other.names,
        )


def points_hit_boxes(points: FloatArray, boxes: BoxArrays, radius: float) -> BoolArray:
    """``(p, m)`` mask: is point ``i`` closer than ``radius`` to box ``j``?

    The distance from a point to a rectangle is 0 inside it, so a disc of ``radius``
    centred at the point overlaps the box iff the mask is true.
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(boxes) == 0 or pts.shape[0] == 0:
        return np.zeros((pts.shape[0], len(boxes)), dtype=bool)
    rel = pts[:, None, :] - boxes.center[None, :, :]
    lx = rel[..., 0] * boxes.cos + rel[..., 1] * boxes.sin
    ly = -rel[..., 0] * boxes.sin + rel[..., 1] * boxes.cos
    dx = np.maximum(np.abs(lx) - boxes.half[:, 0], 0.0)
    dy = np.maximum(np.abs(ly) - boxes.half[:, 1], 0.0)
    return dx * dx + dy * dy < radius * radius


_CORNER_SIGNS = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])


def _segment_meets_open_box(
    px: FloatArray,
    py: FloatArray,
    dx: FloatArray,
    dy: FloatArray,
    cross: FloatArray,
    hx: FloatArray,
    hy: FloatArray,
) -> BoolArray:
    """Does segment ``p + t d, t in [0, 1]`` meet the open box ``|x| < hx, |y| < hy``?

    Separating-axis test on the box axes and the segment's normal (``cross`` is
    ``px * dy - py * dx``, the segment line's offset along the normal). Touching counts
    as separated; a degenerate segment (a point) is tested by the box axes alone.
    """
    qx = px + dx
    qy = py + dy
    sep = (np.maximum(px, qx) <= -hx) | (np.minimum(px, qx) >= hx)
    sep |= (np.maximum(py, qy) <= -hy) | (np.minimum(py, qy) >= hy)
    reach = np.abs(dy) * hx + np.abs(dx) * hy
    sep |= (np.abs(cross) >= reach) & (reach > 0.0)
    result: BoolArray = ~sep
    return result


def _segment_box_pairs_hit(
    p: FloatArray, q: FloatArray, boxes: BoxArrays, box_index: IntArray, radius: float
) -> BoolArray:
    """Exact test for pairs: does segment ``k`` pass within ``radius`` of box ``box_index[k]``?

    In the box frame the grown box (a rounded rectangle) is the union of the box grown
    along x, the box grown along y and the four discs at the corners.
    """
    c = boxes.cos[box_index]
    s = boxes.sin[box_index]
    hx = boxes.half[box_index, 0]
    hy = boxes.half[box_index, 1]
    rx = p[:, 0] - boxes.center[box_index, 0]
    ry = p[:, 1] - boxes.center[box_index, 1]
    ex = q[:, 0] - p[:, 0]
    ey = q[:, 1] - p[:, 1]
    px = rx * c + ry * s
    py = ry * c - rx * s
    dx = ex * c + ey * s
    dy = ey * c - ex * s
    cross = px * dy - py * dx
    hit = _segment_meets_open_box(px, py, dx, dy, cross, hx + radius, hy)
    hit |= _segment_meets_open_box(px, py, dx, dy, cross, hx, hy + radius)
    # the four corner discs at once: shape (k, 4)
    inv_dd = (1.0 / np.maximum(dx * dx + dy * dy, 1e-300))[:, None]
    vx = _CORNER_SIGNS[:, 0] * hx[:, None] - px[:, None]
    vy = _CORNER_SIGNS[:, 1] * hy[:, None] - py[:, None]
    dxc = dx[:, None]
    dyc = dy[:, None]
    t = np.minimum(np.maximum((vx * dxc + vy * dyc) * inv_dd, 0.0), 1.0)
    ox = vx - t * dxc
    oy = vy - t * dyc
    hit |= (ox * ox + oy * oy < radius * radius).any(axis=1)
    return hit


def segments_hit_boxes(
    p: FloatArray, q: FloatArray, boxes: BoxArrays, radius: float
) -> tuple[IntArray, IntArray]:
    """All ``(segment, box)`` pairs where segment ``p[k] -> q[k]`` passes within ``radius``.

    A disc of ``radius`` swept along the segment overlaps the box iff the pair is listed.
    Candidate pairs come from a bounding-circle prefilter (distance from the box centre to
    the segment below ``radius + circumradius``); the exact test runs on those only.

    Returns:
        ``(segment_index, box_index)`` arrays, sorted by segment then box.
    """
    p = np.asarray(p, dtype=np.float64).reshape(-1, 2)
    q = np.asarray(q, dtype=np.float64).reshape(-1, 2)
    if len(boxes) == 0 or p.shape[0] == 0:
        empty = np.zeros(0, dtype=np.intp)
        return empty, empty
    dx = (q[:, 0] - p[:, 0])[:, None]
    dy = (q[:, 1] - p[:, 1])[:, None]
    inv_dd = 1.0 / np.maximum(dx * dx + dy * dy, 1e-300)
    # (e, m) distance from each box centre to each segment
    ex = boxes.center[:, 0] - p[:, 0:1]
    ey = boxes.center[:, 1] - p[:, 1:2]
    t = np.minimum(np.maximum((ex * dx + ey * dy) * inv_dd, 0.0), 1.0)
    ox = ex - t * dx
    oy = ey - t * dy
    lim = boxes.reach + radius
    seg_i, box_j = np.nonzero(ox * ox + oy * oy < lim * lim)
    if seg_i.size == 0:
        return seg_i, box_j
    hit = _segment_box_pairs_hit(p[seg_i], q[seg_i], boxes, box_j, radius)
    return seg_i[hit], box_j[hit]


def _point_hits_any(
    x: float,
    y: float,
    boxes: tuple[list[float], ...],
    radius: float,
    hint: list[int] | None = None,
) -> bool:
    """:func:`points_hit_boxes` for one point and any box, on Python floats (same operations).

    The boxes are tried from ``hint[0]`` on (the box that the caller's last point hit:
    points asked in a row mostly hit the same one; the answer does not depend on the
    order), and ``hint[0]`` is set to the box hit.
    """
    if hint is None:
        hint = _LAST_POINT_HIT
    bcx, bcy, bcos, bsin, bhx, bhy, breach = boxes
    r2 = radius * radius
    n = len(bcx)
    first = hint[0] if hint[0] < n else 0
    for k in itertools.chain(range(first, n), range(first)):
        rx = x - bcx[k]
        ry = y - bcy[k]
        far = breach[k] + radius + 1e-6  # the point is at least this far from the box centre
        if rx * rx + ry * ry > far * far:
            continue  # farther than circumradius + radius (+ a margin above rounding)
        c, s = bcos[k], bsin[k]
        lx = rx * c + ry * s
        ly = -rx * s + ry * c
        dx = max(abs(lx) - bhx[k], 0.0)
        dy = max(abs(ly) - bhy[k], 0.0)
        if dx * dx + dy * dy < r2:
            hint[0] = k
            return True
    return False


#: Index of the box that the last point of :func:`_point_hits_any` hit.
_LAST_POINT_HIT = [0]


def _point_hit_indices(
    x: float, y: float, boxes: tuple[list[float], ...], radius: float
) -> list[int]:
    """The boxes :func:`points_hit_boxes` marks for one point, in order (floats)."""
    bcx, bcy, bcos, bsin, bhx, bhy, breach = boxes
    r2 = radius * radius
    out = []
    for k in range(len(bcx)):
        rx = x - bcx[k]
        ry = y - bcy[k]
        far = breach[k] + radius + 1e-6
        if rx * rx + ry * ry > far * far:
            continue
        c, s = bcos[k], bsin[k]
        lx = rx * c + ry * s
        ly = -rx * s + ry * c
        dx = max(abs(lx) - bhx[k], 0.0)
        dy = max(abs(ly) - bhy[k], 0.0)
        if dx * dx + dy * dy < r2:
            out.append(k)
    return out


def _open_box_met(
    px: float, py: float, dx: float, dy: float, cross: float, hx: float, hy: float
) -> bool:
    """:func:`_segment_meets_open_box` for one segment, on Python floats."""
    qx = px + dx
    qy = py + dy
    if max(px, qx) <= -hx or min(px, qx) >= hx or max(py, qy) <= -hy or min(py, qy) >= hy:
        return False
    reach = abs(dy) * hx + abs(dx) * hy
    return not (abs(cross) >= reach and reach > 0.0)


def _segment_hits_any(
    p0: float,
    p1: float,
    q0: float,
    q1: float,
    boxes: tuple[list[float], ...],
    radius: float,
    hint: list[int] | None = None,
) -> bool:
    """``segments_hit_any`` for the one segment ``p -> q``, on Python floats.

    Every quantity is the elementwise expression of :func:`segments_hit_boxes` and
    :func:`_segment_box_pairs_hit` for this segment, evaluated in the same order with
    the same IEEE operations (no reduction reorders a sum), so the answer is identical;
    for one segment against a few dozen boxes it is several times cheaper than the
    array version's fixed costs. The boxes are tried from ``hint[0]`` on (the box that
    blocked the caller's last segment; the answer does not depend on the order), and
    ``hint[0]`` is set to the blocking box.
    """
    if hint is None:
        hint = _LAST_HIT
    bcx, bcy, bcos, bsin, bhx, bhy, breach = boxes
    dx = q0 - p0
    dy = q1 - p1
    inv_dd = 1.0 / max(dx * dx + dy * dy, 1e-300)
    r2 = radius * radius
    n = len(bcx)
    first = hint[0] if hint[0] < n else 0
    # the box that blocked the last segment first: segments asked in a row are mostly
    # blocked by the same wall (the answer does not depend on the order)
    for k in itertools.chain(range(first, n), range(first)):
        cx, cy = bcx[k], bcy[k]
        ex = cx - p0
        ey = cy - p1
        t = min(max((ex * dx + ey * dy) * inv_dd, 0.0), 1.0)
        ox = ex - t * dx
        oy = ey - t * dy
        lim = breach[k] + radius
        if not ox * ox + oy * oy < lim * lim:
            continue
        # the exact test in the box frame
        c, s = bcos[k], bsin[k]
        hx, hy = bhx[k], bhy[k]
        rx = p0 - cx
        ry = p1 - cy
        px = rx * c + ry * s
        py = ry * c - rx * s
        sdx = dx * c + dy * s
        sdy = dy * c - dx * s
        cross = px * sdy - py * sdx
        if _open_box_met(px, py, sdx, sdy, cross, hx + radius, hy) or _open_box_met(
            px, py, sdx, sdy, cross, hx, hy + radius
        ):
            hint[0] = k
            return True
        inv = 1.0 / max(sdx * sdx + sdy * sdy, 1e-300)
        for sx, sy in ((1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)):
            vx = sx * hx - px
            vy = sy * hy - py
            tc = min(max((vx * sdx + vy * sdy) * inv, 0.0), 1.0)
            wx = vx - tc * sdx
            wy = vy - tc * sdy
            if wx * wx + wy * wy < r2:
                hint[0] = k
                return True
    return False


#: Index of the box that blocked the last segment of :func:`_segment_hits_any`.
_LAST_HIT = [0]


def segments_hit_any(p: FloatArray, q: FloatArray, boxes: BoxArrays, radius: float) -> BoolArray:
    """``(e,)`` mask: does segment ``k`` pass within ``radius`` of any box?"""
    p = np.asarray(p, dtype=np.float64).reshape(-1, 2)
    out = np.zeros(p.shape[0], dtype=bool)
    seg_i, _ = segments_hit_boxes(p, q, boxes, radius)
    out[seg_i] = True
    return out


def points_inside(
    pts: FloatArray, workspace: tuple[float, float, float, float], radius: float
) -> BoolArray:
    """``(p,)`` mask: does the disc of ``radius`` at each point stay inside ``workspace``
    (``(xmin, xmax, ymin, ymax)``; touching its border counts as inside)?"""
    xmin, xmax, ymin, ymax = workspace
    result: BoolArray = (
        (pts[:, 0] >= xmin + radius)
        & (pts[:, 0] <= xmax - radius)
        & (pts[:, 1] >= ymin + radius)
        & (pts[:, 1] <= ymax - radius)
    )
    return result
