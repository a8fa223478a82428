r"""The GP surrogate shared by the Bayesian-optimisation baselines (GP-UCB, REMBO, BaMSOO).

Three pieces:

* :class:`SurrogateConfig`: the GP and cost options every BO config inherits (kernel,
  hyperparameter bounds, refit schedule, cap on conditioned points), validated.
* :class:`Surrogate`: a :class:`~voot.optim.gp.GaussianProcess` on the unit cube kept in
  sync with the optimiser's growing data; it decides when to refit hyperparameters and
  when a cheap rank-1 update suffices.
* :func:`maximize_ucb`: maximise :math:`\mu(x) + \zeta\sigma(x)` over the unit cube the
  way the paper's baseline did: the best of many uniform random candidates (10^4), then
  L-BFGS-B with the analytic gradient from the best one (or best few).

Cost (n conditioned points, m candidates, d dimensions): a hyperparameter fit costs
``O(n^3)`` per likelihood evaluation (tens of evaluations per start); a rank-1 update
``O(n^2)``; one acquisition maximisation ``O(m n d)`` for the means plus ``O(m n^2)`` for
the standard deviations, the dominant term for large n. The refit schedule
(``refit_every``, ``refit_growth``) bounds the first, ``max_points`` bounds n.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
from scipy.optimize import minimize

from voot import validation as V
from voot.optim.base import FloatArray, OptimizerConfig
from voot.optim.gp import GaussianProcess, GPMean


class SubsetRule(StrEnum):
    """Which points the GP conditions on once there are more than ``max_points``.

    ``best``: the ``max_points`` best values. ``recent``: the ``max_points`` most recent.
    ``best_recent``: the best half and the most recent half (the recent points keep the
    acquisition from re-proposing places just evaluated; the best keep the model right
    where it matters).
    """

    BEST = "best"
    RECENT = "recent"
    BEST_RECENT = "best_recent"


def _check_pair(name: str, value: object) -> tuple[float, float]:
    if not isinstance(value, tuple | list) or len(value) != 2:
        raise ValueError(f"{name} must be a (low, high) pair, got {value!r}")
    if not (V.is_number(value[0]) and V.is_number(value[1])):
        raise ValueError(f"{name} must be a (low, high) pair of numbers, got {value!r}")
    lo, hi = float(value[0]), float(value[1])
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
        raise ValueError(f"{name} must satisfy 0 < low <= high < inf, got {value!r}")
    return lo, hi


@dataclass(frozen=True)
class SurrogateConfig(OptimizerConfig):
    """GP options shared by GP-UCB, REMBO and BaMSOO.

    The GP lives on the search box mapped to the unit cube (REMBO: the low-dimensional
    box), so the bounds below are in unit-cube lengths and standardised-target units.

    Attributes:
        ard: one length scale per dimension (default: one shared length scale, as GPy's
            ``RBF`` used by the paper's authors).
        gp_mean: prior mean, ``constant`` (data mean, as GPy's normaliser) or ``zero``.
        lengthscale_bounds: bounds of the RBF length scale(s).
        signal_variance_bounds: bounds of :math:`\\sigma_f^2`.
        noise_variance_bounds: bounds of :math:`\\sigma_n^2` (fitted like GPy's Gaussian
            likelihood; equal bounds fix it).
        fit_restarts: random restarts of the marginal-likelihood fit besides the warm start.
        fit_maxiter: L-BFGS-B iterations per start (and at most twice as many likelihood
            evaluations).
        refit_every: refit hyperparameters only when at least this many points arrived
            since the last fit (1 = every point, the original's setting for REMBO/BaMSOO;
            its GP-UCB used a frequency, e.g. 30 for Rastrigin).
        refit_growth: also require ``n >= refit_growth * n_last_fit`` (geometric spacing:
            O(log n) fits in total). 1.0 disables this condition. The paper is silent;
            the default 1.1 (every point up to n = 10, then every 10% growth: 53 fits in a
            1000-evaluation run, ~30 of its ~70 CPU-seconds in 20-D) is the cheap choice;
            ``refit_growth=1.0`` refits at every point (~40 CPU-minutes for 1000 points).
            Between fits a new point costs an ``O(n^2)`` Cholesky update.
        max_points: condition the GP on at most this many points, chosen by ``subset``
            (None: all). The default 1000 never binds at the paper's usual budgets
            (<= 1000 evaluations, so those runs are exact) and keeps the 5000-evaluation
            Shekel-20D runs feasible: without a cap one hyperparameter fit at n = 5000
            costs ~20 CPU-minutes, with it ~5-10 s and ~0.1 s per evaluation.
        subset: which points, see :class:`SubsetRule`.
    """

    ard: bool = False
    gp_mean: GPMean | str = GPMean.CONSTANT
    lengthscale_bounds: tuple[float, float] = (1e-2, 1e2)
    signal_variance_bounds: tuple[float, float] = (1e-2, 1e2)
    noise_variance_bounds: tuple[float, float] = (1e-6, 1.0)
    fit_restarts: int = 2
    fit_maxiter: int = 100
    refit_every: int = 1
    refit_growth: float = 1.1
    max_points: int | None = 1000
    subset: SubsetRule | str = SubsetRule.BEST_RECENT

    def __post_init__(self) -> None:
        V.flag(self.ard, "ard")
        object.__setattr__(self, "gp_mean", V.choice(GPMean, self.gp_mean, "gp_mean"))
        for name in ("lengthscale_bounds", "signal_variance_bounds", "noise_variance_bounds"):
            object.__setattr__(self, name, _check_pair(name, getattr(self, name)))
        V.integer(self.fit_restarts, "fit_restarts", 0)
        for name in ("fit_maxiter", "refit_every"):
            V.integer(getattr(self, name), name, 1)
        g = self.refit_growth
        if isinstance(g, bool) or not isinstance(g, int | float) or not 1.0 <= float(g) < 1e6:
            raise ValueError(f"refit_growth must be a number >= 1.0, got {g!r}")
        V.optional_integer(self.max_points, "max_points", 2)
        object.__setattr__(self, "subset", V.choice(SubsetRule, self.subset, "subset"))


@dataclass(frozen=True)
class UCBConfig(SurrogateConfig):
    """The options of a GP-UCB acquisition step (GP-UCB, REMBO), on top of the GP's.

    Attributes:
        zeta: UCB exploration weight :math:`\\zeta \\ge 0`.
        n_candidates: uniform random candidates scored per ask (paper: 10^4).
        n_local_starts: L-BFGS-B runs from the best candidates (original code: 1).
        local_maxiter: L-BFGS-B iterations per run (0 disables the local refinement).
        n_initial: uniform random asks before the GP is used (including ``initial_point``).
    """

    zeta: float = 1.0
    n_candidates: int = 10_000
    n_local_starts: int = 1
    local_maxiter: int = 100
    n_initial: int = 1

    def __post_init__(self) -> None:
        super().__post_init__()
        check_zeta(self.zeta)
        for name in ("n_candidates", "n_local_starts", "n_initial"):
            V.integer(getattr(self, name), name, 1)
        V.integer(self.local_maxiter, "local_maxiter", 0)

    def maximize_ucb(
        self, gp: GaussianProcess, rng: np.random.Generator
    ) -> tuple[FloatArray, float]:
        """:func:`maximize_ucb` with these options: the next point (unit cube) and its UCB."""
        return maximize_ucb(
            gp,
            float(self.zeta),
            rng,
            n_candidates=self.n_candidates,
            n_starts=self.n_local_starts,
            maxiter=self.local_maxiter,
        )


def check_zeta(zeta: object, name: str = "zeta") -> None:
    """UCB exploration weights must be finite and >= 0."""
    V.positive(zeta, name, allow_zero=True)


def finite_targets(y: FloatArray) -> FloatArray:
    """``y`` with every ``-inf`` (a failed evaluation) replaced by the worst finite value.

    A GP needs finite targets; the worst value seen tells it the region is bad without
    an outlier that would dominate the standardised targets. 0 if no value is finite.
    """
    out = np.array(y, dtype=np.float64, copy=True)
    bad = ~np.isfinite(out)
    if bad.any():
        finite = out[~bad]
        out[bad] = float(finite.min()) if finite.size else 0.0
    return out


class Surrogate:
    """A GP on the unit cube kept in sync with a growing data set.

    Call :meth:`sync` with *all* data so far before using :attr:`gp`. It refits the
    hyperparameters when the schedule says so (random restarts from ``rng``), extends the
    Cholesky factor by one row when exactly one point was appended, and otherwise
    refactors with the current hyperparameters.
    """

    def __init__(self, dim: int, config: SurrogateConfig, rng: np.random.Generator) -> None:
        self.config = config
        self.rng = rng
        self.gp = GaussianProcess(
            dim,
            ard=config.ard,
            mean=config.gp_mean,
            lengthscale_bounds=config.lengthscale_bounds,
            signal_variance_bounds=config.signal_variance_bounds,
            noise_variance_bounds=config.noise_variance_bounds,
        )
        self._n_synced = 0  # rows of the data the GP reflects
        self._prefix = True  # the GP holds exactly rows [0, _n_synced) of the data
        self._dirty = False
        self._last_fit_n = 0
        #: Number of hyperparameter fits so far (a cost diagnostic).
        self.n_fits = 0

    def is_synced(self, n: int) -> bool:
        """Whether the GP already reflects ``n`` data points (no :meth:`sync` needed)."""
        return n == self._n_synced and not self._dirty

    def invalidate(self) -> None:
        """Values changed in place (revalue): refactor at the next :meth:`sync`."""
        self._dirty = True

    def _due_for_fit(self, n: int) -> bool:
        if n < 2:
            return False
        if not self.gp.fitted:
            return True
        cfg = self.config
        return n - self._last_fit_n >= cfg.refit_every and n >= cfg.refit_growth * self._last_fit_n

    def _subset(self, y: FloatArray) -> np.ndarray | None:
        """Indices to condition on (sorted), or None for all points."""
        cap = self.config.max_points
        n = y.size
        if cap is None or n <= cap:
            return None
        rule = self.config.subset
        if rule is SubsetRule.RECENT:
            return np.arange(n - cap, n)
        order = np.argsort(-y, kind="stable")
        if rule is SubsetRule.BEST:
            return np.sort(order[:cap])
        keep = np.zeros(n, dtype=bool)
        keep[order[: cap // 2]] = True
        need = cap - int(keep.sum())
        keep[np.flatnonzero(~keep)[-need:]] = True  # the most recent of the others
        return np.flatnonzero(keep)

    def sync(self, X: FloatArray, y: FloatArray) -> GaussianProcess:
        """Bring the GP up to date with data ``X (n, d)`` in the unit cube, ``y (n,)``."""
        n = y.size
        if n == 0:
            return self.gp
        if self.is_synced(n):
            return self.gp
        failed = not np.isfinite(y).all()
        if failed:
            y = finite_targets(y)
        idx = self._subset(y)
        Xs, ys = (X, y) if idx is None else (X[idx], y[idx])
        if self._due_for_fit(n):
            self.gp.set_data(Xs, ys)
            self.gp.fit(
                self.rng,
                restarts=self.config.fit_restarts,
                maxiter=self.config.fit_maxiter,
            )
            self._last_fit_n = n
            self.n_fits += 1
        elif (
            idx is None
            and self._prefix
            and not self._dirty
            and not failed  # the stand-in of a -inf moves with the worst value: refactor
            and self.gp.n == self._n_synced
        ):
            for i in range(self._n_synced, n):
                self.gp.add_point(X[i], float(y[i]))
        else:
            self.gp.set_data(Xs, ys)
        self._prefix = idx is None
        self._n_synced = n
        self._dirty = False
        return self.gp


def maximize_ucb(
    gp: GaussianProcess,
    zeta: float,
    rng: np.random.Generator,
    *,
    n_candidates: int,
    n_starts: int,
    maxiter: int,
    chunk: int = 2048,
) -> tuple[FloatArray, float]:
    """Maximise :math:`\\mu + \\zeta\\sigma` over the unit cube ``[0, 1]^d``.

    ``n_candidates`` uniform random points (from ``rng``) are scored; L-BFGS-B with the
    analytic gradient then starts from the ``n_starts`` best of them. Returns the best
    point found and its acquisition value. Deterministic for a given ``rng`` state.
    """
    d = gp.dim
    C = rng.random((n_candidates, d))
    order, scores = gp.top_ucb(C, zeta, min(n_starts, n_candidates), chunk=chunk)
    if order.size == 0 or not np.isfinite(scores[0]):
        # no candidate has a finite acquisition (a model of values near the float
        # limits overflowed): the first uniform candidate, no local search on it
        return C[0].copy(), -math.inf
    best_x, best_v = C[order[0]].copy(), float(scores[0])
    if maxiter < 1:
        return best_x, best_v

    def negacq(u: FloatArray) -> tuple[float, FloatArray]:
        m, s, dm, ds = gp.predict_with_gradient(u)
        return -(m + zeta * s), -(dm + zeta * ds)

    bounds = [(0.0, 1.0)] * d
    for i in order:
        res = minimize(
            negacq,
            C[i],
            jac=True,
            method="L-BFGS-B",
            bounds=bounds,
            options={"maxiter": int(maxiter), "maxfun": 2 * int(maxiter)},
        )
        v = -float(res.fun)
        if np.isfinite(v) and v > best_v:
            best_x, best_v = np.clip(res.x, 0.0, 1.0), v
    return best_x, best_v
