"""Tests of the registry and maximize() (voot.optim.registry), over every registered method."""

from __future__ import annotations

import numpy as np
import pytest

from voot.optim import (
    Bounds,
    available_methods,
    make_config,
    make_optimizer,
    maximize,
    optimizer_class,
)
from voot.optim.registry import normalize_method
from voot.optim.voo import VOOConfig

METHODS = available_methods()
BOX = Bounds([-1.0, 0.0, -2.0], [2.0, 1.0, 2.0])  # 3-D: REMBO needs dim > its low_dim 2


#: Cheaper settings for the surrogate-based methods (the contract tested is the same).
_FAST = {"n_candidates": 300, "fit_restarts": 1, "local_maxiter": 10, "fit_maxiter": 30}


def fast(method: str) -> dict[str, object]:
    """The keys of _FAST that ``method``'s config has."""
    fields = optimizer_class(method).config_class.__dataclass_fields__
    return {k: v for k, v in _FAST.items() if k in fields}


def quadratic(x: np.ndarray) -> float:
    return -float(np.sum((x - np.array([0.5, 0.25, 0.0])) ** 2))


def test_available_methods() -> None:
    assert available_methods() == sorted(
        ["voo", "doo", "rand_doo", "soo", "gp_ucb", "cmaes", "random", "rembo", "bamsoo"]
    )


@pytest.mark.parametrize("method", METHODS)
def test_maximize_result(method: str) -> None:
    res = maximize(quadratic, BOX, method=method, budget=8, seed=0, **fast(method))
    assert res.method == method
    assert res.n_evaluations == 8 and res.best_so_far.shape == (8,)
    assert res.xs.shape == (8, 3)
    assert np.all(np.diff(res.best_so_far) >= 0)
    np.testing.assert_array_equal(res.best_so_far, np.maximum.accumulate(res.values))
    assert res.best_value == res.values.max() == res.best_so_far[-1]
    np.testing.assert_array_equal(res.best_x, res.xs[int(np.argmax(res.values))])
    assert np.all(res.xs >= BOX.lower) and np.all(res.xs <= BOX.upper)
    np.testing.assert_array_equal(res.values, [quadratic(x) for x in res.xs])


@pytest.mark.parametrize("method", METHODS)
def test_initial_point_is_first_evaluation(method: str) -> None:
    x0 = np.array([1.5, 0.9, 1.0])
    res = maximize(quadratic, BOX, method, budget=3, seed=1, initial_point=x0, **fast(method))
    np.testing.assert_array_equal(res.xs[0], x0)


@pytest.mark.parametrize("method", METHODS)
def test_same_seed_same_points(method: str) -> None:
    a = maximize(quadratic, BOX, method=method, budget=6, seed=4, **fast(method))
    b = maximize(quadratic, BOX, method=method, budget=6, seed=4, **fast(method))
    np.testing.assert_array_equal(a.xs, b.xs)


@pytest.mark.parametrize("method", METHODS)
def test_config_class_defaults(method: str) -> None:
    cls = optimizer_class(method)
    cfg = make_config(method)
    assert isinstance(cfg, cls.config_class)
    assert cls.name == method
    opt = make_optimizer(method, BOX, seed=0)
    assert isinstance(opt, cls) and opt.config == cfg
    grid = cls.config_class.paper_grid()
    assert set(grid) <= set(cfg.to_dict())  # the grid names real fields


@pytest.mark.parametrize("budget", [0, -3, 2.5, True, "10", None])
def test_bad_budget(budget: object) -> None:
    with pytest.raises(ValueError, match="budget must be an integer >= 1"):
        maximize(quadratic, BOX, method="random", budget=budget)  # type: ignore[arg-type]


def test_numpy_integer_budget() -> None:
    assert maximize(quadratic, BOX, method="random", budget=np.int64(3)).n_evaluations == 3


def test_unknown_method_lists_valid_names() -> None:
    with pytest.raises(ValueError, match="unknown method 'nelder_mead'") as err:
        maximize(quadratic, BOX, method="nelder_mead")
    for name in available_methods():
        assert name in str(err.value)


def test_method_names_are_normalised() -> None:
    assert normalize_method(" RAND-DOO ") == "rand_doo"
    assert optimizer_class("VOO").name == "voo"
    assert maximize(quadratic, BOX, method="Random", budget=2).method == "random"


def test_unknown_option_lists_valid_options() -> None:
    with pytest.raises(ValueError, match=r"unknown option\(s\) \['omgea'\]") as err:
        maximize(quadratic, BOX, method="voo", omgea=0.1)
    assert "omega" in str(err.value)
    with pytest.raises(ValueError, match="unknown option"):
        make_config("random", omega=0.1)


def test_options_or_config_not_both() -> None:
    with pytest.raises(ValueError, match="either config= or keyword options"):
        make_optimizer("voo", BOX, config=VOOConfig(), omega=0.1)
    opt = make_optimizer("voo", BOX, config=VOOConfig(omega=0.5))
    assert opt.config == VOOConfig(omega=0.5)


def test_options_reach_the_optimizer() -> None:
    opt = make_optimizer("voo", BOX, seed=0, omega=0.3)
    assert isinstance(opt.config, VOOConfig) and opt.config.omega == 0.3
    with pytest.raises(ValueError, match="omega"):
        maximize(quadratic, BOX, method="voo", omega=2.0)


@pytest.mark.parametrize("seed", [-1, True, 2.0, "1"])
def test_make_optimizer_and_maximize_check_the_seed(seed: object) -> None:
    with pytest.raises(ValueError, match="seed must be None, an integer >= 0"):
        make_optimizer("voo", [[0.0, 1.0]], seed=seed)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="seed must be None, an integer >= 0"):
        maximize(lambda x: 0.0, [[0.0, 1.0]], budget=2, seed=seed)  # type: ignore[arg-type]


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("told", [0, 1, 7])
def test_every_optimiser_pickles_mid_run_and_continues_bit_for_bit(method: str, told: int) -> None:
    """After ``told`` evaluations (and one more point asked, not yet told) a pickled copy,
    and a deep copy, ask the same points as the original from then on."""
    import copy
    import pickle

    opt = make_optimizer(method, BOX, seed=3, **fast(method))
    for _ in range(told):
        x = opt.ask()
        opt.tell(x, quadratic(x))
    opt.ask()  # pending
    copies = [pickle.loads(pickle.dumps(opt)), copy.deepcopy(opt)]
    for _ in range(6):
        x = opt.ask()
        for other in copies:
            assert np.array_equal(other.ask(), x)
            other.tell(x, quadratic(x))
        opt.tell(x, quadratic(x))
    for other in copies:
        assert np.array_equal(other.xs, opt.xs) and np.array_equal(other.values, opt.values)
        assert other.rng.bit_generator.state == opt.rng.bit_generator.state


@pytest.mark.parametrize("method", ["soo", "bamsoo"])
def test_a_shared_generator_pickles_with_the_state_each_call_saw(method: str) -> None:
    """A random generator shared with another user (the tree search hands one to every
    node) moves between calls: the replay sets the state each call saw."""
    import pickle

    rng = np.random.default_rng(5)
    opt = make_optimizer(method, BOX, seed=rng, **fast(method))  # type: ignore[arg-type]
    for _ in range(4):
        rng.random(3)  # the other user
        x = opt.ask()
        opt.tell(x, quadratic(x))
    twin = pickle.loads(pickle.dumps(opt))
    for _ in range(6):
        x = opt.ask()
        assert np.array_equal(twin.ask(), x)
        opt.tell(x, quadratic(x))
        twin.tell(x, quadratic(x))


@pytest.mark.parametrize("method", ["soo", "bamsoo"])
def test_a_pickle_keeps_the_told_points_as_they_were_told(method: str) -> None:
    """A caller may reuse its array after a tell; the replay needs the point it told."""
    import pickle

    opt = make_optimizer(method, BOX, seed=3, **fast(method))
    for _ in range(4):
        x = opt.ask()
        opt.tell(x, quadratic(x))
        x[:] = BOX.lower  # the caller's buffer, reused
    twin = pickle.loads(pickle.dumps(opt))
    assert np.array_equal(twin.xs, opt.xs)
    for _ in range(4):
        x = opt.ask()
        assert np.array_equal(twin.ask(), x)
        opt.tell(x, quadratic(x))
        twin.tell(x, quadratic(x))
