"""The floor area swept by the robot along a fixed base path, and the objects it meets.

In the kitchen task the obstacles are "those objects whose footprint meets the swept
volume of the robot along the fixed path to the sink" (7 in the original problem); the
goal is reached when none is left. As in :mod:`voot.envs.motion.planner` the robot is a
disc of radius ``robot_radius`` (rotation-invariant), so the swept area of a polyline
path is the set of points within ``robot_radius`` of the polyline (its Minkowski sum
with the disc), and an object meets it iff its footprint rectangle comes within
``robot_radius`` of the polyline.

:func:`obstacles_on_path` decides this exactly with the vectorised segment-rectangle
test of the planner (no polygonal approximation of the disc), so a footprint that just
touches the swept area counts (within ``tolerance``). :func:`swept_footprint` returns
the area as a shapely polygon for display and for callers that want shapely's
predicates; its circular arcs are approximated by ``quad_segs`` segments per quarter
circle and lie slightly inside the exact area.
"""

from __future__ import annotations

import itertools
from collections import OrderedDict
from collections.abc import Sequence

import numpy as np
import shapely
from numpy.typing import ArrayLike

from voot.envs.motion.disc_geometry import (
    BoolArray,
    BoxArrays,
    FloatArray,
    _segment_hits_any,
    segments_hit_boxes,
)
from voot.envs.motion.planar import Box2D

__all__ = ["PathProbe", "obstacles_on_path", "path_hits", "swept_footprint"]


def _polyline(waypoints: ArrayLike) -> FloatArray:
    """``(k, 2)`` positions from ``(k, 2)`` or ``(k, 3)`` waypoints, validated."""
    w = np.asarray(waypoints, dtype=np.float64)
    if w.ndim != 2 or w.shape[1] not in (2, 3) or w.shape[0] < 1:
        raise ValueError(
            f"waypoints must have shape (k >= 1, 2) or (k >= 1, 3) (x, y[, theta]), got {w.shape}"
        )
    if not np.all(np.isfinite(w)):
        raise ValueError("waypoints must be finite")
    xy: FloatArray = w[:, :2]
    return xy


def _radius(robot_radius: float) -> float:
    r = float(robot_radius)
    if not (np.isfinite(r) and r > 0.0):
        raise ValueError(f"robot_radius must be a finite number > 0, got {robot_radius!r}")
    return r


def swept_footprint(
    path_waypoints: ArrayLike, robot_radius: float, quad_segs: int = 16
) -> shapely.Polygon:
    """The area swept by a disc of ``robot_radius`` moving along the polyline.

    Args:
        path_waypoints: ``(k, 2)`` or ``(k, 3)`` waypoints (headings are ignored: the disc
            is rotation-invariant).
        robot_radius: Disc radius (> 0).
        quad_segs: Segments per quarter circle of the buffer's round caps and joins.

    Returns:
        A shapely polygon (the buffer of the polyline, or of the point if ``k == 1`` or
        all waypoints coincide).
    """
    xy = _polyline(path_waypoints)
    r = _radius(robot_radius)
    if quad_segs < 1:
        raise ValueError(f"quad_segs must be >= 1, got {quad_segs}")
    unique = np.unique(xy, axis=0)
    geom = shapely.Point(xy[0]) if unique.shape[0] == 1 else shapely.LineString(xy)
    area = geom.buffer(r, quad_segs=quad_segs)
    if not isinstance(area, shapely.Polygon):  # a buffer of a connected curve is one polygon
        raise RuntimeError(f"unexpected swept footprint type {type(area).__name__}")
    return area


def path_hits(
    waypoints: ArrayLike,
    robot_radius: float,
    objects: Sequence[Box2D],
    tolerance: float = 1e-9,
) -> BoolArray:
    """``(n,)`` mask: does object ``i``'s footprint meet the swept area of the path?

    True iff the footprint rectangle comes within ``robot_radius + tolerance`` of the
    polyline (so touching counts).
    """
    xy = _polyline(waypoints)
    r = _radius(robot_radius)
    if not (np.isfinite(tolerance) and tolerance >= 0.0):
        raise ValueError(f"tolerance must be a finite number >= 0, got {tolerance!r}")
    objs = list(objects)
    for i, b in enumerate(objs):
        if not isinstance(b, Box2D):
            raise ValueError(f"obstacle {i} must be a Box2D, got {type(b).__name__}")
    # Each box's answer depends on the path and that box alone (a pair test per
    # segment), so answers are remembered per path and box: the kitchen asks about its
    # fixed path after every placement, and all but the moved object are known.
    key = (xy.tobytes(), xy.shape, float(r + tolerance))
    memo = _PATH_HITS.get(key)
    if memo is None:
        memo = _PATH_HITS[key] = {}
        if len(_PATH_HITS) > 8:
            _PATH_HITS.popitem(last=False)
    missing = list(dict.fromkeys(b for b in objs if b not in memo))
    if missing:
        if len(memo) > 100_000:
            memo.clear()
        memo.update(zip(missing, _path_hits_arrays(xy, r + tolerance, missing), strict=True))
    return np.array([memo[b] for b in objs], dtype=bool)


class PathProbe:
    """:func:`path_hits` of one fixed path, checked once, for callers that ask it about
    many boxes (the kitchen, about its fixed path after every placement; it remembers
    the answers per footprint itself).

    Args:
        waypoints: The path, as for :func:`path_hits` (copied).
        robot_radius: Radius of the disc swept along it (> 0).
        tolerance: As for :func:`path_hits`.
    """

    __slots__ = ("_reach", "_xy")

    def __init__(self, waypoints: ArrayLike, robot_radius: float, tolerance: float = 1e-9):
        self._xy = _polyline(waypoints).copy()
        r = _radius(robot_radius)
        if not (np.isfinite(tolerance) and tolerance >= 0.0):
            raise ValueError(f"tolerance must be a finite number >= 0, got {tolerance!r}")
        self._reach = float(r + tolerance)

    def hits(self, objects: Sequence[Box2D]) -> list[bool]:
        """Does each box meet the path? (:func:`path_hits`'s answers, as a list.)"""
        objs = list(objects)
        return _path_hits_arrays(self._xy, self._reach, objs) if objs else []


#: Per path (waypoint bytes, shape, radius + tolerance): box -> does it meet the path?
_PATH_HITS: OrderedDict[tuple[bytes, tuple[int, ...], float], dict[Box2D, bool]] = OrderedDict()


#: Up to this many (box, waypoint) pairs :func:`_path_hits_arrays` tests on floats.
_FLOAT_PAIRS = 256


def _path_hits_arrays(xy: np.ndarray, reach: float, objects: list[Box2D]) -> list[bool]:
    """The segment-box test of :func:`path_hits`, for ``objects``.

    :func:`segments_hit_boxes`'s answers; for a few boxes (the kitchen asks about the one
    it just moved) from :func:`_segment_hits_any`, its float twin (the same operations
    per pair, so the same answers), which is cheaper than the arrays for a short path.
    """
    boxes = BoxArrays.from_boxes(objects)
    if len(objects) * xy.shape[0] <= _FLOAT_PAIRS:
        lists = boxes.lists()
        pts = xy.tolist()
        segments = list(itertools.pairwise(pts)) if len(pts) > 1 else [(pts[0], pts[0])]
        out = []
        for k in range(len(objects)):
            one = tuple([col[k]] for col in lists)
            out.append(
                any(_segment_hits_any(a[0], a[1], b[0], b[1], one, reach, [0]) for a, b in segments)
            )
        return out
    hit = np.zeros(len(boxes), dtype=bool)
    # a single waypoint is a degenerate segment (a point)
    p = xy[:-1] if xy.shape[0] > 1 else xy
    q = xy[1:] if xy.shape[0] > 1 else xy
    _, box_j = segments_hit_boxes(p, q, boxes, reach)
    hit[box_j] = True
    return hit.tolist()  # type: ignore[no-any-return]


def obstacles_on_path(
    waypoints: np.ndarray,
    robot_radius: float,
    objects: Sequence[Box2D],
    tolerance: float = 1e-9,
) -> list[str]:
    """Names of the objects whose footprint meets the robot's swept area along the path.

    Args:
        waypoints: ``(k, 2)`` or ``(k, 3)`` polyline (e.g. :attr:`BasePath.waypoints`).
        robot_radius: Radius of the disc enclosing the robot (> 0).
        objects: Object footprints; their names must be non-empty and distinct.
        tolerance: A footprint within ``robot_radius + tolerance`` of the path counts
            (metres, >= 0), so exact touching is "on the path".

    Returns:
        The names, in the order of ``objects``.
    """
    objs = list(objects)
    names = [o.name if isinstance(o, Box2D) else "" for o in objs]
    if any(not n for n in names) or len(set(names)) != len(names):
        raise ValueError(
            f"obstacles_on_path: every object needs a non-empty, distinct name; got {names!r}"
        )
    hit = path_hits(waypoints, robot_radius, objs, tolerance)
    return [n for n, h in zip(names, hit.tolist(), strict=True) if h]
