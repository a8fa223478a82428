"""Tests of the CMA-ES adapter (voot.optim.cmaes)."""

from __future__ import annotations

import numpy as np
import pytest

from voot.optim import Bounds, make_optimizer
from voot.optim.cmaes import CMAES, CMAESConfig, RestartStrategy


def sphere(x: np.ndarray) -> float:
    return -float(np.sum((x - 0.3) ** 2))


def rastrigin(x: np.ndarray) -> float:
    return -float(10 * x.size + np.sum(x**2 - 10 * np.cos(2 * np.pi * x)))


def run(opt: CMAES, f, budget: int, disturb: bool = False) -> np.ndarray:
    xs = []
    for i in range(budget):
        if disturb:  # reseed and consume numpy's global RNG between calls
            np.random.seed(1000 + i)  # noqa: NPY002
            np.random.rand(3)  # noqa: NPY002
        x = opt.ask()
        xs.append(x)
        opt.tell(x, f(x))
    return np.array(xs)


@pytest.mark.parametrize("restarts", ["ipop", "bipop"])
def test_same_seed_same_asks_despite_global_rng(restarts: str) -> None:
    box = Bounds.cube(-5.12, 5.12, 2)
    a = make_optimizer("cmaes", box, seed=7, restarts=restarts)
    b = make_optimizer("cmaes", box, seed=7, restarts=restarts)
    xa = run(a, rastrigin, 1500)
    xb = run(b, rastrigin, 1500, disturb=True)
    assert a.n_restarts >= 1  # the comparison covers restarted runs too
    np.testing.assert_array_equal(xa, xb)
    c = make_optimizer("cmaes", box, seed=8, restarts=restarts)
    assert not np.array_equal(run(c, rastrigin, 50), xa[:50])


def test_global_rng_untouched() -> None:
    np.random.seed(5)  # noqa: NPY002
    before = np.random.get_state()  # noqa: NPY002
    opt = make_optimizer("cmaes", Bounds.cube(-5.12, 5.12, 2), seed=0, restarts="bipop")
    run(opt, rastrigin, 1000)
    after = np.random.get_state()  # noqa: NPY002
    assert opt.n_restarts >= 1
    np.testing.assert_array_equal(before[1], after[1])
    assert before[2:] == after[2:]


@pytest.mark.parametrize("handling", ["transform", "penalty"])
def test_asks_inside_bounds(handling: str) -> None:
    box = Bounds([-1.0, 10.0, 0.0], [2.0, 10.5, 1e-3])
    opt = make_optimizer("cmaes", box, seed=3, bound_handling=handling, sigma0=1.0)

    def corner(x: np.ndarray) -> float:  # optimum on a corner outside-pushing
        return float(np.sum((x - box.lower) / box.width))

    xs = run(opt, corner, 600)
    assert np.all(xs >= box.lower) and np.all(xs <= box.upper)
    assert np.allclose(opt.best_x, box.upper, atol=1e-3 * box.width.max())


def test_penalty_clipping_duplicates_do_not_stall() -> None:
    # 1-D, optimum on the bound: many members clip to the same point and must all count
    opt = make_optimizer("cmaes", [[0.0, 1.0]], seed=0, bound_handling="penalty", sigma0=1.0)
    run(opt, lambda x: -float(x[0]), 400)
    assert sum(r.evaluations for r in opt.runs) == 400
    assert opt.best_value == 0.0


def test_solves_10d_sphere() -> None:
    opt = make_optimizer("cmaes", Bounds.cube(-5.0, 5.0, 10), seed=0)
    run(opt, sphere, 2500)
    assert opt.best_value > -1e-8
    assert np.allclose(opt.best_x, 0.3, atol=1e-3)


def test_ipop_restarts_grow_the_population() -> None:
    opt = make_optimizer("cmaes", Bounds.cube(-5.12, 5.12, 2), seed=1)
    run(opt, rastrigin, 2000)
    assert opt.n_restarts >= 2
    pops = [r.popsize for r in opt.runs]
    assert pops == [pops[0] * 2**i for i in range(len(pops))]
    assert all(r.stop for r in opt.runs[:-1])  # every finished run says why it stopped
    assert sum(r.evaluations for r in opt.runs) == opt.n_told == 2000


def test_bipop_interleaves_small_runs() -> None:
    opt = make_optimizer("cmaes", Bounds.cube(-5.12, 5.12, 2), seed=1, restarts="bipop")
    run(opt, rastrigin, 3000)
    regimes = [r.regime for r in opt.runs]
    assert regimes[:2] == ["first", "large"]
    assert "small" in regimes
    small = [r for r in opt.runs if r.regime == "small"]
    assert all(r.sigma0 <= 0.3 for r in small)


def test_no_restarts_and_max_restarts() -> None:
    box = Bounds.cube(-5.12, 5.12, 2)
    none = make_optimizer("cmaes", box, seed=1, restarts=RestartStrategy.NONE)
    run(none, rastrigin, 1500)
    assert none.n_restarts == 0
    capped = make_optimizer("cmaes", box, seed=1, max_restarts=1)
    run(capped, rastrigin, 2000)
    assert capped.n_restarts == 1


def test_initial_point_is_first_ask_and_first_mean() -> None:
    box = Bounds([0.0, -2.0], [4.0, 2.0])
    opt = make_optimizer("cmaes", box, seed=0, initial_point=[1.0, 1.0])
    x = opt.ask()
    np.testing.assert_array_equal(x, [1.0, 1.0])
    np.testing.assert_allclose(opt.es.mean, [0.25, 0.75])
    opt.tell(x, sphere(x))  # not asked by pycma: history only
    assert opt.runs[0].evaluations == 0 and opt.n_told == 1


def test_center_and_random_initial_mean() -> None:
    box = Bounds([0.0, -2.0], [4.0, 2.0])
    np.testing.assert_allclose(make_optimizer("cmaes", box, seed=0).es.mean, [0.5, 0.5])
    a = make_optimizer("cmaes", box, seed=0, initial_mean="random").es.mean
    b = make_optimizer("cmaes", box, seed=1, initial_mean="random").es.mean
    assert not np.allclose(a, b) and np.all((a >= 0) & (a <= 1))


def test_untold_members_are_asked_again_and_foreign_tells_ignored() -> None:
    opt = make_optimizer("cmaes", Bounds.cube(-1.0, 1.0, 3), seed=0, popsize=4)
    asked = [opt.ask() for _ in range(4)]
    again = opt.ask()  # whole population handed out, none told
    np.testing.assert_array_equal(again, asked[0])
    opt.tell(np.zeros(3), 1.0)  # foreign point: history only
    for x in asked:
        opt.tell(x, sphere(x))
    assert opt.es.countiter == 1 and opt.n_told == 5
    assert not any(np.array_equal(opt.ask(), x) for x in asked)


def test_minus_infinity_values_are_accepted() -> None:
    opt = make_optimizer("cmaes", Bounds.cube(-1.0, 1.0, 2), seed=0)
    run(opt, lambda x: -np.inf if x[0] < 0 else sphere(x), 300)
    assert opt.best_value > -1e-6


def test_revalue_not_supported() -> None:
    opt = make_optimizer("cmaes", Bounds.cube(-1.0, 1.0, 2), seed=0)
    x = opt.ask()
    opt.tell(x, 0.0)
    assert CMAES.supports_revalue is False
    with pytest.raises(NotImplementedError):
        opt.revalue(0, 1.0)


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"sigma0": 0.0}, "sigma0"),
        ({"sigma0": 1.5}, "sigma0"),
        ({"sigma0": True}, "sigma0"),
        ({"restarts": "lpop"}, "valid values are: ipop, bipop, none"),
        ({"bound_handling": "clip"}, "transform, penalty"),
        ({"initial_mean": "initial"}, "initial_mean"),
        ({"restart_mean": "center"}, "restart_mean"),
        ({"incpopsize": 0.5}, "incpopsize"),
        ({"popsize": 1}, "popsize"),
        ({"popsize": 4.0}, "popsize"),
        ({"max_restarts": -1}, "max_restarts"),
        ({"pycma_options": {"tolfunn": 1}}, "unknown pycma option"),
        ({"pycma_options": {"seed": 1}}, "set by the adapter"),
    ],
)
def test_bad_config(options: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        CMAESConfig(**options)


def test_pycma_options_passed_through() -> None:
    cfg = CMAESConfig(pycma_options={"CMA_active": False})
    opt = CMAES(Bounds.cube(0.0, 1.0, 2), cfg, seed=0)
    assert opt.es.opts["CMA_active"] is False
    assert CMAESConfig.paper_grid() == {"sigma0": [0.1, 0.3, 0.5]}
