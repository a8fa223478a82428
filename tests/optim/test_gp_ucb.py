"""Tests of GP-UCB (voot.optim.gp_ucb) and its shared GP surrogate."""

from __future__ import annotations

import numpy as np
import pytest
from optim_fixtures import bowl, run_on

from voot.optim import make_config, make_optimizer, maximize
from voot.optim._surrogate import Surrogate, SurrogateConfig
from voot.optim.gp_ucb import GPUCB, GPUCBConfig

FAST = {"n_candidates": 2000, "fit_restarts": 1}


def run(seed: int, d: int = 2, budget: int = 12, **options) -> GPUCB:
    return run_on(GPUCB, seed, d, budget, **{**FAST, **options})


def test_registered_with_paper_grid() -> None:
    cfg = make_config("gp_ucb", zeta=5.0)
    assert isinstance(cfg, GPUCBConfig)
    assert GPUCBConfig.paper_grid() == {"zeta": [0.01, 0.1, 1.0, 5.0, 10.0, 30.0]}
    assert cfg.n_candidates == 10_000 and cfg.max_points == 1000


def test_deterministic_for_a_seed() -> None:
    a, b, c = run(3), run(3), run(4)
    np.testing.assert_array_equal(a.xs, b.xs)
    np.testing.assert_array_equal(a.values, b.values)
    assert not np.array_equal(a.xs, c.xs)


def test_points_inside_bounds_and_initial_point_first() -> None:
    lo, hi = np.array([-2.0, 0.0, 5.0]), np.array([-1.0, 3.0, 9.0])
    opt = make_optimizer("gp_ucb", (lo, hi), seed=0, initial_point=[-1.5, 1.0, 6.0], **FAST)
    for _ in range(10):
        x = opt.ask()
        assert np.all(x >= lo) and np.all(x <= hi)
        opt.tell(x, -float(np.sum(x**2)))
    np.testing.assert_array_equal(opt.xs[0], [-1.5, 1.0, 6.0])


@pytest.mark.parametrize(("d", "budget"), [(2, 25), (5, 40)])
def test_beats_random_search_on_a_smooth_function(d: int, budget: int) -> None:
    bounds = [[-1.0, 1.0]] * d
    x0 = np.full(d, 0.9)
    gp, rnd = [], []
    for seed in (0, 1):
        gp.append(maximize(bowl, bounds, "gp_ucb", budget, seed, x0, **FAST).best_value)
        rnd.append(maximize(bowl, bounds, "random", budget, seed, x0).best_value)
    # regret at least 10x smaller than random search's, on every seed
    assert all(g > 0.1 * r for g, r in zip(gp, rnd, strict=True)), (gp, rnd)
    assert max(gp) > -0.05 * d


def test_refit_schedule_and_point_cap() -> None:
    opt = run(0, d=3, budget=30, refit_every=10, refit_growth=1.0, max_points=12)
    gp = opt.surrogate.gp
    assert gp.n == 12  # conditioned on a capped subset
    assert opt.surrogate.n_fits == 3  # fitted at n = 2 (first), 12, 22
    best = np.argsort(-opt.values, kind="stable")[:6]
    held = {tuple(r) for r in gp.X}
    unit = (opt.xs + 1.0) / 2.0
    assert all(tuple(unit[i]) in held for i in best)  # best_recent keeps the best half
    assert tuple(unit[-2]) in held  # the most recent point at the last ask


def test_surrogate_incremental_updates_match_refit_free_refactor() -> None:
    cfg = SurrogateConfig(refit_every=100)
    rng = np.random.default_rng(0)
    X, y = rng.random((20, 2)), rng.random(20)
    s = Surrogate(2, cfg, np.random.default_rng(1))
    s.sync(X[:5], y[:5])
    for n in range(6, 21):
        s.sync(X[:n], y[:n])
    assert s.n_fits == 1 and s.gp.n == 20
    fresh = Surrogate(2, cfg, np.random.default_rng(1))
    fresh.gp.hyper = s.gp.hyper
    fresh.gp.set_data(X, y)
    Q = rng.random((10, 2))
    np.testing.assert_allclose(s.gp.predict(Q)[0], fresh.gp.predict(Q)[0], rtol=1e-8)


def test_revalue_changes_the_model() -> None:
    opt = run(0, budget=6)
    opt.revalue(2, 10.0)
    assert opt.best_index == 2
    opt.ask()
    assert opt.surrogate.gp.y.max() == 10.0


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"zeta": -1.0}, "zeta"),
        ({"n_candidates": 0}, "n_candidates"),
        ({"n_local_starts": 0}, "n_local_starts"),
        ({"local_maxiter": -1}, "local_maxiter"),
        ({"refit_every": 0}, "refit_every"),
        ({"refit_growth": 0.5}, "refit_growth"),
        ({"max_points": 1}, "max_points"),
        ({"subset": "worst"}, "subset"),
        ({"gp_mean": "linear"}, "gp_mean"),
        ({"lengthscale_bounds": (1.0,)}, "lengthscale_bounds"),
        ({"noise_variance_bounds": (1.0, 1e-3)}, "noise_variance_bounds"),
        ({"lengthscale_bounds": (True, True)}, "lengthscale_bounds must be a .* of numbers"),
        ({"signal_variance_bounds": ("0.1", "1")}, "signal_variance_bounds must be a .* of num"),
        ({"fit_restarts": -1}, "fit_restarts"),
        ({"ard": "yes"}, "ard"),
        ({"zetta": 1.0}, "unknown option"),
    ],
)
def test_bad_config_raises(options: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        make_config("gp_ucb", **options)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # the model's predictions overflow
@pytest.mark.parametrize("method", ["gp_ucb", "rembo", "bamsoo"])
@pytest.mark.parametrize(
    "values",
    [
        [1e308, -1e308],  # alternating at the limits: the variance overflowed
        [1.7e308],  # all at the limit
        [-1.7e308, 0.0, 1.0],  # one failure-like value among ordinary ones
    ],
    ids=["alternating", "constant", "one-huge"],
)
def test_values_near_the_float_limits_give_finite_points_inside(
    method: str, values: list[float]
) -> None:
    """GP-UCB and REMBO raised IndexError (no candidate had a finite acquisition)."""
    from voot.optim.base import Bounds

    box = Bounds([0.0] * 3, [1.0] * 3)
    fast = {"fit_restarts": 1} if method == "bamsoo" else {"n_candidates": 200, "fit_restarts": 1}
    opt = make_optimizer(method, box, seed=0, **fast)
    for i in range(12):
        x = opt.ask()
        assert np.all(np.isfinite(x)) and box.contains(x)
        opt.tell(x, values[i % len(values)])


def test_standardising_huge_values_matches_ordinary_ones() -> None:
    """The overflow-free standardisation gives what the ordinary one gives, scaled."""
    from voot.optim.gp import GaussianProcess

    y = np.array([3.0, -1.0, 2.0, 0.5])
    gp = GaussianProcess(1)
    small, m, s = gp._standardize(y)
    huge, mh, sh = gp._standardize(y * 1e300)
    assert np.allclose(small, huge, rtol=1e-12)
    assert np.isclose(mh, m * 1e300) and np.isclose(sh, s * 1e300)
    flat, mf, sf = gp._standardize(np.full(3, 1.7e308))
    assert np.all(flat == 0.0) and mf == 1.7e308 and sf == 1.7e308
