"""Tests of BaMSOO (voot.optim.bamsoo)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from optim_fixtures import bowl, run_on

from voot.optim import make_config, maximize
from voot.optim.bamsoo import BaMSOO, BaMSOOConfig, _Node

FAST = {"fit_restarts": 1}


def run(seed: int, d: int = 2, budget: int = 15, f=bowl, **options) -> BaMSOO:
    return run_on(BaMSOO, seed, d, budget, f, **{**FAST, **options})


def test_split_trisects_the_longest_side() -> None:
    node = _Node(np.array([0.0, 0.0]), np.array([1.0, 3.0]), 0)
    kids = node.split(3)
    np.testing.assert_allclose([k.lo[1] for k in kids], [0.0, 1.0, 2.0])
    np.testing.assert_allclose([k.hi[1] for k in kids], [1.0, 2.0, 3.0])
    assert all(k.lo[0] == 0.0 and k.hi[0] == 1.0 and k.depth == 1 for k in kids)
    np.testing.assert_array_equal(kids[1].x, node.x)  # middle child shares the centre
    halves = node.split(2)
    np.testing.assert_allclose([h.x[1] for h in halves], [0.75, 2.25])
    anchored = _Node(np.zeros(2), np.array([1.0, 3.0]), 0, np.array([0.2, 0.6]))
    left, right = anchored.split_at_point()
    assert left.hi[1] == right.lo[1] == 0.6 and left.lo[1] == 0.0 and right.hi[1] == 3.0
    np.testing.assert_allclose(left.x, [0.2, 0.3])
    np.testing.assert_allclose(right.x, [0.2, 1.8])


def test_first_points_are_the_root_centre_and_children() -> None:
    opt = run(0, budget=3, f=lambda x: -float(np.sum(x**2)))
    np.testing.assert_array_equal(opt.xs[0], [0.0, 0.0])
    # trisection of [-1, 1] along dimension 0: outer centres at -2/3 and +2/3
    assert sorted(x[0] for x in opt.xs[1:3]) == pytest.approx([-2.0 / 3.0, 2.0 / 3.0])


def test_deterministic_for_a_seed_and_inside_bounds() -> None:
    a, b = run(5, d=3), run(5, d=3)
    np.testing.assert_array_equal(a.xs, b.xs)
    np.testing.assert_array_equal(a.values, b.values)
    assert np.all(np.abs(a.xs) <= 1.0)


def test_initial_point_first_and_modelled() -> None:
    x0 = np.array([0.9, -0.9])
    opt = run(0, budget=6, initial_point=x0)
    np.testing.assert_array_equal(opt.xs[0], x0)
    np.testing.assert_array_equal(opt.xs[1], [0.0, 0.0])
    assert bowl(x0) in opt.surrogate.gp.y.tolist()


def test_gp_lets_it_skip_evaluations() -> None:
    opt = run(0, d=3, budget=40)
    assert opt.n_skipped > 0
    assert opt.n_nodes > opt.n_told  # the tree holds unevaluated (GP-valued) nodes


@pytest.mark.parametrize(("d", "budget"), [(2, 25), (5, 40)])
def test_beats_random_search_on_a_smooth_function(d: int, budget: int) -> None:
    bounds = [[-1.0, 1.0]] * d
    x0 = np.full(d, 0.9)
    for seed in (0, 1):
        bam = maximize(bowl, bounds, "bamsoo", budget, seed, x0, **FAST).best_value
        rnd = maximize(bowl, bounds, "random", budget, seed, x0).best_value
        assert bam > 0.1 * rnd, (seed, bam, rnd)  # regret at least 10x smaller


def test_binary_split_and_variance_bound_run() -> None:
    opt = run(0, budget=12, branching=2, bound_uses_variance=True, eta=0.9)
    assert opt.n_told == 12
    np.testing.assert_array_equal(opt.xs[1], [-0.5, 0.0])  # binary split: quarter points


def test_authors_random_root_partition() -> None:
    a = run(3, budget=12, branching=2, root_point="random")
    b = run(3, budget=12, branching=2, root_point="random")
    c = run(4, budget=12, branching=2, root_point="random")
    np.testing.assert_array_equal(a.xs, b.xs)
    assert not np.array_equal(a.xs[0], c.xs[0])  # the root point is random
    assert not np.allclose(a.xs[0], 0.0)
    # the first cut is at the root point along dimension 0; children halfway to the faces
    r = a.xs[0]
    kids = sorted(x[0] for x in a.xs[1:3])
    np.testing.assert_allclose(kids, [(r[0] - 1.0) / 2.0, (r[0] + 1.0) / 2.0])
    assert np.all(np.abs(a.xs) <= 1.0)


def test_max_skips_forces_evaluations() -> None:
    opt = run(0, d=3, budget=30, max_skips=1)
    assert opt.n_skipped <= opt.n_told  # never two GP-only children in a row


def test_paper_grid_and_b_n() -> None:
    assert BaMSOOConfig.paper_grid() == {"eta": [0.1, 0.7, 0.9]}
    opt = run(0, budget=4)
    upper, lower = opt._bounds_at(np.array([0.5, 0.5]), 7)
    b = math.sqrt(2.0 * math.log(math.pi**2 * 49 / (6.0 * 0.1)))
    mu, sd = opt.surrogate.gp.predict(np.array([[0.5, 0.5]]))
    assert upper == pytest.approx(mu[0] + b * sd[0]) and lower == pytest.approx(mu[0] - b * sd[0])


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"eta": 0.0}, "eta"),
        ({"eta": 1.0}, "eta"),
        ({"branching": 1}, "branching"),
        ({"h_max_exponent": 0.0}, "h_max_exponent"),
        ({"max_skips": 0}, "max_skips"),
        ({"min_width": 0.0}, "min_width"),
        ({"bound_uses_variance": 1}, "bound_uses_variance"),
        ({"max_points": 0}, "max_points"),
        ({"root_point": "corner"}, "root_point"),
        ({"root_point": "random"}, "branching=2"),
    ],
)
def test_bad_config_raises(options: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        make_config("bamsoo", **options)
