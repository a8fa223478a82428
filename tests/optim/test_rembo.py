"""Tests of REMBO (voot.optim.rembo)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from optim_fixtures import bowl, run_on

from voot.optim import make_config, make_optimizer, maximize
from voot.optim.rembo import REMBO, REMBOConfig, default_low_dim

FAST = {"n_candidates": 2000, "fit_restarts": 1}


def run(seed: int, d: int = 5, budget: int = 10, **options) -> REMBO:
    return run_on(REMBO, seed, d, budget, **{**FAST, **options})


def test_default_low_dim_follows_the_paper() -> None:
    assert default_low_dim(10) == 2 and default_low_dim(20) == 3
    opt = make_optimizer("rembo", [[0.0, 1.0]] * 20, seed=0)
    assert isinstance(opt, REMBO)
    assert opt.low_dim == 3 and opt.A.shape == (20, 3)
    assert opt.half_width == pytest.approx(math.sqrt(3))
    assert REMBOConfig.paper_grid() == {"zeta": [0.01, 0.1, 0.5, 1.0]}


def test_embedding_clips_into_the_box() -> None:
    lo, hi = np.array([-5.0, 0.0, 10.0, 2.0]), np.array([5.0, 1.0, 20.0, 3.0])
    opt = make_optimizer("rembo", (lo, hi), seed=1, low_dim=2)
    assert isinstance(opt, REMBO)
    z = np.random.default_rng(0).uniform(-opt.half_width, opt.half_width, (200, 2))
    x = opt.low_to_box(z)
    assert np.all(x >= lo) and np.all(x <= hi)
    y = np.clip(z @ opt.A.T, -1.0, 1.0)
    np.testing.assert_allclose(x, lo + (y + 1.0) / 2.0 * (hi - lo))
    np.testing.assert_allclose(opt.low_to_box(np.zeros(2)), (lo + hi) / 2.0)


def test_deterministic_for_a_seed_and_inside_bounds() -> None:
    a, b, c = run(3), run(3), run(4)
    np.testing.assert_array_equal(a.xs, b.xs)
    np.testing.assert_array_equal(a.A, b.A)
    assert not np.array_equal(a.A, c.A)
    assert np.all(np.abs(a.xs) <= 1.0)


def test_initial_point_is_evaluated_but_not_modelled() -> None:
    x0 = np.full(5, 0.9)
    opt = run(0, budget=6, initial_point=x0)
    np.testing.assert_array_equal(opt.xs[0], x0)
    assert opt.surrogate.gp.n == 4  # synced at the 6th ask: 5 told, minus the initial point
    assert bowl(x0) not in opt.surrogate.gp.y.tolist()
    assert opt.best_value >= bowl(x0)


def test_every_proposal_lies_on_the_embedding() -> None:
    opt = run(2, budget=8)
    for x in opt.xs:
        # x = clip(A z) for some z: unclipped coordinates are in the column space of A
        inside = np.abs(x) < 1.0 - 1e-12
        z, *_ = np.linalg.lstsq(opt.A[inside], x[inside], rcond=None)
        np.testing.assert_allclose(opt.A[inside] @ z, x[inside], atol=1e-9)


def test_beats_random_search_on_a_smooth_function() -> None:
    bounds = [[-1.0, 1.0]] * 5
    x0 = np.full(5, 0.9)
    for seed in (0, 1):
        rembo = maximize(bowl, bounds, "rembo", 30, seed, x0, low_dim=2, **FAST).best_value
        rnd = maximize(bowl, bounds, "random", 30, seed, x0).best_value
        assert rembo > 0.6 * rnd, (seed, rembo, rnd)  # regret at least 40% smaller


def test_low_dim_must_be_below_dim() -> None:
    with pytest.raises(ValueError, match="low_dim < dim"):
        make_optimizer("rembo", [[0.0, 1.0]] * 3, low_dim=3)
    with pytest.raises(ValueError, match="gp_ucb"):
        make_optimizer("rembo", [[0.0, 1.0]] * 2)
    opt = make_optimizer("rembo", [[0.0, 1.0]] * 3)  # default 2 < 3 is allowed
    assert isinstance(opt, REMBO) and opt.low_dim == 2


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"low_dim": 0}, "low_dim"),
        ({"box_half_width": -1.0}, "box_half_width"),
        ({"zeta": float("inf")}, "zeta"),
        ({"n_candidates": 0}, "n_candidates"),
        ({"refit_growth": 0.0}, "refit_growth"),
    ],
)
def test_bad_config_raises(options: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        make_config("rembo", **options)
