"""Tests of the numpy/scipy Gaussian process in voot.optim.gp."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import approx_fprime
from scipy.stats import multivariate_normal

from voot.optim.gp import GaussianProcess, GPHyperparameters


def _data(n: int, d: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    X = rng.random((n, d))
    y = np.sin(4.0 * X[:, 0]) + 0.5 * np.cos(3.0 * X[:, -1]) + 2.0
    return X, y


def _brute_force(gp: GaussianProcess, X, y, Q):
    """Textbook GP formulas with explicit inverses (standardised targets)."""
    h = gp.hyper
    ell = h.lengthscales

    def k(A, B):
        diff = (A[:, None, :] - B[None, :, :]) / ell
        return h.signal_variance * np.exp(-0.5 * np.sum(diff**2, axis=-1))

    m, s = float(np.mean(y)), float(np.std(y))
    ys = (y - m) / s
    K = k(X, X) + (h.noise_variance + gp.jitter) * np.eye(len(y))
    Kinv = np.linalg.inv(K)
    Ks = k(Q, X)
    mu = m + s * Ks @ Kinv @ ys
    var = h.signal_variance - np.einsum("ij,jk,ik->i", Ks, Kinv, Ks)
    lml = multivariate_normal(mean=np.zeros(len(y)), cov=K).logpdf(ys)
    return mu, s * np.sqrt(np.maximum(var, 0.0)), lml


@pytest.mark.parametrize("ard", [False, True])
def test_posterior_and_likelihood_match_brute_force(ard: bool) -> None:
    X, y = _data(25, 3)
    gp = GaussianProcess(3, ard=ard)
    ell = np.array([0.3, 0.5, 0.8]) if ard else np.array([0.4])
    gp.hyper = GPHyperparameters(ell, 1.7, 1e-3)
    gp.set_data(X, y)
    Q = np.random.default_rng(1).random((40, 3))
    mu, sd = gp.predict(Q)
    mu_bf, sd_bf, lml_bf = _brute_force(gp, X, y, Q)
    np.testing.assert_allclose(mu, mu_bf, rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(sd, sd_bf, rtol=1e-6, atol=1e-8)
    assert gp.log_marginal_likelihood() == pytest.approx(lml_bf, rel=1e-9)


@pytest.mark.parametrize("ard", [False, True])
def test_likelihood_gradient_matches_finite_differences(ard: bool) -> None:
    X, y = _data(30, 3, seed=2)
    gp = GaussianProcess(3, ard=ard)
    gp.set_data(X, y)
    theta = gp.hyper.to_log() + np.random.default_rng(3).normal(0.0, 0.3, gp.hyper.to_log().size)
    value, grad = gp.log_marginal_likelihood(theta, grad=True)
    fd = approx_fprime(theta, lambda t: gp.log_marginal_likelihood(t), 1e-6)
    np.testing.assert_allclose(grad, fd, rtol=1e-3, atol=1e-3)
    assert value == pytest.approx(gp.log_marginal_likelihood(theta))


def test_interpolates_data_and_uncertainty_grows_away_from_it() -> None:
    X, y = _data(20, 2)
    gp = GaussianProcess(2, noise_variance_bounds=(1e-8, 1e-8))
    gp.set_data(X, y)
    gp.fit(np.random.default_rng(0))
    mu, sd = gp.predict(X)
    np.testing.assert_allclose(mu, y, atol=1e-3 * np.ptp(y))
    assert np.all(sd < 1e-2 * np.std(y))
    far = np.array([[60.0, 60.0], [-50.0, 80.0]])
    mu_far, sd_far = gp.predict(far)
    prior_sd = np.std(y) * math.sqrt(gp.hyper.signal_variance)
    np.testing.assert_allclose(sd_far, prior_sd, rtol=1e-6)
    np.testing.assert_allclose(mu_far, np.mean(y), atol=1e-6 * np.ptp(y))
    ray = np.array([1.0, 1.0]) + np.outer([0.0, 0.5, 1.0, 2.0, 4.0], [1.0, 0.5])
    sd_ray = gp.predict(ray)[1]
    assert np.all(np.diff(sd_ray) > 0.0)
    assert sd_ray[1] > 100 * sd.max()


def test_fit_recovers_length_scale_of_a_gp_sample() -> None:
    rng = np.random.default_rng(7)
    true_ell = 0.12
    X = np.sort(rng.random(80))[:, None]
    K = np.exp(-0.5 * (X - X.T) ** 2 / true_ell**2) + 1e-8 * np.eye(80)
    y = np.linalg.cholesky(K) @ rng.standard_normal(80)
    gp = GaussianProcess(1)
    gp.set_data(X, y)
    h = gp.fit(np.random.default_rng(0), restarts=3)
    assert 0.7 * true_ell < h.lengthscales[0] < 1.4 * true_ell
    assert h.noise_variance < 1e-2


def test_ard_finds_the_irrelevant_dimension() -> None:
    rng = np.random.default_rng(4)
    X = rng.random((60, 2))
    y = np.sin(6.0 * X[:, 0])
    gp = GaussianProcess(2, ard=True)
    gp.set_data(X, y)
    h = gp.fit(np.random.default_rng(0))
    assert h.lengthscales[1] > 5.0 * h.lengthscales[0]


def test_fit_is_deterministic_for_a_given_rng() -> None:
    X, y = _data(30, 4)
    results = []
    for _ in range(2):
        gp = GaussianProcess(4, ard=True)
        gp.set_data(X, y)
        results.append(gp.fit(np.random.default_rng(11)).to_log())
    np.testing.assert_array_equal(results[0], results[1])


def test_add_point_equals_refactorisation() -> None:
    X, y = _data(40, 3)
    a = GaussianProcess(3)
    a.set_data(X[:10], y[:10])
    a.fit(np.random.default_rng(0))
    b = GaussianProcess(3)
    b.hyper = a.hyper
    for i in range(10, 40):
        a.add_point(X[i], y[i])
    b.set_data(X, y)
    Q = np.random.default_rng(5).random((30, 3))
    for got, want in zip(a.predict(Q), b.predict(Q), strict=True):
        np.testing.assert_allclose(got, want, rtol=1e-7, atol=1e-9)
    assert a.n == 40


def test_add_point_to_empty_gp_and_prior_prediction() -> None:
    gp = GaussianProcess(2)
    mu, sd = gp.predict(np.zeros((3, 2)))
    np.testing.assert_array_equal(mu, 0.0)
    np.testing.assert_allclose(sd, math.sqrt(gp.hyper.signal_variance))
    gp.add_point([0.5, 0.5], 3.0)
    mu, _ = gp.predict(np.array([[0.5, 0.5], [5.0, 5.0]]))
    assert mu[0] == pytest.approx(3.0) and mu[1] == pytest.approx(3.0)


def test_gradients_of_mean_and_std() -> None:
    X, y = _data(25, 3)
    gp = GaussianProcess(3, ard=True)
    gp.set_data(X, y)
    gp.fit(np.random.default_rng(0))
    x = np.array([0.3, 0.6, 0.2])
    mu, sd, dmu, dsd = gp.predict_with_gradient(x)
    m2, s2 = gp.predict(x[None, :])
    assert mu == pytest.approx(m2[0]) and sd == pytest.approx(s2[0])
    fd_mu = approx_fprime(x, lambda q: gp.predict(q[None, :])[0][0], 1e-7)
    fd_sd = approx_fprime(x, lambda q: gp.predict(q[None, :])[1][0], 1e-7)
    np.testing.assert_allclose(dmu, fd_mu, rtol=1e-4, atol=1e-5)
    np.testing.assert_allclose(dsd, fd_sd, rtol=1e-4, atol=1e-5)


@pytest.mark.parametrize(("d", "ell", "zeta"), [(2, 0.2, 1.0), (10, 0.15, 5.0), (10, 0.6, 0.01)])
def test_top_ucb_equals_brute_force(d: int, ell: float, zeta: float) -> None:
    rng = np.random.default_rng(d)
    X = rng.random((150, d))
    y = np.sin(3.0 * X).sum(axis=1)
    gp = GaussianProcess(d)
    gp.hyper = GPHyperparameters(np.array([ell]), 1.0, 1e-6)
    gp.set_data(X, y)
    Q = rng.random((3000, d))
    Q[:500] = np.clip(X[rng.integers(0, 150, 500)] + 0.03 * rng.standard_normal((500, d)), 0, 1)
    mu, sd = gp.predict(Q)
    score = mu + zeta * sd
    want = np.argsort(-score, kind="stable")[:4]
    got, vals = gp.top_ucb(Q, zeta, 4)
    np.testing.assert_array_equal(got, want)
    np.testing.assert_allclose(vals, score[want], rtol=1e-10, atol=1e-10)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"dim": 0}, "dim"),
        ({"dim": 2, "mean": "linear"}, "mean"),
        ({"dim": 2, "lengthscale_bounds": (1.0, 0.1)}, "lengthscale_bounds"),
        ({"dim": 2, "noise_variance_bounds": (0.0, 1.0)}, "noise_variance_bounds"),
        ({"dim": 2, "jitter": -1.0}, "jitter"),
    ],
)
def test_bad_arguments_raise(kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        GaussianProcess(**kwargs)


def test_bad_data_raise() -> None:
    gp = GaussianProcess(2)
    with pytest.raises(ValueError, match="rows"):
        gp.set_data(np.zeros((3, 2)), np.zeros(2))
    with pytest.raises(ValueError, match="finite"):
        gp.set_data(np.zeros((1, 2)), [np.nan])
    with pytest.raises(ValueError, match="at least one"):
        gp.fit(np.random.default_rng(0))


@pytest.mark.parametrize("mean", ["constant", "zero"])
def test_standardising_huge_values_matches_ordinary_ones_for_either_mean(mean: str) -> None:
    """Values beyond 1e150 are standardised without overflow (``_standardize_huge``) to
    what the ordinary standardisation gives them in exact arithmetic, for a constant
    prior mean (centred, then scaled) and a zero one (only scaled by the root mean
    square); test_gp_ucb.py checks the constant mean and the optimiser around it."""
    y = np.array([3.0, -1.0, 2.0, 0.5])
    gp = GaussianProcess(1, mean=mean)
    small, m, s = gp._standardize(y)
    huge, mh, sh = gp._standardize(y * 1e300)
    np.testing.assert_allclose(huge, small, rtol=1e-12)
    assert mh == pytest.approx(m * 1e300, rel=1e-12, abs=0.0)
    assert sh == pytest.approx(s * 1e300, rel=1e-12)


def test_huge_values_that_differ_by_a_few_parts_in_1e12_are_not_constant() -> None:
    """Only a spread below 1e-12 of the largest value counts as constant (the ordinary
    standardisation's rule, ``scale > 1e-12 max(1, |mean|)``): just above it the values
    are standardised, not flattened to zeros in units of the largest."""
    big = 1e300
    spread = np.array([-1.0, 1.0]) * 1.5e-12
    gp = GaussianProcess(1)
    z, mean, scale = gp._standardize(big * (1.0 + spread))
    np.testing.assert_allclose(z, [-1.0, 1.0], rtol=1e-3)
    assert mean == pytest.approx(big, rel=1e-12) and scale == pytest.approx(1.5e288, rel=1e-3)
    flat, _, _ = gp._standardize(big * (1.0 + spread / 3.0))
    assert np.all(np.abs(flat) < 1e-11)  # below the rule: constant, in units of big
