"""SOO (voot.optim.soo)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voot.optim import Bounds, make_optimizer, maximize
from voot.optim.soo import SOO, SOOConfig

Q_OPT = np.array([0.3, -0.2, 0.1])


def quad(x: np.ndarray) -> float:
    return -float(np.sum((x - Q_OPT) ** 2))


def branin(x: np.ndarray) -> float:
    """Negated Branin on [-5, 10] x [0, 15], maximum -0.397887."""
    b, c, t = 5.1 / (4 * np.pi**2), 5 / np.pi, 1 / (8 * np.pi)
    return -float((x[1] - b * x[0] ** 2 + c * x[0] - 6) ** 2 + 10 * (1 - t) * np.cos(x[0]) + 10)


_H_A = np.array([[3.0, 10, 30], [0.1, 10, 35], [3.0, 10, 30], [0.1, 10, 35]])
_H_C = np.array([1.0, 1.2, 3.0, 3.2])
_H_P = 1e-4 * np.array(
    [[3689, 1170, 2673], [4699, 4387, 7470], [1091, 8732, 5547], [381, 5743, 8828]]
)


def hartmann3(x: np.ndarray) -> float:
    return float(_H_C @ np.exp(-np.sum(_H_A * (x - _H_P) ** 2, axis=1)))


def run(opt: SOO, f, n: int) -> SOO:
    for _ in range(n):
        x = opt.ask()
        opt.tell(x, f(x))
    return opt


def naive_soo(f, lower, upper, n: int) -> np.ndarray:
    """Munos (2011) SOO with K = 3 written plainly: leaves in a list, h_max(t) = sqrt(t)."""
    lo0, hi0 = np.asarray(lower, float), np.asarray(upper, float)
    x0 = 0.5 * (lo0 + hi0)
    leaves = [(0, 0, lo0, hi0, x0, f(x0))]  # (id, depth, lower, upper, x, value)
    pts = [x0]
    next_id, t = 1, 0
    while True:
        v_max, h = -math.inf, 0
        while h <= min(max(L[1] for L in leaves), math.sqrt(t)):
            at_h = [L for L in leaves if L[1] == h]
            if at_h:
                best = max(at_h, key=lambda L: (L[5], -L[0]))
                if best[5] >= v_max:
                    leaves.remove(best)
                    _, depth, lo, hi, x, v = best
                    j = int(np.argmax(hi - lo))
                    a, b = (2 * lo[j] + hi[j]) / 3, (lo[j] + 2 * hi[j]) / 3
                    for k, (e0, e1) in enumerate(((lo[j], a), (a, b), (b, hi[j]))):
                        clo, chi, cx = lo.copy(), hi.copy(), x.copy()
                        clo[j], chi[j] = e0, e1
                        if k == 1:
                            cv = v
                        else:
                            cx[j] = 0.5 * (e0 + e1)
                            cv = f(cx)
                            pts.append(cx)
                            if len(pts) == n:
                                return np.array(pts)
                        leaves.append((next_id, depth + 1, clo, chi, cx, cv))
                        next_id += 1
                    v_max, t = v, t + 1
            h += 1


@pytest.mark.parametrize(
    "f,lo,hi",
    [(branin, [-5, 0], [10, 15]), (quad, [-1] * 3, [1] * 3), (hartmann3, [0] * 3, [1] * 3)],
)
def test_matches_naive_reference(f, lo, hi):
    opt = run(SOO(Bounds(lo, hi)), f, 200)
    np.testing.assert_array_equal(opt.xs, naive_soo(f, lo, hi, 200))


def test_deterministic_whatever_the_seed():
    a = run(SOO(Bounds.cube(-1, 1, 3), seed=0), quad, 300)
    b = run(SOO(Bounds.cube(-1, 1, 3), seed=12345), quad, 300)
    assert a.xs.tobytes() == b.xs.tobytes()


@pytest.mark.parametrize("split", ["trisect", "bisect"])
def test_points_inside_bounds_and_never_repeated(split):
    bounds = Bounds([-3.0, 0.0, 10.0], [-1.0, 0.5, 100.0])
    opt = make_optimizer("soo", bounds, split=split)
    run(opt, lambda x: -float(np.sum(np.abs(x - [-2.2, 0.1, 40.0]))), 400)
    assert np.all(opt.xs >= bounds.lower) and np.all(opt.xs <= bounds.upper)
    assert len({tuple(x) for x in opt.xs}) == opt.n_told


def test_converges_on_quadratic_branin_and_hartmann3():
    # tolerances: value gap after 500 evaluations
    assert maximize(quad, [[-1, 1]] * 3, method="soo", budget=500).best_value > -5e-5
    assert (
        maximize(branin, [[-5, 10], [0, 15]], method="soo", budget=500).best_value
        > -0.397887 - 1e-4
    )
    assert maximize(hartmann3, [[0, 1]] * 3, method="soo", budget=500).best_value > 3.86278 - 1e-3
    res = maximize(branin, [[-5, 10], [0, 15]], method="soo", budget=500, split="bisect")
    assert res.best_value > -0.397887 - 1e-3


def test_trisection_costs_two_evaluations_per_expansion():
    opt = run(SOO(Bounds.cube(0, 1, 2)), quad_2d := (lambda x: -float(np.sum((x - 0.2) ** 2))), 1)
    np.testing.assert_array_equal(opt.xs[0], [0.5, 0.5])
    run(opt, quad_2d, 40)
    # 20 expansions are complete; telling the 41st point started the 21st
    assert opt.n_told == 41 and opt.n_expansions == 21
    assert opt.n_cells == 1 + 3 * 21


def test_depth_limit():
    """A cell is expanded only at depth <= max(h_max(t), shallowest leaf depth)."""
    opt = run(
        SOO(Bounds.cube(0, 1, 2), SOOConfig(depth_exponent=0.25)), lambda x: -float(x @ x), 300
    )
    tree = opt.partition
    depth = tree.depth[: tree.n]
    shallowest = int(depth[tree.leaf[: tree.n]].min())
    bound = max(math.floor(opt.h_max(opt.n_expansions)), shallowest)
    assert int(depth.max()) <= bound + 1
    max_depth = int(depth.max())
    deep = run(SOO(Bounds.cube(0, 1, 2), SOOConfig(depth_scale=3.0)), lambda x: -float(x @ x), 300)
    assert int(deep.partition.depth[: deep.n_cells].max()) > max_depth


def test_tiny_depth_scale_still_progresses():
    opt = run(SOO(Bounds.cube(0, 1, 2), SOOConfig(depth_scale=1e-6)), lambda x: -float(x @ x), 100)
    assert opt.n_expansions >= 40
    assert opt.best_value > -0.01


def test_initial_point_represents_the_root():
    x0 = np.array([0.9, -0.7, 0.2])
    opt = SOO(Bounds.cube(-1, 1, 3), initial_point=x0)
    x = opt.ask()
    np.testing.assert_array_equal(x, x0)
    opt.tell(x, quad(x))
    run(opt, quad, 3)
    # the root point is not the box centre, so all three thirds are evaluated
    np.testing.assert_allclose(opt.xs[1:4], [[-2 / 3, 0, 0], [0, 0, 0], [2 / 3, 0, 0]], atol=1e-15)
    assert opt.n_cells == 1 + 3 * 2  # root's thirds, and the next expansion has started
    run(opt, quad, 300)
    assert opt.best_value > -1e-3


def test_reask_returns_the_same_point():
    opt = run(SOO(Bounds.cube(0, 1, 2)), lambda x: float(x[0]), 5)
    assert np.array_equal(opt.ask(), opt.ask())
    assert not SOO.supports_revalue


def test_float_resolution_exhausts_then_uniform():
    bounds = Bounds([1.0, 2.0], [1.0 + 1e-13, 2.0 + 1e-13])
    opt = run(SOO(bounds, seed=0), lambda x: float(x.sum()), 300)
    assert opt._exhausted
    assert np.all(opt.xs >= bounds.lower) and np.all(opt.xs <= bounds.upper)


def test_speed_sanity_d20():
    """2000 evaluations in 20-D (no timing assert)."""
    opt = run(SOO(Bounds.cube(-500, 500, 20)), lambda x: -float(np.sum((x - 123.0) ** 2)), 2000)
    assert opt.n_told == 2000 and opt.n_cells <= 1 + 3 * opt.n_expansions


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"split": "halves"}, "split.*bisect, trisect"),
        ({"depth_scale": 0.0}, "depth_scale"),
        ({"depth_scale": math.inf}, "depth_scale"),
        ({"depth_scale": "1"}, "depth_scale"),
        ({"depth_exponent": 0.0}, "depth_exponent.*\\(0, 1\\]"),
        ({"depth_exponent": 1.5}, "depth_exponent"),
        ({"depth_exponent": True}, "depth_exponent"),
        ({"scale": "log"}, "scale"),
        ({"scale": [1.0, 0.0]}, "scale"),
    ],
)
def test_bad_config(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SOOConfig(**kwargs)


def test_config_defaults_and_registry():
    cfg = SOOConfig()
    assert cfg.split == "trisect" and cfg.depth_scale == 1.0 and cfg.depth_exponent == 0.5
    assert SOOConfig.paper_grid() == {}
    assert isinstance(make_optimizer("SOO", Bounds.cube(0, 1, 2)), SOO)
    with pytest.raises(ValueError, match="2 dimensions"):
        SOO(Bounds.cube(0, 1, 2), SOOConfig(scale=(1.0,)))
