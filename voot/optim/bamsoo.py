r"""BaMSOO: Bayesian Multi-Scale Optimistic Optimization (Wang, Shakibi, Jin, de Freitas 2014).

BaMSOO is SOO (Munos 2011) with a Gaussian process deciding which cell points deserve a
real evaluation. The tree partitions the box: a node is a cell with a representative
point (its centre); expanding it splits the cell into ``branching`` equal parts along its
longest side (ties: the first such dimension). Every sweep walks the depths
``h = 0 .. min(depth, h_max(n))`` with :math:`h_{\max}(n) = n^{p}` (``h_max_exponent``
p, n the number of expansions so far) and expands, at each depth, the leaf with the
largest value g if it is at least the largest g expanded earlier in the sweep
(:math:`\nu_{\max}`). A new child point x is

* evaluated, :math:`g(x) = f(x)`, if its GP upper bound reaches the best value so far,
  :math:`U_N(x) = \mu(x) + B_N\sigma(x) \ge f^+`;
* otherwise *not* evaluated: :math:`g(x) = L_N(x) = \mu(x) - B_N\sigma(x)`;

then :math:`f^+ \leftarrow \max(f^+, g(x))`. Here :math:`B_N = \sqrt{2\log(\pi^2N^2/(6\eta))}`
with N the number of child points considered so far and :math:`\eta \in (0, 1)`. With an
odd ``branching`` the middle child shares its parent's centre and inherits its g (no
evaluation, no GP query).

The GP is that of :mod:`voot.optim.gp_ucb` (unit cube, RBF, marginal-likelihood fit on the
shared refit schedule) and conditions on every real evaluation, the shared
``initial_point`` included (which also seeds :math:`f^+`). ``ask``/``tell`` see real
evaluations only; GP-only decisions happen inside the search loop.

The authors' code differs; its choices are options: ``root_point="random"`` (their
partition: the root point is uniform in the box, each cell is cut in two *at its point*
along the longest side, and a child's point lies halfway between the parent's point and
the child's far face; note that the box centre is the optimum of the symmetric Griewank
and Rastrigin benchmarks, which a centred root evaluates first) and
``bound_uses_variance=True`` (:math:`\mu \pm B_N\sigma^2` instead of
:math:`\mu \pm B_N\sigma`). Their grid over :math:`\eta` was {0.1, 0.7, 0.9}.

Safety net (not in the paper, whose loop only counts real evaluations): after
``max_skips`` consecutive GP-only children the next child is evaluated anyway. Without
it BaMSOO can refine its tree for ever once :math:`f^+` is (near) the global maximum and
the GP is confident, because no upper bound reaches :math:`f^+` any more; each skip costs
one GP prediction and one tree node. Cells whose longest side is below ``min_width``
(unit-cube units) are not expanded, and when no leaf can be expanded the search ends and
asks fall back to uniform sampling.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

import numpy as np

from voot import validation as V
from voot.optim._generator import GeneratorOptimizer, Search
from voot.optim._surrogate import Surrogate, SurrogateConfig
from voot.optim.base import FloatArray
from voot.optim.gp import GaussianProcess


class RootPoint(StrEnum):
    """Where the tree's points lie: ``center`` (cell centres, SOO as published) or
    ``random`` (the authors' code: random root point, binary cuts at the points)."""

    CENTER = "center"
    RANDOM = "random"


@dataclass(frozen=True)
class BaMSOOConfig(SurrogateConfig):
    """BaMSOO hyperparameters (GP options: see :class:`SurrogateConfig`).

    Attributes:
        eta: confidence parameter :math:`\\eta \\in (0, 1)` of :math:`B_N` (the authors'
            grid {0.1, 0.7, 0.9}).
        branching: children per expansion (3: trisection, as in SOO/DIRECT; 2: the
            authors' binary split). Must be 2 with ``root_point="random"``.
        root_point: see :class:`RootPoint`.
        h_max_exponent: p in :math:`h_{\\max}(n) = n^p` (SOO's usual choice 1/2).
        bound_uses_variance: use :math:`\\mu \\pm B_N\\sigma^2` like the authors' code
            instead of the paper's :math:`\\mu \\pm B_N\\sigma`.
        max_skips: consecutive GP-only children after which the next one is evaluated
            (a safety net, see the module docstring).
        min_width: cells whose longest side (unit cube) is below this are not expanded.
    """

    eta: float = 0.1
    branching: int = 3
    root_point: RootPoint | str = RootPoint.CENTER
    h_max_exponent: float = 0.5
    bound_uses_variance: bool = False
    max_skips: int = 1000
    min_width: float = 1e-12

    def __post_init__(self) -> None:
        super().__post_init__()
        e = self.eta
        V.number(e, "eta", 0.0, 1.0, open_low=True, open_high=True)
        V.integer(self.branching, "branching", 2)
        object.__setattr__(self, "root_point", V.choice(RootPoint, self.root_point, "root_point"))
        if self.root_point is RootPoint.RANDOM and self.branching != 2:
            raise ValueError(
                f"root_point='random' (the authors' partition) needs branching=2, got {self.branching}"
            )
        p = self.h_max_exponent
        V.number(p, "h_max_exponent", 0.0, 1.0, open_low=True)
        V.flag(self.bound_uses_variance, "bound_uses_variance")
        V.integer(self.max_skips, "max_skips", 1)
        w = self.min_width
        V.number(w, "min_width", 0.0, 1.0, open_low=True, open_high=True)

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"eta": [0.1, 0.7, 0.9]}


@dataclass(eq=False)
class _Node:
    """A cell ``[lo, hi]`` of the unit cube, its representative point and value g.

    The point is the cell centre unless given (the authors' anchored partition).
    """

    lo: FloatArray
    hi: FloatArray
    depth: int
    point: FloatArray | None = None
    g: float = -math.inf
    evaluated: bool = False
    width: float = field(init=False)

    def __post_init__(self) -> None:
        if self.point is None:
            self.point = 0.5 * (self.lo + self.hi)
        self.width = float(np.max(self.hi - self.lo))

    @property
    def x(self) -> FloatArray:
        assert self.point is not None
        return self.point

    def split(self, k: int) -> list[_Node]:
        """``k`` equal children along the longest side (first such dimension); with odd
        ``k`` the middle child's centre is this cell's centre, exactly."""
        width = self.hi - self.lo
        j = int(np.argmax(width))
        edges = self.lo[j] + width[j] * np.arange(k + 1) / k
        edges[-1] = self.hi[j]
        children = []
        for i in range(k):
            lo, hi = self.lo.copy(), self.hi.copy()
            lo[j], hi[j] = edges[i], edges[i + 1]
            children.append(_Node(lo, hi, self.depth + 1))
        if k % 2 == 1:
            children[k // 2].point = self.x.copy()
        return children

    def split_at_point(self) -> list[_Node]:
        """The authors' binary split: cut the longest side at this node's point; each
        child's point is halfway between that point and the child's far face."""
        j = int(np.argmax(self.hi - self.lo))
        p = self.x
        left_hi, right_lo = self.hi.copy(), self.lo.copy()
        left_hi[j] = right_lo[j] = p[j]
        left_x, right_x = p.copy(), p.copy()
        left_x[j] = 0.5 * (self.lo[j] + p[j])
        right_x[j] = 0.5 * (p[j] + self.hi[j])
        return [
            _Node(self.lo.copy(), left_hi, self.depth + 1, left_x),
            _Node(right_lo, self.hi.copy(), self.depth + 1, right_x),
        ]


class BaMSOO(GeneratorOptimizer, name="bamsoo", config_class=BaMSOOConfig):
    """Bayesian Multi-Scale Optimistic Optimization. See the module docstring."""

    config: BaMSOOConfig

    def _setup(self) -> None:
        super()._setup()
        self.surrogate = Surrogate(self.bounds.dim, self.config, self.rng)
        #: Children whose value was set from the GP lower bound (not evaluated).
        self.n_skipped = 0
        #: Node expansions so far.
        self.n_expansions = 0
        #: Number of nodes in the tree.
        self.n_nodes = 0

    def _model(self) -> GaussianProcess:
        if self.surrogate.is_synced(self._n):
            return self.surrogate.gp
        return self.surrogate.sync(self.bounds.to_unit(self.xs), self.values)

    def _bounds_at(self, u: FloatArray, n_considered: int) -> tuple[float, float]:
        """``(U_N(u), L_N(u))`` from the current GP."""
        mu, sd = self._model().predict(u[None, :])
        b = math.sqrt(2.0 * math.log(math.pi**2 * n_considered**2 / (6.0 * self.config.eta)))
        spread = float(sd[0]) ** 2 if self.config.bound_uses_variance else float(sd[0])
        return float(mu[0]) + b * spread, float(mu[0]) - b * spread

    def _search(self) -> Search:
        cfg = self.config
        k = int(cfg.branching)
        d = self.bounds.dim
        anchored = cfg.root_point is RootPoint.RANDOM
        root_x = self.rng.random(d) if anchored else None
        root = _Node(np.zeros(d), np.ones(d), 0, root_x)
        root.g = yield self.bounds.from_unit(root.x)
        root.evaluated = True
        self.n_nodes = 1
        f_plus = max(root.g, self.best_value)
        # Expandable leaves per depth as max-heaps of (-g, creation order, node): the
        # first-created leaf wins ties, and g never changes once set.
        leaves: list[list[tuple[float, int, _Node]]] = [[(-root.g, 0, root)]]
        order = 1
        n_considered = 1  # N: child points considered (root included)
        skips = 0
        unlimited = False
        while True:
            v_max = -math.inf
            limit = math.inf if unlimited else float(self.n_expansions) ** cfg.h_max_exponent
            expanded = False
            h = 0
            while h < len(leaves) and h <= limit:
                level = leaves[h]
                if not level or -level[0][0] < v_max:
                    h += 1
                    continue
                node = heapq.heappop(level)[2]
                children = node.split_at_point() if anchored else node.split(k)
                for child in children:
                    if not anchored and k % 2 == 1 and child is children[k // 2]:
                        child.g, child.evaluated = node.g, node.evaluated
                        continue
                    n_considered += 1
                    upper, lower = self._bounds_at(child.x, n_considered)
                    if upper >= f_plus or skips >= cfg.max_skips:
                        child.g = yield self.bounds.from_unit(child.x)
                        child.evaluated = True
                        skips = 0
                    else:
                        child.g = lower
                        self.n_skipped += 1
                        skips += 1
                    f_plus = max(f_plus, child.g)
                if len(leaves) == h + 1:
                    leaves.append([])
                for child in children:
                    if child.width >= cfg.min_width:
                        heapq.heappush(leaves[h + 1], (-child.g, order, child))
                    order += 1
                self.n_nodes += len(children)
                self.n_expansions += 1
                v_max = node.g
                expanded = True
                h += 1
            if not expanded:
                if not any(leaves):
                    return  # every cell is below min_width
                unlimited = True  # all leaves lie deeper than h_max: lift it for one sweep
            else:
                unlimited = False
