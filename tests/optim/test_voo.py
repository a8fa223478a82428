"""Tests of VOO (voot.optim.voo): best-cell samplers, exactness, determinism, convergence."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from voot.functions import get_function
from voot.optim import Bounds, make_optimizer, maximize, voo
from voot.optim.voo import NEAR, NEIGHBOURS, VOO, BestCellSampler, VOOConfig

SAMPLERS = [s.value for s in BestCellSampler]


def brute_in_cell(xs: np.ndarray, b: int, p: np.ndarray, rtol: float = 0.0) -> bool:
    """Is p at least as close to xs[b] as to every row of xs (distances from differences)?"""
    d = np.sqrt(np.sum((xs - p) ** 2, axis=1))
    return bool(d[b] <= d.min() * (1.0 + rtol))


def told(
    points: np.ndarray, values: np.ndarray, box: Bounds, seed: int = 0, **options: object
) -> VOO:
    opt = VOO(box, VOOConfig(**options), seed=seed)  # type: ignore[arg-type]
    for x, v in zip(points, values, strict=True):
        opt.tell(x, float(v))
    return opt


def random_state(n: int, d: int, seed: int = 0, **options: object) -> VOO:
    rng = np.random.default_rng(seed)
    box = Bounds.cube(-1.0, 1.0, d)
    xs = box.sample(rng, n)
    return told(xs, -np.sum((xs - 0.2) ** 2, axis=1), box, seed=seed, **options)


def clustered_state(n: int, d: int, scale: float, seed: int = 0) -> VOO:
    """n points within `scale` of 0.3 (far below the box's scale), best in the middle."""
    rng = np.random.default_rng(seed)
    box = Bounds.cube(-1.0, 1.0, d)
    xs = 0.3 + scale * rng.standard_normal((n, d))
    values = -np.sum((xs - 0.3) ** 2, axis=1)
    return told(xs, values, box, seed=seed)


# ----- the returned points lie in the best cell ------------------------------------------


@pytest.mark.parametrize("sampler", SAMPLERS)
def test_samples_lie_in_best_cell(sampler: str) -> None:
    n = 30 if sampler == "uniform" else 300  # the uniform sampler must succeed in 1000 tries
    opt = random_state(n, 4, seed=1, sampler=sampler)
    xs, b = opt.xs.copy(), opt.best_index
    rejected = [opt.n_rejected]
    for _ in range(200):
        p = opt.sample_best_cell()
        assert opt.bounds.contains(p)
        assert brute_in_cell(xs, b, p, rtol=1e-12)
        rejected.append(opt.n_rejected)
    assert opt.n_fallbacks == 0
    # a count of the tries rejected: it never goes down, and some were
    assert np.all(np.diff(rejected) >= 0) and rejected[-1] > 0
    assert opt.sampler.value == sampler


@pytest.mark.parametrize("scale", [1e-3, 1e-8, 1e-13])
def test_samples_lie_in_best_cell_of_tight_clusters(scale: float) -> None:
    opt = clustered_state(500, 6, scale, seed=2)
    xs, b = opt.xs.copy(), opt.best_index
    for _ in range(100):
        p = opt.sample_best_cell()
        assert brute_in_cell(xs, b, p, rtol=1e-9)
    assert opt.n_fallbacks == 0


def _proposals_at_all_scales(opt: VOO, rng: np.random.Generator, m: int) -> np.ndarray:
    best = opt.xs[opt.best_index]
    spread = np.max(np.abs(opt.xs - best))
    r = spread * 10.0 ** rng.uniform(-4, 0.5, size=(m, 1))
    u = rng.standard_normal((m, best.size))
    return r * u / np.linalg.norm(u, axis=1, keepdims=True)


@pytest.mark.parametrize(
    "make",
    [
        lambda: random_state(20, 3, seed=3),  # fewer points than the neighbour cache
        lambda: random_state(1000, 5, seed=4),  # many more
        lambda: clustered_state(400, 8, 1e-9, seed=5),
    ],
)
def test_fast_test_matches_brute_force(make) -> None:  # type: ignore[no-untyped-def]
    opt = make()
    rng = np.random.default_rng(0)
    sorted_used = []
    for step in range(3):
        cell = opt._best_cell()
        xs, b = opt.xs.copy(), opt.best_index
        q = _proposals_at_all_scales(opt, rng, 400)
        fast = np.array([opt._first_inside(cell, q[i : i + 1]) == 0 for i in range(len(q))])
        brute = np.array([brute_in_cell(xs, b, xs[b] + qi) for qi in q])
        exact = opt.in_best_cell(xs[b] + q)
        assert 0 < fast.sum() < len(q)  # both outcomes are exercised
        # decisions agree except at floating-point ties (none expected here)
        np.testing.assert_array_equal(fast, brute)
        np.testing.assert_array_equal(exact, brute)
        # batches ordered like tries (shrinking radius): the first inside is found
        for _ in range(40):
            batch = _proposals_at_all_scales(opt, rng, 30)
            batch = batch[np.argsort(-np.linalg.norm(batch, axis=1))]
            inside = [brute_in_cell(xs, b, xs[b] + qi) for qi in batch]
            expected = inside.index(True) if any(inside) else -1
            assert opt._first_inside(cell, batch) == expected
        sorted_used.append(cell.ordered)
        # tell more points (and sometimes a new best) and test the updated cache again
        for x in xs[b] + q[:5] * 0.3:
            opt.tell(x, float(opt.values.min()) - 1.0)
        if step == 1:
            opt.tell(xs[b] + q[0] * 1e-3, opt.best_value + 1.0)
    if opt.n_told > 2 * NEIGHBOURS:  # the exact check used the sorted structure
        assert any(sorted_used)


@pytest.mark.parametrize(("n_close", "far_first"), [(400, False), (100, True)])
def test_rejection_by_a_point_beyond_the_neighbour_tiers(n_close: int, far_first: bool) -> None:
    # x* = 0 with close points on its +e1 side and one far point at -e1: a proposal
    # towards -e1 passes every cached-neighbour filter and only the far point rejects it
    # (told last, or first: the exact check must see the first told point too)
    d = 3
    box = Bounds.cube(-2.0, 2.0, d)
    rng = np.random.default_rng(0)
    close = 1e-3 * np.abs(rng.standard_normal((n_close, d)))
    close[:, 0] += 1e-3
    far = -np.eye(d)[0]
    if far_first:
        pts = np.vstack([far, np.zeros(d), close])
        values = np.r_[0.0, 1.0, np.zeros(n_close)]
    else:
        pts = np.vstack([np.zeros(d), close, far])
        values = np.r_[1.0, np.zeros(n_close + 1)]
    opt = told(pts, values, box)
    b = opt.best_index
    cell = opt._best_cell()
    q = np.array([[-0.6, 0.0, 0.0], [-0.4, 0.0, 0.0]])
    assert [brute_in_cell(opt.xs, b, x) for x in q] == [False, True]
    assert opt._first_inside(cell, q[:1]) == -1
    assert opt._first_inside(cell, q) == 1


def test_a_far_proposal_is_checked_against_the_nearest_point_outside_the_cache() -> None:
    # x* = 0, NEIGHBOURS close points (the cache) and one point at -e1, the nearest outside
    # the cache (out2 = 1): a proposal 2.5 away towards it is closer to it than to x*
    d = 3
    rng = np.random.default_rng(2)
    close = 1e-3 * np.abs(rng.standard_normal((NEIGHBOURS, d)))
    close[:, 0] += 1e-3
    pts = np.vstack([np.zeros(d), close, -np.eye(d)[0]])
    opt = told(pts, np.r_[1.0, np.zeros(NEIGHBOURS + 1)], Bounds.cube(-3.0, 3.0, d))
    cell = opt._best_cell()
    assert cell.out2 == 1.0
    q = np.array([[-2.5, 0.0, 0.0]])
    assert not brute_in_cell(opt.xs, 0, q[0])
    assert opt._first_inside(cell, q) == -1


def test_rejection_by_a_point_told_after_the_sort() -> None:
    # x* = 0, 100 close points on its +e1 side (they fill the neighbour cache), then, after
    # the exact check sorted them, one far point at -2 e1: only the unsorted tail of the
    # exact check sees it, and it must reject -1.2 e1 (closer to it) but not -0.9 e1
    d = 3
    box = Bounds.cube(-3.0, 3.0, d)
    rng = np.random.default_rng(1)
    close = 1e-3 * np.abs(rng.standard_normal((100, d)))
    close[:, 0] += 1e-3
    opt = told(np.vstack([np.zeros(d), close]), np.r_[1.0, np.zeros(100)], box)
    cell = opt._best_cell()
    assert opt._first_inside(cell, np.array([[-0.5, 0.0, 0.0]])) == 0
    assert cell.ordered and cell.tail == opt.n_told  # the exact check sorted the points
    opt.tell(-2.0 * np.eye(d)[0], 0.0)
    cell = opt._best_cell()
    assert cell.tail < cell.n == opt.n_told
    q = np.array([[-1.2, 0.0, 0.0], [-0.9, 0.0, 0.0]])
    assert [brute_in_cell(opt.xs, 0, x) for x in q] == [False, True]
    assert opt._first_inside(cell, q[:1]) == -1
    assert opt._first_inside(cell, q[1:]) == 0
    assert opt._first_inside(cell, q) == 1


def test_a_copy_of_the_best_told_with_a_rejecting_point() -> None:
    # few points (cache not full): a copy of x* and, in the same update of the cache, a
    # point at +e1 that must enter it and reject +0.6 e1
    d = 2
    box = Bounds.cube(-2.0, 2.0, d)
    opt = told(np.array([[0.0, 0.0], [0.0, -1.0]]), np.array([1.0, 0.0]), box)
    cell = opt._best_cell()
    opt.tell(np.zeros(d), 0.5)  # a copy of x*
    opt.tell(np.array([1.0, 0.0]), 0.0)
    cell = opt._best_cell()
    assert cell.count == 2
    q = np.array([[0.6, 0.0], [0.4, 0.0]])
    assert opt._first_inside(cell, q[:1]) == -1
    assert opt._first_inside(cell, q) == 1


def test_neighbour_cache_invariants() -> None:
    opt = random_state(3 * NEIGHBOURS, 3, seed=6)
    rng = np.random.default_rng(1)
    for i in range(150):
        x = opt.ask()
        opt.tell(x, float(rng.normal()) if i % 10 else opt.best_value + 1.0)
        if i % 7 == 0:
            opt.revalue(int(rng.integers(opt.n_told)), float(rng.normal()))
        cell = opt._best_cell()
        v = opt.xs - opt.xs[opt.best_index]
        d2 = np.sum(v**2, axis=1)
        d2[d2 == 0.0] = np.inf
        order = np.sort(d2)
        assert cell.count == NEIGHBOURS
        np.testing.assert_allclose(np.sort(cell.k2[: cell.count]), order[:NEIGHBOURS])
        assert cell.out2 == pytest.approx(order[NEIGHBOURS])


def test_copies_of_the_best_are_harmless() -> None:
    box = Bounds.cube(-1.0, 1.0, 3)
    rng = np.random.default_rng(0)
    others = box.sample(rng, 10)
    best = np.array([0.1, 0.2, 0.3])
    pts = np.vstack([best, np.repeat(best[None], 3 * NEIGHBOURS, axis=0), others])
    vals = np.r_[1.0, np.zeros(3 * NEIGHBOURS), -np.ones(10)]
    opt = told(pts, vals, box)
    cell = opt._best_cell()
    assert cell.count == 10  # only the real neighbours are cached
    for _ in range(50):
        assert brute_in_cell(opt.xs, opt.best_index, opt.sample_best_cell())


# ----- determinism and exploration -------------------------------------------------------


def quadratic(x: np.ndarray) -> float:
    return -float(np.sum((x - 0.3) ** 2))


@pytest.mark.parametrize("sampler", SAMPLERS)
def test_same_seed_same_points(sampler: str) -> None:
    box = Bounds.cube(-1.0, 1.0, 3)
    a = maximize(quadratic, box, "voo", budget=150, seed=9, sampler=sampler, omega=0.1)
    b = maximize(quadratic, box, "voo", budget=150, seed=9, sampler=sampler, omega=0.1)
    c = maximize(quadratic, box, "voo", budget=150, seed=10, sampler=sampler, omega=0.1)
    np.testing.assert_array_equal(a.xs, b.xs)
    assert not np.array_equal(a.xs, c.xs)


def test_omega_one_is_uniform_search() -> None:
    box = Bounds([0.0, -5.0], [1.0, 5.0])
    a = maximize(quadratic, box, "voo", budget=1500, seed=0, omega=1.0)
    b = maximize(lambda x: float(x[0]), box, "voo", budget=1500, seed=0, omega=1.0)
    np.testing.assert_array_equal(a.xs, b.xs)  # the values told do not matter
    u = (a.xs - box.lower) / box.width
    for j in range(2):
        assert stats.kstest(u[:, j], "uniform").pvalue > 1e-3


def test_omega_zero_always_exploits() -> None:
    opt = random_state(50, 3, seed=0, omega=0.0)
    for _ in range(100):
        xs, b = opt.xs.copy(), opt.best_index
        x = opt.ask()
        assert brute_in_cell(xs, b, x, rtol=1e-12)
        opt.tell(x, quadratic(x))


def test_first_two_asks_are_uniform() -> None:
    opt = VOO(Bounds.cube(0.0, 1.0, 2), VOOConfig(omega=0.0), seed=0)
    x0 = opt.ask()
    opt.tell(x0, 0.0)
    x1 = opt.ask()
    rng = np.random.default_rng(0)
    np.testing.assert_array_equal(x0, rng.random(2))
    np.testing.assert_array_equal(x1, rng.random(2))


def test_the_third_ask_exploits() -> None:
    # with omega = 0 every ask after the first two samples the best cell; here it is the
    # 0.75 % of the box left of -0.985, so uniform asks would miss it
    for seed in range(20):
        opt = VOO(Bounds([-1.0], [1.0]), VOOConfig(omega=0.0), seed=seed)
        opt.tell(np.array([-0.99]), 1.0)
        opt.tell(np.array([-0.98]), 0.0)
        assert opt.ask()[0] <= -0.985


def test_sample_best_cell_needs_a_point() -> None:
    with pytest.raises(ValueError, match="at least one told point"):
        VOO(Bounds.cube(0.0, 1.0, 2)).sample_best_cell()


# ----- caps, fallback and the uniform -> gaussian switch ---------------------------------


def test_uniform_fallback_switches_to_gaussian() -> None:
    opt = random_state(2000, 6, seed=0, sampler="uniform", uniform_max_tries=3)
    before = opt.n_rejected
    p = opt.sample_best_cell()
    assert opt.n_fallbacks == 1 and opt.n_rejected - before == 3
    assert opt.sampler is BestCellSampler.GAUSSIAN
    assert opt.bounds.contains(p)
    keep = random_state(
        2000, 6, seed=0, sampler="uniform", uniform_max_tries=3, uniform_switch_to_gaussian=False
    )
    keep.sample_best_cell()
    assert keep.n_fallbacks == 1 and keep.sampler is BestCellSampler.UNIFORM
    # a cap that is not a whole number of batches (8 + 2 tries): exactly the cap is tried
    ten = random_state(2000, 6, seed=0, sampler="uniform", uniform_max_tries=10)
    before = ten.n_rejected
    ten.sample_best_cell()
    assert ten.n_fallbacks == 1 and ten.n_rejected - before == 10


@pytest.mark.parametrize("sampler", ["centered_uniform", "gaussian"])
def test_try_cap_returns_closest_proposal(sampler: str) -> None:
    # max_tries=1: the single proposal is returned whether inside the cell or not
    opt = random_state(500, 5, seed=2, sampler=sampler, max_tries=1)
    outside = 0
    for _ in range(60):
        p = opt.sample_best_cell()
        assert opt.bounds.contains(p)
        outside += not brute_in_cell(opt.xs, opt.best_index, p)
    assert opt.n_fallbacks == outside > 0
    assert opt.sampler.value == sampler


# ----- custom metric and revalue ---------------------------------------------------------


def test_custom_metric() -> None:
    def l1(points: np.ndarray, y: np.ndarray) -> np.ndarray:
        return np.sum(np.abs(points - y), axis=1)

    opt = random_state(200, 3, seed=3, metric=l1)
    xs, b = opt.xs.copy(), opt.best_index
    for _ in range(50):
        p = opt.sample_best_cell()
        d = l1(xs, p)
        assert d[b] <= d.min()
    # the metric is used: some L1 cells differ from Euclidean ones
    rng = np.random.default_rng(0)
    q = xs[b] + 0.3 * rng.standard_normal((2000, 3))
    euclid = VOO(opt.bounds, seed=0)
    for x, v in zip(xs, opt.values, strict=True):
        euclid.tell(x, float(v))
    assert np.any(opt.in_best_cell(q) != euclid.in_best_cell(q))
    # a batch with no proposal inside the L1 cell: none is accepted
    cell = opt._best_cell()
    outside = q[~opt.in_best_cell(q)][:5] - cell.best
    assert len(outside) == 5 and opt._first_inside(cell, outside) == -1


def test_semi_metric_ignoring_a_coordinate() -> None:
    def first_only(points: np.ndarray, y: np.ndarray) -> np.ndarray:
        return np.abs(points[:, 0] - y[0])

    opt = random_state(100, 2, seed=4, metric=first_only)
    xs, b = opt.xs.copy(), opt.best_index
    ps = np.array([opt.sample_best_cell() for _ in range(300)])
    assert all(first_only(xs, p)[b] <= first_only(xs, p).min() for p in ps)
    assert np.ptp(ps[:, 1]) > 0.5  # the ignored coordinate roams over the box


def test_revalue_moves_the_best_cell() -> None:
    opt = random_state(200, 3, seed=5)
    old = opt.best_index
    opt.sample_best_cell()  # builds the cache for the old best
    new = int(np.argmin(opt.values))
    opt.revalue(new, opt.best_value + 10.0)
    assert opt.best_index == new != old
    for _ in range(50):
        assert brute_in_cell(opt.xs, new, opt.sample_best_cell(), rtol=1e-12)
    opt.revalue(new, opt.values.min() - 1.0)  # and back
    assert opt.best_index == old
    assert brute_in_cell(opt.xs, old, opt.sample_best_cell(), rtol=1e-12)


# ----- convergence -----------------------------------------------------------------------


def shekel_like(x: np.ndarray) -> float:
    """Four peaks in [0, 10]^3; the highest (about 1/0.1 = 10) at (4, 4, 4)."""
    a = np.array([[4.0, 4.0, 4.0], [1.0, 1.0, 1.0], [8.0, 8.0, 8.0], [6.0, 7.0, 6.0]])
    c = np.array([0.1, 0.2, 0.2, 0.4])
    return float(np.sum(1.0 / (c + np.sum((x - a) ** 2, axis=1))))


def test_converges_on_a_quadratic() -> None:
    box = Bounds.cube(-1.0, 1.0, 5)
    res = maximize(quadratic, box, "voo", budget=600, seed=0)
    rand = maximize(quadratic, box, "random", budget=600, seed=0)
    assert res.best_value > -1e-3
    assert res.best_value > rand.best_value + 0.05


def test_converges_on_a_shekel_like_function() -> None:
    box = Bounds.cube(0.0, 10.0, 3)
    runs = [maximize(shekel_like, box, "voo", budget=1000, seed=s, omega=0.1) for s in range(6)]
    found = [r for r in runs if r.best_value > 10.0]  # the global peak (about 10.115)
    assert len(found) >= 3  # VOO is greedy: some runs settle on another peak
    for r in found:
        np.testing.assert_allclose(r.best_x, 4.0, atol=0.01)
    rand = [maximize(shekel_like, box, "random", budget=1000, seed=s).best_value for s in range(6)]
    assert np.median([r.best_value for r in runs]) > np.median(rand)


# ----- configuration ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"omega": -0.1}, "omega must be a probability"),
        ({"omega": 1.5}, "omega must be a probability"),
        ({"omega": "0.1"}, "omega must be a probability"),
        ({"omega": True}, "omega must be a probability"),
        ({"omega": np.bool_(False)}, "omega must be a probability"),
        ({"omega": float("nan")}, "omega must be a probability"),
        ({"sampler": "gauss"}, "valid samplers are: centered_uniform, gaussian, uniform"),
        ({"max_tries": 0}, "max_tries must be an integer >= 1"),
        ({"max_tries": True}, "max_tries"),
        ({"uniform_max_tries": 2.0}, "uniform_max_tries"),
        ({"batch_size": 0}, "batch_size"),
        ({"metric": "euclidean"}, "metric must be callable"),
    ],
)
def test_bad_config(options: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        VOOConfig(**options)


def test_config_defaults_and_grid() -> None:
    cfg = VOOConfig(sampler="gaussian")
    assert cfg.sampler is BestCellSampler.GAUSSIAN
    assert VOOConfig().omega == 0.001 and VOOConfig().sampler is BestCellSampler.CENTERED_UNIFORM
    assert VOOConfig().max_tries == VOOConfig().uniform_max_tries == 1000
    assert VOOConfig.paper_grid() == {"omega": [0.001, 0.01, 0.05, 0.1, 0.3, 0.5]}
    opt = make_optimizer("voo", Bounds.cube(0.0, 1.0, 2), sampler="uniform")
    assert isinstance(opt, VOO) and opt.sampler is BestCellSampler.UNIFORM
    assert VOO.supports_revalue


def test_a_pairwise_metric_gives_the_same_points_as_its_single_calls() -> None:
    """A metric's ``pairwise`` only batches the best-cell test: the same draws result."""

    class Manhattan:
        def __call__(self, points: np.ndarray, y: np.ndarray) -> np.ndarray:
            return np.abs(points - y).sum(axis=1)

        def pairwise(self, points: np.ndarray, ys: np.ndarray) -> np.ndarray:
            return np.stack([self(points, y) for y in ys])

    def single(points: np.ndarray, y: np.ndarray) -> np.ndarray:
        return Manhattan()(points, y)

    f = get_function("shekel", 3)
    runs = []
    for metric in (Manhattan(), single):
        opt = VOO(f.bounds, VOOConfig(omega=0.1, sampler="uniform", metric=metric), seed=3)
        xs = []
        for _ in range(40):
            x = opt.ask()
            opt.tell(x, f(x))
            xs.append(x)
        runs.append(np.array(xs))
    assert runs[0].tobytes() == runs[1].tobytes()


# ----- what a planted bug would change (issue: tests that catch real bugs) -----------------
@pytest.mark.parametrize("sampler", SAMPLERS)
def test_the_best_cell_stays_exact_as_it_outgrows_the_neighbour_cache(sampler: str) -> None:
    """Exploit one fixed best point: its cell fills with more than NEIGHBOURS told points,
    and every ask must still land in the brute-force best cell."""
    box = Bounds.cube(-1.0, 1.0, 3)
    opt = VOO(box, VOOConfig(omega=0.0, sampler=sampler), seed=2)
    opt.tell(np.full(3, 0.1), 10.0)  # the best, for good
    opt.tell(np.full(3, -0.9), 0.0)
    checked = 0
    for _ in range(3 * NEIGHBOURS):
        fallbacks = opt.n_fallbacks
        x = opt.ask()
        # not the try cap's closest-proposal fallback, and far enough from x* for
        # absolute distances (the brute force) to resolve the cell's faces
        near = np.linalg.norm(x - opt.xs[opt.best_index]) < 1e-9
        if opt.n_fallbacks == fallbacks and not near:
            assert brute_in_cell(opt.xs, opt.best_index, x), x
            checked += 1
        opt.tell(x, -1.0)
    cell = opt._best_cell()
    assert cell.count == NEIGHBOURS and opt.n_told > 2 * NEIGHBOURS
    assert checked > NEIGHBOURS // 2  # enough asks were real best-cell draws


def test_centered_uniform_first_try_is_uniform_in_the_shrunk_box() -> None:
    """Try 1 draws uniformly in [x* + (lb - x*)/e, x* + (ub - x*)/e] (the authors' schedule)."""
    box = Bounds.cube(-1.0, 1.0, 2)
    best, far = np.array([0.5, -0.2]), np.array([-1.0, 1.0])
    draws = []
    for seed in range(400):
        opt = told(np.stack([best, far]), np.array([1.0, 0.0]), box, seed=seed, omega=0.0)
        draws.append(opt.sample_best_cell())
    d = np.array(draws)
    lo = best + (box.lower - best) / np.e
    hi = best + (box.upper - best) / np.e
    assert np.all(d >= lo - 1e-12) and np.all(d <= hi + 1e-12)
    # uniform over [lo, hi] per axis (most first tries are accepted: the other point is far)
    for k in range(2):
        u = (d[:, k] - lo[k]) / (hi[k] - lo[k])
        assert stats.kstest(u, "uniform").pvalue > 1e-3
        assert u.min() < 0.05 and u.max() > 0.95


def test_gaussian_first_try_has_the_documented_scale() -> None:
    """Try 1 draws N(x*, s_1^2), s_1 = max(|ub - x*|, |lb - x*|) / e, clipped to the box."""
    box = Bounds.cube(-10.0, 10.0, 1)
    best, far = np.array([0.0]), np.array([-10.0])
    draws = []
    for seed in range(600):
        opt = told(
            np.stack([best, far]),
            np.array([1.0, 0.0]),
            box,
            seed=seed,
            omega=0.0,
            sampler="gaussian",
        )
        draws.append(float(opt.sample_best_cell()[0]))
    d = np.array(draws)
    s1 = 10.0 / np.e
    # accepted draws lie right of -5 (the cell's edge); above x* nothing is rejected
    right = d[d > 0]
    assert stats.kstest(right / s1, stats.halfnorm.cdf).pvalue > 1e-3


def test_gaussian_scale_uses_the_larger_side_of_an_asymmetric_box() -> None:
    """In [0, 10] with x* = 8: s_1 = max(10 - 8, 8 - 0) / e (the lower side).

    The other point told is a copy of x*, so the cell is the whole box and every first
    try is accepted: the draws are N(8, s_1^2) clipped to the box.
    """
    box = Bounds([0.0], [10.0])
    best = np.array([8.0])
    draws = []
    for seed in range(400):
        opt = told(np.stack([best, best]), np.array([1.0, 0.0]), box, seed=seed, sampler="gaussian")
        draws.append(float(opt.sample_best_cell()[0]))
    d = np.array(draws)
    left = (8.0 - d[d < 8.0]) / (8.0 / np.e)
    assert stats.kstest(left, stats.halfnorm.cdf).pvalue > 1e-3


# ----- the pruned test accepts exactly what the brute-force test accepts ------------------
def reference_first_inside(xs: np.ndarray, b: int, q: np.ndarray) -> int:
    """The first row of ``q`` with ``q . v_i <= |v_i|^2 / 2`` for every told point (the
    definition of the best cell relative to x*, with ties inside), or -1. No pruning."""
    v = xs - xs[b]
    h = 0.5 * np.einsum("ij,ij->i", v, v)
    hits = np.flatnonzero((q @ v.T <= h).all(axis=1))
    return int(hits[0]) if hits.size else -1


class ReferenceVOO(VOO):
    """VOO whose acceptance test is :func:`reference_first_inside`: everything else (the
    random stream, batches, caps) is VOO's own, so both must ask the same points."""

    def _first_inside(self, cell: voo._BestCell, q: np.ndarray) -> int:
        return reference_first_inside(self.xs, self.best_index, q)


def spy(monkeypatch: pytest.MonkeyPatch, names: list[str]) -> dict[str, int]:
    """Count calls of the named _BestCell methods (which paths a run exercised)."""
    calls = dict.fromkeys(names, 0)
    for name in names:
        method = getattr(voo._BestCell, name)

        def counted(*args: object, _m=method, _n=name, **kwargs: object) -> object:  # type: ignore[no-untyped-def]
            calls[_n] += 1
            return _m(*args, **kwargs)

        monkeypatch.setattr(voo._BestCell, name, counted)
    return calls


def run_both(f, box: Bounds, n: int, seed: int, revalue: bool = False, **options: object) -> None:  # type: ignore[no-untyped-def]
    fast = VOO(box, VOOConfig(**options), seed=seed)  # type: ignore[arg-type]
    ref = ReferenceVOO(box, VOOConfig(**options), seed=seed)  # type: ignore[arg-type]
    rng = np.random.default_rng(seed)
    for i in range(n):
        x, y = fast.ask(), ref.ask()
        assert x.tobytes() == y.tobytes(), f"ask {i} differs"
        v = f(x)
        fast.tell(x, v)
        ref.tell(y, v)
        if revalue and i % 3 == 2:  # as the tree search does: any point may become x*
            j = int(rng.integers(fast.n_told))
            w = float(rng.normal())
            fast.revalue(j, w)
            ref.revalue(j, w)
    assert (fast.n_rejected, fast.n_fallbacks) == (ref.n_rejected, ref.n_fallbacks)


@pytest.mark.parametrize(
    ("name", "dim", "n", "sampler"),
    [
        ("sphere", 20, 1500, "centered_uniform"),  # x* improves all the time
        ("shekel", 20, 1500, "centered_uniform"),  # x* settles
        ("rastrigin", 20, 600, "centered_uniform"),  # x* jumps between basins
        ("griewank", 10, 600, "gaussian"),
        ("griewank", 3, 1200, "uniform"),  # the uniform sampler, then its gaussian switch
    ],
)
def test_fast_voo_asks_the_points_of_the_brute_force_reference(
    monkeypatch: pytest.MonkeyPatch, name: str, dim: int, n: int, sampler: str
) -> None:
    """Whole runs, bit for bit: the same proposals accepted in the same order."""
    calls = spy(monkeypatch, ["_gather", "_full", "_sort", "check"])
    if name == "sphere":
        box = Bounds.cube(-1.0, 1.0, dim)
        f = lambda x: -float(x @ x)  # noqa: E731 - optimum at the box centre
    else:
        g = get_function(name, dim)
        box, f = g.bounds, g.value
    run_both(f, box, n, seed=1, sampler=sampler, omega=0.01)
    # the pruned paths ran: x* moved with (and without) a full pass; near set sorted
    # the pruned paths ran: x* moved from the near set alone (gather) and from every
    # point (full pass, also at the start); proposals needed the exact check
    assert calls["_gather"] > 0 and calls["_full"] > 1
    assert dim < 10 or (calls["check"] > 0 and calls["_sort"] > 0)


@pytest.mark.parametrize("sampler", SAMPLERS)
def test_fast_voo_matches_the_reference_under_revalue(sampler: str) -> None:
    """Tree-search use: few points, and x* moves anywhere (revalue) every third ask."""
    f = get_function("shekel", 3)
    for seed in range(8):
        run_both(f.value, f.bounds, 80, seed=seed, revalue=True, sampler=sampler, omega=0.3)


def lattice_state(n: int, d: int, seed: int, half: int = 6) -> VOO:
    """n points of the integer lattice in [-half, half]^d, repeats (copies) included:
    with proposals on the half-integer lattice, q . v = |v|^2 / 2 holds exactly for many
    pairs, so ties (inside, by definition) are common and computed without rounding."""
    rng = np.random.default_rng(seed)
    xs = rng.integers(-half, half + 1, size=(n, d)).astype(float)
    box = Bounds.cube(-2.0 * half, 2.0 * half, d)
    return told(xs, rng.normal(size=n), box, seed=seed)


@pytest.mark.parametrize(
    "make",
    [
        lambda: lattice_state(40, 2, seed=0),  # fewer points than the neighbour cache
        lambda: lattice_state(3 * NEAR, 3, seed=1),  # more than the near set
        lambda: lattice_state(2 * NEAR, 4, seed=2),
        lambda: clustered_state(3 * NEAR, 6, 1e-13, seed=3),  # at the resolution of x*
    ],
)
def test_first_inside_equals_the_reference_with_ties_and_moves(
    monkeypatch: pytest.MonkeyPatch,
    make,  # type: ignore[no-untyped-def]
) -> None:
    """Batches at every scale, including exact ties; then x* moves (a better point told
    near it, a copy of it told, a far point revalued best) and again."""
    opt = make()
    calls = spy(monkeypatch, ["_gather", "_full", "_whole"])
    rng = np.random.default_rng(7)
    ties = 0
    for step in range(6):
        cell = opt._best_cell()
        xs, b = opt.xs.copy(), opt.best_index
        spread = float(np.max(np.abs(xs - xs[b]))) or 1.0
        for _ in range(30):
            m = int(rng.integers(1, 40))
            scale = spread * 2.0 ** rng.integers(-6, 2)
            if opt.bounds.width[0] > 1.0:  # the lattice: half-integer proposals
                q = np.round(rng.uniform(-1, 1, (m, xs.shape[1])) * scale * 2.0) / 2.0
                v = xs - xs[b]
                ties += int(np.sum(q @ v.T == 0.5 * np.einsum("ij,ij->i", v, v)))
            else:
                q = rng.standard_normal((m, xs.shape[1])) * scale
            q = q[np.argsort(np.linalg.norm(q, axis=1), kind="stable")[::-1]]
            assert opt._first_inside(cell, q) == reference_first_inside(xs, b, q)
        x_b = opt.xs[opt.best_index]
        if step % 3 == 0:  # a better point in the best cell: x* moves a little
            q = np.round(rng.uniform(-1, 1, x_b.size)) / 2.0 if ties else 1e-3 * spread
            opt.tell(np.clip(x_b + q, opt.bounds.lower, opt.bounds.upper), opt.best_value + 1.0)
        elif step % 3 == 1:  # a copy of x*, and points around it
            opt.tell(x_b.copy(), opt.best_value - 1.0)
            for x in x_b + rng.standard_normal((5, x_b.size)) * spread:
                opt.tell(np.clip(x, opt.bounds.lower, opt.bounds.upper), -100.0)
        else:  # the worst point becomes the best: x* jumps
            opt.revalue(int(np.argmin(opt.values)), opt.best_value + 1.0)
    if opt.bounds.width[0] > 1.0:
        assert ties > 0  # ties were exercised
    # x* moved with the near set alone; and some proposals reached past the near set
    # (every point tested) where there is one
    assert calls["_gather"] > 0
    assert opt.n_told <= NEAR or calls["_whole"] > calls["_full"]


def test_near_set_invariants() -> None:
    """After every ask: the near set's distances and offsets are exact, every point outside
    it and the tail lies at least lb2 away, and the whole-set buffer (when valid) is exact."""
    rng = np.random.default_rng(3)
    box = Bounds.cube(-1.0, 1.0, 4)
    opt = VOO(box, VOOConfig(omega=0.05), seed=3)
    for i in range(3 * NEAR):
        x = opt.ask()
        value = -float(x @ x) if i % 50 else float(rng.normal())
        opt.tell(x, value)
        if i % 97 == 96:  # a far jump of x*, as revalue in tree search does
            opt.revalue(int(rng.integers(opt.n_told)), opt.best_value + 1.0)
        if i % 9:
            continue
        cell = opt._best_cell()
        cell.first_inside(opt._xs, np.full((1, 4), 2.0))  # a far proposal: the exact test
        cell._sort(opt._xs)
        xs, best = opt.xs, opt.xs[opt.best_index]
        assert cell.best.tobytes() == best.tobytes() and cell.n == opt.n_told
        v = xs[cell.near] - best
        assert cell.vs.tobytes() == v.tobytes()
        assert cell.d2s.tobytes() == np.einsum("ij,ij->i", v, v).tobytes()
        assert np.all(np.diff(cell.d2s) >= 0) and cell.ordered
        outside = np.setdiff1d(np.arange(cell.tail), cell.near)
        d2 = np.sum((xs[outside] - best) ** 2, axis=1)
        assert np.all(d2 >= cell.lb2 * (1.0 - 1e-9))
        t = xs[cell.tail :] - best
        assert np.array_equal(cell.td2[: len(t)], np.einsum("ij,ij->i", t, t))
        w = cell.whole
        assert cell.buf[:w].tobytes() == (xs[:w] - best).tobytes()
    assert opt.n_told > 2 * NEAR


def test_a_move_of_the_best_point_finds_a_point_outside_the_old_near_set() -> None:
    """x* = 0 with NEAR points on the unit circle near +-60 degrees (its near set) and P at
    (1.01, 0), just outside it. A new best z = (0.5, 0) is 0.51 from P, nearer than any
    point of the old near set (0.87 or more): the bound carried over (1.01 - 0.5) must
    send the rebuild to every point, and P must reject z + (0.3, 0), which is nearer to it
    (0.21) than to z (0.3)."""
    rng = np.random.default_rng(0)
    angle = np.deg2rad(rng.uniform(50.0, 70.0, NEAR)) * rng.choice([-1.0, 1.0], NEAR)
    radius = rng.uniform(1.0, 1.005, NEAR)
    ring = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=1)
    p = np.array([1.01, 0.0])
    opt = told(
        np.vstack([np.zeros(2), ring, p]), np.r_[1.0, np.zeros(NEAR + 1)], Bounds.cube(-2, 2, 2)
    )
    cell = opt._best_cell()
    assert np.count_nonzero(cell.d2s) == NEAR and cell.lb2 == pytest.approx(1.01**2)  # P: out
    z = np.array([0.5, 0.0])
    opt.tell(z, 2.0)
    cell = opt._best_cell()
    assert cell.best.tolist() == z.tolist()
    assert np.any(np.abs(cell.k2[: cell.count] - 0.51**2) < 1e-12)  # P is a neighbour
    q = np.array([[0.3, 0.0]])
    assert reference_first_inside(opt.xs, opt.best_index, q) == -1
    assert opt._first_inside(cell, q) == -1
    assert opt._first_inside(cell, np.array([[0.3, 0.0], [0.2, 0.0]])) == 1


def test_random_tie_break_exploits_every_tied_best_point() -> None:
    """tie_break="random": x* is drawn among the points sharing the best value (the
    authors' get_best_evaled_action); "first" always takes the first of them."""
    from voot.optim.voo import VOO, VOOConfig

    bounds = [[0.0, 1.0]] * 2
    sites = np.array([[0.1, 0.1], [0.9, 0.9], [0.5, 0.5], [0.1, 0.9]])
    values = [1.0, 1.0, 0.0, 1.0]  # three points tie at the best value

    def owners(tie_break: str, seed: int) -> set[int]:
        opt = VOO(bounds, VOOConfig(omega=0.0, sampler="uniform", tie_break=tie_break), seed=seed)
        for x, v in zip(sites, values, strict=True):
            opt.tell(x, v)
        got = set()
        for _ in range(60):
            p = opt.sample_best_cell()
            got.add(int(np.argmin(np.linalg.norm(sites - p, axis=1))))
        return got

    assert owners("first", 0) == {0}
    assert owners("random", 0) == {0, 1, 3}


def test_random_tie_break_without_ties_changes_nothing() -> None:
    """Until two points share the best value, "random" asks exactly what "first" asks
    (it draws no random number)."""
    from voot.functions import get_function
    from voot.optim import make_optimizer

    f = get_function("shekel", dim=3)
    runs = {}
    for tie_break in ("first", "random"):
        opt = make_optimizer("voo", f.bounds, seed=3, tie_break=tie_break)
        xs, values = [], []
        for _ in range(200):
            x = opt.ask()
            xs.append(x)
            values.append(f(x))
            opt.tell(x, values[-1])
        runs[tie_break] = (np.array(xs), np.array(values))
    xs, values = runs["first"]
    best = np.maximum.accumulate(values)
    tied = [i for i in range(len(values)) if np.sum(values[: i + 1] == best[i]) > 1]
    first_tie = tied[0] if tied else len(values)
    assert first_tie > 50
    # the ask after the first tie may differ; every ask up to it is the same
    np.testing.assert_array_equal(runs["random"][0][: first_tie + 1], xs[: first_tie + 1])


def test_unknown_tie_break_names_the_choices() -> None:
    from voot.optim.voo import VOOConfig

    with pytest.raises(ValueError, match="tie_break must be one of first, random"):
        VOOConfig(tie_break="last")
