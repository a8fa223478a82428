"""DOO and RAND-DOO (voot.optim.doo)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from voot.optim import Bounds, make_optimizer, maximize
from voot.optim.doo import DOO, PAPER_EPSILONS, DOOConfig, RandDOO, RandDOOConfig

# ----- test functions (maximised) ----------------------------------------------------------
Q_OPT = np.array([0.3, -0.2, 0.1])


def quad(x: np.ndarray) -> float:
    return -float(np.sum((x - Q_OPT) ** 2))


_H_A = np.array([[3.0, 10, 30], [0.1, 10, 35], [3.0, 10, 30], [0.1, 10, 35]])
_H_C = np.array([1.0, 1.2, 3.0, 3.2])
_H_P = 1e-4 * np.array(
    [[3689, 1170, 2673], [4699, 4387, 7470], [1091, 8732, 5547], [381, 5743, 8828]]
)
HART3_MAX = 3.86278


def hartmann3(x: np.ndarray) -> float:
    """Hartmann 3-D on [0, 1]^3, maximum 3.86278 at (0.1146, 0.5556, 0.8525)."""
    return float(_H_C @ np.exp(-np.sum(_H_A * (x - _H_P) ** 2, axis=1)))


def branin(x: np.ndarray) -> float:
    """Negated Branin on [-5, 10] x [0, 15], maximum -0.397887."""
    b, c, t = 5.1 / (4 * np.pi**2), 5 / np.pi, 1 / (8 * np.pi)
    return -float((x[1] - b * x[0] ** 2 + c * x[0] - 6) ** 2 + 10 * (1 - t) * np.cos(x[0]) + 10)


def run(opt: DOO, f, n: int) -> DOO:
    for _ in range(n):
        x = opt.ask()
        opt.tell(x, f(x))
    return opt


# ----- a naive reference DOO (the authors' binary tree, written as plainly as possible) ----
def naive_doo(f, lower, upper, eps: float, n: int) -> np.ndarray:
    """Leaves in a list; b = f(centre) + eps * diagonal; expand the max-b (oldest) leaf."""

    def diag(lo, hi):
        s = hi - lo
        return math.sqrt(float(s @ s))

    lo0, hi0 = np.asarray(lower, float), np.asarray(upper, float)
    x0 = 0.5 * (lo0 + hi0)
    leaves = [(0, lo0, hi0, x0, f(x0))]
    pts = [x0]
    next_id = 1
    while len(pts) < n:
        best = max(leaves, key=lambda L: (L[4] + eps * diag(L[1], L[2]), -L[0]))
        leaves.remove(best)
        _, lo, hi, x, _ = best
        j = int(np.argmax(hi - lo))
        for a, b in ((lo[j], x[j]), (x[j], hi[j])):
            clo, chi, cx = lo.copy(), hi.copy(), x.copy()
            clo[j], chi[j], cx[j] = a, b, 0.5 * (a + b)
            pts.append(cx)
            leaves.append((next_id, clo, chi, cx, f(cx)))
            next_id += 1
    return np.array(pts[:n])


# ----- behaviour ----------------------------------------------------------------------------
@pytest.mark.parametrize(
    "f,lo,hi,eps", [(branin, [-5, 0], [10, 15], 1.0), (quad, [-1] * 3, [1] * 3, 0.01)]
)
def test_doo_matches_naive_reference(f, lo, hi, eps):
    opt = run(DOO(Bounds(lo, hi), DOOConfig(epsilon=eps)), f, 150)
    ref = naive_doo(f, lo, hi, eps, 150)
    np.testing.assert_array_equal(opt.xs, ref)


def test_doo_is_deterministic_and_rand_doo_bit_identical_per_seed():
    a = run(DOO(Bounds.cube(-1, 1, 3), seed=0), quad, 200)
    b = run(DOO(Bounds.cube(-1, 1, 3), seed=99), quad, 200)
    assert np.array_equal(a.xs, b.xs)  # no randomness at all
    r1 = run(RandDOO(Bounds.cube(-1, 1, 3), seed=7), quad, 200)
    r2 = run(RandDOO(Bounds.cube(-1, 1, 3), seed=7), quad, 200)
    r3 = run(RandDOO(Bounds.cube(-1, 1, 3), seed=8), quad, 200)
    assert r1.xs.tobytes() == r2.xs.tobytes()
    assert not np.array_equal(r1.xs, r3.xs)


def test_rand_doo_bit_identical_across_processes():
    code = (
        "import numpy as np, hashlib\n"
        "from voot.optim import maximize\n"
        "r = maximize(lambda x: -float(x @ x), [[-1, 2]] * 4, method='rand_doo', budget=100, seed=3)\n"
        "print(hashlib.sha256(r.xs.tobytes()).hexdigest())\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    import hashlib

    res = maximize(lambda x: -float(x @ x), [[-1, 2]] * 4, method="rand_doo", budget=100, seed=3)
    assert out.stdout.strip() == hashlib.sha256(res.xs.tobytes()).hexdigest()


@pytest.mark.parametrize("method", ["doo", "rand_doo"])
@pytest.mark.parametrize("split", ["bisect", "trisect"])
def test_points_inside_bounds(method, split):
    bounds = Bounds([-3.0, 0.0, 10.0], [-1.0, 0.5, 100.0])
    opt = make_optimizer(method, bounds, seed=1, split=split, epsilon=0.5)
    run(opt, lambda x: -float(np.sum(np.abs(x))), 400)
    assert np.all(opt.xs >= bounds.lower) and np.all(opt.xs <= bounds.upper)


def test_doo_converges_on_quadratic():
    # tolerance: 1e-5 in value, i.e. about 3e-3 in distance, after 200 evaluations
    res = maximize(quad, [[-1, 1]] * 3, method="doo", budget=200, epsilon=0.01)
    assert res.best_value > -1e-5
    assert np.linalg.norm(res.best_x - Q_OPT) < 5e-3


def test_doo_converges_on_hartmann3():
    res = maximize(hartmann3, [[0, 1]] * 3, method="doo", budget=200, epsilon=0.1)
    assert HART3_MAX - res.best_value < 1e-4


def test_rand_doo_converges():
    for seed in range(3):
        res = maximize(quad, [[-1, 1]] * 3, method="rand_doo", budget=200, seed=seed, epsilon=1.0)
        assert res.best_value > -2e-2
        res = maximize(
            branin, [[-5, 10], [0, 15]], method="rand_doo", budget=200, seed=seed, epsilon=10.0
        )
        assert res.best_value > -0.397887 - 0.25


def test_trisection_middle_child_keeps_parent_point():
    opt = DOO(Bounds.cube(0, 1, 2), DOOConfig(split="trisect"))
    run(opt, quad_2d := (lambda x: -float(np.sum((x - 0.2) ** 2))), 3)
    # root at the centre, then only the two outer thirds are evaluated
    np.testing.assert_allclose(opt.xs, [[0.5, 0.5], [1 / 6, 0.5], [5 / 6, 0.5]], rtol=1e-15)
    assert opt.n_cells == 4 and opt.n_expansions == 1
    lo, hi = opt.cell_bounds(0)
    np.testing.assert_allclose([lo[0], hi[0]], [1 / 3, 2 / 3])
    run(opt, quad_2d, 20)
    assert len({tuple(x) for x in opt.xs}) == opt.n_told  # never evaluates a point twice


def test_cell_size_radius_is_half_the_diagonal_at_the_centre():
    d = DOO(Bounds.cube(0, 2, 2), DOOConfig(epsilon=1.0))
    r = DOO(Bounds.cube(0, 2, 2), DOOConfig(epsilon=1.0, cell_size="radius"))
    for o in (d, r):
        o.tell(o.ask(), 0.0)
    assert d.b_values()[0] == pytest.approx(2 * math.sqrt(2))
    assert r.b_values()[0] == pytest.approx(math.sqrt(2))


def test_scale_unit_makes_epsilon_box_independent():
    a = DOO(Bounds.cube(0, 1, 3), DOOConfig(epsilon=1.0, scale="unit"))
    b = DOO(Bounds([0, 0, 0], [1000, 1, 5]), DOOConfig(epsilon=1.0, scale="unit"))
    for o in (a, b):
        o.tell(o.ask(), 0.0)
    assert a.b_values()[0] == pytest.approx(math.sqrt(3))
    assert b.b_values()[0] == pytest.approx(math.sqrt(3))
    # with the unit scale the first cut is along the longest side in unit-cube terms (dim 0
    # on ties), with weights the cut follows the weighted widths
    w = DOO(Bounds([0, 0], [10, 1]), DOOConfig(scale=(0.01, 1.0)))
    w.tell(w.ask(), 0.0)
    x = w.ask()
    assert x[0] == 5.0 and x[1] == 0.25


# ----- initial point ------------------------------------------------------------------------
@pytest.mark.parametrize("cls", [DOO, RandDOO])
def test_initial_point_represents_the_root(cls):
    x0 = np.array([0.9, -0.7])
    opt = cls(Bounds.cube(-1, 1, 2), seed=0, initial_point=x0)
    x = opt.ask()
    np.testing.assert_array_equal(x, x0)
    opt.tell(x, quad(np.r_[x, 0.0]))
    lo, hi = opt.cell_bounds(0)
    np.testing.assert_array_equal(lo, [-1, -1])
    np.testing.assert_array_equal(hi, [1, 1])
    run(opt, lambda x: quad(np.r_[x, 0.0]), 100)
    assert opt.best_value > quad(np.r_[x0, 0.0]) + 0.4  # -0.62 at x0
    if cls is DOO:  # cut at the box centre: the next points are the halves' centres
        np.testing.assert_array_equal(opt.xs[1:3], [[-0.5, 0.0], [0.5, 0.0]])


def test_split_at_initial_point_cuts_through_it():
    x0 = np.array([0.5, -0.5])
    opt = DOO(Bounds.cube(-1, 1, 2), DOOConfig(split_at_initial_point=True), initial_point=x0)
    opt.tell(opt.ask(), 0.0)
    x1 = opt.ask()
    lo, hi = opt.proposal_bounds
    np.testing.assert_array_equal(lo, [-1, -1])
    np.testing.assert_array_equal(hi, [0.5, 1])
    np.testing.assert_array_equal(x1, [-0.25, -0.5])


def test_unproposed_points_stay_out_of_the_tree():
    opt = DOO(Bounds.cube(0, 1, 2))
    opt.tell(opt.ask(), 1.0)  # root
    opt.tell(np.array([0.1, 0.1]), 5.0)  # not proposed
    assert opt.cell_bounds(1) is None
    assert opt.best_index == 1 and opt.n_cells == 1
    opt.revalue(1, -5.0)  # harmless
    assert opt.ask().shape == (2,)


# ----- revalue ------------------------------------------------------------------------------
def test_revalue_changes_the_next_selected_cell():
    def f(x):
        return quad(np.r_[x, 0.0])

    def grown():
        return run(DOO(Bounds.cube(-1, 1, 2), DOOConfig(epsilon=0.1)), f, 41)

    a, b = grown(), grown()
    assert not a._queue  # 1 + 2 * 20 tells: the next ask selects a leaf
    bv = a.b_values()
    leaves = np.flatnonzero(np.isfinite(bv))
    best, worst = int(leaves[np.argmax(bv[leaves])]), int(leaves[np.argmin(bv[leaves])])
    i = int(a.partition.point[worst])
    lo, hi = a.cell_bounds(i)
    b.revalue(i, 100.0)  # the worst leaf now has the largest b-value
    xa, xb = a.ask(), b.ask()
    assert not (np.all(xa >= lo) and np.all(xa <= hi))
    assert np.all(xb >= lo) and np.all(xb <= hi)
    assert b.partition.parent[b._proposal_cell] == worst
    assert a.partition.parent[a._proposal_cell] == best
    # lowering the best leaf's value moves the selection away from it too
    c = grown()
    c.revalue(int(c.partition.point[best]), -100.0)
    c.ask()
    assert c.partition.parent[c._proposal_cell] != best


def test_revalue_updates_b_value_in_place():
    opt = run(DOO(Bounds.cube(0, 1, 2), DOOConfig(epsilon=0.5)), lambda x: float(x.sum()), 9)
    i = opt.n_told - 1
    c = int(opt._cell_of[i])
    assert c >= 0
    before = opt.b_values()[c]
    opt.revalue(i, opt.values[i] - 3.0)
    assert opt.b_values()[c] == pytest.approx(before - 3.0)
    assert DOO.supports_revalue and RandDOO.supports_revalue


# ----- RAND-DOO specifics ---------------------------------------------------------------------
def test_rand_doo_points_lie_in_the_chosen_cell():
    opt = RandDOO(Bounds.cube(-2, 2, 3), RandDOOConfig(epsilon=0.3), seed=4)
    for _ in range(300):
        x = opt.ask()
        lo, hi = opt.proposal_bounds
        assert np.all(x >= lo) and np.all(x <= hi)
        c = opt._proposal_cell
        # the chosen cell is a child of an expanded leaf (or the root)
        assert c == 0 or opt.b_values()[opt.partition.parent[c]] == -np.inf
        opt.tell(x, quad(x))
        i = opt.n_told - 1
        np.testing.assert_array_equal(opt.cell_bounds(i)[0], lo)


def test_rand_doo_reask_redraws_in_the_same_cell():
    opt = run(RandDOO(Bounds.cube(0, 1, 2), seed=0), lambda x: float(x[0]), 7)
    x1 = opt.ask()
    b1 = opt.proposal_bounds
    x2 = opt.ask()
    b2 = opt.proposal_bounds
    assert not np.array_equal(x1, x2)
    np.testing.assert_array_equal(b1[0], b2[0])
    np.testing.assert_array_equal(b1[1], b2[1])
    opt.tell(x2, 0.0)  # telling the latest proposal assigns it
    assert opt.cell_bounds(opt.n_told - 1) is not None


def test_mark_infeasible_does_not_split():
    opt = run(RandDOO(Bounds.cube(0, 1, 2), seed=0), lambda x: float(x[0]), 5)
    x = opt.ask()
    lo, hi = opt.proposal_bounds
    opt.tell(x, -2.0)
    i = opt.n_told - 1
    cells = opt.n_cells
    assert opt.mark_infeasible(i)
    assert opt.cell_bounds(i) is None and opt.infeasible == [i]
    assert opt.values[i] == -2.0  # stays in the history
    y = opt.ask()  # the same cell is sampled again
    np.testing.assert_array_equal(opt.proposal_bounds[0], lo)
    assert np.all(y >= lo) and np.all(y <= hi) and not np.array_equal(x, y)
    assert opt.n_cells == cells
    assert not opt.mark_infeasible(i)  # already marked: nothing to do
    opt.tell(np.array([0.5, 0.5]), -2.0)  # not proposed: outside the tree
    assert not opt.mark_infeasible(opt.n_told - 1)
    assert opt.infeasible == [i]
    with pytest.raises(IndexError):
        opt.mark_infeasible(opt.n_told)


def test_mark_infeasible_root_resamples_root():
    opt = RandDOO(Bounds.cube(0, 1, 2), seed=0)
    opt.tell(opt.ask(), -2.0)
    opt.mark_infeasible(0)
    opt.ask()
    lo, hi = opt.proposal_bounds
    np.testing.assert_array_equal(lo, [0, 0])
    np.testing.assert_array_equal(hi, [1, 1])
    assert opt.n_cells == 1


def test_reuse_parent_point_saves_evaluations():
    plain = run(RandDOO(Bounds.cube(0, 1, 2), seed=0), lambda x: float(x[0]), 101)
    reuse = run(
        RandDOO(Bounds.cube(0, 1, 2), RandDOOConfig(reuse_parent_point=True), seed=0),
        lambda x: float(x[0]),
        101,
    )
    assert plain.n_expansions == 50
    assert reuse.n_expansions == 100  # one new sample per bisection
    # each point represents at most one leaf, and reused points lie in their leaf
    for i in range(reuse.n_told):
        cb = reuse.cell_bounds(i)
        if cb is not None:
            assert np.all(reuse.xs[i] >= cb[0]) and np.all(reuse.xs[i] <= cb[1])


# ----- resolution, speed sanity ---------------------------------------------------------------
def test_float_resolution_retires_cells_and_falls_back_to_uniform():
    bounds = Bounds([1.0], [1.0 + 1e-13])
    opt = run(DOO(bounds, DOOConfig(epsilon=0.0)), lambda x: float(x[0]), 200)
    assert opt.n_leaves == 0 and opt.proposal_bounds is None
    assert np.all(opt.xs >= bounds.lower) and np.all(opt.xs <= bounds.upper)


def test_speed_sanity_d20():
    """2000 evaluations in 20-D: cells grow linearly (no timing assert)."""
    rng = np.random.default_rng(0)
    centre = rng.uniform(-400, 400, 20)
    for cls in (DOO, RandDOO):
        opt = run(
            cls(Bounds.cube(-500, 500, 20), seed=0),
            lambda x: -float(np.sum((x - centre) ** 2)),
            2000,
        )
        assert opt.n_told == 2000 and opt.n_cells <= 2001
        assert opt.n_leaves <= opt.n_cells


# ----- configuration --------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"epsilon": -1.0}, "epsilon"),
        ({"epsilon": float("nan")}, "epsilon"),
        ({"epsilon": "big"}, "epsilon"),
        ({"epsilon": True}, "epsilon"),
        ({"split": "quarter"}, "split.*bisect, trisect"),
        ({"cell_size": "area"}, "cell_size.*diagonal, radius"),
        ({"scale": "log"}, "scale.*absolute.*unit"),
        ({"scale": (1.0, -1.0)}, "scale"),
        ({"scale": ()}, "scale"),
        ({"split_at_initial_point": 1}, "split_at_initial_point"),
        ({"split_at_initial_point": True, "split": "trisect"}, "split_at_initial_point.*bisect"),
    ],
)
def test_bad_config(kwargs, match):
    with pytest.raises(ValueError, match=match):
        DOOConfig(**kwargs)


def test_bad_rand_config_and_scale_length():
    with pytest.raises(ValueError, match="reuse_parent_point"):
        RandDOOConfig(reuse_parent_point="yes")
    with pytest.raises(ValueError, match=r"3 weights.*2 dimensions"):
        DOO(Bounds.cube(0, 1, 2), DOOConfig(scale=[1.0, 2.0, 3.0]))
    with pytest.raises(ValueError, match="unknown option"):
        make_optimizer("doo", Bounds.cube(0, 1, 2), explr_p=0.1)


def test_config_values_are_normalised_and_grid():
    cfg = DOOConfig(split="trisect", scale=[1, 2])
    assert cfg.split == "trisect" and cfg.scale == (1.0, 2.0)
    grid = DOOConfig.paper_grid()["epsilon"]
    assert grid == PAPER_EPSILONS and grid == sorted(grid)
    assert grid[0] == np.finfo(float).eps and grid[-1] == 1.0
    assert RandDOOConfig.paper_grid() == DOOConfig.paper_grid()
    assert isinstance(make_optimizer("rand-doo", Bounds.cube(0, 1, 2)), RandDOO)
