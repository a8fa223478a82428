r"""Deterministic Optimistic Optimization (DOO, Munos 2011) and its randomised variant.

DOO grows a hierarchical partition of the box (a :class:`~voot.optim._partition.CellTree`).
Every cell :math:`X_c` has a representative point :math:`x_c` that is evaluated, and an
optimistic bound on :math:`f` over the cell (its *b-value*)

.. math:: b_c = f(x_c) + \varepsilon \, \delta(X_c),

where :math:`\delta` is the cell's size under the metric
:math:`\ell(x, y) = \|w \odot (x - y)\|_2` and :math:`\varepsilon` plays the role of the
(unknown) local Lipschitz constant. Each step expands the leaf of largest b-value: it is
split along its longest side and its children are evaluated, one per ``ask``.

Choices, as options of :class:`DOOConfig` (defaults: the authors' code):

* ``epsilon`` multiplies the size in the units set by ``scale``. The authors used box
  units (``scale="absolute"``) and searched
  :math:`\varepsilon \in \{2.2\cdot10^{-16}, \dots, 1\}` per problem (:meth:`DOOConfig.paper_grid`),
  so :math:`\varepsilon` absorbs the scale of :math:`f` and of the box.
  ``scale="unit"`` measures sizes in the unit cube instead (root diagonal
  :math:`\sqrt d`), which makes one :math:`\varepsilon` transferable between boxes.
* ``cell_size="diagonal"`` (the authors' final code: twice the centre-to-corner distance)
  or ``"radius"``: Munos' :math:`\sup_{x \in X_c} \ell(x_c, x)`, the distance from the
  representative point to the farthest corner (half the diagonal for a centre). The two
  differ by a factor of at most 2, which the :math:`\varepsilon` grid absorbs.
* ``split="bisect"`` (the authors') evaluates both halves at their centres, two
  evaluations per expansion; ``"trisect"`` keeps the parent's centre as the middle third's
  point, so also two evaluations per expansion but three children.

The common initial point of the benchmark (``initial_point``, returned by the first
``ask``) becomes the root's representative point, so its value seeds the root's b-value.
With ``split_at_initial_point=True`` the tree is also cut through it, as in the authors'
code whose root point was drawn at random; by default cuts are at cell midpoints.

Tree search (DOOT) changes the value of a told action as its subtree is explored:
:meth:`DOO.revalue` updates the b-value of the leaf cell that the point represents, in
:math:`O(1)`. Selection is one ``argmax`` over an array of b-values (non-leaves hold
:math:`-\infty`), :math:`O(\#\text{cells})` at numpy speed with no invalidation to manage;
ties go to the oldest cell.

RAND-DOO (the paper's RAND-DOOT sampler) evaluates a uniform point of the chosen cell
instead of its centre. Asking again without telling redraws in the same cell, and
:meth:`RandDOO.mark_infeasible` returns a told point's cell to the queue, so infeasible
samples do not split.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, ClassVar

import numpy as np

from voot import validation as V
from voot.optim._partition import (
    CellTree,
    Scale,
    Split,
    parse_scale,
    parse_split,
    scale_weights,
)
from voot.optim.base import FloatArray, Optimizer, OptimizerConfig

#: The authors' epsilon grid for DOO on the synthetic functions (sorted, duplicates
#: removed): float64 and float32 machine epsilon, 1e-7, 1e-6, 1e-4, 1e-3, 0.01, 0.1, 1.
PAPER_EPSILONS: list[float] = [
    float(np.finfo(np.float64).eps),
    1e-7,
    float(np.finfo(np.float32).eps),
    1e-6,
    1e-4,
    1e-3,
    1e-2,
    0.1,
    1.0,
]


class CellSize(StrEnum):
    """The size :math:`\\delta(X_c)` in the b-value (see the module docstring)."""

    DIAGONAL = "diagonal"
    RADIUS = "radius"


@dataclass(frozen=True)
class DOOConfig(OptimizerConfig):
    """DOO hyperparameters (defaults: the authors' code, except ``epsilon``).

    Attributes:
        epsilon: exploration weight :math:`\\varepsilon \\ge 0` of the cell size in the
            b-value. The paper gives no single value (it was searched per problem over
            :meth:`paper_grid`); 0.1 is a middle-of-the-grid default.
        split: ``"bisect"`` (authors) or ``"trisect"`` along the longest side.
        cell_size: ``"diagonal"`` (authors) or ``"radius"`` (Munos' sup distance).
        scale: metric weights: ``"absolute"`` (box units, authors), ``"unit"`` (unit
            cube) or a sequence of one weight > 0 per dimension. The longest side (the
            one that is cut) is measured with the same weights.
        split_at_initial_point: cut the tree through a root point that the tree did not
            propose (the initial point) instead of through the box centre. Bisection only.
    """

    epsilon: float = 0.1
    split: Split | str = Split.BISECT
    cell_size: CellSize | str = CellSize.DIAGONAL
    scale: Scale = "absolute"
    split_at_initial_point: bool = False

    def __post_init__(self) -> None:
        V.positive(self.epsilon, "epsilon", allow_zero=True)
        object.__setattr__(self, "split", parse_split(self.split))
        object.__setattr__(self, "cell_size", V.choice(CellSize, self.cell_size, "cell_size"))
        object.__setattr__(self, "scale", parse_scale(self.scale))
        V.flag(self.split_at_initial_point, "split_at_initial_point")
        if self.split_at_initial_point and self.split is not Split.BISECT:
            raise ValueError(
                "split_at_initial_point=True needs split='bisect' (a trisection cuts at"
                f" thirds), got split={self.split!r}"
            )

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"epsilon": list(PAPER_EPSILONS)}


class DOO(Optimizer, name="doo", config_class=DOOConfig, supports_revalue=True):
    """Deterministic Optimistic Optimization (maximisation). See the module docstring.

    Each ``ask`` returns the representative point of the next cell to evaluate: the
    children of the last expanded leaf, in order, then (once all are told) the children
    of the leaf with the largest b-value. A tell of the proposed point assigns it to its
    cell; a point the tree did not propose is kept in the history but outside the tree,
    except the first one, which represents the root (the common initial point). When no
    cell can be split any more (float resolution), asks are uniform in the box.
    """

    config: DOOConfig
    #: Representative points uniform in the cell (RAND-DOO) instead of the centre.
    _random_points: ClassVar[bool] = False

    def _setup(self) -> None:
        super()._setup()
        cfg = self.config
        weights = scale_weights(cfg.scale, self.bounds)
        #: The cells (bounds, centres, depths, representative points, b-values).
        self.partition = CellTree(self.bounds, Split(cfg.split), weights)
        self._epsilon = float(cfg.epsilon)
        self._radius = CellSize(cfg.cell_size) is CellSize.RADIUS
        #: Cells waiting for their point, evaluated first-in first-out (root first).
        self._queue: deque[int] = deque([0])
        #: Exploration bonus epsilon * delta of each cell, set when its point is known.
        self._bonus = np.zeros(self.partition.key.shape[0])
        #: Told index -> the leaf cell it represents (-1: none).
        self._cell_of = np.full(self._xs.shape[0], -1, dtype=np.intp)
        self._proposal: FloatArray | None = None
        self._proposal_cell = -1
        #: Number of expansions (selected leaves that were split).
        self.n_expansions = 0

    # ----- public ----------------------------------------------------------------------
    @property
    def n_cells(self) -> int:
        """Cells created so far (leaves, inner cells and cells waiting for a point)."""
        return self.partition.n

    @property
    def n_leaves(self) -> int:
        """Evaluated cells that are not split yet (the candidates for expansion)."""
        return int(np.count_nonzero(self.partition.leaf[: self.partition.n]))

    def cell_bounds(self, index: int) -> tuple[FloatArray, FloatArray] | None:
        """``(lower, upper)`` of the leaf cell represented by told point ``index``.

        None if the point represents no leaf (its cell was split, or the tree did not
        propose it).
        """
        if not 0 <= index < self._n:
            raise IndexError(f"index {index} out of range for {self._n} told points")
        c = int(self._cell_of[index])
        return None if c < 0 else self.partition.cell_bounds(c)

    @property
    def proposal_bounds(self) -> tuple[FloatArray, FloatArray] | None:
        """``(lower, upper)`` of the cell the last ask proposed a point for (or None)."""
        c = self._proposal_cell
        return None if c < 0 else self.partition.cell_bounds(c)

    def b_values(self) -> FloatArray:
        """b-value of every cell (``-inf`` for cells that are not selectable leaves)."""
        return self.partition.key[: self.partition.n].copy()

    # ----- ask / tell ------------------------------------------------------------------
    def _ask(self) -> FloatArray:
        tree = self.partition
        while not self._queue:
            c = self._select()
            if c < 0:  # nothing left to split: the partition hit float resolution
                self._proposal, self._proposal_cell = None, -1
                return self.bounds.sample(self.rng)
            self._expand(c)
        c = self._queue[0]
        x = tree.uniform(c, self.rng) if self._random_points else tree.centre[c].copy()
        self._proposal, self._proposal_cell = x, c
        return x.copy()

    def _tell(self, x: FloatArray, value: float) -> None:
        i = self._n - 1
        if self._cell_of.shape[0] < self._xs.shape[0]:
            grown = np.full(self._xs.shape[0], -1, dtype=np.intp)
            grown[:i] = self._cell_of[:i]
            self._cell_of = grown
        self._cell_of[i] = -1
        c = self._proposal_cell
        if c >= 0 and self._proposal is not None and bool(np.all(x == self._proposal)):
            self._queue.remove(c)
            self.partition.at_centre[c] = not self._random_points
            self._assign(c, i)
        elif self.partition.point[0] < 0 and self._queue and self._queue[0] == 0:
            # The first point told before the root was evaluated (the initial point)
            # represents the root.
            if self.config.split_at_initial_point:
                self.partition.anchor_root(x)
                self.partition.at_centre[0] = True
            self._queue.popleft()
            self._assign(0, i)
        else:
            return  # a point the tree did not propose: history only
        self._proposal, self._proposal_cell = None, -1

    def _revalue(self, index: int, value: float) -> None:
        c = int(self._cell_of[index])
        if c >= 0:
            self.partition.key[c] = value + self._bonus[c]

    # ----- internals -------------------------------------------------------------------
    def _assign(self, c: int, i: int) -> None:
        """Make told point ``i`` the representative of cell ``c`` and ``c`` a leaf."""
        tree = self.partition
        if self._bonus.shape[0] < tree.key.shape[0]:
            grown = np.zeros(tree.key.shape[0])
            grown[: self._bonus.shape[0]] = self._bonus
            self._bonus = grown
        size = tree.radius(c, self._xs[i]) if self._radius else float(tree.diag[c])
        self._bonus[c] = self._epsilon * size
        tree.point[c] = i
        tree.leaf[c] = True
        tree.key[c] = self._values[i] + self._bonus[c]
        self._cell_of[i] = c

    def _select(self) -> int:
        """The leaf of largest b-value (oldest on ties), or -1 if there is none."""
        tree = self.partition
        keys = tree.key[: tree.n]
        c = int(np.argmax(keys))
        if keys[c] == -np.inf:  # all leaves have b = -inf, or there are none
            leaves = np.flatnonzero(tree.leaf[: tree.n])
            return int(leaves[0]) if leaves.size else -1
        return c

    def _heir(self, parent: int, kids: list[int], keep: int) -> int:
        """Index in ``kids`` of the child that inherits the parent's point, or -1."""
        return keep if self.partition.at_centre[parent] else -1

    def _expand(self, c: int) -> None:
        """Split leaf ``c``; its children join the queue (or inherit its point)."""
        tree = self.partition
        p = int(tree.point[c])
        tree.leaf[c] = False
        tree.key[c] = -np.inf
        self._cell_of[p] = -1
        split = tree.split(c)
        if split is None:
            return  # too small to split: retired
        kids, keep = split
        self.n_expansions += 1
        heir = self._heir(c, kids, keep)
        for k, kid in enumerate(kids):
            if k == heir:
                tree.at_centre[kid] = tree.at_centre[c]
                self._assign(kid, p)
            else:
                self._queue.append(kid)


@dataclass(frozen=True)
class RandDOOConfig(DOOConfig):
    """RAND-DOO hyperparameters: :class:`DOOConfig` plus

    Attributes:
        reuse_parent_point: when a leaf is split, the child containing the leaf's point
            keeps it (it is uniform in that child too), so only the other children are
            sampled. Off in the authors' code (every child gets a fresh sample).
    """

    reuse_parent_point: bool = False

    def __post_init__(self) -> None:
        super().__post_init__()
        V.flag(self.reuse_parent_point, "reuse_parent_point")


class RandDOO(DOO, name="rand_doo", config_class=RandDOOConfig):
    """RAND-DOO: DOO whose cells are represented by a uniform point of the cell.

    For tree search, where an infeasible sample must not split its cell (RAND-DOOT):

    * before telling, just ``ask`` again: the next point is a fresh uniform draw in the
      same cell;
    * after telling (the sample was executed and its value recorded), call
      :meth:`mark_infeasible` with its index: the value stays in the history, but the
      cell loses its point and is the next one sampled.
    """

    config: RandDOOConfig
    _random_points: ClassVar[bool] = True

    def _setup(self) -> None:
        super()._setup()
        #: Told indices marked infeasible (they represent no cell).
        self.infeasible: list[int] = []

    def mark_infeasible(self, index: int) -> bool:
        """Told point ``index`` was infeasible: its cell is not split but sampled again.

        Call it right after telling the point. Returns True if a cell was returned to the
        queue, False if the point represents no leaf cell (a point the tree did not
        propose, which is outside the tree anyway, or one already marked or split).
        """
        if not 0 <= index < self._n:
            raise IndexError(f"index {index} out of range for {self._n} told points")
        c = int(self._cell_of[index])
        if c < 0:
            return False
        tree = self.partition
        tree.leaf[c] = False
        tree.key[c] = -np.inf
        tree.point[c] = -1
        self._cell_of[index] = -1
        self._queue.appendleft(c)
        self.infeasible.append(index)
        return True

    def _heir(self, parent: int, kids: list[int], keep: int) -> int:
        if not self.config.reuse_parent_point:
            return -1
        tree = self.partition
        x = self._xs[int(tree.point[parent])]
        for k, kid in enumerate(kids):
            if np.all(x >= tree.lower[kid]) and np.all(x <= tree.upper[kid]):
                return k
        return -1
