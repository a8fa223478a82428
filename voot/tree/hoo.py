r"""Hierarchical Optimistic Optimization (HOO, Bubeck et al. 2011), the bandit of HOOT.

HOO grows a binary tree of cells over the action box. Every cell :math:`(h, i)` that has
been played keeps its count :math:`T_{h,i}`, its mean reward :math:`\hat\mu_{h,i}` and

.. math::

    U_{h,i} = \hat\mu_{h,i} + c\,\sqrt{2 \ln n / T_{h,i}} + \nu_1 \rho^h, \qquad
    B_{h,i} = \min\bigl(U_{h,i},\ \max(B_{h+1,2i-1}, B_{h+1,2i})\bigr),

with :math:`B = +\infty` for cells not played yet. Each round follows the larger
:math:`B` from the root down to a cell that has not been played, plays a point of that
cell and updates the statistics of the cells on the path. Cells are split in half along
their longest side (relative to the box).

Choices of this implementation (HOOT in a deterministic tree search, Mansley et al. 2011):

* every cell draws its point once, when it is first played, so a cell is one *arm* and
  can be played again; the tree is truncated at ``max_depth`` (truncated HOO), and a
  path that reaches a cell at that depth plays that cell's point again. In a tree search
  the same point means the same tree edge, so its subtree keeps growing;
* :math:`B` is stored, refreshed along the played path after each round (the classic
  :math:`O(\text{depth})` implementation); during the descent the two children compared
  get a fresh :math:`U` (with the current :math:`\ln n`), their subtrees' stored
  :math:`B`. A cell off the path is therefore never starved by a stale confidence term.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from voot import validation as V
from voot.optim.base import Bounds, FloatArray


class HOOPoint(StrEnum):
    """Where a new cell's point is drawn: uniform in the cell, or its centre."""

    UNIFORM = "uniform"
    CENTER = "center"


@dataclass(frozen=True)
class HOOConfig:
    """HOO hyperparameters (not given by the VOOT paper, which did not run HOOT).

    Attributes:
        v1: smoothness scale :math:`\\nu_1 \\ge 0`, in units of the reward.
        rho: shrink factor :math:`\\rho \\in (0, 1)` of the smoothness bonus per depth.
        exploration: scale :math:`c \\ge 0` of the confidence term (1: Bubeck et al.'s,
            for rewards in [0, 1]; scale it with the range of the returns).
        max_depth: truncation depth of the cell tree (>= 1).
        point: where a new cell's point is drawn, see :class:`HOOPoint`.
    """

    v1: float = 1.0
    rho: float = 0.5
    exploration: float = 1.0
    max_depth: int = 20
    point: HOOPoint | str = HOOPoint.UNIFORM

    def __post_init__(self) -> None:
        for name in ("v1", "exploration"):
            v = getattr(self, name)
            V.positive(v, name, allow_zero=True)
        V.number(self.rho, "rho", 0.0, 1.0, open_low=True, open_high=True)
        V.integer(self.max_depth, "max_depth", 1)
        object.__setattr__(self, "point", V.choice(HOOPoint, self.point, "point"))


class HOO:
    """A HOO bandit over a box (maximisation): ``select`` a cell, play it, ``update``.

    >>> import numpy as np
    >>> hoo = HOO(Bounds([0.0], [1.0]), rng=np.random.default_rng(0))
    >>> for _ in range(200):
    ...     cell, _ = hoo.select()
    ...     hoo.update(cell, 1.0 - abs(float(hoo.point(cell)[0]) - 0.3))
    >>> abs(float(hoo.point(hoo.best_cell())[0]) - 0.3) < 0.05
    True
    """

    def __init__(
        self,
        bounds: Bounds,
        config: HOOConfig | None = None,
        rng: np.random.Generator | None = None,
    ) -> None:
        self.bounds = bounds
        self.config = config if config is not None else HOOConfig()
        self.rng = rng if rng is not None else np.random.default_rng()
        # One entry per cell; plain lists, because every operation touches a few scalars.
        self._lo: list[FloatArray] = [bounds.lower]
        self._hi: list[FloatArray] = [bounds.upper]
        self._x: list[FloatArray | None] = [None]
        self._left: list[int] = [-1]
        self._right: list[int] = [-1]
        self._parent: list[int] = [-1]
        self._depth: list[int] = [0]
        self._count: list[float] = [0.0]
        self._mean: list[float] = [0.0]
        self._b: list[float] = [math.inf]
        self._played: list[bool] = [False]
        self._inv_width = 1.0 / bounds.width
        #: Number of rounds (updates) so far.
        self.n = 0

    @property
    def n_cells(self) -> int:
        return len(self._lo)

    def point(self, cell: int) -> FloatArray:
        """The point of ``cell`` (a view: do not modify)."""
        x = self._x[cell]
        if x is None:
            raise ValueError(f"cell {cell} has no point yet")
        return x

    def cell_bounds(self, cell: int) -> tuple[FloatArray, FloatArray]:
        return self._lo[cell].copy(), self._hi[cell].copy()

    def depth(self, cell: int) -> int:
        return self._depth[cell]

    def select(self) -> tuple[int, bool]:
        """Follow the larger B down the tree; return ``(cell, is_new)``.

        A new cell gets its point here; ``is_new`` is False when a played cell at
        ``max_depth`` is played again.
        """
        c = 0
        cfg = self.config
        max_depth = cfg.max_depth
        rng = self.rng
        left, right, _b, played, depth = self._left, self._right, self._b, self._played, self._depth
        count, mean = self._count, self._mean
        c2 = cfg.exploration * math.sqrt(2.0 * math.log(max(self.n, 1)))
        v1, rho = cfg.v1, cfg.rho
        while True:
            if c and depth[c] >= max_depth:
                return c, False
            lc = left[c]
            if lc < 0:
                self._split(c)
                lc = left[c]
            rc = right[c]
            lp, rp = played[lc], played[rc]
            if not (lp and rp):
                if not (lp or rp):
                    kid = lc if rng.random() < 0.5 else rc
                else:
                    kid = rc if lp else lc
                self._draw(kid)
                return kid, True
            # B of the two children with a fresh confidence term (the current n).
            smooth = v1 * rho ** depth[lc]
            bl = min(mean[lc] + c2 / math.sqrt(count[lc]) + smooth, self._below(lc))
            br = min(mean[rc] + c2 / math.sqrt(count[rc]) + smooth, self._below(rc))
            if bl > br:
                c = lc
            elif br > bl:
                c = rc
            else:
                c = lc if rng.random() < 0.5 else rc

    def _below(self, c: int) -> float:
        """max(B of the children) if both were played, else +inf."""
        lc = self._left[c]
        if lc < 0:
            return math.inf
        rc = self._right[c]
        if not (self._played[lc] and self._played[rc]):
            return math.inf
        return max(self._b[lc], self._b[rc])

    def redraw(self, cell: int) -> FloatArray:
        """Draw a new point for a cell that was selected but not played yet.

        Used when the drawn point failed a feasibility check.
        """
        self._draw(cell)
        return self.point(cell)

    def update(self, cell: int, reward: float) -> None:
        """Report the reward of playing ``cell``; refresh statistics along its path."""
        self.n += 1
        self._played[cell] = True
        cfg = self.config
        c2 = cfg.exploration * math.sqrt(2.0 * math.log(self.n))
        v1, rho = cfg.v1, cfg.rho
        count, mean, b, played = self._count, self._mean, self._b, self._played
        left, right, depth, parent = self._left, self._right, self._depth, self._parent
        c = cell
        while c >= 0:  # bottom-up: children's B are fresh when the parent's is computed
            n_c = count[c] + 1.0
            count[c] = n_c
            m = mean[c] + (reward - mean[c]) / n_c
            mean[c] = m
            u = m + c2 / math.sqrt(n_c) + v1 * rho ** depth[c]
            lc = left[c]
            if lc >= 0 and played[lc] and played[right[c]]:
                u = min(u, max(b[lc], b[right[c]]))
            b[c] = u
            c = parent[c]

    def best_cell(self) -> int:
        """The played cell with the highest mean reward (the recommendation)."""
        best, best_mean = -1, -math.inf
        for c in range(1, len(self._mean)):
            if self._played[c] and (best < 0 or self._mean[c] > best_mean):
                best, best_mean = c, self._mean[c]
        return best

    # ----- internals ------------------------------------------------------------------
    def _draw(self, cell: int) -> None:
        lo, hi = self._lo[cell], self._hi[cell]
        if self.config.point is HOOPoint.CENTER:
            self._x[cell] = 0.5 * (lo + hi)
        else:
            self._x[cell] = lo + self.rng.random(lo.size) * (hi - lo)

    def _split(self, c: int) -> None:
        lo, hi = self._lo[c], self._hi[c]
        k = int(np.argmax((hi - lo) * self._inv_width))
        mid = 0.5 * (lo[k] + hi[k])
        hi_a = hi.copy()
        hi_a[k] = mid
        lo_b = lo.copy()
        lo_b[k] = mid
        a = len(self._lo)
        self._lo += [lo, lo_b]
        self._hi += [hi_a, hi]
        self._x += [None, None]
        self._left += [-1, -1]
        self._right += [-1, -1]
        self._parent += [c, c]
        d = self._depth[c] + 1
        self._depth += [d, d]
        self._count += [0.0, 0.0]
        self._mean += [0.0, 0.0]
        self._b += [math.inf, math.inf]
        self._played += [False, False]
        self._left[c], self._right[c] = a, a + 1
