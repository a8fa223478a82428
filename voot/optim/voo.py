r"""Voronoi Optimistic Optimization (VOO), the paper's Algorithm 3.

VOO keeps the evaluated points :math:`x_1, \dots, x_t` and, implicitly, their Voronoi
partition of the box :math:`X`. Each ask:

* with probability :math:`\omega` (and always while fewer than two points are known)
  samples uniformly in :math:`X`: a uniform point falls in cell :math:`C(x_i)` with
  probability proportional to its volume (the *Voronoi bias*), which is exploration;
* otherwise samples from the best cell
  :math:`C(x^*) = \{x : d(x, x^*) \le d(x, x_i)\ \forall i\}`, with
  :math:`x^* = \arg\max_i f(x_i)` (first argmax), which is exploitation.

The best cell is never built. A proposal :math:`p` is accepted when its nearest
evaluated point is :math:`x^*`; for the Euclidean metric that is the set of linear
inequalities :math:`2\,p\cdot(x_i - x^*) \le \|x_i\|^2 - \|x^*\|^2`, tested for a whole
batch of proposals with one matrix product. Proposals come from one of the best-cell
samplers of the authors' code (:class:`BestCellSampler`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from voot.optim.base import Bounds, FloatArray, Optimizer, OptimizerConfig

#: A semi-metric evaluated from many points to one: ``metric(points (n, d), y (d,)) -> (n,)``.
Metric = Callable[[FloatArray, FloatArray], FloatArray]


class BestCellSampler(StrEnum):
    """How VOO draws a point from the best Voronoi cell.

    ``centered_uniform``
        Try ``k = 1, 2, ...``: uniform in the box shrunk towards the best point by
        :math:`e^{-k}`, i.e. ``[best + (lb - best)/e^k, best + (ub - best)/e^k]``
        (the authors' synthetic-function default).
    ``gaussian``
        Try ``k``: :math:`\\mathcal N(x^*, s_k^2)` clipped to the box, with
        ``s_k = max(|ub - best|, |lb - best|) / e^k`` per dimension.
    ``uniform``
        Plain rejection sampling from the whole box (the paper's description and the
        authors' robot-domain default); after ``uniform_max_tries`` failures it returns
        the proposal closest to the best point and, if ``uniform_switch_to_gaussian``,
        uses ``gaussian`` for the rest of this optimiser's life.
    """

    CENTERED_UNIFORM = "centered_uniform"
    GAUSSIAN = "gaussian"
    UNIFORM = "uniform"


@dataclass(frozen=True)
class VOOConfig(OptimizerConfig):
    """VOO hyperparameters (defaults: the paper's synthetic-function setting).

    Attributes:
        omega: exploration probability :math:`\\omega \\in [0, 1]` (paper: 0.001 on the
            synthetic functions; grid {0.001, 0.01, 0.05, 0.1, 0.3, 0.5} elsewhere).
        sampler: best-cell sampler, see :class:`BestCellSampler`.
        max_tries: try cap of ``centered_uniform`` and ``gaussian``; when reached, the
            proposal closest to the best point is returned.
        uniform_max_tries: try cap of ``uniform`` before its fallback (original: 1000).
        uniform_switch_to_gaussian: after a failed ``uniform`` search, switch to
            ``gaussian`` for good (the original's behaviour).
        metric: optional semi-metric ``metric(points, y) -> distances``; Euclidean if None.
        batch_size: proposals tested per matrix product (speed only; changes the random
            stream, not the distribution).
    """

    omega: float = 0.001
    sampler: BestCellSampler | str = BestCellSampler.CENTERED_UNIFORM
    max_tries: int = 1000
    uniform_max_tries: int = 1000
    uniform_switch_to_gaussian: bool = True
    metric: Metric | None = None
    batch_size: int = 8

    def __post_init__(self) -> None:
        if not (isinstance(self.omega, int | float) and 0.0 <= float(self.omega) <= 1.0):
            raise ValueError(f"omega must be a probability in [0, 1], got {self.omega!r}")
        try:
            object.__setattr__(self, "sampler", BestCellSampler(self.sampler))
        except ValueError:
            valid = ", ".join(s.value for s in BestCellSampler)
            raise ValueError(
                f"unknown sampler {self.sampler!r}; valid samplers are: {valid}"
            ) from None
        for name in ("max_tries", "uniform_max_tries", "batch_size"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
        if self.metric is not None and not callable(self.metric):
            raise ValueError("metric must be callable metric(points, y) -> distances, or None")

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"omega": [0.001, 0.01, 0.05, 0.1, 0.3, 0.5]}


class VOO(Optimizer):
    """Voronoi Optimistic Optimization (maximisation). See the module docstring."""

    name: ClassVar[str] = "voo"
    config_class: ClassVar[type[OptimizerConfig]] = VOOConfig
    supports_revalue: ClassVar[bool] = True
    config: VOOConfig

    def __init__(
        self,
        bounds: Bounds | ArrayLike,
        config: OptimizerConfig | None = None,
        seed: int | np.random.SeedSequence | None = None,
        initial_point: ArrayLike | None = None,
    ) -> None:
        super().__init__(bounds, config, seed, initial_point)
        self._sqnorm = np.empty(self._xs.shape[0])
        self._dist_best = np.empty(0)
        self._dist_best_n = 0
        self._dist_best_index = -1
        self._nearest = np.empty(0, dtype=np.intp)
        self._nearest_key = (-1, -1)
        self.sampler = BestCellSampler(self.config.sampler)
        #: Number of proposals rejected so far (a diagnostic of the best-cell sampler).
        self.n_rejected = 0
        #: Number of asks that hit a try cap and returned the closest proposal.
        self.n_fallbacks = 0

    # ----- hooks --------------------------------------------------------------------
    def _tell(self, x: FloatArray, value: float) -> None:
        i = self._n - 1
        if self._sqnorm.shape[0] < self._xs.shape[0]:
            grown = np.empty(self._xs.shape[0])
            grown[:i] = self._sqnorm[:i]
            self._sqnorm = grown
        self._sqnorm[i] = float(x @ x)

    def _ask(self) -> FloatArray:
        explore = self.rng.random() <= self.config.omega
        if explore or self._n < 2:
            return self.bounds.sample(self.rng)
        return self.sample_best_cell()

    # ----- best-cell sampling ---------------------------------------------------------
    def in_best_cell(self, proposals: FloatArray) -> np.ndarray:
        """Boolean mask: is each row of ``proposals`` (m, d) in the best point's cell?"""
        xs = self._xs[: self._n]
        metric = self.config.metric
        if metric is not None:
            mask = np.empty(proposals.shape[0], dtype=bool)
            for k, p in enumerate(proposals):
                d = metric(xs, p)
                mask[k] = d[self._best_index] <= d.min()
            return mask
        return self._closer_to_best(proposals, np.arange(self._n))

    def _closer_to_best(self, proposals: FloatArray, idx: np.ndarray) -> np.ndarray:
        """Mask: is each proposal at least as close to x* as to every point in ``idx``?"""
        b = self._best_index
        best = self._xs[b]
        pts = self._xs[idx]
        # |p - x_i|^2 >= |p - x*|^2  <=>  2 p.(x_i - x*) <= |x_i|^2 - |x*|^2
        lhs = 2.0 * (proposals @ pts.T - (proposals @ best)[:, None])
        rhs = self._sqnorm[idx] - self._sqnorm[b]
        return np.all(lhs <= rhs + 1e-12 * (1.0 + np.abs(rhs)), axis=1)

    def _first_in_best_cell(self, proposals: FloatArray) -> int:
        """Index of the first proposal inside the best cell, or -1 if none is.

        Exact, and much cheaper than testing every point when n is large: a proposal at
        distance r from x* can only be closer to points within 2r of x* (triangle
        inequality), and it is usually rejected by one of x*'s nearest neighbours, which
        are tested first for the whole batch.
        """
        if self.config.metric is not None:
            ok = np.flatnonzero(self.in_best_cell(proposals))
            return int(ok[0]) if ok.size else -1
        dist = self._distances_to_best()
        survivors = np.flatnonzero(self._closer_to_best(proposals, self._nearest_to_best()))
        best = self._xs[self._best_index]
        for i in survivors:
            p = proposals[i : i + 1]
            r = float(np.sqrt(np.sum((p[0] - best) ** 2)))
            near = np.flatnonzero(dist <= 2.0 * r * (1.0 + 1e-9))
            if self._closer_to_best(p, near)[0]:
                return int(i)
        return -1

    def _nearest_to_best(self, k: int = 32) -> np.ndarray:
        """Indices of the (up to) k told points nearest to x* (cached until n or x* change)."""
        key = (self._best_index, self._n)
        if self._nearest_key != key:
            dist = self._distances_to_best()
            if dist.size <= k:
                self._nearest = np.arange(dist.size)
            else:
                self._nearest = np.argpartition(dist, k)[:k]
            self._nearest_key = key
        return self._nearest

    def _distances_to_best(self) -> FloatArray:
        """Euclidean distance of every told point to the best one (cached, O(d) per tell)."""
        b, n = self._best_index, self._n
        if self._dist_best_index != b:
            self._dist_best = np.empty(self._xs.shape[0])
            self._dist_best_n = 0
            self._dist_best_index = b
        if self._dist_best.shape[0] < n:
            grown = np.empty(self._xs.shape[0])
            grown[: self._dist_best_n] = self._dist_best[: self._dist_best_n]
            self._dist_best = grown
        if self._dist_best_n < n:
            diff = self._xs[self._dist_best_n : n] - self._xs[b]
            self._dist_best[self._dist_best_n : n] = np.sqrt(np.einsum("ij,ij->i", diff, diff))
            self._dist_best_n = n
        return self._dist_best[:n]

    def _proposals(self, first_try: int, count: int) -> FloatArray:
        """Proposals for tries ``first_try .. first_try + count - 1`` (1-based)."""
        best = self._xs[self._best_index]
        lb, ub = self.bounds.lower, self.bounds.upper
        if self.sampler is BestCellSampler.UNIFORM:
            return self.bounds.sample(self.rng, count)
        k = np.arange(first_try, first_try + count, dtype=np.float64)[:, None]
        shrink = np.exp(-k)
        if self.sampler is BestCellSampler.CENTERED_UNIFORM:
            lo = best + (lb - best) * shrink
            hi = best + (ub - best) * shrink
            return lo + self.rng.random((count, best.size)) * (hi - lo)
        scale = np.maximum(np.abs(ub - best), np.abs(lb - best)) * shrink
        return np.clip(best + scale * self.rng.standard_normal((count, best.size)), lb, ub)

    def sample_best_cell(self) -> FloatArray:
        """Draw one point from the best Voronoi cell (with the configured sampler)."""
        cfg = self.config
        uniform = self.sampler is BestCellSampler.UNIFORM
        cap = cfg.uniform_max_tries if uniform else cfg.max_tries
        best = self._xs[self._best_index]
        closest: FloatArray | None = None
        closest_d = math.inf
        tried = 0
        batch = cfg.batch_size
        while tried < cap:
            m = min(batch, cap - tried)
            props = self._proposals(tried + 1, m)
            first = self._first_in_best_cell(props)
            if first >= 0:
                self.n_rejected += first
                return props[first]
            self.n_rejected += m
            d = np.einsum("ij,ij->i", props - best, props - best)
            j = int(np.argmin(d))
            if d[j] < closest_d:
                closest, closest_d = props[j], float(d[j])
            tried += m
            batch = min(batch * 2, 256)
        self.n_fallbacks += 1
        if uniform and cfg.uniform_switch_to_gaussian:
            self.sampler = BestCellSampler.GAUSSIAN
        assert closest is not None
        return closest.copy()
