"""Deterministic base motion planning for a holonomic mobile base in a 2-D floor plan.

The benchmark environments need, for every place action, a collision-free path of the
mobile base from its current pose to the new one, and the length of that path (the
kitchen reward is ``min(1/L, 2)`` or ``max(-L, -2)``, the conveyor reward
``exp(-0.1 L)``). The planner must be deterministic (same inputs, same path, also in
another process) and fast (a place action, including its path, in under 5 ms).

Model
-----
* The floor plan is a rectangle ``workspace = (xmin, xmax, ymin, ymax)`` holding
  obstacles whose footprints are oriented rectangles (:class:`Box2D`): *static* ones
  (walls, counters, furniture), given once, and *movable* ones (the objects), given per
  call.
* The robot, together with the object it carries, is a **disc** of radius
  ``robot_radius`` (the circumscribed radius of its footprint) plus
  :attr:`BasePlannerConfig.clearance`. A disc is rotation-invariant, so the
  configuration-space obstacles are the rectangles grown by the radius (rounded
  rectangles) and the heading can be turned anywhere along the path. The model is
  conservative: a door of width ``w`` lets the robot through iff
  ``w > 2 * (robot_radius + clearance)``. That is how "a door too narrow for the robot"
  (kitchen) and "a door too narrow for the two big boxes" (storage rooms: carrying a big
  box gives a larger radius) arise.
* Path length is the original's "sum of SE(2) distances" between consecutive waypoints,
  ``sum_i ||p_{i+1} - p_i|| + rotation_weight * |wrap(theta_{i+1} - theta_i)|``
  (:func:`path_length`). The original (``get_trajectory_length`` with
  ``se2_distance(a, b, 1, 1)``) weighted translation and rotation by 1 each and measured
  the rotation as the chord ``2 |sin(dtheta / 2)|`` between consecutive points of a dense
  RRT path; for a dense path the chord sum converges to the arc ``|dtheta|`` used here,
  which, unlike the chord, does not depend on how densely the path is sampled. The
  default ``rotation_weight`` is 1 as in the original.

Algorithm (exact geometry, approximate corners)
-----------------------------------------------
The shortest path for a disc among convex obstacles bends only at obstacle corners, so
we search a *reduced visibility graph*:

1. Each grown rectangle is enclosed by a polygon whose edges are tangent to it: the four
   straight sides, and ``corner_segments`` segments around each rounded corner. Its
   ``4 * corner_segments`` vertices, pushed out by a micrometre
   (:attr:`BasePlannerConfig.vertex_margin`), are the graph's nodes, once pruned of
   those in collision or outside the workspace.
2. Two nodes are joined iff the segment between them is *bitangent* (the line through
   each polygon vertex does not separate the vertex's two polygon neighbours; other
   edges can never be on a shortest path) and collision-free. Collision tests are exact:
   a segment collides with a rectangle iff it passes within the disc radius of it
   (slab test against the rectangle grown along each axis, plus point-to-segment
   distances to the four corners), vectorised over all (segment, rectangle) pairs after
   a bounding-circle prefilter.
3. A* (Euclidean heuristic, ties broken by node index) from the start over the nodes
   plus start and goal gives the shortest polyline; headings are interpolated linearly in
   travelled distance along it by the shortest turn from the start to the goal heading.

Two shortcuts answer exactly as the steps above: a query whose start or goal is in
collision, or whose straight segment is free, is decided by single-point and
single-segment tests on Python floats (the array kernels' expressions, evaluated in the
same order); and a query is answered "no path" without A* when no graph node the goal
connects to lies in a connected component of a node the start connects to (components
and, per start, the reachable nodes are cached with the graph: tree search asks many
goals from one start, most of them unreachable).

The static part (static vertices and their mutual visibility) is computed once per radius
that recurs and cached (a radius seen for the first time gets its whole graph in one pass
over all obstacles, the same graph); the graph including the movable obstacles is cached per
``(radius, movable)`` (tree search queries many goals from the same state); a query then
only connects its start and goal. Every returned path is collision-free under the exact
disc model. The polygonal corners make it a shortest path up to a factor of at most
``1 / cos(pi / (4 * corner_segments))`` around corners (1.08 for the default 2), and a
gap between two obstacle *corners* narrower than that factor can be missed; gaps between
flat sides, such as doors, are exact.

Why not OMPL or an RRT
----------------------
The original planned with a bidirectional RRT with shortcutting, retried with growing
caps. OMPL's Python bindings (``ompl`` 2.0.1 on PyPI, nanobind) offer the same
(``RRTConnect`` in ``SE2StateSpace``) and are deterministic when
``ompl.util.RNG.setSeed`` is called before each plan, but every state-validity check is
a Python callback: through the kitchen-sized floor plan's 1.0 m door a plan took 5-9 s
and 20,000-33,000 callbacks (``docs/motion-planning.md``), against about 2 ms here. A
sampling planner also cannot prove that no path exists (the answer for most infeasible
place actions: it runs to its time limit), and its path length, which is the reward,
varies with the seed. The visibility graph is exact for the disc model, complete,
answers "no path" as fast as "a path", gives the shortest path (so the reward's path
length is a property of the state, not of a random seed) and needs only numpy.

Size: one planner (a visibility graph over inflated boxes with its caches), plus exact
float fast paths of its geometric tests that keep a simulation cheap; splitting them
from the tests they shortcut would separate each shortcut from its reference.
"""

from __future__ import annotations

import heapq
import itertools
import math
import struct
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.intp]
BoolArray = NDArray[np.bool_]

__all__ = [
    "BasePath",
    "BasePlanner",
    "BasePlannerConfig",
    "Box2D",
    "Pose2D",
    "path_length",
    "se2_distance",
    "wrap_angle",
]


# ----------------------------------------------------------------------------------------
# Poses, boxes, path length
# ----------------------------------------------------------------------------------------
def wrap_angle(angle: ArrayLike) -> Any:
    """Wrap angles to ``[-pi, pi)`` (works on floats and arrays)."""
    return (np.asarray(angle, dtype=np.float64) + math.pi) % (2.0 * math.pi) - math.pi


def _finite(value: float, name: str) -> float:
    if not V.is_number(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return v


@dataclass(frozen=True)
class Pose2D:
    """A planar base pose: position ``(x, y)`` in metres and heading ``theta`` in radians."""

    x: float
    y: float
    theta: float

    def __post_init__(self) -> None:
        for name in ("x", "y", "theta"):
            object.__setattr__(self, name, _finite(getattr(self, name), f"Pose2D.{name}"))

    @classmethod
    def coerce(cls, pose: Pose2D | ArrayLike, name: str = "pose") -> Pose2D:
        """Accept a :class:`Pose2D` or a length-3 ``(x, y, theta)`` sequence/array."""
        if isinstance(pose, Pose2D):
            return pose
        if type(pose) is np.ndarray and pose.dtype == np.float64 and pose.shape == (3,):
            x, y, theta = pose.tolist()
            if math.isfinite(x) and math.isfinite(y) and math.isfinite(theta):
                out = object.__new__(cls)  # the fields are valid floats: skip __init__
                out.__dict__.update(x=x, y=y, theta=theta)
                return out
            return cls(x, y, theta)
        arr = np.asarray(pose, dtype=np.float64).reshape(-1)
        if arr.shape != (3,):
            raise ValueError(f"{name} must be a Pose2D or (x, y, theta); got shape {arr.shape}")
        return cls(float(arr[0]), float(arr[1]), float(arr[2]))

    def as_array(self) -> FloatArray:
        """``[x, y, theta]`` as a float64 array."""
        return np.array([self.x, self.y, self.theta], dtype=np.float64)


@dataclass(frozen=True)
class Box2D:
    """An oriented rectangle: the floor footprint of a wall, a piece of furniture or an object.

    Attributes:
        cx: Centre x in metres.
        cy: Centre y in metres.
        half_x: Half extent along the box's own x axis (> 0).
        half_y: Half extent along the box's own y axis (> 0).
        yaw: Rotation of the box's x axis from the world x axis, radians.
        name: Identifier reported by :func:`voot.envs.swept_volume.obstacles_on_path`
            and :meth:`BasePlanner.colliding`.
    """

    cx: float
    cy: float
    half_x: float
    half_y: float
    yaw: float = 0.0
    name: str = ""

    def __post_init__(self) -> None:
        for field_name in ("cx", "cy", "half_x", "half_y", "yaw"):
            value = _finite(getattr(self, field_name), f"Box2D.{field_name}")
            object.__setattr__(self, field_name, value)
        if self.half_x <= 0.0 or self.half_y <= 0.0:
            raise ValueError(
                f"Box2D {self.name!r}: half_x and half_y must be > 0, got "
                f"half_x={self.half_x}, half_y={self.half_y}"
            )
        if not isinstance(self.name, str):
            raise ValueError(f"Box2D.name must be a str, got {type(self.name).__name__}")
        # boxes key the planner's graph cache: hash once (the fields are frozen)
        object.__setattr__(
            self,
            "_hash",
            hash((self.cx, self.cy, self.half_x, self.half_y, self.yaw, self.name)),
        )

    def __hash__(self) -> int:
        return self._hash  # type: ignore[attr-defined,no-any-return]

    @classmethod
    def fast(
        cls, cx: float, cy: float, half_x: float, half_y: float, yaw: float, name: str
    ) -> Box2D:
        """The box of these fields, built without the dataclass machinery when they are valid.

        The same object as ``Box2D(...)`` (fields as Python floats, the same hash); any
        invalid field goes through the constructor, which raises as usual. The envs make
        a footprint per feasibility check, where the validation was a visible cost.
        """
        cx, cy, half_x, half_y, yaw = float(cx), float(cy), float(half_x), float(half_y), float(yaw)
        if not (
            type(name) is str
            and half_x > 0.0
            and half_y > 0.0
            and math.isfinite(cx + cy + half_x + half_y + yaw)
        ):
            return cls(cx, cy, half_x, half_y, yaw, name)
        box = object.__new__(cls)
        box.__dict__.update(
            cx=cx,
            cy=cy,
            half_x=half_x,
            half_y=half_y,
            yaw=yaw,
            name=name,
            _hash=hash((cx, cy, half_x, half_y, yaw, name)),
        )
        return box

    def __reduce__(self) -> tuple[type[Box2D], tuple[float, float, float, float, float, str]]:
        # rebuild through __init__ so that the cached hash is recomputed (string hashes
        # differ between processes)
        return (type(self), (self.cx, self.cy, self.half_x, self.half_y, self.yaw, self.name))

    @classmethod
    def from_bounds(
        cls, xmin: float, xmax: float, ymin: float, ymax: float, name: str = ""
    ) -> Box2D:
        """An axis-aligned box from its extent (convenient for walls)."""
        if not (xmin < xmax and ymin < ymax):
            raise ValueError(
                f"Box2D.from_bounds {name!r}: need xmin < xmax and ymin < ymax, got "
                f"({xmin}, {xmax}, {ymin}, {ymax})"
            )
        return cls(
            0.5 * (xmin + xmax), 0.5 * (ymin + ymax), 0.5 * (xmax - xmin), 0.5 * (ymax - ymin),
            0.0, name,
        )  # fmt: skip

    def corners(self) -> FloatArray:
        """The four corners, shape ``(4, 2)``, counter-clockwise from ``(+half_x, +half_y)``."""
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        local = np.array(
            [
                [self.half_x, self.half_y],
                [-self.half_x, self.half_y],
                [-self.half_x, -self.half_y],
                [self.half_x, -self.half_y],
            ]
        )
        rot = np.array([[c, -s], [s, c]])
        return local @ rot.T + np.array([self.cx, self.cy])


def se2_distance(a: Pose2D | ArrayLike, b: Pose2D | ArrayLike, rotation_weight: float) -> float:
    """``||p_b - p_a|| + rotation_weight * |wrap(theta_b - theta_a)|``."""
    pa, pb = Pose2D.coerce(a, "a"), Pose2D.coerce(b, "b")
    dtheta = abs(float(wrap_angle(pb.theta - pa.theta)))
    return math.hypot(pb.x - pa.x, pb.y - pa.y) + rotation_weight * dtheta


def path_length(waypoints: ArrayLike, rotation_weight: float) -> float:
    """Sum of :func:`se2_distance` over consecutive rows of a ``(k, 3)`` waypoint array."""
    w = np.asarray(waypoints, dtype=np.float64)
    if w.ndim != 2 or w.shape[1] != 3:
        raise ValueError(f"waypoints must have shape (k, 3), got {w.shape}")
    if w.shape[0] < 2:
        return 0.0
    if w.shape[0] == 2:
        # one segment (a straight path): the same operations on floats (numpy's hypot;
        # Python's float % is numpy's remainder), without the array round trips
        (x0, y0, t0), (x1, y1, t1) = w.tolist()
        step = float(np.hypot(x1 - x0, y1 - y0))
        turn = abs((t1 - t0 + math.pi) % (2.0 * math.pi) - math.pi)
        return float(step + rotation_weight * turn)
    diff = np.diff(w, axis=0)
    trans = np.hypot(diff[:, 0], diff[:, 1])
    rot = np.abs(wrap_angle(diff[:, 2]))
    return float(np.sum(trans) + rotation_weight * np.sum(rot))


@dataclass(frozen=True, eq=False)
class BasePath:
    """A base path: waypoints ``(k, 3)`` of ``(x, y, theta)`` and its SE(2) length.

    Consecutive waypoints are joined by straight segments along which the heading turns
    linearly. ``length`` is :func:`path_length` of the waypoints with the planner's
    ``rotation_weight``. The array is stored read-only.
    """

    waypoints: FloatArray
    length: float

    def __post_init__(self) -> None:
        w = np.array(self.waypoints, dtype=np.float64, copy=True)
        if w.ndim != 2 or w.shape[1] != 3 or w.shape[0] < 1:
            raise ValueError(f"BasePath.waypoints must have shape (k >= 1, 3), got {w.shape}")
        if not np.all(np.isfinite(w)):
            raise ValueError("BasePath.waypoints must be finite")
        w.setflags(write=False)
        object.__setattr__(self, "waypoints", w)
        object.__setattr__(self, "length", _finite(self.length, "BasePath.length"))

    @classmethod
    def from_waypoints(cls, waypoints: ArrayLike, rotation_weight: float = 1.0) -> BasePath:
        """Build a path and compute its length with :func:`path_length`."""
        w = np.asarray(waypoints, dtype=np.float64)
        return cls(w, path_length(w, rotation_weight))

    @classmethod
    def _from_owned(cls, waypoints: FloatArray, rotation_weight: float) -> BasePath:
        """:meth:`from_waypoints` of a new ``(k, 3)`` float64 array nobody else holds.

        The planner's and the envs' own paths: the array is made read-only in place
        instead of copied, and its shape and finiteness (the planner's inputs are
        validated) are checked only if it is not a finite ``(k, 3)`` array; the path is
        the same as :meth:`from_waypoints` builds.
        """
        w = waypoints
        length = path_length(w, rotation_weight)
        if not (
            type(w) is np.ndarray
            and w.dtype == np.float64
            and w.ndim == 2
            and w.shape[1] == 3
            and w.shape[0] >= 1
            and math.isfinite(length)
            and math.isfinite(float(w.sum()))
        ):
            return cls(w, length)
        w.setflags(write=False)
        path = object.__new__(cls)
        object.__setattr__(path, "waypoints", w)
        object.__setattr__(path, "length", float(length))
        return path

    @property
    def translation_length(self) -> float:
        """Length of the polyline in the plane (metres), ignoring rotation."""
        d = np.diff(self.waypoints[:, :2], axis=0)
        return float(np.sum(np.hypot(d[:, 0], d[:, 1])))

    def interpolate(self, max_step: float) -> FloatArray:
        """Poses along the path, at most ``max_step`` metres apart (for checks and display).

        Each segment is cut into ``ceil(segment_length / max_step)`` equal pieces; headings
        turn linearly (shortest way) along each segment. Returns shape ``(n, 3)`` including
        both ends.
        """
        step = _finite(max_step, "max_step")
        if step <= 0.0:
            raise ValueError(f"max_step must be > 0, got {max_step}")
        w = self.waypoints
        out = [w[:1]]
        for a, b in itertools.pairwise(w):
            n = max(1, math.ceil(math.hypot(b[0] - a[0], b[1] - a[1]) / step))
            t = np.arange(1, n + 1, dtype=np.float64)[:, None] / n
            seg = a + t * np.array([b[0] - a[0], b[1] - a[1], float(wrap_angle(b[2] - a[2]))])
            seg[:, 2] = wrap_angle(seg[:, 2])
            seg[-1] = b
            out.append(seg)
        return np.concatenate(out, axis=0)

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, BasePath)
            and self.length == other.length
            and np.array_equal(self.waypoints, other.waypoints)
        )

    def __hash__(self) -> int:
        return hash((self.waypoints.tobytes(), self.length))


# ----------------------------------------------------------------------------------------
# Configuration
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BasePlannerConfig:
    """Settings of :class:`BasePlanner` (all validated).

    Attributes:
        rotation_weight: Weight of ``|dtheta|`` (radians) against metres in the path
            length. 1.0 as in the original's ``se2_distance(a, b, 1, 1)``; >= 0.
        clearance: Safety distance (metres) added to every robot radius; >= 0. 0 keeps the
            door rule ``width > 2 * robot_radius`` exact.
        corner_segments: Tangent segments approximating each quarter-circle corner of a
            grown rectangle, in [1, 8]. More means shorter paths around corners (within a
            factor ``1 / cos(pi / (4 n))``: 1.17, 1.08, 1.035, 1.02 for n = 1..4) and more
            graph nodes (``4 n`` per obstacle).
        vertex_margin: How far (metres) graph nodes are pushed out beyond the grown
            obstacles, so that edges grazing an obstacle are robustly free; in (0, 1e-3].
            A door passes iff ``width > 2 * (radius + clearance + vertex_margin)``.
        contact_tolerance: Numerical slack (metres) of collision tests: a disc collides
            iff it is deeper than this inside an obstacle; in [0, vertex_margin).
        radius_step: 0 (default) plans with the exact radius. A positive step (metres,
            <= 0.05) rounds every inflated radius *up* to a multiple of it, so that
            nearly equal radii (a carried object's enclosing disc varies with the grasp)
            share cached graphs; conservative, it narrows doors by at most ``2 * step``.
        static_cache_size: Number of radii whose static visibility graph is kept; >= 1.
        graph_cache_size: Number of ``(radius, movable obstacles)`` graphs kept; >= 0
            (0 disables the cache: every query rebuilds the movable part).
    """

    rotation_weight: float = 1.0
    clearance: float = 0.0
    corner_segments: int = 2
    vertex_margin: float = 1e-6
    contact_tolerance: float = 1e-9
    radius_step: float = 0.0
    static_cache_size: int = 8
    graph_cache_size: int = 32

    def __post_init__(self) -> None:
        rw = _finite(self.rotation_weight, "BasePlannerConfig.rotation_weight")
        if rw < 0.0:
            raise ValueError(f"BasePlannerConfig.rotation_weight must be >= 0, got {rw}")
        cl = _finite(self.clearance, "BasePlannerConfig.clearance")
        if cl < 0.0:
            raise ValueError(f"BasePlannerConfig.clearance must be >= 0, got {cl}")
        if isinstance(self.corner_segments, bool) or not isinstance(self.corner_segments, int):
            raise ValueError(
                f"BasePlannerConfig.corner_segments must be an int in [1, 8], got "
                f"{self.corner_segments!r}"
            )
        if not 1 <= self.corner_segments <= 8:
            raise ValueError(
                f"BasePlannerConfig.corner_segments must be in [1, 8], got {self.corner_segments}"
            )
        vm = _finite(self.vertex_margin, "BasePlannerConfig.vertex_margin")
        if not 0.0 < vm <= 1e-3:
            raise ValueError(f"BasePlannerConfig.vertex_margin must be in (0, 1e-3], got {vm}")
        ct = _finite(self.contact_tolerance, "BasePlannerConfig.contact_tolerance")
        if not 0.0 <= ct < vm:
            raise ValueError(
                f"BasePlannerConfig.contact_tolerance must be in [0, vertex_margin={vm}), got {ct}"
            )
        rs = _finite(self.radius_step, "BasePlannerConfig.radius_step")
        if not 0.0 <= rs <= 0.05:
            raise ValueError(f"BasePlannerConfig.radius_step must be in [0, 0.05], got {rs}")
        object.__setattr__(self, "radius_step", rs)
        for name, low in (("static_cache_size", 1), ("graph_cache_size", 0)):
            value = getattr(self, name)
            V.integer(value, f"BasePlannerConfig.{name}", low)
        object.__setattr__(self, "rotation_weight", rw)
        object.__setattr__(self, "clearance", cl)
        object.__setattr__(self, "vertex_margin", vm)
        object.__setattr__(self, "contact_tolerance", ct)


# ----------------------------------------------------------------------------------------
# Vectorised geometry kernels (also used by voot.envs.swept_volume)
# ----------------------------------------------------------------------------------------
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
        ``(+, +)`` as :meth:`BasePlanner._polygon_nodes` orders them) and the half extents
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


def _box_lists(scene: _Scene) -> tuple[list[float], ...]:
    """The scene's boxes as lists of Python floats (built once per scene)."""
    if scene.lists is None:
        scene.lists = scene.boxes.lists()
    return scene.lists


def _component_lists(graph: _Graph) -> list[tuple[list[Any], ...]]:
    """The graph's connected components, each as the node lists :func:`_sees_any` takes.

    Union-find over the edges (a property of the graph: no arithmetic involved), then per
    component its nodes' positions, neighbour directions and blocking-box hints.
    """
    n = len(graph.nodes)
    parent = list(range(n))

    def root(v: int) -> int:
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for a, b in zip(graph.i.tolist(), graph.j.tolist(), strict=True):
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    groups: dict[int, list[int]] = {}
    for v in range(n):
        groups.setdefault(root(v), []).append(v)
    nodes = graph.nodes
    cols = (
        nodes.pos[:, 0].tolist(),
        nodes.pos[:, 1].tolist(),
        nodes.to_prev[:, 0].tolist(),
        nodes.to_prev[:, 1].tolist(),
        nodes.to_next[:, 0].tolist(),
        nodes.to_next[:, 1].tolist(),
    )
    shared = [0]  # the box that blocked the last segment from the start, for every node
    return [
        (*([col[v] for v in members] for col in cols), [shared] * len(members))
        for members in groups.values()
    ]


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


def _sees_any(
    nodes: tuple[list[Any], ...],
    x: float,
    y: float,
    boxes: tuple[list[float], ...],
    radius: float,
) -> bool:
    """Does the point ``(x, y)`` connect to any of ``nodes``, as :meth:`BasePlanner._search`
    connects an end (tangent at the node, segment clear of every box)?

    ``nodes`` holds the nodes' positions and neighbour directions as lists, and a hint
    per node for :func:`_segment_hits_any` (the box that blocked it last). The tangency
    test is :func:`_tangent_grid`'s expression and the segment test
    :func:`_segment_hits_any`, both on Python floats with the same operations, so each
    pair's answer is the array version's; it stops at the first connected node.
    """
    xs, ys, pxs, pys, nxs, nys, hints = nodes
    for k in range(len(xs)):
        nx_, ny_ = xs[k], ys[k]
        ux = nx_ - x
        uy = ny_ - y
        cross_prev = ux * pys[k] - uy * pxs[k]
        cross_next = ux * nys[k] - uy * nxs[k]
        if not cross_prev * cross_next >= -_TANGENT_EPS * (ux * ux + uy * uy):
            continue
        if not _segment_hits_any(x, y, nx_, ny_, boxes, radius, hints[k]):
            return True
    return False


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


# ----------------------------------------------------------------------------------------
# The planner
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class _Nodes:
    """Graph nodes: positions and unit directions to their two polygon neighbours."""

    pos: FloatArray  # (n, 2)
    to_prev: FloatArray  # (n, 2) unit vector towards the previous polygon vertex
    to_next: FloatArray  # (n, 2) unit vector towards the next polygon vertex

    def __len__(self) -> int:
        return int(self.pos.shape[0])

    def take(self, index: IntArray) -> _Nodes:
        return _Nodes(self.pos[index], self.to_prev[index], self.to_next[index])

    def part(self, start: int, stop: int) -> _Nodes:
        """Nodes ``start`` to ``stop - 1`` (views)."""
        return _Nodes(self.pos[start:stop], self.to_prev[start:stop], self.to_next[start:stop])

    def concat(self, other: _Nodes) -> _Nodes:
        return _Nodes(
            np.concatenate([self.pos, other.pos]),
            np.concatenate([self.to_prev, other.to_prev]),
            np.concatenate([self.to_next, other.to_next]),
        )


@dataclass(eq=False)
class _Graph:
    """Nodes and undirected weighted edges ``(i, j, w)``; adjacency lists built on demand."""

    nodes: _Nodes
    i: IntArray
    j: IntArray
    w: FloatArray
    _adjacency: list[list[tuple[int, float]]] | None = None

    def adjacency(self) -> list[list[tuple[int, float]]]:
        if self._adjacency is None:
            adj: list[list[tuple[int, float]]] = [[] for _ in range(len(self.nodes))]
            for a, b, w in zip(self.i.tolist(), self.j.tolist(), self.w.tolist(), strict=True):
                adj[a].append((b, w))
                adj[b].append((a, w))
            self._adjacency = adj
        return self._adjacency


class DiscProbe:
    """The planner's start and goal tests of a disc, for one set of obstacles.

    :meth:`blocked` is exactly the test that makes :meth:`BasePlanner.plan` return None
    for an end point (and :meth:`BasePlanner.colliding` non-empty): the disc leaves the
    workspace or overlaps an obstacle. :meth:`verdict` answers the same question for a
    centre and radius that the caller knows only to within ``margin`` (computed on
    Python floats where the exact numbers come from numpy, whose rounding may differ in
    the last bits): True or False when the answer is the same for every disc within
    ``margin``, None when it is too close to tell (ask the exact test then).
    """

    __slots__ = ("_blocked_hint", "_lists", "_planner", "_verdict_hint")

    def __init__(self, planner: BasePlanner, lists: tuple[list[float], ...]) -> None:
        self._planner = planner
        self._lists = lists
        # the box that decided the last answer, tried first (the answers do not depend on
        # the order of the boxes)
        self._blocked_hint = [0]
        self._verdict_hint = [0]

    def blocked(self, x: float, y: float, robot_radius: float) -> bool:
        """Does the disc at ``(x, y)`` leave the workspace or touch an obstacle? (exact)"""
        planner = self._planner
        r_hit = planner._inflated_radius(robot_radius) - planner.config.contact_tolerance
        return not planner._inside_xy(x, y, r_hit) or _point_hits_any(
            x, y, self._lists, r_hit, self._blocked_hint
        )

    def verdict(self, x: float, y: float, robot_radius: float, margin: float) -> bool | None:
        """:meth:`blocked` for a disc known to within ``margin`` metres; None if unsure."""
        planner = self._planner
        cfg = planner.config
        if cfg.radius_step > 0.0:
            return None  # rounding the radius up to a step is not continuous
        r_hit = robot_radius + cfg.clearance - cfg.contact_tolerance
        xmin, xmax, ymin, ymax = planner.workspace
        lo, hi = r_hit - margin, r_hit + margin
        if not (xmin + lo <= x <= xmax - lo and ymin + lo <= y <= ymax - lo):
            return True
        unsure = not (xmin + hi <= x <= xmax - hi and ymin + hi <= y <= ymax - hi)
        bcx, bcy, bcos, bsin, bhx, bhy, breach = self._lists
        lo2, hi2 = lo * lo, hi * hi
        hint = self._verdict_hint
        n = len(bcx)
        first = hint[0] if hint[0] < n else 0
        for k in itertools.chain(range(first, n), range(first)):
            rx = x - bcx[k]
            ry = y - bcy[k]
            far = breach[k] + hi + 1e-6
            if rx * rx + ry * ry > far * far:
                continue
            c, s = bcos[k], bsin[k]
            lx = rx * c + ry * s
            ly = -rx * s + ry * c
            dx = max(abs(lx) - bhx[k], 0.0)
            dy = max(abs(ly) - bhy[k], 0.0)
            d2 = dx * dx + dy * dy
            if d2 < lo2:
                hint[0] = k
                return True
            if d2 <= hi2:
                unsure = True
        return None if unsure else False


@dataclass(eq=False)
class _Scene:
    """What one ``(radius, movable)`` pair needs: the obstacle arrays and, once built, the graph."""

    radius: float
    movable: BoxArrays
    boxes: BoxArrays  # static then movable
    graph: _Graph | None = None
    # for the no-path shortcut (BasePlanner._no_path): the graph's connected components,
    # and per start point the nodes in the components the start sees
    components: list[tuple[list[Any], ...]] | None = None
    reach: OrderedDict[tuple[float, float], tuple[list[Any], ...]] = field(
        default_factory=OrderedDict
    )
    # the boxes as Python lists, for the single-segment test
    lists: tuple[list[float], ...] | None = None


#: How many radii :meth:`BasePlanner._build_graph` remembers having seen (a radius seen
#: again gets its static graph built and cached).
_RADII_REMEMBERED = 256

#: Lines through a vertex whose sines to both neighbours multiply to more than
#: ``-_TANGENT_EPS`` count as tangent (collinear neighbours, up to rounding, are allowed).
_TANGENT_EPS = 1e-12


def _tangent_grid(nodes: _Nodes, ux: FloatArray, uy: FloatArray, axis: int) -> BoolArray:
    """Tangency at the nodes of a grid of lines with directions ``(ux, uy)``.

    ``axis`` says which grid axis indexes ``nodes``. A line through a convex polygon
    vertex is tangent there iff it does not strictly separate the vertex's two polygon
    neighbours (the product of the two cross products is not negative); only tangent
    lines can carry a shortest path bending at the vertex. The test is invariant under
    ``u -> -u``, so one grid of directions serves both ends of every segment.
    """
    shape = (-1, 1) if axis == 0 else (1, -1)
    px = nodes.to_prev[:, 0].reshape(shape)
    py = nodes.to_prev[:, 1].reshape(shape)
    nx = nodes.to_next[:, 0].reshape(shape)
    ny = nodes.to_next[:, 1].reshape(shape)
    cross_prev = ux * py - uy * px
    cross_next = ux * ny - uy * nx
    result: BoolArray = cross_prev * cross_next >= -_TANGENT_EPS * (ux * ux + uy * uy)
    return result


def _astar(
    adjacency: list[list[tuple[int, float]]],
    start_edges: list[tuple[int, float]],
    goal_edges: dict[int, float],
    heuristic: list[float],
) -> list[int] | None:
    """A* from a virtual start to a virtual goal over ``adjacency`` (Euclidean heuristic).

    Node ``-1`` is the start, ``-2`` the goal. Ties are broken by ``(f, g, node)``, so the
    result is deterministic. Returns the node sequence (without start and goal) or None.
    """
    start, goal = -1, -2
    best: dict[int, float] = {start: 0.0}
    parent: dict[int, int] = {}
    heap: list[tuple[float, float, int]] = [(0.0, 0.0, start)]
    closed: set[int] = set()
    while heap:
        _, g, v = heapq.heappop(heap)
        if v == goal:
            path = []
            v = parent[goal]
            while v != start:
                path.append(v)
                v = parent[v]
            path.reverse()
            return path
        if v in closed:
            continue
        closed.add(v)
        for u, w in start_edges if v == start else adjacency[v]:
            ng = g + w
            if ng < best.get(u, math.inf):
                best[u] = ng
                parent[u] = v
                heapq.heappush(heap, (ng + heuristic[u], ng, u))
        if v in goal_edges:
            ng = g + goal_edges[v]
            if ng < best.get(goal, math.inf):
                best[goal] = ng
                parent[goal] = v
                heapq.heappush(heap, (ng, ng, goal))
    return None


class BasePlanner:
    """Shortest collision-free paths of a disc-shaped holonomic base (see the module doc).

    Args:
        workspace: ``(xmin, xmax, ymin, ymax)``: the disc must stay inside it.
        static_obstacles: Footprints that never move (walls, furniture).
        config: Settings; defaults to :class:`BasePlannerConfig`.

    Deterministic: no randomness; caches only store results that are recomputed
    identically, so the same inputs give the same path whatever was planned before.
    """

    def __init__(
        self,
        workspace: tuple[float, float, float, float],
        static_obstacles: Sequence[Box2D],
        config: BasePlannerConfig | None = None,
    ) -> None:
        if config is None:
            config = BasePlannerConfig()
        if not isinstance(config, BasePlannerConfig):
            raise ValueError(f"config must be a BasePlannerConfig, got {type(config).__name__}")
        ws = tuple(float(v) for v in workspace)
        if len(ws) != 4 or not all(math.isfinite(v) for v in ws):
            raise ValueError(
                f"workspace must be 4 finite numbers (xmin, xmax, ymin, ymax), got {workspace!r}"
            )
        if not (ws[0] < ws[1] and ws[2] < ws[3]):
            raise ValueError(f"workspace needs xmin < xmax and ymin < ymax, got {ws}")
        self.workspace: tuple[float, float, float, float] = (ws[0], ws[1], ws[2], ws[3])
        self.config = config
        self.static_obstacles: tuple[Box2D, ...] = tuple(static_obstacles)
        self._static = BoxArrays.from_boxes(self.static_obstacles)
        self._template = self._make_template(config.corner_segments)
        self._static_cache: OrderedDict[float, _Graph] = OrderedDict()
        self._radii_seen: OrderedDict[float, None] = OrderedDict()
        self._static_lists: tuple[list[float], ...] | None = None
        self._last_plan: tuple[bytes, tuple[Box2D, ...], BasePath | None] | None = None
        self._lists_cache: dict[tuple[Box2D, ...], tuple[tuple[list[float], ...], list[str]]] = {}
        self._arrays_cache: dict[tuple[Box2D, ...], tuple[BoxArrays, BoxArrays]] = {}
        self._graph_cache: OrderedDict[tuple[float, tuple[Box2D, ...]], _Scene] = OrderedDict()

    # ----- public API -------------------------------------------------------------------
    def plan(
        self,
        start: Pose2D | ArrayLike,
        goal: Pose2D | ArrayLike,
        robot_radius: float,
        movable: Sequence[Box2D] = (),
    ) -> BasePath | None:
        """Shortest collision-free path from ``start`` to ``goal``, or None.

        Args:
            start: Start base pose (a :class:`Pose2D` or ``(x, y, theta)``).
            goal: Goal base pose.
            robot_radius: Radius of the disc enclosing the robot and what it carries (> 0).
            movable: Footprints of the movable objects (leave out the carried one).

        Returns:
            The path (first waypoint ``start``, last ``goal``, exactly), or None if start or
            goal is in collision or outside the workspace, or no path exists. A query
            repeating the last one (the same numbers, bit for bit, and the same box
            objects) returns the last answer itself: an env's pre-screen plans the path
            its step then plans again.
        """
        s = Pose2D.coerce(start, "start")
        g = Pose2D.coerce(goal, "goal")
        mov = self._movable(movable)
        key = struct.pack("<7d", s.x, s.y, s.theta, g.x, g.y, g.theta, float(robot_radius))
        last = self._last_plan
        if (
            last is not None
            and last[0] == key
            and len(last[1]) == len(mov)
            and all(a is b for a, b in zip(last[1], mov, strict=True))
        ):
            return last[2]
        path = self._plan(s, g, robot_radius, mov)
        self._last_plan = (key, mov, path)
        return path

    def _plan(
        self, s: Pose2D, g: Pose2D, robot_radius: float, mov: tuple[Box2D, ...]
    ) -> BasePath | None:
        """:meth:`plan` without its memory of the last query."""
        scene = self._scene(self._inflated_radius(robot_radius), mov)
        r_hit = scene.radius - self.config.contact_tolerance
        if not (self._inside_xy(s.x, s.y, r_hit) and self._inside_xy(g.x, g.y, r_hit)):
            return None
        lists = _box_lists(scene)
        if _point_hits_any(s.x, s.y, lists, r_hit) or _point_hits_any(g.x, g.y, lists, r_hit):
            return None
        ends = np.array([[s.x, s.y], [g.x, g.y]])
        if not _segment_hits_any(s.x, s.y, g.x, g.y, lists, r_hit):
            return self._make_path(s, g, ends)
        if scene.graph is None:
            scene.graph = self._build_graph(scene)
        if self._no_path(scene, s.x, s.y, g.x, g.y, r_hit):
            return None
        polyline = self._search(scene.graph, ends, scene.boxes, r_hit)
        if polyline is None:
            return None
        return self._make_path(s, g, polyline)

    def is_free(
        self, pose: Pose2D | ArrayLike, robot_radius: float, movable: Sequence[Box2D] = ()
    ) -> bool:
        """Is the disc at ``pose`` inside the workspace and clear of every obstacle?"""
        p = Pose2D.coerce(pose, "pose")
        scene = self._scene(self._inflated_radius(robot_radius), self._movable(movable))
        r_hit = scene.radius - self.config.contact_tolerance
        if not self._inside_xy(p.x, p.y, r_hit):
            return False
        return not bool(points_hit_boxes(np.array([[p.x, p.y]]), scene.boxes, r_hit).any())

    def colliding(
        self, pose: Pose2D | ArrayLike, robot_radius: float, movable: Sequence[Box2D] = ()
    ) -> list[str]:
        """Names of the obstacles (static first, then movable) the disc at ``pose`` overlaps.

        ``"workspace"`` is listed first if the disc leaves the workspace. Useful for an
        environment's "collision with what" diagnostics.
        """
        p = Pose2D.coerce(pose, "pose")
        radius = self._inflated_radius(robot_radius)
        mov = self._movable(movable)
        r_hit = radius - self.config.contact_tolerance
        # the point test of points_hit_boxes box by box on floats; a one-off radius (a
        # carried object's disc) needs no scene in the graph cache
        scene = self._graph_cache.get((radius, mov))
        lists, names = self._lists_and_names(mov)
        if scene is not None:
            lists = _box_lists(scene)
        out = [names[k] for k in _point_hit_indices(p.x, p.y, lists, r_hit)]
        if not self._inside_xy(p.x, p.y, r_hit):
            out.insert(0, "workspace")
        return out

    def _lists_and_names(
        self, movable: tuple[Box2D, ...]
    ) -> tuple[tuple[list[float], ...], list[str]]:
        """:meth:`_box_lists_of` ``movable`` and the boxes' names, static first.

        Remembered for the last few obstacle sets (a pure function of the boxes): an
        env asks :meth:`colliding` with one set of objects and a new radius (a carried
        object's disc) at every pick it checks.
        """
        hit = self._lists_cache.get(movable)
        if hit is None:
            names = [*(b.name for b in self.static_obstacles), *(b.name for b in movable)]
            hit = (self._box_lists_of(movable), names)
            if len(self._lists_cache) >= 16:
                self._lists_cache.clear()
            self._lists_cache[movable] = hit
        return hit

    def _box_lists_of(self, movable: tuple[Box2D, ...]) -> tuple[list[float], ...]:
        """:func:`_box_lists` of the static boxes followed by ``movable``, without a scene.

        Cosines and sines come from numpy over the movable yaws, as
        :meth:`BoxArrays.from_boxes` computes them; the rest are the boxes' own fields.
        """
        if self._static_lists is None:
            st = self._static
            self._static_lists = (
                st.center[:, 0].tolist(), st.center[:, 1].tolist(), st.cos.tolist(),
                st.sin.tolist(), st.half[:, 0].tolist(), st.half[:, 1].tolist(),
                st.reach.tolist(),
            )  # fmt: skip
        if not movable:
            return self._static_lists
        yaw = np.array([b.yaw for b in movable], dtype=np.float64)
        half = np.array([[b.half_x, b.half_y] for b in movable], dtype=np.float64)
        extra = (
            [b.cx for b in movable], [b.cy for b in movable], np.cos(yaw).tolist(),
            np.sin(yaw).tolist(), [b.half_x for b in movable], [b.half_y for b in movable],
            np.hypot(half[:, 0], half[:, 1]).tolist(),
        )  # fmt: skip
        return tuple(a + b for a, b in zip(self._static_lists, extra, strict=True))

    def path_is_free(
        self, waypoints: ArrayLike, robot_radius: float, movable: Sequence[Box2D] = ()
    ) -> bool:
        """Is the disc swept along the polyline ``waypoints`` (``(k, 2)`` or ``(k, 3)``) free?"""
        w = np.asarray(waypoints, dtype=np.float64)
        if w.ndim != 2 or w.shape[1] not in (2, 3) or w.shape[0] < 1:
            raise ValueError(f"waypoints must have shape (k, 2) or (k, 3), got {w.shape}")
        xy = w[:, :2]
        scene = self._scene(self._inflated_radius(robot_radius), self._movable(movable))
        r_hit = scene.radius - self.config.contact_tolerance
        if not np.all(self._inside(xy, r_hit)):
            return False
        if points_hit_boxes(xy, scene.boxes, r_hit).any():
            return False
        return not bool(segments_hit_any(xy[:-1], xy[1:], scene.boxes, r_hit).any())

    def disc_probe(self, movable: Sequence[Box2D] = ()) -> DiscProbe:
        """Point tests of a disc among the static obstacles and ``movable`` (see :class:`DiscProbe`).

        For callers that test many disc positions against one set of obstacles (an env's
        pre-screen at one state): the obstacle lists are looked up once.
        """
        mov = self._movable(movable)
        lists, _ = self._lists_and_names(mov)
        return DiscProbe(self, lists)

    def clear_caches(self) -> None:
        """Drop the cached graphs (results do not change; only the next query's time)."""
        self._static_cache.clear()
        self._radii_seen.clear()
        self._graph_cache.clear()
        self._lists_cache.clear()
        self._arrays_cache.clear()
        self._last_plan = None

    # ----- internals --------------------------------------------------------------------
    def _inflated_radius(self, robot_radius: float) -> float:
        r = _finite(robot_radius, "robot_radius")
        if r <= 0.0:
            raise ValueError(f"robot_radius must be > 0, got {robot_radius}")
        r += self.config.clearance
        step = self.config.radius_step
        if step > 0.0:
            # round up; the 1e-9 keeps exact multiples (0.48 / 0.01 = 47.999...) in place
            r = math.ceil(r / step - 1e-9) * step
        return r

    @staticmethod
    def _movable(movable: Sequence[Box2D]) -> tuple[Box2D, ...]:
        mov = tuple(movable)
        for i, b in enumerate(mov):
            if not isinstance(b, Box2D):
                raise ValueError(f"movable[{i}] must be a Box2D, got {type(b).__name__}")
        return mov

    def _inside_xy(self, x: float, y: float, radius: float) -> bool:
        xmin, xmax, ymin, ymax = self.workspace
        return xmin + radius <= x <= xmax - radius and ymin + radius <= y <= ymax - radius

    def _inside(self, pts: FloatArray, radius: float) -> BoolArray:
        xmin, xmax, ymin, ymax = self.workspace
        result: BoolArray = (
            (pts[:, 0] >= xmin + radius)
            & (pts[:, 0] <= xmax - radius)
            & (pts[:, 1] >= ymin + radius)
            & (pts[:, 1] <= ymax - radius)
        )
        return result

    def _polygon_nodes(self, boxes: BoxArrays, radius: float) -> _Nodes:
        """Vertices of the tangent polygons enclosing the boxes grown by ``radius``.

        Corner ``k`` (signs ``(+,+), (-,+), (-,-), (+,-)``, counter-clockwise) carries ``m``
        vertices at angles ``phi`` mid-way between consecutive tangent lines, at distance
        ``(radius + vertex_margin) / cos(pi / (4 m))`` from the corner. The polygon edge
        after a vertex is the tangent line at ``phi + pi / (4 m)`` (direction
        ``phi + pi / (4 m) + pi / 2``), the edge before it the one at ``phi - pi / (4 m)``.
        """
        if len(boxes) == 0:
            z = np.zeros((0, 2))
            return _Nodes(z, z, z)
        m = self.config.corner_segments
        corner, unit, to_prev, to_next = self._template
        dist = (radius + self.config.vertex_margin) / math.cos(math.pi / (4 * m))
        lx = corner[:, 0] * boxes.half[:, 0:1] + dist * unit[:, 0]  # (nb, 4m)
        ly = corner[:, 1] * boxes.half[:, 1:2] + dist * unit[:, 1]
        c = boxes.cos[:, None]
        s = boxes.sin[:, None]
        pos = np.empty((len(boxes), 4 * m, 2))
        pos[..., 0] = boxes.center[:, 0:1] + c * lx - s * ly
        pos[..., 1] = boxes.center[:, 1:2] + s * lx + c * ly
        prev = np.empty_like(pos)
        prev[..., 0] = c * to_prev[:, 0] - s * to_prev[:, 1]
        prev[..., 1] = s * to_prev[:, 0] + c * to_prev[:, 1]
        nxt = np.empty_like(pos)
        nxt[..., 0] = c * to_next[:, 0] - s * to_next[:, 1]
        nxt[..., 1] = s * to_next[:, 0] + c * to_next[:, 1]
        return _Nodes(pos.reshape(-1, 2), prev.reshape(-1, 2), nxt.reshape(-1, 2))

    @staticmethod
    def _make_template(m: int) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Per-vertex corner signs, unit offsets and unit neighbour directions (local frame)."""
        k = np.repeat(np.arange(4), m)
        jj = np.tile(np.arange(m), 4)
        phi = k * (math.pi / 2) + (jj + 0.5) * (math.pi / (2 * m))
        half_step = math.pi / (4 * m)
        unit = np.column_stack([np.cos(phi), np.sin(phi)])
        after = phi + half_step + math.pi / 2
        before = phi - half_step + math.pi / 2
        to_next = np.column_stack([np.cos(after), np.sin(after)])
        to_prev = -np.column_stack([np.cos(before), np.sin(before)])
        return _CORNER_SIGNS[k], unit, to_prev, to_next

    def _free_mask(
        self, owners: BoxArrays, nodes: _Nodes, boxes: BoxArrays, radius: float, r_hit: float
    ) -> BoolArray:
        """Which of the polygon nodes ``nodes`` of the boxes ``owners`` (at ``radius``, as
        :meth:`_polygon_nodes` makes them) lie inside the workspace and clear of ``boxes``
        (for the one-pass build: every obstacle's nodes against every obstacle).

        :func:`points_hit_boxes`'s test, on the node-box pairs that can meet only: the
        ``m`` nodes of a corner lie within ``dist`` of it (their distance from the
        corner), so a corner farther than ``dist + r_hit`` (plus a micrometre for
        rounding) from a box's axis-aligned bounding box along x or y cannot meet the
        box. Each remaining pair's numbers are :func:`points_hit_boxes`'s, so the mask is.
        """
        inside = self._inside(nodes.pos, r_hit)
        if len(boxes) == 0 or len(nodes) == 0:
            return inside
        m = self.config.corner_segments
        dist = (radius + self.config.vertex_margin) / math.cos(math.pi / (4 * m))
        kx, ky, _, _ = owners.corners_and_extents
        _, _, ax, ay = boxes.corners_and_extents
        reach = dist + r_hit + 1e-6
        gap_x = np.abs(kx[:, None] - boxes.center[:, 0]) - ax
        gap_y = np.abs(ky[:, None] - boxes.center[:, 1]) - ay
        corner, box = np.nonzero((gap_x < reach) & (gap_y < reach))
        node = ((corner * m)[:, None] + np.arange(m)).ravel()
        box = np.repeat(box, m)
        pos = nodes.pos[node]
        rx = pos[:, 0] - boxes.center[box, 0]
        ry = pos[:, 1] - boxes.center[box, 1]
        c, s = boxes.cos[box], boxes.sin[box]
        lx = rx * c + ry * s
        ly = -rx * s + ry * c
        dx = np.maximum(np.abs(lx) - boxes.half[box, 0], 0.0)
        dy = np.maximum(np.abs(ly) - boxes.half[box, 1], 0.0)
        inside[node[dx * dx + dy * dy < r_hit * r_hit]] = False
        return inside

    def _free_polygon_nodes(self, owners: BoxArrays, boxes: BoxArrays, radius: float) -> _Nodes:
        """The polygon nodes of ``owners`` at ``radius`` clear of ``boxes``.

        Every node-box pair tested (:func:`points_hit_boxes`): the layered build's node
        sets are small enough that the prefilter of :meth:`_free_mask` costs more than it
        saves (measured on the conveyor, whose radii recur).
        """
        nodes = self._polygon_nodes(owners, radius)
        r_hit = radius - self.config.contact_tolerance
        free = self._inside(nodes.pos, r_hit) & ~points_hit_boxes(nodes.pos, boxes, r_hit).any(
            axis=1
        )
        return nodes.take(np.flatnonzero(free))

    @staticmethod
    def _candidates(a: _Nodes, b: _Nodes, same: bool) -> tuple[IntArray, IntArray]:
        """Bitangent pairs between node sets ``a`` and ``b`` (``i < j`` if ``same``)."""
        ux = b.pos[None, :, 0] - a.pos[:, 0:1]
        uy = b.pos[None, :, 1] - a.pos[:, 1:2]
        ia, ib = np.nonzero(_tangent_grid(a, ux, uy, 0) & _tangent_grid(b, ux, uy, 1))
        if same:
            upper = ia < ib
            ia, ib = ia[upper], ib[upper]
        return ia, ib

    @staticmethod
    def _keep_free(
        pos: FloatArray, ia: IntArray, ib: IntArray, boxes: BoxArrays, r_hit: float
    ) -> tuple[IntArray, IntArray, FloatArray]:
        """The collision-free edges among ``(ia, ib)`` (indices into ``pos``) and their lengths."""
        pa, pb = pos[ia], pos[ib]
        ok = ~segments_hit_any(pa, pb, boxes, r_hit)
        d = pb[ok] - pa[ok]
        return ia[ok], ib[ok], np.hypot(d[:, 0], d[:, 1])

    def _static_graph(self, radius: float) -> _Graph:
        """Free vertices of the grown static obstacles and their static visibility edges."""
        cached = self._static_cache.get(radius)
        if cached is not None:
            self._static_cache.move_to_end(radius)
            return cached
        r_hit = radius - self.config.contact_tolerance
        nodes = self._free_polygon_nodes(self._static, self._static, radius)
        ia, ib = self._candidates(nodes, nodes, same=True)
        graph = _Graph(nodes, *self._keep_free(nodes.pos, ia, ib, self._static, r_hit))
        self._static_cache[radius] = graph
        if len(self._static_cache) > self.config.static_cache_size:
            self._static_cache.popitem(last=False)
        return graph

    def _scene(self, radius: float, movable: tuple[Box2D, ...]) -> _Scene:
        """The (cached) obstacle arrays and graph slot for ``(radius, movable)``."""
        key = (radius, movable)
        scene = self._graph_cache.get(key)
        if scene is not None:
            self._graph_cache.move_to_end(key)
            return scene
        arrays = self._arrays_cache.get(movable)
        if arrays is None:  # one obstacle set meets many radii (one per grasp)
            movable_arrays = BoxArrays.from_boxes(movable)
            arrays = (movable_arrays, self._static.concat(movable_arrays))
            if len(self._arrays_cache) >= 16:
                self._arrays_cache.clear()
            self._arrays_cache[movable] = arrays
        scene = _Scene(radius, *arrays)
        if self.config.graph_cache_size > 0:
            self._graph_cache[key] = scene
            if len(self._graph_cache) > self.config.graph_cache_size:
                self._graph_cache.popitem(last=False)
        return scene

    def _build_graph(self, scene: _Scene) -> _Graph:
        """The visibility graph among the static and movable obstacles of ``scene``.

        Two ways to the same graph (the same nodes, edges, orientations and order, bit
        for bit: every test is elementwise): on top of the static graph of the radius,
        cached for the radii that recur, or, the first time a radius is seen (a carried
        object's disc changes with every grasp, so most radii never recur), in one pass
        over all obstacles, which skips the static graph's own edge tests.
        """
        radius = scene.radius
        if radius not in self._static_cache:
            seen = self._radii_seen
            if radius not in seen:
                seen[radius] = None
                if len(seen) > _RADII_REMEMBERED:
                    seen.popitem(last=False)
                return self._one_pass_graph(scene)
        static = self._static_graph(radius)
        if len(scene.movable) == 0:
            return static
        r_hit = radius - self.config.contact_tolerance
        # static vertices not covered by a movable obstacle, re-indexed
        covered = points_hit_boxes(static.nodes.pos, scene.movable, r_hit).any(axis=1)
        alive = np.asarray(~covered, dtype=bool)
        new_index = np.cumsum(alive) - 1
        keep = alive[static.i] & alive[static.j]
        base = static.nodes.take(np.flatnonzero(alive))
        mnodes = self._free_polygon_nodes(scene.movable, scene.boxes, radius)
        nodes = base.concat(mnodes)
        nb = len(base)
        # candidate edges: surviving static ones (only the movable obstacles can block
        # them), movable-to-static and movable-to-movable bitangents (all obstacles)
        mi, bj = self._candidates(mnodes, base, same=False)
        mi2, mj2 = self._candidates(mnodes, mnodes, same=True)
        ia = np.concatenate([new_index[static.i[keep]], mi + nb, mi2 + nb])
        ib = np.concatenate([new_index[static.j[keep]], bj, mj2 + nb])
        return _Graph(nodes, *self._keep_free(nodes.pos, ia, ib, scene.boxes, r_hit))

    def _one_pass_graph(self, scene: _Scene) -> _Graph:
        """:meth:`_build_graph` without the static graph: the same nodes and edges, in the
        same order (static edges, movable-to-static, movable-to-movable)."""
        r_hit = scene.radius - self.config.contact_tolerance
        boxes = scene.boxes
        polygon = self._polygon_nodes(boxes, scene.radius)
        free = self._free_mask(boxes, polygon, boxes, scene.radius, r_hit)
        nodes = polygon.take(np.flatnonzero(free))
        # the polygon nodes come box by box, the static boxes first
        nb = int(np.count_nonzero(free[: len(self._static) * 4 * self.config.corner_segments]))
        # all bitangent pairs i < j at once, then in the layered build's order and
        # orientation: the tangency of a pair does not depend on its orientation (the
        # direction's sign cancels exactly), its segment test may
        i, j = self._candidates(nodes, nodes, same=True)
        movable_i, movable_j = i >= nb, j >= nb
        static_pair = ~movable_j
        mixed = movable_j & ~movable_i
        both = movable_i
        mixed_i, mixed_j = i[mixed], j[mixed]
        order = np.lexsort((mixed_i, mixed_j))  # by movable node, then static node
        ia = np.concatenate([i[static_pair], mixed_j[order], i[both]])
        ib = np.concatenate([j[static_pair], mixed_i[order], j[both]])
        return _Graph(nodes, *self._keep_free(nodes.pos, ia, ib, boxes, r_hit))

    @staticmethod
    def _visible(nodes: _Nodes, point: FloatArray, boxes: BoxArrays, r_hit: float) -> IntArray:
        """Indices of ``nodes`` that ``point`` connects to, as :meth:`_search` connects it.

        The same elementwise tangency and segment tests as :meth:`_search` runs for each
        end (each pair's answer depends on that pair alone), so the set is the same.
        """
        ux = nodes.pos[None, :, 0] - point[0]
        uy = nodes.pos[None, :, 1] - point[1]
        _, node_k = np.nonzero(_tangent_grid(nodes, ux, uy, 1))
        if node_k.size == 0:
            return node_k
        ok = ~segments_hit_any(
            np.broadcast_to(point, (node_k.size, 2)), nodes.pos[node_k], boxes, r_hit
        )
        visible: IntArray = node_k[ok]
        return visible

    def _no_path(
        self, scene: _Scene, sx: float, sy: float, gx: float, gy: float, r_hit: float
    ) -> bool:
        """Is it certain that :meth:`_search` finds no path from ``(sx, sy)`` to ``(gx, gy)``?

        :meth:`_search` fails iff no node the goal connects to is in a connected component
        of the graph holding a node the start connects to. The components are computed
        once per graph and, per start point, the nodes of the components the start
        connects to (a planning session asks many goals from one start; one connected
        node settles a component); the goal is then tested against those nodes only,
        until one connects. A False answer runs :meth:`_search` as before, so every path
        returned is the one it always was.
        """
        graph = scene.graph
        assert graph is not None
        nodes = graph.nodes
        if len(nodes) == 0:
            return True
        key = (sx, sy)
        reach = scene.reach.get(key)
        if reach is None:
            if scene.components is None:
                scene.components = _component_lists(graph)
            boxes = _box_lists(scene)
            # the components the start connects to (one connected node is enough)
            seen = [c for c in scene.components if _sees_any(c, sx, sy, boxes, r_hit)]
            reach = tuple(
                [v for c in seen for v in c[f]] if f < 6 else [[0] for c in seen for _ in c[0]]
                for f in range(7)
            )
            scene.reach[key] = reach
            if len(scene.reach) > 16:
                scene.reach.popitem(last=False)
        return not _sees_any(reach, gx, gy, _box_lists(scene), r_hit)

    def _search(
        self, graph: _Graph, ends: FloatArray, boxes: BoxArrays, r_hit: float
    ) -> FloatArray | None:
        """Connect start and goal to the graph and run A*; the polyline or None."""
        nodes = graph.nodes
        n = len(nodes)
        if n == 0:
            return None
        ux = nodes.pos[None, :, 0] - ends[:, 0:1]
        uy = nodes.pos[None, :, 1] - ends[:, 1:2]
        end_k, node_k = np.nonzero(_tangent_grid(nodes, ux, uy, 1))
        ok = ~segments_hit_any(ends[end_k], nodes.pos[node_k], boxes, r_hit)
        end_k, node_k = end_k[ok], node_k[ok]
        if not (np.any(end_k == 0) and np.any(end_k == 1)):
            return None
        lengths = np.hypot(ux[end_k, node_k], uy[end_k, node_k]).tolist()
        start_edges: list[tuple[int, float]] = []
        goal_edges: dict[int, float] = {}
        for e, v, w in zip(end_k.tolist(), node_k.tolist(), lengths, strict=True):
            if e == 0:
                start_edges.append((v, w))
            else:
                goal_edges[v] = w
        heuristic = np.hypot(ux[1], uy[1]).tolist()
        order = _astar(graph.adjacency(), start_edges, goal_edges, heuristic)
        if order is None:
            return None
        polyline: FloatArray = np.concatenate(
            [ends[:1], nodes.pos[np.array(order, dtype=np.intp)], ends[1:]]
        )
        return polyline

    def _make_path(self, start: Pose2D, goal: Pose2D, polyline: FloatArray) -> BasePath:
        """Add headings turning linearly in travelled distance by the shortest way."""
        if len(polyline) == 2:
            # the two ends keep their own headings (the interpolation below is
            # overwritten at both ends): the straight path needs no arithmetic
            waypoints = np.array([[start.x, start.y, start.theta], [goal.x, goal.y, goal.theta]])
            return BasePath._from_owned(waypoints, self.config.rotation_weight)
        xy = np.array(polyline, dtype=np.float64)
        xy[0] = (start.x, start.y)
        xy[-1] = (goal.x, goal.y)
        seg = np.hypot(np.diff(xy[:, 0]), np.diff(xy[:, 1]))
        total = float(np.sum(seg))
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        frac = cum / total if total > 0.0 else np.linspace(0.0, 1.0, xy.shape[0])
        dtheta = float(wrap_angle(goal.theta - start.theta))
        theta = wrap_angle(start.theta + frac * dtheta)
        theta[0] = start.theta
        theta[-1] = goal.theta
        waypoints = np.column_stack([xy, theta])
        return BasePath._from_owned(waypoints, self.config.rotation_weight)
