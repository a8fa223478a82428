"""Tests of voot.validation: the shared argument checks."""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from functools import partial

import numpy as np
import pytest

from voot import validation as V


class Colour(StrEnum):
    RED = "red"
    BLUE = "blue"


def test_integers() -> None:
    assert V.integer(np.int64(3), "n", 1) == 3 and type(V.integer(3, "n")) is int
    for bad in (True, 1.0, "2", 0, None):
        with pytest.raises(ValueError, match=r"^n must be an integer >= 1, got"):
            V.integer(bad, "n", 1)
    with pytest.raises(ValueError, match=r"in \[1, 20\] \(boxes\), got 21"):
        V.integer(21, "n", 1, 20, hint="boxes")
    assert V.optional_integer(None, "h", 1) is None
    with pytest.raises(ValueError, match="h must be an integer >= 1 or None"):
        V.optional_integer(0, "h", 1)
    assert V.integers([1, np.int32(2)], "dims", 1) == [1, 2]
    with pytest.raises(ValueError, match="dims must be integers >= 1, got 0"):
        V.integers([1, 0], "dims", 1)


def test_numbers() -> None:
    assert V.number(np.float32(0.5), "p", 0, 1) == 0.5
    for bad in (math.nan, math.inf, True, "0.5"):
        with pytest.raises(ValueError, match="p must be a finite number"):
            V.number(bad, "p")
    with pytest.raises(ValueError, match=r"eta must be a finite number in \(0, 1\), got 1"):
        V.number(1, "eta", 0, 1, open_low=True, open_high=True)
    with pytest.raises(ValueError, match="c must be a finite number > 0, got 0"):
        V.positive(0, "c")
    assert V.positive(0, "c", allow_zero=True) == 0.0
    assert V.probability(1, "omega") == 1.0


def test_flags_choices_and_tuples() -> None:
    assert V.flag(np.bool_(True), "x") is True
    with pytest.raises(ValueError, match="x must be True or False, got 1"):
        V.flag(1, "x")
    assert V.choice(Colour, "red", "colour") is Colour.RED
    with pytest.raises(ValueError, match="unknown colour 'green'; valid choices are: red, blue"):
        V.choice(Colour, "green", "colour")
    with pytest.raises(ValueError, match="mode must be one of a, b, got 'c'"):
        V.one_of("c", "mode", ("a", "b"))
    assert V.range_pair("r", (0, 1)) == (0.0, 1.0)
    with pytest.raises(ValueError, match="low < high"):
        V.range_pair("r", (1, 0))
    with pytest.raises(ValueError, match="4 finite numbers"):
        V.region("house", (0, 1, 2))
    with pytest.raises(ValueError, match="3 finite numbers"):
        V.pose("start", (0, math.nan, 0))
    assert V.positive_number("r", "0.5") == 0.5


def test_seed() -> None:
    seq = np.random.SeedSequence(4)
    gen = np.random.default_rng(1)
    assert V.seed(None) is None and V.seed(seq) is seq and V.seed(gen) is gen
    assert V.seed(np.int64(7)) == 7 and type(V.seed(np.int64(7))) is int
    for bad in (-1, True, 1.5, "3", np.bool_(True)):
        with pytest.raises(ValueError, match="seed must be None, an integer >= 0"):
            V.seed(bad)
    with pytest.raises(ValueError, match=r"^n_seed must be"):
        V.seed(-2, "n_seed")


def test_no_argparse_helper_in_the_library() -> None:
    # command-line types live in voot.bench.cli.types (the library raises ValueError)
    assert not hasattr(V, "seed_argument")


def test_tuples_and_positive_numbers_refuse_booleans() -> None:
    with pytest.raises(ValueError, match="must be a number"):
        V.positive_number("r", True)
    with pytest.raises(ValueError, match="pair of numbers"):
        V.range_pair("r", (False, 2.0))
    with pytest.raises(ValueError, match=r"\(xmin, xmax, ymin, ymax\)"):
        V.region("house", (0, True, 0, 1))
    with pytest.raises(ValueError, match=r"\(x, y, theta\)"):
        V.pose("start", (0, 0, np.bool_(True)))


def test_real_array_takes_real_numbers_only() -> None:
    """Bools, complex numbers, strings and objects are refused (numpy would read them as
    numbers: True as 1, "0.1" parsed, 1+2j with its imaginary part dropped)."""
    a = np.array([0.5, -1.0])
    assert V.real_array(a, "x") is a  # float64: as is, no copy
    for good in ([1, 2], np.array([1, 2], dtype=np.uint8), np.float32([0.5, 2.0]), 3.0):
        out = V.real_array(good, "x")
        assert out.dtype == np.float64
        assert np.array_equal(out, np.asarray(good, dtype=np.float64))
    nan = V.real_array([math.nan], "x")  # NaN is the caller's to refuse
    assert math.isnan(nan[0])
    bad: list[object] = [
        [True, False],
        np.array(["0.1"]),
        ["0.1", "0.2"],
        np.array([0.1], dtype=object),
        np.array([1 + 2j]),
        None,
        {"a": 1},
        [0.0, [1.0]],
        [2**70],
    ]
    for value in bad:
        with pytest.raises(ValueError, match=r"^action must be numeric, real numbers \(ints or"):
            V.real_array(value, "action")


def test_check_fields_stores_canonical_values_in_table_order() -> None:
    @dataclass(frozen=True)
    class Cfg:
        n: object = np.int64(3)
        on: object = np.bool_(True)

    cfg = Cfg()
    V.check_fields(cfg, {"n": partial(V.integer, low=1), "on": V.flag})
    assert type(cfg.n) is int and cfg.n == 3 and cfg.on is True
    with pytest.raises(ValueError, match=r"^n must be an integer >= 1, got 0$"):
        V.check_fields(Cfg(n=0, on="yes"), {"n": partial(V.integer, low=1), "on": V.flag})


def test_at_most_names_both_fields() -> None:
    V.at_most(3, "elites", 3, "population")
    with pytest.raises(ValueError, match=r"^elites must be <= population \(8\), got 9$"):
        V.at_most(9, "elites", 8, "population")
    with pytest.raises(ValueError, match=r"^a must be <= b \(0\.1\): a floor, got 0\.2$"):
        V.at_most(0.2, "a", 0.1, "b", "a floor")


def test_real_number_takes_real_numbers_and_names_everything_else() -> None:
    from fractions import Fraction

    from voot.validation import real_number

    for value, expected in (
        (1.5, 1.5),
        (2, 2.0),
        (np.float32(0.5), 0.5),
        (np.int8(-3), -3.0),
        (Fraction(3, 4), 0.75),
        (np.array(7), 7.0),
        (math.inf, math.inf),
    ):
        got = real_number(value, "r")
        assert type(got) is float and got == expected
    for bad in (
        True,
        np.bool_(True),
        1j,
        np.complex64(1),
        "1",
        None,
        [1.0],
        np.array([1.0]),
        np.array("1"),
        object(),
    ):
        with pytest.raises(
            ValueError, match=f"r must be a real number .*of type {type(bad).__name__}"
        ):
            real_number(bad, "r")
