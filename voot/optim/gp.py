r"""A small, fast Gaussian process for Bayesian optimisation (numpy/scipy only).

Model. Targets are standardised, :math:`\tilde y = (y - m) / s` (``mean="constant"``:
:math:`m` is the data mean; ``mean="zero"``: :math:`m = 0`; :math:`s` is the data standard
deviation, or 1 when it is zero), and modelled as :math:`\tilde y = g(x) + \varepsilon` with

.. math::

    g \sim \mathcal{GP}(0, k), \qquad
    k(x, x') = \sigma_f^2 \exp\Big(-\tfrac12 \sum_k (x_k - x'_k)^2 / \ell_k^2\Big), \qquad
    \varepsilon \sim \mathcal N(0, \sigma_n^2).

The squared-exponential (RBF) kernel has one length scale (isotropic, as GPy's ``RBF`` that
the paper's authors used) or one per dimension (``ard=True``). Hyperparameters
:math:`\theta = (\log \ell, \log \sigma_f^2, \log \sigma_n^2)` maximise the log marginal
likelihood

.. math::

    \log p(\tilde y \mid X, \theta) = -\tfrac12 \tilde y^\top K^{-1} \tilde y
        - \sum_i \log L_{ii} - \tfrac n2 \log 2\pi, \qquad K = L L^\top,

with its analytic gradient :math:`\tfrac12 \operatorname{tr}((\alpha\alpha^\top - K^{-1})
\partial K / \partial\theta_j)`, :math:`\alpha = K^{-1}\tilde y`, by L-BFGS-B on box bounds
in log space, from a warm start plus a few random restarts drawn from a caller's generator.

Prediction (latent :math:`g`, i.e. without the noise term, in the units of ``y``):

.. math::

    \mu(x) = m + s\, k_*^\top \alpha, \qquad
    \sigma^2(x) = s^2 \big(\sigma_f^2 - \|L^{-1} k_*\|^2\big),

vectorised over many query points. :meth:`GaussianProcess.add_point` conditions on one more
point in :math:`O(n^2)` by bordering the Cholesky factor, without refitting
hyperparameters.

Inputs are used as given; the optimisers in :mod:`voot.optim` feed points mapped to the
unit cube so that the default length-scale bounds make sense in every problem.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
import scipy.linalg as sla
from numpy.typing import ArrayLike
from scipy.optimize import minimize

from voot import validation as V
from voot.optim.base import FloatArray

_LOG_2PI = math.log(2.0 * math.pi)
#: Scaled squared distances beyond this give correlations exp(-40) ~ 4e-18, treated as 0
#: when scoring many query points: far queries then cost no exp() and no triangular solve.
_SQ_CUTOFF = 80.0
#: Up to this many data points, :meth:`GaussianProcess.top_ucb` scores every query exactly.
_SMALL_N = 128
#: Told values beyond this magnitude are standardised by :meth:`GaussianProcess._standardize_huge`
#: (their squares, and so their variance, would overflow a float64).
_HUGE = 1e150


class GPMean(StrEnum):
    """Prior mean of the GP in the units of ``y``.

    ``constant``: the mean of the conditioned targets (standardise, then a zero-mean GP).
    ``zero``: zero (targets are only scaled).
    """

    CONSTANT = "constant"
    ZERO = "zero"


def _check_bounds(name: str, bounds: tuple[float, float]) -> tuple[float, float]:
    try:
        lo, hi = (float(b) for b in bounds)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a (low, high) pair of numbers, got {bounds!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
        raise ValueError(f"{name} must satisfy 0 < low <= high < inf, got {bounds!r}")
    return lo, hi


@dataclass(frozen=True)
class GPHyperparameters:
    """Kernel hyperparameters (in standardised-target units).

    Attributes:
        lengthscales: shape ``(1,)`` (isotropic) or ``(d,)`` (ARD).
        signal_variance: :math:`\\sigma_f^2`.
        noise_variance: :math:`\\sigma_n^2`.
    """

    lengthscales: FloatArray
    signal_variance: float
    noise_variance: float

    def to_log(self) -> FloatArray:
        """``theta = (log l..., log sf2, log sn2)``."""
        return np.concatenate(
            [
                np.log(self.lengthscales),
                [math.log(self.signal_variance), math.log(self.noise_variance)],
            ]
        )

    @classmethod
    def from_log(cls, theta: FloatArray) -> GPHyperparameters:
        t = np.asarray(theta, dtype=np.float64)
        return cls(np.exp(t[:-2]), float(np.exp(t[-2])), float(np.exp(t[-1])))


class GaussianProcess:
    """GP regression with an RBF kernel; see the module docstring for the model.

    Args:
        dim: input dimension.
        ard: one length scale per dimension instead of one shared length scale.
        mean: prior mean, see :class:`GPMean`.
        lengthscale_bounds: bounds of every length scale (input units).
        signal_variance_bounds: bounds of :math:`\\sigma_f^2` (standardised units).
        noise_variance_bounds: bounds of :math:`\\sigma_n^2` (standardised units); equal
            bounds fix the noise.
        jitter: added to the diagonal of :math:`K` for numerical stability only.
    """

    def __init__(
        self,
        dim: int,
        *,
        ard: bool = False,
        mean: GPMean | str = GPMean.CONSTANT,
        lengthscale_bounds: tuple[float, float] = (1e-2, 1e2),
        signal_variance_bounds: tuple[float, float] = (1e-2, 1e2),
        noise_variance_bounds: tuple[float, float] = (1e-6, 1.0),
        jitter: float = 1e-10,
    ) -> None:
        V.integer(dim, "dim", 1)
        self.dim = int(dim)
        self.ard = bool(ard)
        self.mean = V.choice(GPMean, mean, "mean", "means")
        self.lengthscale_bounds = _check_bounds("lengthscale_bounds", lengthscale_bounds)
        self.signal_variance_bounds = _check_bounds(
            "signal_variance_bounds", signal_variance_bounds
        )
        self.noise_variance_bounds = _check_bounds("noise_variance_bounds", noise_variance_bounds)
        if not (math.isfinite(jitter) and jitter >= 0.0):
            raise ValueError(f"jitter must be finite and >= 0, got {jitter!r}")
        self.jitter = float(jitter)
        n_ls = self.dim if self.ard else 1
        self.hyper = GPHyperparameters(
            np.full(n_ls, self._clip(0.5, self.lengthscale_bounds)),
            self._clip(1.0, self.signal_variance_bounds),
            self._clip(1e-2, self.noise_variance_bounds),
        )
        #: Whether :meth:`fit` has set the hyperparameters at least once.
        self.fitted = False
        self._X = np.empty((0, self.dim))
        self._y = np.empty(0)
        self._L = np.empty((0, 0))
        self._alpha = np.empty(0)
        self._y_mean = 0.0
        self._y_scale = 1.0
        self._diag = 1.0  # K_ii of the current factor (signal + noise + jitter)

    # ----- data ---------------------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of conditioned points."""
        return int(self._y.size)

    @property
    def X(self) -> FloatArray:
        return self._X

    @property
    def y(self) -> FloatArray:
        return self._y

    def set_data(self, X: ArrayLike, y: ArrayLike) -> None:
        """Condition on ``(X, y)`` with the current hyperparameters (``O(n^3)``)."""
        Xa = np.array(X, dtype=np.float64, copy=True).reshape(-1, self.dim)
        ya = np.array(y, dtype=np.float64, copy=True).reshape(-1)
        if Xa.shape[0] != ya.size:
            raise ValueError(f"X has {Xa.shape[0]} rows but y has {ya.size} entries")
        if not (np.all(np.isfinite(Xa)) and np.all(np.isfinite(ya))):
            raise ValueError("X and y must be finite")
        self._X, self._y = Xa, ya
        self._factorize()

    def add_point(self, x: ArrayLike, y: float) -> None:
        """Condition on one more point without refitting hyperparameters (``O(n^2)``).

        Borders the Cholesky factor: with :math:`l = L^{-1} k(X, x)` and
        :math:`\\lambda = \\sqrt{k(x, x) + \\sigma_n^2 - l^\\top l}`, the new factor is
        ``[[L, 0], [l^T, lambda]]``. Falls back to a full factorisation if that is not
        numerically positive.
        """
        xa = np.asarray(x, dtype=np.float64).reshape(self.dim)
        yv = float(y)
        if not (np.all(np.isfinite(xa)) and math.isfinite(yv)):
            raise ValueError("x and y must be finite")
        n = self.n
        X = np.empty((n + 1, self.dim))
        X[:n] = self._X
        X[n] = xa
        Y = np.empty(n + 1)
        Y[:n] = self._y
        Y[n] = yv
        if n == 0:
            self._X, self._y = X, Y
            self._factorize()
            return
        h = self.hyper
        kx = h.signal_variance * self._corr(xa[None, :], self._X)[0]
        l_vec = sla.solve_triangular(self._L, kx, lower=True, check_finite=False)
        lam2 = self._diag - float(l_vec @ l_vec)
        self._X, self._y = X, Y
        if not lam2 > 1e-12 * h.signal_variance:
            self._factorize()
            return
        L = np.zeros((n + 1, n + 1))
        L[:n, :n] = self._L
        L[n, :n] = l_vec
        L[n, n] = math.sqrt(lam2)
        self._L = L
        self._update_alpha()

    # ----- hyperparameters ------------------------------------------------------------
    def _log_bounds(self) -> list[tuple[float, float]]:
        n_ls = self.dim if self.ard else 1
        lb = [(math.log(self.lengthscale_bounds[0]), math.log(self.lengthscale_bounds[1]))]
        return lb * n_ls + [
            (math.log(self.signal_variance_bounds[0]), math.log(self.signal_variance_bounds[1])),
            (math.log(self.noise_variance_bounds[0]), math.log(self.noise_variance_bounds[1])),
        ]

    def log_marginal_likelihood(
        self, theta: ArrayLike | None = None, *, grad: bool = False
    ) -> float | tuple[float, FloatArray]:
        """Log marginal likelihood of the standardised targets at log-hyperparameters
        ``theta`` (default: the current ones); with ``grad=True`` also its gradient."""
        t = self.hyper.to_log() if theta is None else np.asarray(theta, dtype=np.float64)
        if self.n == 0:
            raise ValueError("log_marginal_likelihood needs at least one data point")
        y = self._standardize(self._y)[0]
        return self._lml(t, y, grad)

    def _lml(
        self, theta: FloatArray, y: FloatArray, grad: bool
    ) -> float | tuple[float, FloatArray]:
        h = GPHyperparameters.from_log(theta)
        n = y.size
        Z = self._X / h.lengthscales
        sq = self._sqdist(Z, Z)
        Kf = h.signal_variance * np.exp(-0.5 * sq)
        K = Kf.copy()
        K.flat[:: n + 1] += h.noise_variance + self.jitter
        L, info = sla.lapack.dpotrf(K, lower=1, clean=1, overwrite_a=1)
        if info != 0:
            return (-1e25, np.zeros_like(theta)) if grad else -1e25
        alpha, _ = sla.lapack.dpotrs(L, y, lower=1)
        lml = -0.5 * float(y @ alpha) - float(np.sum(np.log(np.diag(L)))) - 0.5 * n * _LOG_2PI
        if not grad:
            return lml
        Kinv, info = sla.lapack.dpotri(L, lower=1)  # lower triangle of K^-1, upper is 0
        if info != 0:
            return lml, np.zeros_like(theta)
        Kinv += Kinv.T
        Kinv.flat[:: n + 1] *= 0.5
        W = np.outer(alpha, alpha) - Kinv
        M = W * Kf
        g = np.empty_like(theta)
        if self.ard:
            Z2 = Z * Z
            g[:-2] = M.sum(axis=1) @ Z2 - np.einsum("ik,ik->k", Z, M @ Z)
        else:
            g[0] = 0.5 * float(np.sum(M * sq))
        g[-2] = 0.5 * float(np.sum(M))
        g[-1] = 0.5 * h.noise_variance * float(np.trace(W))
        return lml, g

    def fit(
        self,
        rng: np.random.Generator | None = None,
        *,
        restarts: int = 2,
        maxiter: int = 100,
        warm_start: bool = True,
    ) -> GPHyperparameters:
        """Maximise the log marginal likelihood over the hyperparameters, then refactor.

        Each start runs L-BFGS-B for at most ``maxiter`` iterations and ``2 * maxiter``
        likelihood evaluations.

        Starts: the current hyperparameters (``warm_start``; before the first fit they are
        the defaults with the length scale set to the median pairwise distance), plus
        ``restarts`` points drawn log-uniformly in the bounds from ``rng``. The best
        optimum wins (first on ties), so a given ``rng`` state gives a given result.
        """
        if self.n == 0:
            raise ValueError("fit needs at least one data point")
        if restarts < 0 or maxiter < 1:
            raise ValueError(f"need restarts >= 0 and maxiter >= 1, got {restarts}, {maxiter}")
        bounds = self._log_bounds()
        lo = np.array([b[0] for b in bounds])
        hi = np.array([b[1] for b in bounds])
        starts: list[FloatArray] = []
        if warm_start or rng is None:
            start = self.hyper.to_log()
            if not self.fitted and self.n >= 2:
                med = self._median_distance()
                if med > 0:
                    start[:-2] = math.log(self._clip(med, self.lengthscale_bounds))
            starts.append(np.clip(start, lo, hi))
        if rng is not None:
            for _ in range(restarts):
                starts.append(lo + rng.random(lo.size) * (hi - lo))
        y = self._standardize(self._y)[0]

        def objective(t: FloatArray) -> tuple[float, FloatArray]:
            value, g = self._lml(t, y, True)  # type: ignore[misc]
            return -value, -g

        best_t, best_v = starts[0], math.inf
        for s in starts:
            try:
                res = minimize(
                    objective,
                    s,
                    jac=True,
                    method="L-BFGS-B",
                    bounds=bounds,
                    options={"maxiter": int(maxiter), "maxfun": 2 * int(maxiter)},
                )
            except (ValueError, np.linalg.LinAlgError):  # pragma: no cover - defensive
                continue
            if np.isfinite(res.fun) and res.fun < best_v:
                best_t, best_v = np.clip(res.x, lo, hi), float(res.fun)
        self.hyper = GPHyperparameters.from_log(best_t)
        self.fitted = True
        self._factorize()
        return self.hyper

    # ----- prediction -----------------------------------------------------------------
    def predict(
        self, Xq: ArrayLike, *, return_std: bool = True, chunk: int = 4096
    ) -> tuple[FloatArray, FloatArray]:
        r"""Posterior mean and standard deviation of the latent function at ``Xq (m, d)``.

        With no data it returns the prior (mean ``m`` = 0, std ``sqrt(sf2)``). Work is
        chunked over queries to bound memory at ``chunk * n`` floats. ``return_std=False``
        skips the ``O(m n^2)`` variance (std is then returned as zeros).

        Cross-correlations below :math:`e^{-40} \approx 4\cdot10^{-18}` are treated as 0, so
        a query far from all data (common in high dimensions with short length scales)
        costs no ``exp`` and no triangular solve: it gets the prior exactly.
        """
        Q = np.asarray(Xq, dtype=np.float64).reshape(-1, self.dim)
        m = Q.shape[0]
        h = self.hyper
        mu = np.full(m, self._y_mean)
        sd = np.zeros(m)
        if self.n == 0:
            sd[:] = self._y_scale * math.sqrt(h.signal_variance)
            return mu, sd
        step = max(1, int(chunk))
        ell = h.lengthscales
        Zx = self._X / ell
        for a in range(0, m, step):
            b = min(m, a + step)
            sd[a:b] = self._y_scale * math.sqrt(h.signal_variance)
            cross = self._cross(Q[a:b] / ell, Zx)
            if cross is None:
                continue
            rows, Ks = cross
            mu[a + rows] += self._y_scale * (Ks @ self._alpha)
            if return_std:
                V = sla.solve_triangular(self._L, Ks.T, lower=True, check_finite=False)
                var = h.signal_variance - np.einsum("ij,ij->j", V, V)
                sd[a + rows] = self._y_scale * np.sqrt(np.maximum(var, 0.0))
        if not return_std:
            sd[:] = 0.0
        return mu, sd

    def top_ucb(
        self, Q: ArrayLike, zeta: float, k: int = 1, *, chunk: int = 2048
    ) -> tuple[np.ndarray, FloatArray]:
        r"""Exact top-``k`` rows of ``Q (m, d)`` by :math:`\mu + \zeta\sigma` (same as
        :meth:`predict`, much cheaper for large n).

        The means of all rows cost ``O(m n d)``; the standard deviations ``O(n^2)`` per row
        are computed only for rows that could still enter the top ``k``. A row's
        :math:`\sigma` is bounded by conditioning on its most correlated point alone,
        :math:`\sigma^2 \le \sigma_f^2 - \max_i k_i^2 / K_{ii}` (more data never increases
        the posterior variance), so rows are scored exactly in decreasing order of that
        bound until the bound falls below the ``k``-th best exact score.

        Returns ``(indices, scores)`` sorted by decreasing score (lower index first on ties).
        """
        Qa = np.asarray(Q, dtype=np.float64).reshape(-1, self.dim)
        m = Qa.shape[0]
        k = max(1, min(int(k), m))
        z = float(zeta)
        h = self.hyper
        if self.n <= _SMALL_N or z <= 0.0:  # bounds do not pay off: score every row
            mu, sd = self.predict(Qa, return_std=z > 0.0, chunk=chunk)
            score = mu + z * sd
            if k < m:
                part = np.argpartition(-score, k - 1)[:k]
                kth = score[part].min()
                cand = np.flatnonzero(score >= kth)  # all ties of the k-th score, in order
            else:
                cand = np.arange(m)
            idx = cand[np.argsort(-score[cand], kind="stable")[:k]]
            return idx, score[idx]
        sf2 = h.signal_variance
        ell = h.lengthscales
        Zx = self._X / ell
        mu = np.full(m, self._y_mean)
        kmax = np.zeros(m)
        step = max(1, int(chunk))
        for a in range(0, m, step):
            b = min(m, a + step)
            Ks = self._cross(Qa[a:b] / ell, Zx)
            if Ks is None:
                continue
            rows, K = Ks
            mu[a + rows] += self._y_scale * (K @ self._alpha)
            kmax[a + rows] = K.max(axis=1)
        prior_sd = self._y_scale * math.sqrt(sf2)
        var_ub = sf2 - kmax * kmax / self._diag
        bound = mu + z * self._y_scale * np.sqrt(np.maximum(var_ub, 0.0))
        exact = kmax == 0.0  # no correlated data: the bound is the exact prior score
        bound[exact] = mu[exact] + z * prior_sd
        order = np.argsort(-bound, kind="stable")
        top_idx = np.empty(0, dtype=np.intp)
        top_val = np.empty(0)
        block = 256
        pos = 0
        while pos < m:
            # rows left have exact score <= bound <= k-th best: they can only tie (and ties
            # go to lower indices, which equal-bound exact rows already had)
            if top_val.size == k and bound[order[pos]] <= top_val[-1]:
                break
            sel = order[pos : pos + block]
            pos += sel.size
            val = bound[sel].copy()
            need = ~exact[sel]
            if np.any(need):
                rows = sel[need]
                cross = self._cross(Qa[rows] / ell, Zx, all_rows=True)
                assert cross is not None
                V = sla.solve_triangular(self._L, cross[1].T, lower=True, check_finite=False)
                var = sf2 - np.einsum("ij,ij->j", V, V)
                val[need] = mu[rows] + z * self._y_scale * np.sqrt(np.maximum(var, 0.0))
            idx = np.concatenate([top_idx, sel])
            val = np.concatenate([top_val, val])
            keep = np.lexsort((idx, -val))[:k]
            top_idx, top_val = idx[keep], val[keep]
        return top_idx, top_val

    def _cross(
        self, Zq: FloatArray, Zx: FloatArray, *, all_rows: bool = False
    ) -> tuple[np.ndarray, FloatArray] | None:
        """Truncated cross-covariances ``sf2 * exp(-sq/2)`` (0 where ``sq >= cutoff``).

        Returns ``(rows, K)`` for the rows with at least one non-zero entry (all rows with
        ``all_rows``), or None when there are none.
        """
        qq = np.einsum("ij,ij->i", Zq, Zq)
        sq = Zq @ Zx.T
        sq *= -2.0
        sq += np.einsum("ij,ij->i", Zx, Zx)[None, :]  # sq + qq is the squared distance
        near = sq < (_SQ_CUTOFF - qq)[:, None]
        if all_rows:
            rows = np.arange(sq.shape[0])
        else:
            rows = np.flatnonzero(near.any(axis=1))
            if rows.size == 0:
                return None
            if rows.size < sq.shape[0]:
                sq, near, qq = sq[rows], near[rows], qq[rows]
        sq += qq[:, None]
        np.maximum(sq, 0.0, out=sq)
        K = np.zeros_like(sq)
        if near.mean() > 0.5:
            np.exp(-0.5 * sq, out=K, where=near)
        else:
            K[near] = np.exp(-0.5 * sq[near])
        K *= self.hyper.signal_variance
        return rows, K

    def predict_with_gradient(self, x: ArrayLike) -> tuple[float, float, FloatArray, FloatArray]:
        """Mean, std and their gradients w.r.t. ``x`` at one point ``x (d,)``.

        With :math:`k_i = k(x, x_i)`, :math:`\\partial k_i/\\partial x = -k_i (x - x_i)/\\ell^2`,
        :math:`\\nabla\\mu = s \\sum_i \\alpha_i \\nabla k_i` and
        :math:`\\nabla\\sigma^2 = -2 s^2 \\sum_i w_i \\nabla k_i`, :math:`w = K^{-1} k_*`.
        """
        xa = np.asarray(x, dtype=np.float64).reshape(self.dim)
        h = self.hyper
        if self.n == 0:
            z = np.zeros(self.dim)
            return self._y_mean, self._y_scale * math.sqrt(h.signal_variance), z, z.copy()
        ks = h.signal_variance * self._corr(xa[None, :], self._X)[0]
        diff = (xa - self._X) / (h.lengthscales * h.lengthscales)  # (n, d)
        dk = -ks[:, None] * diff  # (n, d)
        mu = self._y_mean + self._y_scale * float(ks @ self._alpha)
        dmu = self._y_scale * (self._alpha @ dk)
        v = sla.solve_triangular(self._L, ks, lower=True, check_finite=False)
        var = max(h.signal_variance - float(v @ v), 0.0)
        w = sla.solve_triangular(self._L, v, lower=True, trans="T", check_finite=False)
        dvar = -2.0 * (w @ dk)
        sd_latent = math.sqrt(var)
        sd = self._y_scale * sd_latent
        dsd = self._y_scale * dvar / (2.0 * max(sd_latent, 1e-12))
        return mu, sd, dmu, dsd

    # ----- internals ------------------------------------------------------------------
    @staticmethod
    def _clip(v: float, bounds: tuple[float, float]) -> float:
        return float(min(max(v, bounds[0]), bounds[1]))

    @staticmethod
    def _sqdist(A: FloatArray, B: FloatArray) -> FloatArray:
        sq = -2.0 * (A @ B.T)
        sq += np.einsum("ij,ij->i", A, A)[:, None]
        sq += np.einsum("ij,ij->i", B, B)[None, :]
        np.maximum(sq, 0.0, out=sq)
        return sq

    def _corr(self, A: FloatArray, B: FloatArray) -> FloatArray:
        """``exp(-0.5 * |a - b|^2_ell)`` for all pairs (without the signal variance)."""
        ell = self.hyper.lengthscales
        sq = self._sqdist(A / ell, B / ell)
        sq *= -0.5
        return np.exp(sq, out=sq)

    def _median_distance(self) -> float:
        X = self._X[:200]
        d = np.sqrt(self._sqdist(X, X)[np.triu_indices(X.shape[0], 1)])
        return float(np.median(d)) if d.size else 0.0

    def _standardize(self, y: FloatArray) -> tuple[FloatArray, float, float]:
        big = float(np.max(np.abs(y))) if y.size else 0.0
        if big > _HUGE:  # near the float limits: the moments below would overflow
            return self._standardize_huge(y, big)
        mean = float(np.mean(y)) if self.mean is GPMean.CONSTANT and y.size else 0.0
        if self.mean is GPMean.CONSTANT:
            scale = float(np.std(y)) if y.size > 1 else 0.0
        else:
            scale = float(np.sqrt(np.mean(y * y))) if y.size else 0.0
        if not (scale > 1e-12 * max(1.0, abs(mean))):
            scale = 1.0
        return (y - mean) / scale, mean, scale

    def _standardize_huge(self, y: FloatArray, big: float) -> tuple[FloatArray, float, float]:
        """:meth:`_standardize` of values up to the float limit: the moments of
        ``y / big`` (all in [-1, 1], so nothing overflows), scaled back. The standardised
        values are as :meth:`_standardize` would give them in exact arithmetic; a
        prediction far beyond the told values may still overflow to an infinity, which
        the acquisition's maximiser passes over (:func:`voot.optim._surrogate.maximize_ucb`)."""
        u = y / big
        mean_u = float(np.mean(u)) if self.mean is GPMean.CONSTANT else 0.0
        if self.mean is GPMean.CONSTANT:
            scale_u = float(np.std(u)) if y.size > 1 else 0.0
        else:
            scale_u = float(np.sqrt(np.mean(u * u)))
        if not (scale_u > 1e-12 * max(1.0, abs(mean_u))):
            return u - mean_u, mean_u * big, big  # (nearly) constant: in units of big
        return (u - mean_u) / scale_u, mean_u * big, scale_u * big

    def _factorize(self) -> None:
        n = self.n
        if n == 0:
            self._L = np.empty((0, 0))
            self._alpha = np.empty(0)
            self._y_mean, self._y_scale = 0.0, 1.0
            return
        h = self.hyper
        K = h.signal_variance * self._corr(self._X, self._X)
        extra = h.noise_variance + self.jitter
        for _ in range(8):
            Kj = K.copy()
            Kj.flat[:: n + 1] += extra
            try:
                self._L = sla.cholesky(Kj, lower=True, check_finite=False)
                self._diag = h.signal_variance + extra
                break
            except np.linalg.LinAlgError:
                extra = max(10.0 * extra, 1e-10 * h.signal_variance)
        else:  # pragma: no cover - only for pathological inputs
            raise np.linalg.LinAlgError("GP kernel matrix is not positive definite")
        self._update_alpha()

    def _update_alpha(self) -> None:
        ys, self._y_mean, self._y_scale = self._standardize(self._y)
        self._alpha = sla.cho_solve((self._L, True), ys, check_finite=False)
