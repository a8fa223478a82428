r"""Simultaneous Optimistic Optimization (SOO, Munos 2011).

SOO grows the same kind of partition as DOO (:mod:`voot.optim._partition`) but needs no
metric and no Lipschitz-like constant: it expands, in one sweep over the depths
:math:`h = 0, 1, \dots, \min(\mathrm{depth}(T), h_{\max}(t))`, the best leaf of each
depth, provided its value is at least the best value expanded so far in the sweep,

.. code-block:: text

    loop:
        v_max = -inf
        for h = 0 .. min(depth(T), h_max(t)):
            (h, i) = argmax of f(x) over the leaves of depth h
            if f(x_(h,i)) >= v_max:
                expand (h, i): evaluate its K children;  v_max = f(x_(h,i));  t = t + 1

with :math:`t` the number of expansions and :math:`h_{\max}(t) = c\, t^{p}` (Munos'
:math:`\sqrt t`: :math:`c = 1`, :math:`p = 1/2`). Cells are cut along their longest side
into thirds (``K = 3``, the standard choice; the middle third keeps the parent's centre
and value, so an expansion costs two evaluations) or halves (``bisect``, the authors'
binary tree, two evaluations per expansion). The loop is written as a generator
(:class:`~voot.optim._generator.GeneratorOptimizer`): each child evaluation is one
``ask``/``tell``.

The first told point, if the tree has not proposed one yet (the common initial point),
represents the root; otherwise the root is evaluated at the box centre. When every leaf
is deeper than :math:`h_{\max}(t)`, Munos' loop would expand nothing forever (this
happens with ``bisect``: after the root and both halves, :math:`t = 3` and
:math:`h_{\max} = 1.7 < 2`); the sweep bound is then raised to the shallowest leaf depth.
It never binds for trisection with the default :math:`\sqrt t`.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass

from voot import validation as V
from voot.optim._generator import GeneratorOptimizer, Search
from voot.optim._partition import CellTree, Scale, Split, parse_scale, parse_split, scale_weights
from voot.optim.base import OptimizerConfig


@dataclass(frozen=True)
class SOOConfig(OptimizerConfig):
    """SOO hyperparameters (defaults: Munos 2011).

    Attributes:
        split: ``"trisect"`` (K = 3, standard) or ``"bisect"`` (the authors' code).
        depth_scale: :math:`c > 0` in :math:`h_{\\max}(t) = c\\, t^{p}`.
        depth_exponent: :math:`p \\in (0, 1]` in :math:`h_{\\max}(t) = c\\, t^{p}`.
        scale: weights used to pick the longest side: ``"absolute"`` (box units),
            ``"unit"`` (unit cube) or one weight > 0 per dimension.
    """

    split: Split | str = Split.TRISECT
    depth_scale: float = 1.0
    depth_exponent: float = 0.5
    scale: Scale = "absolute"

    def __post_init__(self) -> None:
        object.__setattr__(self, "split", parse_split(self.split))
        c = self.depth_scale
        V.positive(c, "depth_scale")
        p = self.depth_exponent
        V.number(p, "depth_exponent", 0.0, 1.0, open_low=True)
        object.__setattr__(self, "scale", parse_scale(self.scale))


class SOO(GeneratorOptimizer, name="soo", config_class=SOOConfig):
    """Simultaneous Optimistic Optimization (maximisation). See the module docstring."""

    config: SOOConfig

    def _setup(self) -> None:
        super()._setup()
        cfg = self.config
        #: The cells (bounds, centres, depths, representative points, b-values).
        self.partition = CellTree(
            self.bounds, Split(cfg.split), scale_weights(cfg.scale, self.bounds)
        )
        #: Number of expansions t.
        self.n_expansions = 0
        #: Number of completed sweeps over the depths.
        self.n_sweeps = 0

    def h_max(self, t: int) -> float:
        """Deepest depth a sweep may expand after ``t`` expansions."""
        return float(self.config.depth_scale) * float(t) ** float(self.config.depth_exponent)

    @property
    def n_cells(self) -> int:
        return self.partition.n

    def _search(self) -> Search:
        tree = self.partition
        values: list[float] = []  # value of each cell's point, by cell id
        if self._n > 0:  # the initial point was told first: it represents the root
            tree.point[0] = 0
            values.append(float(self._values[0]))
        else:
            values.append((yield tree.centre[0].copy()))
            tree.point[0] = self._n - 1
            tree.at_centre[0] = True
        #: heaps[h]: (-value, cell id) of the leaves of depth h (best, then oldest, first).
        heaps: list[list[tuple[float, int]]] = [[(-values[0], 0)]]
        tree.leaf[0] = True
        n_leaves = 1
        while n_leaves > 0:
            v_max = -math.inf
            h = 0
            # Munos' bound, raised to the shallowest leaf if every leaf is deeper (the
            # sweep would otherwise expand nothing; possible with bisection or small c).
            shallowest = next(k for k, heap in enumerate(heaps) if heap)
            while h < len(heaps) and h <= max(self.h_max(self.n_expansions), shallowest):
                heap = heaps[h]
                if not heap or -heap[0][0] < v_max:
                    h += 1
                    continue
                neg_v, c = heapq.heappop(heap)
                tree.leaf[c] = False
                n_leaves -= 1
                split = tree.split(c)
                if split is None:
                    continue  # too small to split: retired; look at this depth again
                kids, keep = split
                if keep >= 0 and not tree.at_centre[c]:
                    keep = -1
                v_max = -neg_v
                self.n_expansions += 1
                if h + 1 == len(heaps):
                    heaps.append([])
                for k, kid in enumerate(kids):
                    if k == keep:
                        tree.point[kid] = tree.point[c]
                        value = values[c]
                    else:
                        value = yield tree.centre[kid].copy()
                        tree.point[kid] = self._n - 1
                    tree.at_centre[kid] = True
                    values.extend([0.0] * (kid + 1 - len(values)))
                    values[kid] = value
                    heapq.heappush(heaps[h + 1], (-value, kid))
                    tree.leaf[kid] = True
                    n_leaves += 1
                h += 1
            self.n_sweeps += 1
