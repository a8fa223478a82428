"""Tests of voot.functions: values against DEAP, optima, Shekel instances, input checks."""

from __future__ import annotations

import dataclasses
import math
import pickle
import subprocess
import sys

import numpy as np
import pytest
from deap import benchmarks

from voot.functions import (
    INSTANCE_MARGIN,
    SCHWEFEL_ARGMAX,
    SHEKEL_DIMS,
    SHEKEL_OPTIMA,
    SHEKEL_REFERENCE_OPTIMA,
    SHEKEL_SEEDS,
    SHIFTED_FUNCTIONS,
    TestFunction,
    available_functions,
    get_function,
    make_shekel,
    shekel_optimum,
    shekel_parameters,
    shifted,
)
from voot.optim import Bounds, maximize

NEGATED = {
    "griewank": benchmarks.griewank,
    "rastrigin": benchmarks.rastrigin,
    "ackley": benchmarks.ackley,
    "rosenbrock": benchmarks.rosenbrock,
    "schwefel": benchmarks.schwefel,
}
ALL_CASES = [(name, d) for name in sorted(NEGATED) for d in (2, 3, 10, 20)] + [
    ("shekel", d) for d in SHEKEL_DIMS
]


def deap_value(f: TestFunction, x: np.ndarray) -> float:
    """The maximised value of ``x`` computed by DEAP (the paper's source of the formulas)."""
    if f.name == "shekel":
        a, c = shekel_parameters(f.dim)
        return float(benchmarks.shekel(x, a, c)[0])
    return -float(NEGATED[f.name](x)[0])


def sample_points(f: TestFunction, n: int, seed: int) -> np.ndarray:
    """Uniform points in the domain, plus (for Shekel) points where the peaks are."""
    rng = np.random.default_rng(seed)
    pts = f.bounds.sample(rng, n)
    if f.name == "shekel":
        a, _ = shekel_parameters(f.dim)
        near = a[rng.integers(0, len(a), n)] + rng.normal(0.0, 0.05, (n, f.dim))
        pts = np.vstack([pts, a, near, rng.random((n, f.dim)) * 10.0])
    return pts


# ----- values ------------------------------------------------------------------------------
@pytest.mark.parametrize(("name", "dim"), ALL_CASES)
def test_values_match_deap(name: str, dim: int) -> None:
    f = get_function(name, dim)
    pts = sample_points(f, 40, seed=dim)
    ours = f(pts)
    theirs = np.array([deap_value(f, x) for x in pts])
    assert ours.shape == (len(pts),)
    np.testing.assert_allclose(ours, theirs, rtol=1e-12, atol=1e-12)
    if name == "shekel":  # the near-peak points must probe values far above the flat part
        assert theirs.max() > 0.5 * f.optimum_value


@pytest.mark.parametrize(("name", "dim"), ALL_CASES)
def test_scalar_and_batch_agree(name: str, dim: int) -> None:
    f = get_function(name, dim)
    pts = sample_points(f, 10, seed=100 + dim)
    batch = f(pts)
    for x, v in zip(pts, batch, strict=True):
        single = f(x)
        assert isinstance(single, float)
        assert single == pytest.approx(v, rel=1e-14, abs=1e-14)
        assert f.value(x) == single
        assert f(x.tolist()) == single  # lists work too
    np.testing.assert_array_equal(f.values(pts), batch)
    assert f(pts[:0]).shape == (0,)


def test_known_values() -> None:
    # Griewank and Rastrigin at simple points, by hand.
    assert get_function("griewank", 1)([math.pi]) == pytest.approx(
        -(1 + math.pi**2 / 4000 - math.cos(math.pi))
    )
    assert get_function("rastrigin", 2)([0.5, 0.5]) == pytest.approx(-(20 + 0.5 - 10 * -2))
    assert get_function("rosenbrock", 2)([0.0, 0.0]) == -1.0


# ----- optima --------------------------------------------------------------------------------
@pytest.mark.parametrize(("name", "dim"), ALL_CASES)
def test_optimum_is_attained_and_not_beaten(name: str, dim: int) -> None:
    f = get_function(name, dim)
    assert f.bounds.contains(f.optimum_x)
    assert f(f.optimum_x) == f.optimum_value
    assert f.regret(f.optimum_value) == 0.0
    assert deap_value(f, f.optimum_x) == pytest.approx(f.optimum_value, rel=1e-12, abs=1e-9)
    pts = sample_points(f, 500, seed=7)
    assert np.all(f(pts) <= f.optimum_value + 1e-12)
    # A local maximum: small moves in random directions never go higher.
    rng = np.random.default_rng(3)
    steps = rng.normal(size=(64, dim))
    steps *= 1e-4 / np.linalg.norm(steps, axis=1, keepdims=True)
    assert np.all(f(f.optimum_x + steps) <= f.optimum_value + 1e-12)


@pytest.mark.parametrize("name", sorted(NEGATED))
def test_analytic_optima(name: str) -> None:
    f = get_function(name, 10)
    expected = {"rosenbrock": 1.0, "schwefel": SCHWEFEL_ARGMAX}.get(name, 0.0)
    np.testing.assert_array_equal(f.optimum_x, np.full(10, expected))
    assert abs(f.optimum_value) < 1e-11  # 0 in exact arithmetic
    if name != "schwefel":
        assert f.optimum_value == 0.0 and math.copysign(1.0, f.optimum_value) == 1.0


def test_schwefel_argmax_is_stationary() -> None:
    u = math.sqrt(SCHWEFEL_ARGMAX)
    assert abs(math.sin(u) + 0.5 * u * math.cos(u)) < 1e-13


def test_domains() -> None:
    expected = {
        "griewank": 600.0,
        "rastrigin": 5.12,
        "shekel": 500.0,
        "ackley": 30.0,
        "rosenbrock": 100.0,
        "schwefel": 500.0,
    }
    assert available_functions() == sorted(expected)
    for name, half in expected.items():
        f = get_function(name, 3 if name == "shekel" else 4)
        assert f.bounds == Bounds.cube(-half, half, f.dim)


# ----- Shekel instances ----------------------------------------------------------------------
@pytest.mark.parametrize("dim", SHEKEL_DIMS)
def test_shekel_parameters_follow_the_legacy_recipe(dim: int) -> None:
    # The recipe exactly as written for the original (global legacy generator).
    state = np.random.get_state()  # noqa: NPY002
    try:
        np.random.seed(SHEKEL_SEEDS[dim])  # noqa: NPY002
        a_ref = np.random.rand(10, dim) * 10  # noqa: NPY002
        c_ref = np.random.rand(10)  # noqa: NPY002
        np.random.seed(123)  # noqa: NPY002
        a, c = shekel_parameters(dim)
        after = np.random.rand()  # noqa: NPY002
        np.random.seed(123)  # noqa: NPY002
        assert after == np.random.rand()  # noqa: NPY002 - the global stream is untouched
    finally:
        np.random.set_state(state)  # noqa: NPY002
    np.testing.assert_array_equal(a, a_ref)
    np.testing.assert_array_equal(c, c_ref)
    assert a.shape == (10, dim) and np.all((a >= 0) & (a <= 10)) and np.all(c > 0)


@pytest.mark.parametrize("dim", SHEKEL_DIMS)
def test_shekel_stored_optimum_is_recomputed(dim: int) -> None:
    x_star, v_star = shekel_optimum(*shekel_parameters(dim))
    stored_x, stored_v = SHEKEL_OPTIMA[dim]
    assert v_star == pytest.approx(stored_v, rel=1e-12)
    np.testing.assert_allclose(x_star, stored_x, atol=1e-6)
    f = get_function("shekel", dim)
    assert f.optimum_value == pytest.approx(stored_v, rel=1e-13)
    # The original's reference lines belong to other A, c: none matches these instances.
    assert abs(SHEKEL_REFERENCE_OPTIMA[dim] - stored_v) > 0.05


def test_shekel_optimum_beats_random_multistart() -> None:
    from scipy.optimize import minimize

    f = get_function("shekel", 10)
    rng = np.random.default_rng(0)
    grad = f.kernel.gradient  # type: ignore[attr-defined]
    for start in rng.random((30, 10)) * 10:  # random starts where the peaks are
        res = minimize(lambda x: -f(x), start, jac=lambda x: -grad(x), method="L-BFGS-B")
        assert -res.fun <= f.optimum_value + 1e-9


def test_make_shekel_custom_instance() -> None:
    # DEAP's own 2-D example: five peaks in [0, 1]^2, the highest (1/0.002) at the centre.
    a = [[0.5, 0.5], [0.25, 0.25], [0.25, 0.75], [0.75, 0.25], [0.75, 0.75]]
    c = [0.002, 0.005, 0.005, 0.005, 0.005]
    f = make_shekel(a, c, Bounds.cube(0.0, 1.0, 2), name="shekel2")
    assert (f.name, f.dim, str(f)) == ("shekel2", 2, "shekel2-2d")
    np.testing.assert_allclose(f.optimum_x, [0.5, 0.5], atol=1e-3)
    assert f.optimum_value > 500.0
    pts = np.random.default_rng(1).random((50, 2))
    np.testing.assert_allclose(
        f(pts), [benchmarks.shekel(x, a, c)[0] for x in pts], rtol=1e-12, atol=0
    )
    assert np.all(f(pts) <= f.optimum_value)
    # Peaks outside the box: the optimum is clipped to it.
    g = make_shekel([[2.0, 2.0]], [1.0], Bounds.cube(0.0, 1.0, 2))
    np.testing.assert_allclose(g.optimum_x, [1.0, 1.0])
    assert g.optimum_value == pytest.approx(1 / 3)


@pytest.mark.parametrize(
    ("a", "c", "match"),
    [
        ([1.0, 2.0], [1.0], "a must be a"),
        ([[1.0, 2.0]], [1.0, 2.0], "one entry per row"),
        ([[1.0, 2.0]], [0.0], "c_i must be > 0"),
        ([[1.0, np.nan]], [1.0], "finite"),
    ],
)
def test_make_shekel_rejects_bad_parameters(a: object, c: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        make_shekel(a, c)  # type: ignore[arg-type]


def test_make_shekel_rejects_mismatched_bounds() -> None:
    with pytest.raises(ValueError, match="3 dimensions but a has 2"):
        make_shekel([[1.0, 2.0]], [1.0], Bounds.cube(0.0, 1.0, 3))


# ----- errors, API ----------------------------------------------------------------------------
def test_get_function_errors() -> None:
    with pytest.raises(ValueError, match="valid names are: ackley, griewank, rastrigin"):
        get_function("sphere", 3)
    with pytest.raises(ValueError, match=r"dim in \[3, 10, 20\].*make_shekel"):
        get_function("shekel", 5)
    with pytest.raises(ValueError, match="dim must be >= 2"):
        get_function("rosenbrock", 1)
    for bad in (0, -1, 2.0, True, "3"):
        with pytest.raises(ValueError, match="dim must be an integer"):
            get_function("griewank", bad)  # type: ignore[arg-type]
    assert get_function(" Shekel ", 3).name == "shekel"
    assert get_function("griewank", np.int64(4)).dim == 4


@pytest.mark.parametrize(
    ("x", "match"),
    [
        (np.zeros(4), r"shape \(3,\) for one point or \(n, 3\)"),
        (np.zeros((2, 2)), r"got \(2, 2\)"),
        (np.zeros((2, 2, 3)), r"got \(2, 2, 3\)"),
        (0.0, r"got \(\)"),
        ([0.0, np.nan, 0.0], "finite; found nan at coordinate 1"),
        ([[0.0, 0.0, 0.0], [0.0, 0.0, np.inf]], "found inf at row 1, coordinate 2"),
        (["a", "b", "c"], "array of real numbers"),
    ],
)
def test_bad_points_raise(x: object, match: str) -> None:
    f = get_function("rastrigin", 3)
    with pytest.raises(ValueError, match=match):
        f(x)  # type: ignore[arg-type]


def test_value_values_regret() -> None:
    f = get_function("griewank", 3)
    with pytest.raises(ValueError, match="one point"):
        f.value(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="points of shape"):
        f.values(np.zeros(3))
    assert f.regret(-2.5) == 2.5
    np.testing.assert_array_equal(f.regret(np.array([-1.0, 0.0])), [1.0, 0.0])
    with pytest.raises(ValueError, match="NaN"):
        f.regret(float("nan"))


def test_immutable_picklable_and_described() -> None:
    f = get_function("shekel", 10)
    with pytest.raises(dataclasses.FrozenInstanceError):
        f.dim = 3  # type: ignore[misc]
    with pytest.raises(ValueError):
        f.optimum_x[0] = 1.0
    g = pickle.loads(pickle.dumps(f))
    pts = sample_points(f, 5, seed=0)
    np.testing.assert_array_equal(g(pts), f(pts))
    assert repr(f) == (
        f"TestFunction(name='shekel', dim=10, bounds=[-500, 500]^10,"
        f" optimum_value={f.optimum_value!r})"
    )


def test_constructor_checks() -> None:
    f = get_function("ackley", 2)
    with pytest.raises(ValueError, match="bounds have 2 dimensions but dim is 3"):
        TestFunction("x", 3, f.bounds, 0.0, np.zeros(3), f.kernel)
    with pytest.raises(ValueError, match="optimum_x must be 2 finite numbers"):
        TestFunction("x", 2, f.bounds, 0.0, np.zeros(3), f.kernel)


def test_works_with_maximize() -> None:
    f = get_function("shekel", 3)
    res = maximize(f, f.bounds, method="random", budget=50, seed=0)
    assert res.n_evaluations == 50
    assert f.regret(res.best_value) > 0.0
    np.testing.assert_array_equal(res.values, f(res.xs))


# ----- shifted instances ----------------------------------------------------------------------
SHIFT_CASES = [(name, d) for name in SHIFTED_FUNCTIONS for d in (3, 10)]


@pytest.mark.parametrize(("name", "dim"), [*ALL_CASES[:4], ("shekel", 3)])
def test_instance_zero_is_the_papers_function(name: str, dim: int) -> None:
    f, g = get_function(name, dim), get_function(name, dim, instance=0)
    assert g.instance == 0 and str(g) == str(f) and repr(g) == repr(f)
    np.testing.assert_array_equal(g.shift, np.zeros(dim))
    np.testing.assert_array_equal(g.optimum_x, f.optimum_x)
    assert g.optimum_value == f.optimum_value
    pts = sample_points(f, 20, seed=1)
    np.testing.assert_array_equal(g(pts), f(pts))
    np.testing.assert_allclose(g(pts), [deap_value(f, x) for x in pts], rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize(("name", "dim"), SHIFT_CASES)
def test_shifted_instance_moves_the_optimum(name: str, dim: int) -> None:
    f0 = get_function(name, dim)
    for k in (1, 2, 7):
        f = get_function(name, dim, instance=k)
        assert (f.instance, str(f), f.bounds) == (k, f"{name}-{dim}d-i{k}", f0.bounds)
        assert f"instance={k}" in repr(f)
        # The optimum is where it is said to be, with the paper's optimum value.
        assert f(f.optimum_x) == f.optimum_value
        if name == "shekel":
            assert f.optimum_value == pytest.approx(f0.optimum_value, rel=1e-13)
        else:
            assert f.optimum_value == f0.optimum_value == 0.0
        np.testing.assert_array_equal(f.optimum_x, f0.optimum_x + f.shift)
        # ... in the central 80% of the box (up to the 2^-16 rounding of the shift).
        lo, width = f.bounds.lower, f.bounds.upper - f.bounds.lower
        frac = (f.optimum_x - lo) / width
        assert np.all(frac >= INSTANCE_MARGIN - 1e-6) and np.all(frac <= 1 - INSTANCE_MARGIN + 1e-6)
        # f_k(x) = f(x - s_k), batch and single point alike.
        pts = f.bounds.sample(np.random.default_rng(k), 30)
        np.testing.assert_array_equal(f(pts), f0(pts - f.shift))
        assert f(pts[0]) == f0(pts[0] - f.shift)
        # Nothing beats the optimum: random points nor small moves around it.
        near = f.optimum_x + np.random.default_rng(0).normal(0.0, 1e-4, (64, dim))
        assert np.all(f(np.vstack([pts, near])) <= f.optimum_value + 1e-12)
    # The centre of the box is no longer the optimum.
    centre = 0.5 * (f0.bounds.lower + f0.bounds.upper)
    assert get_function(name, dim, instance=1)(centre) < f0.optimum_value - 1e-3


def test_instances_differ_by_instance_name_and_dim() -> None:
    shifts = {
        (name, dim, k): get_function(name, dim, instance=k).shift
        for name in ("griewank", "rastrigin")
        for dim in (3, 10)
        for k in (1, 2, 3)
    }
    fractions = set()
    for (name, dim, _), s in shifts.items():
        half = get_function(name, dim).bounds.upper[0]
        fractions.add(tuple(np.round(s[:3] / half, 12)))
    assert len(fractions) == len(shifts)  # no two instances share a shift pattern
    assert not np.array_equal(shifts[("griewank", 3, 1)], shifts[("griewank", 3, 2)])


def test_instances_are_deterministic_across_processes() -> None:
    here = {k: get_function("shekel", 10, instance=k).shift.tobytes().hex() for k in (1, 5)}
    code = (
        "from voot.functions import get_function;"
        "print([get_function('shekel', 10, instance=k).shift.tobytes().hex() for k in (1, 5)])"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == str([here[1], here[5]])
    f = get_function("rastrigin", 10, instance=3)
    g = pickle.loads(pickle.dumps(f))
    pts = f.bounds.sample(np.random.default_rng(0), 10)
    np.testing.assert_array_equal(g(pts), f(pts))
    assert (g.instance, g.optimum_value) == (3, f.optimum_value)
    np.testing.assert_array_equal(g.shift, f.shift)


def test_schwefel_is_the_same_in_every_instance() -> None:
    f0, f = get_function("schwefel", 4), get_function("schwefel", 4, instance=2)
    assert f.instance == 2 and "schwefel" not in SHIFTED_FUNCTIONS
    np.testing.assert_array_equal(f.shift, np.zeros(4))
    np.testing.assert_array_equal(f.optimum_x, f0.optimum_x)
    pts = f0.bounds.sample(np.random.default_rng(0), 20)
    np.testing.assert_array_equal(f(pts), f0(pts))
    with pytest.raises(ValueError, match=r"schwefel cannot be shifted.*griewank"):
        shifted(f0, np.ones(4))


def test_shifted_helper() -> None:
    f0 = get_function("rosenbrock", 2)
    f = shifted(f0, [3.0, -4.0])
    np.testing.assert_array_equal(f.optimum_x, [4.0, -3.0])
    assert f.optimum_value == 0.0 and f.instance == 0
    g = shifted(f, [1.0, 1.0], instance=9)  # shifts add up
    np.testing.assert_array_equal(g.shift, [4.0, -3.0])
    assert g.instance == 9 and g([5.0, -2.0]) == 0.0 and g([0.0, 0.0]) == f0([-4.0, 3.0])
    with pytest.raises(ValueError, match="outside the box"):
        shifted(f0, [100.0, 0.0])
    with pytest.raises(ValueError, match="offset must be 2 finite numbers"):
        shifted(f0, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="offset must be 2 finite numbers"):
        shifted(f0, [1.0, np.inf])


@pytest.mark.parametrize("bad", [-1, 1.5, True, "1"])
def test_bad_instances_raise(bad: object) -> None:
    with pytest.raises(ValueError, match=r"instance must be an integer >= 0 \(0 = the paper"):
        get_function("griewank", 3, instance=bad)  # type: ignore[arg-type]
    assert get_function("griewank", 3, instance=np.int64(2)).instance == 2
