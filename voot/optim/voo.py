r"""Voronoi Optimistic Optimization (VOO), the paper's Algorithm 3.

VOO keeps the evaluated points :math:`x_1, \dots, x_t` and, implicitly, their Voronoi
partition of the box :math:`X`. Each ask:

* with probability :math:`\omega` (and always while fewer than two points are known)
  samples uniformly in :math:`X`: a uniform point falls in cell :math:`C(x_i)` with
  probability proportional to its volume (the *Voronoi bias*), which is exploration;
* otherwise samples from the best cell
  :math:`C(x^*) = \{x : d(x, x^*) \le d(x, x_i)\ \forall i\}`, with
  :math:`x^* = \arg\max_i f(x_i)` (first argmax), which is exploitation.

The best cell is never built. A proposal :math:`p = x^* + q` is accepted when its
nearest evaluated point is :math:`x^*` (ties count as inside); for the Euclidean metric
that is the set of linear inequalities :math:`q \cdot v_i \le \|v_i\|^2 / 2` with
:math:`v_i = x_i - x^*`. Proposals come from one of the best-cell samplers of the
authors' code (:class:`BestCellSampler`).

Speed (exact): only points within :math:`2\|q\|` of :math:`x^*` can reject :math:`p`
(triangle inequality). The :data:`NEIGHBOURS` points nearest to :math:`x^*` are cached
(updated in O(d) per tell, rebuilt in O(nd) when :math:`x^*` changes) and a whole batch
of tries is tested against them with one matrix product; a surviving proposal is
accepted at once if no other point lies within :math:`2\|q\|`, and checked against
those points otherwise. Working relative to :math:`x^*` keeps the test accurate when
the points cluster far below the scale of the box, which VOO's exploitation does: its
best cell shrinks geometrically with the evaluations spent in it.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from voot import validation as V
from voot.optim.base import FloatArray, Optimizer, OptimizerConfig

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
            A metric with a ``pairwise(points, ys) -> (m, n)`` method has a batch of
            proposals tested at once (speed only; it must agree with the single calls).
        batch_size: minimum number of tries drawn and tested together (speed only;
            changes the random stream, not the distribution). The first batch of an ask
            grows to cover the try accepted at the previous ask; later batches double,
            up to 256.
    """

    omega: float = 0.001
    sampler: BestCellSampler | str = BestCellSampler.CENTERED_UNIFORM
    max_tries: int = 1000
    uniform_max_tries: int = 1000
    uniform_switch_to_gaussian: bool = True
    metric: Metric | None = None
    batch_size: int = 8

    def __post_init__(self) -> None:
        if not (V.is_number(self.omega) and 0.0 <= float(self.omega) <= 1.0):
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
            V.integer(value, name, 1)
        if self.metric is not None and not callable(self.metric):
            raise ValueError("metric must be callable metric(points, y) -> distances, or None")

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"omega": [0.001, 0.01, 0.05, 0.1, 0.3, 0.5]}


#: Size of the cached set of x*'s nearest neighbours that every proposal is tested against
#: first (speed only: the test stays exact, see :meth:`VOO.sample_best_cell`).
NEIGHBOURS = 64
#: Number of x*'s nearest points (from a sorted copy, built on demand) that proposals
#: surviving the first test are filtered with, before the exact test (speed only).
SECOND_TIER = 256


@functools.lru_cache(maxsize=8)
def _shrink_table(cap: int) -> FloatArray:
    """Read-only column of :math:`e^{-k}`, k = 1..cap: the shrink factor of try k."""
    table = np.exp(-np.arange(1.0, cap + 1.0))[:, None]
    table.setflags(write=False)
    return table


class _BestCell:
    """What the best-cell test needs about the current best point ``x*`` (index ``b``).

    Coordinates are relative to ``x*``: with :math:`v_i = x_i - x^*` and a proposal
    :math:`p = x^* + q`, :math:`\\|p - x^*\\| \\le \\|p - x_i\\|` iff
    :math:`q \\cdot v_i \\le \\|v_i\\|^2 / 2`. Relative coordinates keep this test accurate
    when the points cluster far below the scale of the box (they do: on a smooth function
    VOO's best neighbours reach the floating-point resolution of ``x*`` within a few
    thousand evaluations in 20-D).

    Attributes:
        d2: squared distance of every incorporated point to ``x*`` (``inf`` for ``x*``
            and its exact copies, which cannot reject anything).
        v, h, k2: the (up to) :data:`NEIGHBOURS` other points nearest to ``x*`` (offsets
            :math:`v_i`, :math:`\\|v_i\\|^2/2`, :math:`\\|v_i\\|^2`), exactly.
        out2: squared distance of the nearest point *not* in that set (``inf`` if none).
        sorted_n, d2s, vs, hs: built on demand by :meth:`check`: the first ``sorted_n``
            points sorted by distance to ``x*`` (squared distances, offsets, halves).
    """

    __slots__ = (
        "a",
        "b",
        "best",
        "c",
        "count",
        "d2",
        "d2s",
        "h",
        "hs",
        "k2",
        "n",
        "out2",
        "sorted_n",
        "v",
        "vs",
    )

    #: Points told after the sort that :meth:`check` tests unsorted before re-sorting.
    UNSORTED_MAX = 128

    def __init__(self, xs: FloatArray, b: int, lower: FloatArray, upper: FloatArray) -> None:
        n = xs.shape[0]
        self.b = b
        self.n = n
        self.best = xs[b].copy()
        self.a = lower - self.best  # the box, relative to x*
        self.c = upper - self.best
        diff = xs - self.best
        d2 = np.einsum("ij,ij->i", diff, diff)
        # x* and exact copies of it never reject a proposal (0 <= 0): leave them out
        d2[d2 == 0.0] = math.inf
        self.d2 = np.empty(max(16, 2 * n))
        self.d2[:n] = d2
        finite = np.flatnonzero(d2 < math.inf)
        if finite.size > NEIGHBOURS:
            part = np.argpartition(d2, NEIGHBOURS)
            idx = part[:NEIGHBOURS]
            self.out2 = float(d2[part[NEIGHBOURS]])
        else:
            idx = finite
            self.out2 = math.inf
        self.count = idx.size
        self.v = np.empty((NEIGHBOURS, xs.shape[1]))
        self.v[: self.count] = diff[idx]
        self.k2 = np.empty(NEIGHBOURS)
        self.k2[: self.count] = d2[idx]
        self.h = 0.5 * self.k2
        self.sorted_n = 0
        self.d2s = self.hs = np.empty(0)
        self.vs = np.empty((0, xs.shape[1]))

    def first_inside(self, xs: FloatArray, q: FloatArray) -> int:
        """Index of the first proposal ``x* + q[i]`` inside the best cell, or -1.

        ``xs`` are all told points (``xs[:self.n]`` are incorporated). The whole batch is
        tested against the cached neighbours; survivors (if they need it) against the
        :data:`SECOND_TIER` nearest points of the sorted structure, a cheap filter that
        settles most of them at once; then, in order, exactly by :meth:`check`.
        """
        ok = (q @ self.v[: self.count].T <= self.h[: self.count]).all(axis=1)
        survivors = np.flatnonzero(ok)
        if survivors.size == 0:
            return -1
        first = q[survivors[0]]
        if 4.0 * float(first @ first) * (1.0 + 1e-9) < self.out2:
            return int(survivors[0])
        self._sort(xs)
        m = min(SECOND_TIER, self.d2s.size)
        if m > self.count and survivors.size > 1:
            keep = (q[survivors] @ self.vs[:m].T <= self.hs[:m]).all(axis=1)
            survivors = survivors[keep]
        for j in survivors.tolist():
            if self.check(xs, q[j]):
                return int(j)
        return -1

    def check(self, xs: FloatArray, q: FloatArray) -> bool:
        """Exact test of a proposal ``x* + q`` that passed the nearest-neighbour test.

        Only points within :math:`2\\|q\\|` of ``x*`` can be closer to ``x* + q`` than
        ``x*`` is (triangle inequality): if the cached neighbours include them all, the
        proposal is inside; otherwise it is tested against the points sorted by distance
        up to that radius, and against every point told since the sort (testing more
        points than needed does not change the answer).
        """
        lim = 4.0 * float(q @ q) * (1.0 + 1e-9)
        if lim < self.out2:
            return True
        self._sort(xs)
        c = int(np.searchsorted(self.d2s, lim, side="right"))
        if c and not (self.vs[:c] @ q <= self.hs[:c]).all():
            return False
        n = self.n
        if self.sorted_n < n:
            v = xs[self.sorted_n : n] - self.best
            return bool((v @ q <= 0.5 * self.d2[self.sorted_n : n]).all())
        return True

    def _sort(self, xs: FloatArray) -> None:
        """(Re)build the sorted structure if too many points were told since the last."""
        n = self.n
        if n - self.sorted_n > self.UNSORTED_MAX or self.sorted_n == 0:
            order = np.argsort(self.d2[:n], kind="stable")
            self.d2s = self.d2[order]
            self.vs = xs[order] - self.best
            self.hs = 0.5 * self.d2s
            self.sorted_n = n

    def extend(self, xs: FloatArray) -> None:
        """Incorporate the points ``xs[self.n:]`` told since (``x*`` unchanged)."""
        n0, n = self.n, xs.shape[0]
        diff = xs[n0:] - self.best
        d2 = np.einsum("ij,ij->i", diff, diff)
        d2[d2 == 0.0] = math.inf  # copies of x*
        if self.d2.shape[0] < n:
            grown = np.empty(2 * n)
            grown[:n0] = self.d2[:n0]
            self.d2 = grown
        self.d2[n0:n] = d2
        for j, dj in enumerate(d2.tolist()):
            if dj == math.inf:
                continue
            if self.count < NEIGHBOURS:
                slot = self.count
                self.count += 1
            else:
                slot = int(self.k2.argmax())
                far = float(self.k2[slot])
                if dj >= far:
                    self.out2 = min(self.out2, dj)
                    continue
                self.out2 = min(self.out2, far)  # the evicted point is now outside
            self.v[slot] = diff[j]
            self.k2[slot] = dj
            self.h[slot] = 0.5 * dj
        self.n = n


class VOO(Optimizer):
    """Voronoi Optimistic Optimization (maximisation). See the module docstring."""

    name: ClassVar[str] = "voo"
    config_class: ClassVar[type[OptimizerConfig]] = VOOConfig
    supports_revalue: ClassVar[bool] = True
    config: VOOConfig

    def _setup(self) -> None:
        super()._setup()
        self.sampler = BestCellSampler(self.config.sampler)
        #: Number of proposals rejected so far (a diagnostic of the best-cell sampler).
        self.n_rejected = 0
        #: Number of asks that hit a try cap and returned the closest proposal.
        self.n_fallbacks = 0
        self._cell: _BestCell | None = None
        self._lower = self.bounds.lower
        self._upper = self.bounds.upper
        self._width = self.bounds.width
        self._omega = float(self.config.omega)
        # proposals of the first batch of an ask: grows to cover the try that was
        # accepted last time, so that one matrix product usually settles an ask
        self._first_batch = self.config.batch_size
        self._shrink = _shrink_table(max(self.config.max_tries, self.config.uniform_max_tries))

    # ----- hooks --------------------------------------------------------------------
    def _ask(self) -> FloatArray:
        if self._n < 2 or self.rng.random() < self._omega:
            return self.bounds.sample(self.rng)
        return self.sample_best_cell()

    # ----- best-cell sampling ---------------------------------------------------------
    def in_best_cell(self, proposals: ArrayLike) -> np.ndarray:
        """Boolean mask: is each row of ``proposals`` (m, d) in the best point's cell?

        Brute force against every told point (ties count as inside, as x* is the first
        point of its cell).
        """
        props = np.atleast_2d(np.asarray(proposals, dtype=np.float64))
        xs = self._xs[: self._n]
        b = self._best_index
        metric = self.config.metric
        if metric is not None:
            pairwise = getattr(metric, "pairwise", None)
            if pairwise is not None:  # the whole batch at once
                dist = np.asarray(pairwise(xs, props), dtype=np.float64)
                mask_all: np.ndarray = dist[:, b] <= dist.min(axis=1)
                return mask_all
            mask = np.empty(props.shape[0], dtype=bool)
            for k, p in enumerate(props):
                d = np.asarray(metric(xs, p), dtype=np.float64)
                mask[k] = d[b] <= d.min()
            return mask
        v = xs - xs[b]
        q = props - xs[b]
        return np.all(q @ v.T <= 0.5 * np.einsum("ij,ij->i", v, v), axis=1)

    def _best_cell(self) -> _BestCell:
        """The best-cell cache, rebuilt when x* changed, extended by new points."""
        cell = self._cell
        n = self._n
        if cell is None or cell.b != self._best_index:
            cell = self._cell = _BestCell(self._xs[:n], self._best_index, self._lower, self._upper)
        elif cell.n < n:
            cell.extend(self._xs[:n])
        return cell

    def _offsets(self, cell: _BestCell, first_try: int, count: int) -> FloatArray:
        """Proposals ``q = p - x*`` for tries ``first_try + 1 .. first_try + count``."""
        d = cell.best.shape[0]
        sampler = self.sampler
        if sampler is BestCellSampler.CENTERED_UNIFORM:
            # uniform in [x* + (lb - x*) e^-k, x* + (ub - x*) e^-k]
            u = self.rng.random((count, d))
            return (u * self._width + cell.a) * self._shrink[first_try : first_try + count]
        if sampler is BestCellSampler.GAUSSIAN:
            # N(x*, s_k^2) clipped to the box, s_k = max(|ub - x*|, |lb - x*|) e^-k
            z = self.rng.standard_normal((count, d))
            scale = np.maximum(cell.c, -cell.a)
            return np.clip(z * scale * self._shrink[first_try : first_try + count], cell.a, cell.c)
        return self.rng.random((count, d)) * self._width + cell.a  # uniform in the box

    def _first_inside(self, cell: _BestCell, q: FloatArray) -> int:
        """Index of the first proposal (row of ``q``) inside the best cell, or -1."""
        metric = self.config.metric
        if metric is not None:
            hits = np.flatnonzero(self.in_best_cell(q + cell.best))
            return int(hits[0]) if hits.size else -1
        return cell.first_inside(self._xs, q)

    def sample_best_cell(self) -> FloatArray:
        """Draw one point from the best Voronoi cell (with the configured sampler).

        Tries are drawn in batches; a batch is tested against x*'s cached nearest
        neighbours with one matrix product, survivors against a larger set of near
        points, and the first remaining one exactly against every point that could
        reject it. Accept/reject decisions are those of the brute-force test (up to
        floating-point ties), so the batching changes the random stream but not the
        distribution of the returned point.
        """
        if self._n == 0:
            raise ValueError("sample_best_cell needs at least one told point")
        cfg = self.config
        uniform = self.sampler is BestCellSampler.UNIFORM
        cap = cfg.uniform_max_tries if uniform else cfg.max_tries
        cell = self._best_cell()
        closest: FloatArray | None = None
        closest_r2 = math.inf
        tried = 0
        batch = self._first_batch
        while tried < cap:
            m = min(batch, cap - tried)
            q = self._offsets(cell, tried, m)
            j = self._first_inside(cell, q)
            if j >= 0:
                self.n_rejected += tried + j
                self._first_batch = max(
                    cfg.batch_size, min(256, tried + j + 1 + (tried + j) // 4 + 2)
                )
                return np.minimum(np.maximum(cell.best + q[j], self._lower), self._upper)
            r2 = np.einsum("ij,ij->i", q, q)
            k = int(r2.argmin())
            if r2[k] < closest_r2:
                closest, closest_r2 = q[k], float(r2[k])
            tried += m
            batch = min(batch * 2, 256)
        self.n_rejected += tried
        self.n_fallbacks += 1
        self._first_batch = max(cfg.batch_size, min(256, cap))
        if uniform and cfg.uniform_switch_to_gaussian:
            self.sampler = BestCellSampler.GAUSSIAN
        assert closest is not None
        return np.minimum(np.maximum(cell.best + closest, self._lower), self._upper)
