"""Tests of the optimiser interface (voot.optim.base): Bounds, check_value, Optimizer."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest

from voot.optim.base import Bounds, FloatArray, Optimizer, OptimizerConfig, check_value

# ----- Bounds ---------------------------------------------------------------------------


def test_bounds_stores_read_only_copies() -> None:
    lo, hi = np.array([0.0, -1.0]), np.array([1.0, 2.0])
    b = Bounds(lo, hi)
    lo[0] = 5.0
    assert b.lower[0] == 0.0
    with pytest.raises(ValueError):
        b.lower[0] = 3.0
    assert b.dim == 2
    np.testing.assert_array_equal(b.width, [1.0, 3.0])
    np.testing.assert_array_equal(b.center, [0.5, 0.5])
    assert b.diameter == pytest.approx(math.sqrt(10.0))


@pytest.mark.parametrize(
    ("lower", "upper", "match"),
    [
        ([0.0, 2.0], [1.0, 1.0], "inverted or empty in dimension 1"),
        ([0.0, 1.0], [1.0, 1.0], "inverted or empty in dimension 1"),
        ([0.0, np.nan], [1.0, 1.0], "finite"),
        ([0.0, -np.inf], [1.0, 1.0], "finite"),
        ([0.0], [1.0, np.inf], "lower has 1 entries but upper has 2"),
        ([0.0, 0.0], [1.0], "must match"),
        ([], [], "at least one dimension"),
    ],
)
def test_bounds_validation(lower: list, upper: list, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        Bounds(lower, upper)


def test_cube() -> None:
    b = Bounds.cube(-2.0, 3.0, 4)
    assert b == Bounds([-2.0] * 4, [3.0] * 4)
    with pytest.raises(ValueError, match="dim must be >= 1"):
        Bounds.cube(0.0, 1.0, 0)
    with pytest.raises(ValueError, match="inverted"):
        Bounds.cube(1.0, 0.0, 2)


def test_coerce_formats() -> None:
    b = Bounds([0.0, -1.0, 2.0], [1.0, 1.0, 3.0])
    assert Bounds.coerce(b) is b
    # (lower, upper) pair of vectors
    assert Bounds.coerce(([0.0, -1.0, 2.0], [1.0, 1.0, 3.0])) == b
    # (d, 2) rows of [low, high]
    assert Bounds.coerce([[0.0, 1.0], [-1.0, 1.0], [2.0, 3.0]]) == b
    assert Bounds.coerce(np.array([[0.0, 1.0]] * 3)) == Bounds.cube(0.0, 1.0, 3)
    # a (2, 2) array is read as rows of [low, high]
    assert Bounds.coerce([[0.0, 1.0], [2.0, 3.0]]) == Bounds([0.0, 2.0], [1.0, 3.0])


@pytest.mark.parametrize("bad", [[0.0, 1.0], [[[0.0, 1.0]]], [[0.0, 1.0, 2.0]] * 3, 5.0])
def test_coerce_rejects_other_shapes(bad: object) -> None:
    with pytest.raises(ValueError, match="shape"):
        Bounds.coerce(bad)  # type: ignore[arg-type]


def test_coerce_validates() -> None:
    with pytest.raises(ValueError, match="inverted"):
        Bounds.coerce([[1.0, 0.0], [0.0, 1.0], [0.0, 1.0]])


def test_sample_clip_contains_check_point() -> None:
    b = Bounds([0.0, 10.0], [1.0, 20.0])
    rng = np.random.default_rng(0)
    one = b.sample(rng)
    many = b.sample(rng, 500)
    assert one.shape == (2,) and many.shape == (500, 2)
    assert b.contains(one)
    assert np.all(many >= b.lower) and np.all(many <= b.upper)
    assert np.all(np.abs(many.mean(axis=0) - b.center) < 0.1 * b.width)
    np.testing.assert_array_equal(b.clip([-1.0, 25.0]), [0.0, 20.0])
    assert b.contains([0.0, 20.0]) and not b.contains([0.0, 20.0001])
    np.testing.assert_array_equal(b.check_point([0.5, 11]), [0.5, 11.0])
    with pytest.raises(ValueError, match=r"shape \(2,\)"):
        b.check_point([0.5])
    with pytest.raises(ValueError, match="finite"):
        b.check_point([0.5, np.nan], "x0")


def test_bounds_equality_and_hash() -> None:
    a, b = Bounds([0.0], [1.0]), Bounds(np.array([0]), np.array([1]))
    assert a == b and hash(a) == hash(b)
    assert a != Bounds([0.0], [2.0])
    assert a != "box"
    assert "Bounds(lower=[0.0], upper=[1.0])" == repr(a)


# ----- check_value ----------------------------------------------------------------------


def test_check_value() -> None:
    assert check_value(np.float32(1.5)) == 1.5
    assert isinstance(check_value(np.int64(2)), float)
    assert check_value(-math.inf) == -math.inf  # a failure value is allowed
    with pytest.raises(ValueError, match="NaN"):
        check_value(math.nan)
    with pytest.raises(ValueError, match=r"\+inf"):
        check_value(math.inf, "q")


@pytest.mark.parametrize(
    ("value", "kind"),
    [
        (True, "bool"),
        (np.bool_(False), "bool"),
        (1 + 2j, "complex"),
        (np.complex128(1), "complex128"),
        (None, "NoneType"),
        ("1.0", "str"),
        (b"1", "bytes"),
        ([1.0], "list"),
        (np.array([1.0]), "ndarray"),
    ],
)
def test_check_value_refuses_what_is_not_one_real_number(value: object, kind: str) -> None:
    """Not read as 1.0 (a bool), parsed (a string), or left to a bare TypeError."""
    with pytest.raises(ValueError, match=rf"q must be a real number .*of type {kind}"):
        check_value(value, "q")  # type: ignore[arg-type]


def test_check_value_takes_every_real_number() -> None:
    from fractions import Fraction

    assert check_value(np.array(2.5)) == 2.5  # a 0-d array of a number
    assert check_value(Fraction(1, 4)) == 0.25
    assert check_value(np.uint8(7)) == 7.0


def test_a_refused_value_leaves_the_optimiser_unchanged() -> None:
    from voot.optim import make_optimizer

    opt = make_optimizer("voo", Bounds([0.0], [1.0]), seed=0)
    x = opt.ask()
    for bad in (True, 1j, None, "0.5"):
        with pytest.raises(ValueError, match="value must be a real number"):
            opt.tell(x, bad)  # type: ignore[arg-type]
    assert opt.n_told == 0


@pytest.mark.parametrize(
    ("lower", "upper"), [([-1e308], [1e308]), ([0.0, -1.7e308], [1.0, 1.7e308])]
)
def test_bounds_whose_width_overflows_are_refused(lower: list, upper: list) -> None:
    """Their width would be inf: VOO, SOO and random search asked ``inf`` or nan."""
    with pytest.raises(ValueError, match=r"bounds are too wide in dimension .*overflows a float64"):
        Bounds(lower, upper)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # VOO's squared distances overflow
@pytest.mark.parametrize(
    ("method", "options"),
    [
        ("voo", {}),
        ("random", {}),
        ("soo", {}),
        ("soo", {"split": "bisect"}),
        ("doo", {}),
        ("rand_doo", {"split": "bisect"}),
    ],
)
def test_a_box_near_the_float_limits_gets_finite_points_inside(method: str, options: dict) -> None:
    """A box whose width is finite but whose cell edges' sums overflow (SOO asked -inf)."""
    from voot.optim import make_optimizer

    box = Bounds([-8e307, 0.0], [8e307, 1.0])  # width 1.6e308: finite
    opt = make_optimizer(method, box, seed=0, **options)
    for _ in range(40):
        x = opt.ask()
        assert np.all(np.isfinite(x)) and box.contains(x), (method, x)
        opt.tell(x, float(-abs(x[0]) / 1e300))


# ----- Optimizer ------------------------------------------------------------------------


@dataclass(frozen=True)
class _Cfg(OptimizerConfig):
    step: float = 0.1


class _Counter(Optimizer, name="counter", config_class=_Cfg, supports_revalue=True):
    """Asks the lower corner shifted by step * n; records the hooks it receives."""

    config: _Cfg

    def __init__(self, *args, **kwargs) -> None:  # type: ignore[no-untyped-def]
        super().__init__(*args, **kwargs)
        self.hooks: list[tuple[str, int, float]] = []

    def _ask(self) -> FloatArray:
        return self.bounds.clip(self.bounds.lower + self.config.step * self._n)

    def _tell(self, x: FloatArray, value: float) -> None:
        self.hooks.append(("tell", self._n - 1, value))

    def _revalue(self, index: int, value: float) -> None:
        self.hooks.append(("revalue", index, value))


class _NoRevalue(_Counter, supports_revalue=False):
    """Like its base, without revalue()."""


def test_history_grows_past_initial_capacity() -> None:
    opt = _Counter(Bounds.cube(0.0, 100.0, 2))
    assert opt.n_told == 0 and opt.best_index == -1
    assert opt.best_x is None and opt.best_value == -math.inf
    for i in range(40):
        x = opt.ask()
        opt.tell(x, float(i % 7))
    assert opt.n_told == 40 and opt.xs.shape == (40, 2) and opt.values.shape == (40,)
    np.testing.assert_allclose(opt.xs[:, 0], 0.1 * np.arange(40))
    assert opt.values.tolist() == [float(i % 7) for i in range(40)]
    assert opt.best_index == 6  # first argmax among ties
    assert opt.best_value == 6.0
    assert opt.hooks[-1] == ("tell", 39, 4.0)


def test_best_x_is_a_copy() -> None:
    opt = _Counter(Bounds.cube(0.0, 1.0, 2))
    opt.tell(opt.ask(), 1.0)
    bx = opt.best_x
    assert bx is not None
    bx[0] = 99.0
    assert opt.xs[0, 0] == 0.0


def test_tell_validates() -> None:
    opt = _Counter(Bounds.cube(0.0, 1.0, 2))
    with pytest.raises(ValueError, match="shape"):
        opt.tell([0.0, 0.0, 0.0], 1.0)
    with pytest.raises(ValueError, match="NaN"):
        opt.tell([0.0, 0.0], math.nan)
    with pytest.raises(ValueError, match="finite"):
        opt.tell([0.0, math.inf], 1.0)
    assert opt.n_told == 0
    opt.tell([0.5, 0.5], -math.inf)
    assert opt.best_index == 0 and opt.best_value == -math.inf
    opt.tell([0.5, 0.5], -1e300)
    assert opt.best_index == 1


def test_revalue_semantics() -> None:
    opt = _Counter(Bounds.cube(0.0, 1.0, 1))
    for v in (1.0, 3.0, 2.0):
        opt.tell(opt.ask(), v)
    assert opt.best_index == 1
    opt.revalue(2, 5.0)  # another point overtakes the best
    assert opt.best_index == 2 and opt.best_value == 5.0
    opt.revalue(2, 0.0)  # the best drops: recomputed over all points
    assert opt.best_index == 1 and opt.values.tolist() == [1.0, 3.0, 0.0]
    opt.revalue(0, 2.0)  # non-best point changes without overtaking
    assert opt.best_index == 1
    assert ("revalue", 2, 5.0) in opt.hooks
    with pytest.raises(IndexError):
        opt.revalue(3, 1.0)
    with pytest.raises(IndexError):
        opt.revalue(-1, 1.0)
    with pytest.raises(ValueError, match="NaN"):
        opt.revalue(0, math.nan)


def test_revalue_tie_gives_first_argmax() -> None:
    opt = _Counter(Bounds.cube(0.0, 1.0, 1))
    for v in (1.0, 3.0):
        opt.tell(opt.ask(), v)
    opt.revalue(0, 3.0)
    assert opt.best_index == int(np.argmax(opt.values)) == 0


def test_revalue_unsupported() -> None:
    opt = _NoRevalue(Bounds.cube(0.0, 1.0, 1))
    opt.tell(opt.ask(), 1.0)
    with pytest.raises(NotImplementedError, match="_NoRevalue"):
        opt.revalue(0, 2.0)


def test_initial_point() -> None:
    box = Bounds.cube(0.0, 1.0, 2)
    opt = _Counter(box, initial_point=[0.7, 0.2])
    x = opt.ask()
    np.testing.assert_array_equal(x, [0.7, 0.2])
    x[0] = 0.0  # the caller's copy
    np.testing.assert_array_equal(opt.ask(), [0.7, 0.2])  # still first until told
    opt.tell([0.7, 0.2], 0.0)
    np.testing.assert_array_equal(opt.ask(), [0.1, 0.1])
    with pytest.raises(ValueError, match="outside"):
        _Counter(box, initial_point=[1.5, 0.0])
    with pytest.raises(ValueError, match="initial_point must have shape"):
        _Counter(box, initial_point=[0.5])


def test_config_and_seed() -> None:
    box = [[0.0, 1.0]] * 2
    opt = _Counter(box, config=_Cfg(step=0.2), seed=3)
    assert opt.bounds == Bounds.cube(0.0, 1.0, 2)
    assert opt.config.to_dict() == {"step": 0.2}
    assert _Counter(box).config == _Cfg()
    with pytest.raises(TypeError, match="needs a _Cfg"):
        _Counter(box, config=OptimizerConfig())
    assert opt.rng.random() == np.random.default_rng(3).random()
    assert OptimizerConfig.paper_grid() == {}


def test_cube_is_shared_and_width_is_read_only() -> None:
    from voot.optim.base import Bounds

    a, b = Bounds.cube(-1.0, 1.0, 6), Bounds.cube(-1, 1, 6)
    assert a is b and a.dim == 6
    assert Bounds.cube(-1.0, 1.0, 3) is not a
    box = Bounds([0.0, -2.0], [1.0, 3.0])
    assert box.width.tolist() == [1.0, 5.0] and box.dim == 2
    with pytest.raises(ValueError):
        box.width[0] = 2.0


# ----- every registered method: what a tell accepts, and that a refused one changes nothing
def _every_method(method: str) -> Optimizer:
    from voot.optim import make_optimizer

    options: dict[str, object] = {}
    if method == "rembo":
        options["low_dim"] = 1
    if method in ("gp_ucb", "rembo"):
        options["n_candidates"] = 100
    return make_optimizer(method, [[-1.0, 1.0]] * 2, seed=3, **options)


def _methods() -> list[str]:
    from voot.optim import available_methods

    return available_methods()


def _run(opt: Optimizer, n: int, fail_every: int = 0) -> list[list[float]]:
    asked = []
    for i in range(n):
        x = opt.ask()
        asked.append(x.tolist())
        failed = fail_every and i % fail_every == fail_every - 1
        opt.tell(x, -math.inf if failed else -float(np.sum((x - 0.3) ** 2)))
    return asked


@pytest.mark.parametrize("method", _methods())
def test_tell_outside_the_box_is_refused_by_every_method(method: str) -> None:
    opt = _every_method(method)
    _run(opt, 3)
    with pytest.raises(ValueError, match=r"x = \[5\.0, 5\.0\] lies outside the box"):
        opt.tell(np.array([5.0, 5.0]), 1.0)
    with pytest.raises(ValueError, match=r"dimension 1: -1\.5 not in \[-1\.0, 1\.0\]"):
        opt.tell(np.array([0.0, -1.5]), 1.0)
    assert opt.n_told == 3
    assert opt.best_x is not None and opt.bounds.contains(opt.best_x)
    opt.tell(np.array([-1.0, 1.0]), -5.0)  # the faces belong to the box
    assert opt.n_told == 4


@pytest.mark.parametrize("method", _methods())
@pytest.mark.parametrize(
    ("x", "value", "match"),
    [
        ([5.0, 5.0], 1.0, "outside the box"),
        ([0.0, math.nan], 1.0, "must be finite"),
        ([0.0, 0.0, 0.0], 1.0, "shape"),
        ([0.1, 0.1], math.nan, "NaN"),
        ([0.1, 0.1], math.inf, r"\+inf"),
    ],
)
def test_a_refused_tell_leaves_every_method_unchanged(
    method: str, x: list[float], value: float, match: str
) -> None:
    a, b = _every_method(method), _every_method(method)
    _run(a, 4)
    _run(b, 4)
    a.ask()
    with pytest.raises(ValueError, match=match):
        a.tell(np.array(x), value)
    assert a.n_told == 4 and a.best_index == b.best_index
    b.ask()
    assert _run(a, 4) == _run(b, 4)  # same asks after the refusal as without it


@pytest.mark.parametrize("method", _methods())
def test_minus_inf_is_a_failed_evaluation_for_every_method(method: str) -> None:
    opt = _every_method(method)
    asked = _run(opt, 12, fail_every=3)  # every later ask and tell works
    values = opt.values
    assert np.isneginf(values).sum() == 4
    assert math.isfinite(opt.best_value) and opt.best_value == values[np.isfinite(values)].max()
    assert all(opt.bounds.contains(x) for x in asked)
    if opt.supports_revalue:  # a tried point's value may become -inf too (tree search)
        opt.revalue(opt.best_index, -math.inf)
        _run(opt, 3)
        assert math.isfinite(opt.best_value)
    only_failed = _every_method(method)
    _run(only_failed, 1, fail_every=1)
    assert only_failed.best_value == -math.inf
    _run(only_failed, 3)
    assert math.isfinite(only_failed.best_value)


@pytest.mark.parametrize(
    "bad",
    [
        [[0.0, 1.0], [0.0]],  # ragged rows
        [[0.0, 1.0], [0.0, 1.0, 2.0]],
        [["a", "b"], [1.0, 2.0]],  # strings
        [[0.0, "1"], [0.0, "1"]],
        [[True, False], [False, True]],  # booleans
        "abc",
    ],
)
def test_coerce_names_the_bounds_for_ragged_string_or_boolean_input(bad: object) -> None:
    with pytest.raises(ValueError, match=r"^bounds must be numbers: a Bounds, a \(lower, upper\)"):
        Bounds.coerce(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("lower", "upper", "match"),
    [
        ([0.0, "x"], [1.0, 2.0], "bounds: lower must be a vector of numbers"),
        ([0.0, 0.0], [[1.0], [2.0, 3.0]], "bounds: upper must be a vector of numbers"),
        ([True], [2.0], "bounds: lower must be a vector of numbers"),
    ],
)
def test_bounds_names_the_bad_side(lower: object, upper: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        Bounds(lower, upper)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((0.0, 1.0, True), "dim must be >= 1"),
        ((0.0, 1.0, 2.5), "dim must be >= 1"),
        (("0", 1.0, 2), "low must be a finite number"),
        ((0.0, True, 2), "high must be a finite number"),
    ],
)
def test_cube_checks_its_arguments(args: tuple, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        Bounds.cube(*args)


@pytest.mark.parametrize("seed", [-1, True, 1.5, "0"])
def test_seed_is_checked_by_the_constructor(seed: object) -> None:
    with pytest.raises(ValueError, match="seed must be None, an integer >= 0 or a numpy"):
        _Counter(Bounds([0.0], [1.0]), seed=seed)  # type: ignore[arg-type]


@pytest.mark.parametrize("x", [["a", "b"], [[0.0], [0.1, 0.2]], [True, False]])
def test_told_and_initial_points_must_be_numbers(x: object) -> None:
    opt = _Counter(Bounds([0.0, 0.0], [1.0, 1.0]))
    with pytest.raises(ValueError, match="x must be a vector of numbers"):
        opt.tell(x, 0.0)  # type: ignore[arg-type]
    assert opt.n_told == 0
    with pytest.raises(ValueError, match="initial_point must be a vector of numbers"):
        _Counter(Bounds([0.0, 0.0], [1.0, 1.0]), initial_point=x)  # type: ignore[arg-type]


def test_a_point_past_a_face_by_rounding_is_clipped_onto_it() -> None:
    box = Bounds([0.1, -1.0], [0.7, 1.0])
    opt = _Counter(box)
    x = np.array([np.nextafter(0.7, 1.0), -1.0 - 1e-13])
    opt.tell(x, 1.0)
    assert opt.best_x is not None and box.contains(opt.best_x)
    assert opt.best_x.tolist() == [0.7, -1.0]
    with pytest.raises(ValueError, match="outside the box"):
        opt.tell(np.array([0.7 + 1e-9, 0.0]), 1.0)
