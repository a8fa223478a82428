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
(updated in O(d) per tell) and a whole batch of tries is tested against them with one
matrix product; a surviving proposal is accepted at once if no other point lies within
:math:`2\|q\|`, and checked against those points otherwise, found among the
:data:`NEAR` points nearest to :math:`x^*`. When :math:`x^*` improves, these sets move
to the new best point from the old near set alone whenever a distance bound shows that
suffices, in O(NEAR d) rather than O(nd) (see :class:`_BestCell`), so the cost per ask
hardly depends on how often the best point improves. Working relative to :math:`x^*`
keeps the test accurate when the points cluster far below the scale of the box, which
VOO's exploitation does: its best cell shrinks geometrically with the evaluations spent
in it.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

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
        tie_break: which of several points sharing the best value is :math:`x^*` for an
            exploitation ask: ``first`` (the first told; default) or ``random`` (uniform
            among them, drawn at each such ask: the authors' ``get_best_evaled_action``).
            With no tie the two are the same and ``random`` draws nothing.
    """

    omega: float = 0.001
    sampler: BestCellSampler | str = BestCellSampler.CENTERED_UNIFORM
    max_tries: int = 1000
    uniform_max_tries: int = 1000
    uniform_switch_to_gaussian: bool = True
    metric: Metric | None = None
    batch_size: int = 8
    tie_break: str = "first"

    def __post_init__(self) -> None:
        if not (V.is_number(self.omega) and 0.0 <= float(self.omega) <= 1.0):
            raise ValueError(f"omega must be a probability in [0, 1], got {self.omega!r}")
        object.__setattr__(
            self, "sampler", V.choice(BestCellSampler, self.sampler, "sampler", "samplers")
        )
        for name in ("max_tries", "uniform_max_tries", "batch_size"):
            value = getattr(self, name)
            V.integer(value, name, 1)
        if self.metric is not None and not callable(self.metric):
            raise ValueError("metric must be callable metric(points, y) -> distances, or None")
        V.one_of(self.tie_break, "tie_break", TIE_BREAKS)

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"omega": [0.001, 0.01, 0.05, 0.1, 0.3, 0.5]}


#: Valid :attr:`VOOConfig.tie_break` values.
TIE_BREAKS: tuple[str, ...] = ("first", "random")

#: Size of the cached set of x*'s nearest neighbours that every proposal is tested against
#: first (speed only: the test stays exact, see :meth:`VOO.sample_best_cell`).
NEIGHBOURS = 64
#: Number of x*'s nearest points (from the sorted near set) that proposals surviving the
#: first test are filtered with, before the exact test (speed only).
SECOND_TIER = 256
#: Number of x*'s nearest points kept sorted, with their offsets, for the exact test: the
#: *near set*. Every other point is known to lie at least a certified distance away, so
#: the exact test, and the next best point's sets, are built from the near set alone
#: (speed only; see :class:`_BestCell`).
NEAR = 512

#: Relative slack of the lower bounds carried from one best point to the next (far above
#: the rounding error of a squared distance of 20-odd terms, far below any real gap).
_SLACK = 1e-12


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

    One object serves the whole run; :meth:`center` moves it to a new best point. It
    keeps, besides the neighbour cache:

    * the *near set*: the :data:`NEAR` points nearest to ``x*`` (exactly) and the copies
      of ``x*``, with their offsets, sorted on demand;
    * ``lb2``: a lower bound on the squared distance to ``x*`` of every point outside the
      near set and the tail (the points told since the near set was last sorted).

    Only two steps cost :math:`O(nd)`: a *full pass* (:meth:`_full`), when the near set
    cannot vouch for the new best point's neighbours, and the first exact check of a
    proposal that reaches past ``lb2`` for a given ``x*`` (every point is then tested,
    from the buffer :meth:`_whole` keeps up to date for that ``x*``).

    When ``x*`` moves by :math:`s` to ``z`` (a better point, nearly always one just told
    in the old best cell), the triangle inequality gives :math:`d(x_i, z) \\ge
    \\sqrt{lb2} - s` for every point outside, so the new near set is built from the old
    near set and tail alone (:math:`O(\\text{NEAR} \\cdot d)`) whenever that bound
    still certifies the :data:`NEIGHBOURS` + 1 nearest points of ``z``. Rebuilding from
    every point at each improvement made VOO two to four times slower per ask on an
    objective where ``x*`` keeps improving (a sphere) than on one where it has settled;
    now the difference is about 1.5x (``voot-bench voo-speed``, docs/voo.md).

    Attributes:
        v, h, k2: the (up to) :data:`NEIGHBOURS` points nearest to ``x*`` other than its
            copies (offsets :math:`v_i`, :math:`\\|v_i\\|^2/2`, :math:`\\|v_i\\|^2`),
            exactly: the cache every proposal is tested against first.
        out2: squared distance of the nearest point *not* in that cache (``inf`` if none).
        near, d2s, vs, hs: the near set (indices, squared distances, offsets, halves),
            sorted by distance when ``ordered``. Copies of ``x*`` (distance 0; the
            first ``z0`` entries once sorted) are in it, for when ``x*`` moves, but are
            skipped by the tests and the cache: they cannot reject a proposal (0 <= 0).
        lb2: the lower bound above (``inf``: no such point).
        tail, td2: the points ``tail .. n-1``, told since the last sort and tested
            unsorted, and their squared distances.
    """

    __slots__ = (
        "a",
        "b",
        "bd2",
        "best",
        "buf",
        "c",
        "count",
        "d2s",
        "h",
        "hs",
        "k2",
        "lb2",
        "lower",
        "n",
        "near",
        "ordered",
        "out2",
        "tail",
        "td2",
        "upper",
        "v",
        "vs",
        "whole",
        "z0",
    )

    #: Points told after the sort that :meth:`check` tests unsorted before re-sorting.
    UNSORTED_MAX = 128

    def __init__(self, lower: FloatArray, upper: FloatArray) -> None:
        d = lower.shape[0]
        self.lower = lower
        self.upper = upper
        self.b = -1
        self.n = 0
        self.best = self.a = self.c = np.empty(d)
        self.v = np.empty((NEIGHBOURS, d))
        self.k2 = np.empty(NEIGHBOURS)
        self.h = np.empty(NEIGHBOURS)
        self.count = 0
        self.out2 = math.inf
        self.near = np.empty(0, dtype=np.intp)
        self.d2s = self.hs = np.empty(0)
        self.vs = np.empty((0, d))
        self.ordered = True
        self.z0 = 0
        self.lb2 = math.inf
        self.tail = 0
        self.td2 = np.empty(16)
        # offsets and squared distances of the points [0, whole) from x*, for a full pass
        # or a proposal that reaches past the near set; kept between uses, as a fresh
        # (n, d) array costs more in page faults than the subtraction written into it
        self.buf = np.empty((0, d))
        self.bd2 = np.empty(0)
        self.whole = 0

    # ----- moving to a new best point -----------------------------------------------------
    def center(self, xs: FloatArray, b: int) -> None:
        """Make ``xs[b]`` the best point (``xs`` are all told points)."""
        self.whole = 0
        if self.b >= 0 and self.lb2 > 0.0:
            step = xs[b] - self.best
            s = math.sqrt(float(step @ step))
            near, lb2 = self.near, self.lb2
            if near.size > NEAR:
                near, lb2 = self._nearest(near, self.d2s, NEAR + self._zeros(self.d2s), lb2)
            lb = math.sqrt(lb2) * (1.0 - _SLACK) - s * (1.0 + _SLACK)
            if lb > 0.0:
                tail = np.arange(self.tail, xs.shape[0], dtype=np.intp)
                if self._gather(xs, b, np.concatenate((near, tail)), lb * lb * (1.0 - _SLACK)):
                    return
        self._full(xs, b)

    def _gather(self, xs: FloatArray, b: int, cand: np.ndarray, lb2: float) -> bool:
        """Rebuild around ``xs[b]`` from the points ``cand`` (all others at ``>= lb2``).

        Returns False (and changes nothing) when ``lb2`` does not certify the
        :data:`NEIGHBOURS` + 1 nearest points: then only a full pass can find them.
        """
        best = xs[b].copy()
        diff = np.take(xs, cand, axis=0)
        diff -= best
        d2 = np.einsum("ij,ij->i", diff, diff)
        cache, out2 = self._cache_of(d2)
        if lb2 < out2:
            return False
        self._commit(xs.shape[0], b, best, cand, d2, diff, lb2)
        self._fill_cache(cache, out2)
        return True

    def _full(self, xs: FloatArray, b: int) -> None:
        """Make ``xs[b]`` the best point from every point (:math:`O(nd)`): the near set is
        its :data:`NEAR` nearest, and :meth:`_whole` stays valid for it."""
        n = xs.shape[0]
        best = xs[b].copy()
        self.best = best
        self.whole = 0
        self._whole(xs, n)
        diff, d2 = self.buf[:n], self.bd2[:n]
        near, lb2 = self._nearest(np.arange(n), d2, NEAR + self._zeros(d2), math.inf)
        self._commit(n, b, best, near, d2[near], diff[near], lb2)
        self._fill_cache(*self._cache_of(self.d2s))

    def _whole(self, xs: FloatArray, n: int) -> None:
        """Offsets and squared distances of all points ``xs[:n]`` in ``buf`` and ``bd2``
        (extended from the ``whole`` rows already there, which belong to ``x*``)."""
        w = self.whole
        if w >= n:
            return
        if self.buf.shape[0] < n:
            buf, bd2 = np.empty((2 * n, self.buf.shape[1])), np.empty(2 * n)
            buf[:w] = self.buf[:w]
            bd2[:w] = self.bd2[:w]
            self.buf, self.bd2 = buf, bd2
        diff = self.buf[w:n]
        np.subtract(xs[w:n], self.best, out=diff)
        np.einsum("ij,ij->i", diff, diff, out=self.bd2[w:n])
        self.whole = n

    @staticmethod
    def _nearest(idx: np.ndarray, d2: FloatArray, m: int, lb2: float) -> tuple[np.ndarray, float]:
        """The (at most) ``m`` entries of ``idx`` nearest by ``d2`` (unsorted), and the
        lower bound ``lb2`` lowered to the nearest entry left out."""
        if idx.size > m:
            part = np.argpartition(d2, m)
            cut = float(d2[part[m]])
            if cut < math.inf:  # (overflowed distances are never left out)
                return idx[part[:m]], min(lb2, cut)
        return idx, lb2

    def _commit(
        self,
        n: int,
        b: int,
        best: FloatArray,
        near: np.ndarray,
        d2s: FloatArray,
        vs: FloatArray,
        lb2: float,
    ) -> None:
        self.b = b
        self.n = n
        self.best = best
        self.a = self.lower - best  # the box, relative to x*
        self.c = self.upper - best
        self.near = near
        self.d2s = d2s
        self.vs = vs
        self.hs = 0.5 * d2s
        self.ordered = False
        self.lb2 = lb2
        self.tail = n

    @staticmethod
    def _zeros(d2: FloatArray) -> int:
        """Number of copies of x* (distance 0) among ``d2``."""
        return int(np.count_nonzero(d2 == 0.0))

    @staticmethod
    def _cache_of(d2: FloatArray) -> tuple[np.ndarray, float]:
        """Positions of the :data:`NEIGHBOURS` smallest ``d2`` other than 0 (copies of x*)
        and inf (overflow), and the next smallest such ``d2`` (``inf`` if none)."""
        if d2.size > NEIGHBOURS:
            k = NEIGHBOURS + _BestCell._zeros(d2)
            if d2.size > k:
                part = np.argpartition(d2, k)
                sel = part[:k]
                v = d2[sel]
                return sel[(v > 0.0) & (v < math.inf)], float(d2[part[k]])
        return np.flatnonzero((d2 > 0.0) & (d2 < math.inf)), math.inf

    def _fill_cache(self, sel: np.ndarray, out2: float) -> None:
        """The neighbour cache: entries ``sel`` of the near set."""
        count = sel.size
        self.count = count
        self.v[:count] = self.vs[sel]
        self.k2[:count] = self.d2s[sel]
        self.h = 0.5 * self.k2
        self.out2 = out2

    # ----- the test ---------------------------------------------------------------------
    def first_inside(self, xs: FloatArray, q: FloatArray) -> int:
        """Index of the first proposal ``x* + q[i]`` inside the best cell, or -1.

        ``xs`` are all told points (``xs[:self.n]`` are incorporated). The whole batch is
        tested against the cached neighbours; survivors (if they need it) against the
        :data:`SECOND_TIER` nearest points of the near set, a cheap filter that settles
        most of them at once; then, in order, exactly by :meth:`check`.
        """
        ok = (q @ self.v[: self.count].T <= self.h[: self.count]).all(axis=1)
        survivors = np.flatnonzero(ok)
        if survivors.size == 0:
            return -1
        first = q[survivors[0]]
        if 4.0 * float(first @ first) * (1.0 + 1e-9) < self.out2:
            return int(survivors[0])
        self._sort(xs)
        z = self.z0
        m = min(SECOND_TIER, self.d2s.size - z)
        if m > self.count and survivors.size > 1:
            keep = (q[survivors] @ self.vs[z : z + m].T <= self.hs[z : z + m]).all(axis=1)
            survivors = survivors[keep]
        for j in survivors.tolist():
            if self.check(xs, q[j]):
                return int(j)
        return -1

    def check(self, xs: FloatArray, q: FloatArray) -> bool:
        """Exact test of a proposal ``x* + q`` that passed the nearest-neighbour test.

        Only points within :math:`2\\|q\\|` of ``x*`` can be closer to ``x* + q`` than
        ``x*`` is (triangle inequality): if the cached neighbours include them all, the
        proposal is inside; otherwise it is tested against the near set up to that radius
        and against every point told since the sort, or, if the radius reaches past
        ``lb2``, against every point (testing more points than needed does not change the
        answer).
        """
        lim = 4.0 * float(q @ q) * (1.0 + 1e-9)
        if lim < self.out2:
            return True
        n = self.n
        self._sort(xs)
        if lim >= self.lb2:  # beyond the near set: test every point
            self._whole(xs, n)
            return bool((self.buf[:n] @ q <= 0.5 * self.bd2[:n]).all())
        c, z = int(np.searchsorted(self.d2s, lim, side="right")), self.z0
        if c > z and not (self.vs[z:c] @ q <= self.hs[z:c]).all():
            return False
        if self.tail < n:
            v = xs[self.tail : n] - self.best
            return bool((v @ q <= 0.5 * self.td2[: n - self.tail]).all())
        return True

    def _sort(self, xs: FloatArray) -> None:
        """Sort the near set by distance, with the tail if it holds more than
        :attr:`UNSORTED_MAX` points (keeping the :data:`NEAR` nearest, or as many as
        before if more)."""
        n, t = self.n, self.tail
        if n - t > self.UNSORTED_MAX:
            idx = np.concatenate((self.near, np.arange(t, n)))
            d2 = np.concatenate((self.d2s, self.td2[: n - t]))
            vs = np.concatenate((self.vs, xs[t:n] - self.best))
            keep, lb2 = self._nearest(np.arange(idx.size), d2, NEAR + self._zeros(d2), self.lb2)
            self._commit(n, self.b, self.best, idx[keep], d2[keep], vs[keep], lb2)
        if not self.ordered:
            order = np.argsort(self.d2s, kind="stable")
            self.near = self.near[order]
            self.d2s = self.d2s[order]
            self.vs = self.vs[order]
            self.hs = 0.5 * self.d2s
            self.ordered = True
            self.z0 = int(np.searchsorted(self.d2s, 0.0, side="right"))

    def extend(self, xs: FloatArray) -> None:
        """Incorporate the points ``xs[self.n:]`` told since (``x*`` unchanged)."""
        n0, n = self.n, xs.shape[0]
        diff = xs[n0:] - self.best
        d2 = np.einsum("ij,ij->i", diff, diff)
        t = self.tail
        if self.td2.shape[0] < n - t:
            grown = np.empty(2 * (n - t))
            grown[: n0 - t] = self.td2[: n0 - t]
            self.td2 = grown
        self.td2[n0 - t : n - t] = d2
        for j, dj in enumerate(d2.tolist()):
            if dj == 0.0 or dj == math.inf:  # copies of x* (and overflowed distances)
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


class VOO(Optimizer, name="voo", config_class=VOOConfig, supports_revalue=True):
    """Voronoi Optimistic Optimization (maximisation). See the module docstring."""

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
    def in_best_cell(self, proposals: ArrayLike, b: int | None = None) -> np.ndarray:
        """Boolean mask: is each row of ``proposals`` (m, d) in the best point's cell?

        Brute force against every told point (ties count as inside, as x* is the first
        point of its cell). ``b``: the index of the cell's site (default: the best point).
        """
        props = np.atleast_2d(np.asarray(proposals, dtype=np.float64))
        xs = self._xs[: self._n]
        if b is None:
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

    def _exploited_index(self) -> int:
        """The index of :math:`x^*` for this ask: the best point, or with
        ``tie_break="random"`` one of the points sharing its value, drawn uniformly."""
        b = self._best_index
        if self.config.tie_break == "random":
            values = self._values[: self._n]
            tied = np.flatnonzero(values == values[b])
            if tied.size > 1:
                b = int(tied[self.rng.integers(tied.size)])
        return b

    def _best_cell(self) -> _BestCell:
        """The best-cell cache, moved when x* changed, extended by new points."""
        cell = self._cell
        n = self._n
        if cell is None:
            cell = self._cell = _BestCell(self._lower, self._upper)
        b = self._exploited_index()
        if cell.b != b:
            cell.center(self._xs[:n], b)
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
            hits = np.flatnonzero(self.in_best_cell(q + cell.best, cell.b))
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
