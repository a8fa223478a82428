"""Overhead of an optimiser per ask, measured on a fixed smooth test function.

VOO's cost per ask grows with the number ``n`` of evaluated points (its best-cell test
is a nearest-neighbour query), so its overhead is measured in a realistic state: after
the optimiser itself has run ``n`` evaluations of a shifted sphere, ``repeats`` asks are
timed without tells (without tells the state stays fixed, so every timed ask sees the
same ``n`` points). Optimisers whose cost is per evaluation rather than per ask (CMA-ES
tells pycma whole populations, GP-UCB refits on tell) are timed on ``repeats`` full
ask + tell evaluations instead.

VOO's cost also depends on the objective: each time the best point improves, the
structures of its best-cell test move to the new best point. ``voot-bench measure
voo-speed`` (:func:`measure_voo_cost`, :func:`print_voo_cost`) times whole ask + tell
evaluations after ``n`` evaluations of several objectives, on which the best point
improves at different rates.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from voot import validation as V
from voot.functions import available_functions, get_function
from voot.optim import Bounds, make_optimizer
from voot.optim.registry import normalize_method

#: Methods whose cost is per evaluation (ask + tell), not per ask.
PER_EVALUATION_METHODS = frozenset({"cmaes", "gp_ucb"})

#: Centre of the shifted sphere (a point that is on no grid of DOO/SOO).
SPHERE_SHIFT = 0.3141592653589793


def shifted_sphere(x: np.ndarray) -> float:
    r"""The fixed test function :math:`f(x) = -\|x - 0.314\ldots\|^2` on :math:`[-1, 1]^d`."""
    d = x - SPHERE_SHIFT
    return -float(d @ d)


def measure_ask_cost(
    method: str,
    n: int,
    dim: int,
    repeats: int,
    seed: int,
    *,
    timer: Callable[[], float] = time.perf_counter,
    **options: Any,
) -> float:
    """Mean seconds per ask of ``method`` after ``n`` evaluations in dimension ``dim``.

    The optimiser (built with ``seed`` and ``options``, e.g. ``omega=0.001,
    sampler="centered_uniform"`` for VOO) maximises :func:`shifted_sphere` on
    :math:`[-1, 1]^{dim}` for ``n`` evaluations; then ``repeats`` asks are timed without
    tells. For the methods in :data:`PER_EVALUATION_METHODS` ``repeats`` ask + tell
    evaluations are timed instead, since their cost is per evaluation.

    Args:
        method: a registry name (see :func:`voot.optim.available_methods`).
        n: number of evaluations told before timing (>= 0).
        dim: dimension of the box (>= 1).
        repeats: number of timed asks (or evaluations), >= 1.
        seed: the optimiser's seed.
        timer: the clock, wall time by default; ``time.process_time`` (CPU time of
            this process) is steadier on a shared machine.
        **options: the method's configuration fields.

    Returns:
        Mean wall-clock seconds per ask (or per evaluation).
    """
    key = normalize_method(method)
    for name, value, low in (("n", n, 0), ("dim", dim, 1), ("repeats", repeats, 1)):
        V.integer(value, name, low)
    opt = make_optimizer(key, Bounds.cube(-1.0, 1.0, int(dim)), seed=seed, **options)
    for _ in range(int(n)):
        x = opt.ask()
        opt.tell(x, shifted_sphere(x))
    if key in PER_EVALUATION_METHODS:
        start = timer()
        for _ in range(int(repeats)):
            x = opt.ask()
            opt.tell(x, shifted_sphere(x))
        return (timer() - start) / int(repeats)
    ask = opt.ask
    start = timer()
    for _ in range(int(repeats)):
        ask()
    return (timer() - start) / int(repeats)


# ----- VOO per ask + tell, per objective -------------------------------------------------
#: Objectives of :func:`measure_voo_cost` besides the test functions of
#: :mod:`voot.functions` (on their own boxes): ``sphere`` is :math:`-\\|x\\|^2` on
#: :math:`[-1, 1]^d`, whose optimum at the box centre VOO's default sampler keeps
#: approaching (the best point improves at about one evaluation in seven for thousands
#: of evaluations); ``shifted_sphere`` is :func:`shifted_sphere`, on which VOO reaches the
#: floating-point resolution of its best point within a few thousand evaluations in
#: 20-D and the best point then stays put.
SPHERES: dict[str, Callable[[np.ndarray], float]] = {
    "sphere": lambda x: -float(x @ x),
    "shifted_sphere": shifted_sphere,
}

#: Default objectives of ``voot-bench measure voo-speed``.
VOO_SPEED_OBJECTIVES = ("sphere", "shifted_sphere", "shekel", "rastrigin", "griewank")


def voo_objectives() -> list[str]:
    """Every objective name :func:`measure_voo_cost` takes."""
    return [*SPHERES, *available_functions()]


def measure_voo_cost(
    objective: str,
    n: int,
    dim: int,
    repeats: int,
    seed: int,
    *,
    timer: Callable[[], float] = time.process_time,
    **options: Any,
) -> tuple[float, int]:
    """Mean seconds per VOO ask + tell after ``n`` evaluations of ``objective``.

    VOO (built with ``seed`` and ``options``, default: the paper's ``omega=0.001``,
    ``centered_uniform``) maximises ``objective`` for ``n`` evaluations; then the next
    ``repeats`` evaluations are timed, ask and tell only (the objective's own cost is
    left out). The clock is the process's CPU time by default, steadier than wall time
    on a shared machine.

    Args:
        objective: one of :func:`voo_objectives`.
        n: evaluations before timing (>= 0).
        dim: dimension (>= 1; the Shekel functions exist in 3, 10 and 20).
        repeats: timed evaluations (>= 1).
        seed: VOO's seed.
        timer: the clock.
        **options: :class:`~voot.optim.voo.VOOConfig` fields.

    Returns:
        ``(seconds, improvements)``: mean seconds per ask + tell, and how many of the
        timed evaluations improved the best point (each one moves the best cell).
    """
    valid = voo_objectives()
    if objective not in valid:
        raise ValueError(
            f"unknown objective {objective!r}; valid objectives are: {', '.join(valid)}"
        )
    for name, value, low in (("n", n, 0), ("dim", dim, 1), ("repeats", repeats, 1)):
        V.integer(value, name, low)
    if objective in SPHERES:
        f, bounds = SPHERES[objective], Bounds.cube(-1.0, 1.0, int(dim))
    else:
        fn = get_function(objective, int(dim))
        f, bounds = fn.value, fn.bounds
    opt = make_optimizer("voo", bounds, seed=seed, **options)
    for _ in range(int(n)):
        x = opt.ask()
        opt.tell(x, f(x))
    spent = 0.0
    improvements = 0
    for _ in range(int(repeats)):
        best = opt.best_index
        start = timer()
        x = opt.ask()
        spent += timer() - start
        y = f(x)
        start = timer()
        opt.tell(x, y)
        spent += timer() - start
        improvements += opt.best_index != best
    return spent / int(repeats), improvements


def print_voo_cost(
    objectives: Sequence[str] = VOO_SPEED_OBJECTIVES,
    n: int = 5000,
    dim: int = 20,
    repeats: int = 500,
    seeds: Sequence[int] = (0,),
    *,
    omega: float = 0.001,
    sampler: str = "centered_uniform",
) -> None:
    """``voot-bench measure voo-speed``: print VOO's CPU time per ask + tell after ``n``
    evaluations (:func:`measure_voo_cost`), a row per objective and seed as each is
    measured."""
    print(
        f"VOO ask + tell after n = {n} evaluations, d = {dim}, mean of"
        f" {repeats} evaluations (CPU time; omega = {omega}, {sampler})"
    )
    print("| objective | seed | us per ask + tell | best improved (of the timed) |")
    print("| --- | ---: | ---: | ---: |")
    for objective in objectives:
        for seed in seeds:
            seconds, improved = measure_voo_cost(
                objective, n, dim, repeats, seed, omega=omega, sampler=sampler
            )
            print(f"| {objective} | {seed} | {1e6 * seconds:.1f} | {improved} |", flush=True)
