r"""Hierarchical partitions of a box into hyper-rectangles (the cells of DOO and SOO).

A :class:`CellTree` stores its cells as a structure of arrays (bounds, centre, depth,
representative point, ...), so that selecting among thousands of cells is one numpy
reduction. A cell is split along its longest side (measured with the per-dimension
weights of the metric, see :func:`scale_weights`) into

* two halves (``bisect``, the authors' DOO/SOO code), children centred at the quarters;
* three thirds (``trisect``, Munos 2011's standard for SOO): the middle child keeps the
  parent's centre, so a point evaluated at the parent's centre also represents it.

The split position is the parent's centre coordinate. For a tree grown from the box
centre this is the midpoint of the side; a tree *anchored* at a given root point (the
authors' DOO, whose root point was random) is cut through that point instead.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from enum import StrEnum

import numpy as np
from numpy.typing import NDArray

from voot.optim.base import Bounds, FloatArray

IntArray = NDArray[np.intp]
BoolArray = NDArray[np.bool_]

#: A side narrower than this many float spacings of its end points is not split again.
_MIN_SPACINGS = 64.0


class Split(StrEnum):
    """How a cell is divided along its longest side."""

    BISECT = "bisect"
    TRISECT = "trisect"


#: ``"absolute"`` (box units), ``"unit"`` (box mapped to the unit cube) or d weights.
Scale = str | tuple[float, ...]


def parse_split(value: object, field: str = "split") -> Split:
    """Coerce a config value to :class:`Split`, or raise ValueError listing the choices."""
    if isinstance(value, str) and value in {s.value for s in Split}:
        return Split(value)
    valid = ", ".join(s.value for s in Split)
    raise ValueError(f"unknown {field} {value!r}; valid choices are: {valid}")


def parse_scale(value: object, field: str = "scale") -> Scale:
    """Validate a metric scale: ``"absolute"``, ``"unit"`` or a sequence of weights > 0."""
    if isinstance(value, str):
        if value not in ("absolute", "unit"):
            raise ValueError(
                f"unknown {field} {value!r}; valid choices are: 'absolute', 'unit', or a"
                " sequence of one positive weight per dimension"
            )
        return value
    if isinstance(value, Sequence | np.ndarray):
        try:
            weights = tuple(float(w) for w in value)
        except (TypeError, ValueError):
            weights = ()
        if weights and all(np.isfinite(w) and w > 0.0 for w in weights):
            return weights
    raise ValueError(
        f"{field} must be 'absolute', 'unit', or a non-empty sequence of finite weights > 0;"
        f" got {value!r}"
    )


def scale_weights(scale: Scale, bounds: Bounds, field: str = "scale") -> FloatArray:
    r"""Per-dimension weights :math:`w` of the metric :math:`\ell(x, y) = \|w \odot (x - y)\|_2`.

    ``"absolute"`` gives :math:`w = 1` (distances in box units, as the authors' code),
    ``"unit"`` gives :math:`w = 1 / (u - l)` (the box is the unit cube, so the root's
    diagonal is :math:`\sqrt d` whatever the units of the problem).
    """
    if scale == "absolute":
        return np.ones(bounds.dim)
    if scale == "unit":
        return 1.0 / bounds.width
    w = np.asarray(scale, dtype=np.float64)
    if w.shape != (bounds.dim,):
        raise ValueError(
            f"{field} has {w.size} weights but the bounds have {bounds.dim} dimensions;"
            " give one weight per dimension"
        )
    return w


class CellTree:
    """Cells of a hierarchical partition of ``bounds`` (cell 0 is the whole box).

    Per cell ``c`` (arrays indexed by cell id, valid up to :attr:`n`): ``lower[c]``,
    ``upper[c]``, ``centre[c]`` (the point a deterministic algorithm evaluates),
    ``depth[c]``, ``parent[c]`` (-1 for the root), ``point[c]`` (index of the told point
    representing the cell, -1 if none), ``at_centre[c]`` (that point is ``centre[c]``),
    ``leaf[c]`` (selectable), ``key[c]`` (the owner's selection key, -inf if not a leaf)
    and ``diag[c]``, the weighted length of the cell's diagonal.
    """

    def __init__(self, bounds: Bounds, split: Split, weights: FloatArray) -> None:
        self.bounds = bounds
        self.split_rule = Split(split)
        self.weights = np.asarray(weights, dtype=np.float64)
        d = bounds.dim
        cap = 64
        self.n = 0
        self.lower = np.empty((cap, d))
        self.upper = np.empty((cap, d))
        self.centre = np.empty((cap, d))
        self.depth = np.empty(cap, dtype=np.intp)
        self.parent = np.empty(cap, dtype=np.intp)
        self.point = np.empty(cap, dtype=np.intp)
        self.at_centre = np.empty(cap, dtype=bool)
        self.leaf = np.empty(cap, dtype=bool)
        self.key = np.empty(cap)
        self.diag = np.empty(cap)
        self._add(bounds.lower, bounds.upper, bounds.center, -1, 0)

    # ----- construction ----------------------------------------------------------------
    def _grow(self) -> None:
        cap = 2 * self.lower.shape[0]
        for name in ("lower", "upper", "centre"):
            old = getattr(self, name)
            new = np.empty((cap, old.shape[1]))
            new[: self.n] = old[: self.n]
            setattr(self, name, new)
        for name in ("depth", "parent", "point", "at_centre", "leaf", "key", "diag"):
            old = getattr(self, name)
            new = np.empty(cap, dtype=old.dtype)
            new[: self.n] = old[: self.n]
            setattr(self, name, new)

    def _add(
        self, lower: FloatArray, upper: FloatArray, centre: FloatArray, parent: int, depth: int
    ) -> int:
        if self.n == self.lower.shape[0]:
            self._grow()
        c = self.n
        self.lower[c] = lower
        self.upper[c] = upper
        self.centre[c] = centre
        self.parent[c] = parent
        self.depth[c] = depth
        self.point[c] = -1
        self.at_centre[c] = False
        self.leaf[c] = False
        self.key[c] = -np.inf
        side = (upper - lower) * self.weights
        self.diag[c] = math.sqrt(float(side @ side))
        self.n += 1
        return c

    def anchor_root(self, x: FloatArray) -> None:
        """Use ``x`` as the root's centre, so the partition is cut through ``x``."""
        if self.n != 1:
            raise RuntimeError("the root can only be anchored before it is split")
        self.centre[0] = x

    # ----- queries ---------------------------------------------------------------------
    def cell_bounds(self, c: int) -> tuple[FloatArray, FloatArray]:
        """Copies of ``(lower, upper)`` of cell ``c``."""
        return self.lower[c].copy(), self.upper[c].copy()

    def radius(self, c: int, x: FloatArray) -> float:
        """Weighted distance from ``x`` to the farthest corner of cell ``c``."""
        far = np.maximum(x - self.lower[c], self.upper[c] - x) * self.weights
        return math.sqrt(float(far @ far))

    def uniform(self, c: int, rng: np.random.Generator) -> FloatArray:
        """A uniform point of cell ``c`` (closed box)."""
        lo, hi = self.lower[c], self.upper[c]
        return np.minimum(lo + rng.random(lo.size) * (hi - lo), hi)

    def _split_dim(self, c: int) -> int:
        """Longest weighted side that can still be cut, or -1 if none can."""
        lo, hi = self.lower[c], self.upper[c]
        width = hi - lo
        j = int(np.argmax(width * self.weights))
        if width[j] > _MIN_SPACINGS * np.spacing(max(abs(lo[j]), abs(hi[j]))):
            return j  # the usual case: the longest side is still wide enough
        tiny = _MIN_SPACINGS * np.spacing(np.maximum(np.abs(lo), np.abs(hi)))
        weighted = np.where(width > tiny, width * self.weights, -1.0)
        j = int(np.argmax(weighted))
        return j if weighted[j] > 0.0 else -1

    # ----- splitting -------------------------------------------------------------------
    def split(self, c: int) -> tuple[list[int], int] | None:
        """Add the children of cell ``c`` (lowest first); None if ``c`` is too small.

        Returns the child ids and the index (in that list) of the child whose centre is
        ``centre[c]`` (the middle third of a trisection), or -1 if none.
        """
        j = self._split_dim(c)
        if j < 0:
            return None
        lo, hi, mid = self.lower[c], self.upper[c], self.centre[c]
        depth = int(self.depth[c]) + 1
        if self.split_rule is Split.BISECT:
            cut = float(mid[j])
            if not lo[j] < cut < hi[j]:  # an anchored centre on the boundary
                cut = _between(float(lo[j]), float(hi[j]), 0.5)
            edges = [float(lo[j]), cut, float(hi[j])]
            centres_j = [_between(edges[0], cut, 0.5), _between(cut, edges[2], 0.5)]
            keep = -1
        else:
            a = _between(float(lo[j]), float(hi[j]), 1.0 / 3.0)
            b = _between(float(lo[j]), float(hi[j]), 2.0 / 3.0)
            edges = [float(lo[j]), a, b, float(hi[j])]
            centres_j = [_between(edges[0], a, 0.5), float(mid[j]), _between(b, edges[3], 0.5)]
            keep = 1 if a <= mid[j] <= b else -1
            if keep < 0:
                centres_j[1] = _between(a, b, 0.5)
        kids = []
        for k, cj in enumerate(centres_j):
            clo, chi, cmid = lo.copy(), hi.copy(), mid.copy()
            clo[j], chi[j], cmid[j] = edges[k], edges[k + 1], cj
            kids.append(self._add(clo, chi, cmid, c, depth))
        return kids, keep


def _between(lo: float, hi: float, t: float) -> float:
    """The point a fraction ``t`` (1/3, 1/2 or 2/3) of the way from ``lo`` to ``hi``.

    Computed as the partition always has (``(2 lo + hi) / 3``, ``0.5 (lo + hi)``), so the
    cells are bit for bit those of before; only where that overflows (a box near the
    float limits) as ``lo * (1 - t) + hi * t``, which does not, so every cell stays in
    the box."""
    if t == 0.5:
        v = 0.5 * (lo + hi)
    elif t < 0.5:
        v = (2.0 * lo + hi) / 3.0
    else:
        v = (lo + 2.0 * hi) / 3.0
    if math.isfinite(v):
        return v
    return min(max(lo * (1.0 - t) + hi * t, lo), hi)
