"""Tests of uniform random search (voot.optim.random_search)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from voot.optim import Bounds, make_optimizer
from voot.optim.random_search import RandomSearch, RandomSearchConfig

BOX = Bounds([-3.0, 10.0, 0.0], [1.0, 11.0, 1e-3])


def asks(opt: RandomSearch, n: int, value: float | None = None) -> np.ndarray:
    xs = []
    for i in range(n):
        x = opt.ask()
        xs.append(x)
        opt.tell(x, float(i) if value is None else value)
    return np.array(xs)


def test_uniform_in_the_box() -> None:
    xs = asks(RandomSearch(BOX, seed=0), 2000)
    assert np.all(xs >= BOX.lower) and np.all(xs <= BOX.upper)
    u = (xs - BOX.lower) / BOX.width
    for j in range(BOX.dim):  # each coordinate is U(0, 1) after normalisation
        assert stats.kstest(u[:, j], "uniform").pvalue > 1e-3
    assert abs(np.corrcoef(u[:, 0], u[:, 1])[0, 1]) < 0.1


def test_deterministic_and_independent_of_values() -> None:
    a = asks(RandomSearch(BOX, seed=5), 50)
    b = asks(RandomSearch(BOX, seed=5), 50, value=-1.0)  # other told values
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, asks(RandomSearch(BOX, seed=6), 50))


def test_registry_and_config() -> None:
    opt = make_optimizer("random", BOX, seed=0)
    assert isinstance(opt, RandomSearch) and opt.config == RandomSearchConfig()
    assert RandomSearchConfig().to_dict() == {}
    assert RandomSearchConfig.paper_grid() == {}
    with pytest.raises(ValueError, match="unknown option"):
        make_optimizer("random", BOX, omega=0.1)


def test_revalue_moves_the_best() -> None:
    opt = RandomSearch(BOX, seed=0)
    asks(opt, 5)
    assert opt.best_index == 4
    opt.revalue(1, 100.0)
    assert opt.best_index == 1 and opt.best_value == 100.0
    np.testing.assert_array_equal(opt.best_x, opt.xs[1])


def test_initial_point_first() -> None:
    x0 = [0.0, 10.5, 0.0]
    xs = asks(RandomSearch(BOX, seed=0, initial_point=x0), 3)
    np.testing.assert_array_equal(xs[0], x0)
    assert not np.array_equal(xs[1], x0)
