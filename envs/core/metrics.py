r"""The authors' distances between actions, per operator (for VOO's Voronoi cells).

VOO's best cell is the set of actions nearer to the best action than to every other
one, so the distance decides what "near" means. The authors' code does not use the
Euclidean distance in the parameter box; it measures, per operator:

* **place**: the placed object's position only, :math:`\sqrt{\Delta x^2 + \Delta y^2}`
  (the heading is ignored, a quirk of the original kept as it ran). On the conveyor an
  action places three boxes; its distance is the Euclidean distance of the three
  positions together.
* **pick**: the weighted SE(2) distance of the two base poses,
  :math:`\|\Delta p\| + w\,|\mathrm{wrap}(\Delta\theta)|`, plus the Euclidean norm of
  the difference of the grasp parameters (angle in radians, height and depth
  fractions). The base pose of pick parameters is
  ``object + r (cos a, sin a)``, heading ``a + pi + offset`` relative to the object's
  frame, with ``r = base distance x arm reach`` and ``a`` the base angle; the object's
  own pose cancels from every difference, so the distance does not depend on the state.

Every distance here is vectorised from many points to one,
``metric(points (n, d), y (d,)) -> (n,)`` (:data:`voot.tree.problem.ActionDistance`),
and from many points to many, ``metric.pairwise(points, ys) -> (m, n)``, which VOO uses
to test a batch of proposals at once; both in the paper's units, and
:func:`to_action_units` makes one for affinely scaled actions.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from voot.envs.robot.model import ARM_REACH

FloatArray = NDArray[np.float64]


class Distance:
    """A distance from many points to one, computed as one row of :meth:`pairwise`.

    ``pairwise(points (n, d), ys (m, d)) -> (m, n)`` is what VOO uses to test a batch of
    proposals at once; a single call is its first row, so both give the same bits.
    """

    def pairwise(self, points: FloatArray, ys: FloatArray) -> FloatArray:
        raise NotImplementedError

    def __call__(self, points: FloatArray, y: FloatArray) -> FloatArray:
        out: FloatArray = self.pairwise(points, np.asarray(y, dtype=np.float64)[None, :])[0]
        return out


def _norm(diff: FloatArray) -> FloatArray:
    """Euclidean norm over the last axis, summing the squares left to right."""
    sq = diff * diff
    total = sq[..., 0].copy()
    for k in range(1, sq.shape[-1]):
        total += sq[..., k]
    out: FloatArray = np.sqrt(total)
    return out


class PlaceDistance(Distance):
    """Distance of the placed objects' (x, y), ignoring their headings.

    Args:
        n_placements: placements per action, each ``(x, y, theta)`` (1 kitchen, 3 conveyor).
    """

    def __init__(self, n_placements: int = 1) -> None:
        self.columns = np.array([3 * k + j for k in range(n_placements) for j in (0, 1)])

    def pairwise(self, points: FloatArray, ys: FloatArray) -> FloatArray:
        c = self.columns
        p = np.asarray(points, dtype=np.float64)[:, c]
        q = np.asarray(ys, dtype=np.float64)[:, c]
        return _norm(p[None, :, :] - q[:, None, :])


class PickDistance(Distance):
    """Weighted SE(2) distance of the pick base poses plus the grasp parameters' norm.

    Args:
        rotation_weight: :math:`w`, metres per radian of heading (the base planner's).
        reach: the arm reach that scales the base-distance fraction (metres).
    """

    def __init__(self, rotation_weight: float = 1.0, reach: float = ARM_REACH) -> None:
        if not (math.isfinite(rotation_weight) and rotation_weight >= 0):
            raise ValueError(f"rotation_weight must be a finite number >= 0, got {rotation_weight}")
        self.rotation_weight = float(rotation_weight)
        self.reach = float(reach)

    def pairwise(self, points: FloatArray, ys: FloatArray) -> FloatArray:
        p = np.asarray(points, dtype=np.float64)
        q = np.asarray(ys, dtype=np.float64)
        rp, rq = p[:, 3] * self.reach, q[:, 3] * self.reach
        bx = rp * np.cos(p[:, 4])
        by = rp * np.sin(p[:, 4])
        qx = rq * np.cos(q[:, 4])
        qy = rq * np.sin(q[:, 4])
        dx = bx[None, :] - qx[:, None]
        dy = by[None, :] - qy[:, None]
        dtheta = (p[:, 4] + p[:, 5])[None, :] - (q[:, 4] + q[:, 5])[:, None]
        wrapped = np.abs((dtheta + math.pi) % (2.0 * math.pi) - math.pi)
        grasp = p[None, :, :3] - q[:, None, :3]
        out: FloatArray = np.hypot(dx, dy) + self.rotation_weight * wrapped + _norm(grasp)
        return out


def place_distance(n_placements: int = 1) -> PlaceDistance:
    """The place distance (see :class:`PlaceDistance`)."""
    return PlaceDistance(n_placements)


def pick_distance(rotation_weight: float = 1.0) -> PickDistance:
    """The pick distance (see :class:`PickDistance`)."""
    return PickDistance(rotation_weight)


class ScaledDistance(Distance):
    """``metric`` applied to actions mapped to the paper's units by ``a * scale + offset``."""

    def __init__(self, metric: Distance, scale: FloatArray, offset: FloatArray):
        self.metric = metric
        self.scale = np.asarray(scale, dtype=np.float64)
        self.offset = np.asarray(offset, dtype=np.float64)

    def pairwise(self, points: FloatArray, ys: FloatArray) -> FloatArray:
        s, o = self.scale, self.offset
        return self.metric.pairwise(np.asarray(points) * s + o, np.asarray(ys) * s + o)


def to_action_units(metric: Distance, scale: FloatArray, offset: FloatArray) -> ScaledDistance:
    """``metric`` for actions ``a`` whose paper-unit value is ``a * scale + offset``."""
    return ScaledDistance(metric, scale, offset)
