"""Overhead of an optimiser per ask, measured on a fixed smooth test function.

VOO's cost per ask grows with the number ``n`` of evaluated points (its best-cell test
is a nearest-neighbour query), so its overhead is measured in a realistic state: after
the optimiser itself has run ``n`` evaluations of a shifted sphere, ``repeats`` asks are
timed without tells (without tells the state stays fixed, so every timed ask sees the
same ``n`` points). Optimisers whose cost is per evaluation rather than per ask (CMA-ES
tells pycma whole populations, GP-UCB refits on tell) are timed on ``repeats`` full
ask + tell evaluations instead.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np

from voot import validation as V
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
