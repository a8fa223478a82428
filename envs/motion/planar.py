"""Planar values of base motion planning: poses, footprints, paths and their lengths.

Everything the planner takes and returns, and nothing it computes with: a base pose
:class:`Pose2D` ``(x, y, theta)``, an obstacle footprint :class:`Box2D` (an oriented
rectangle), a base path :class:`BasePath` (waypoints and length) and the SE(2) distance
they are measured by (:func:`se2_distance`, :func:`path_length`, :func:`wrap_angle`).
The environments build these values on every step (a footprint per object, a path per
place action), so the module keeps them apart from the planner
(:mod:`voot.envs.motion.planner`) and its geometry kernels (:mod:`voot.envs.motion.disc_geometry`):
a caller that only needs a footprint or a path length imports neither.

Path length is the original's "sum of SE(2) distances" between consecutive waypoints,
``sum_i ||p_{i+1} - p_i|| + rotation_weight * |wrap(theta_{i+1} - theta_i)|``. The
original (``get_trajectory_length`` with ``se2_distance(a, b, 1, 1)``) weighted
translation and rotation by 1 each and measured the rotation as the chord
``2 |sin(dtheta / 2)|`` between consecutive points of a dense RRT path; for a dense path
the chord sum converges to the arc ``|dtheta|`` used here, which, unlike the chord, does
not depend on how densely the path is sampled.

The values validate their fields (finite numbers, positive extents) and offer unchecked
fast constructors (:meth:`Box2D.fast`, :meth:`BasePath._from_owned`) for the hot paths,
which build the same objects.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V

FloatArray = NDArray[np.float64]

__all__ = ["BasePath", "Box2D", "Pose2D", "path_length", "se2_distance", "wrap_angle"]


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
        name: Identifier reported by :func:`voot.envs.motion.swept_volume.obstacles_on_path`
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
