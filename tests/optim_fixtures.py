"""A test objective and run loop shared by the optimisers' tests (not a test module)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

from voot.optim import make_optimizer
from voot.optim.base import Optimizer

Opt = TypeVar("Opt", bound=Optimizer)


def bowl(x: np.ndarray) -> float:
    """A concave quadratic with its maximum 0 at ``linspace(0.3, -0.2, d)``."""
    c = np.linspace(0.3, -0.2, x.size)
    return -float(np.sum((x - c) ** 2))


def run_on(
    cls: type[Opt],
    seed: int,
    d: int,
    budget: int,
    f: Callable[[np.ndarray], float] = bowl,
    **options: Any,
) -> Opt:
    """``budget`` ask/tell rounds of optimiser ``cls`` (made by its registry name) on ``f``
    over ``[-1, 1]^d``."""
    opt = make_optimizer(cls.name, [[-1.0, 1.0]] * d, seed=seed, **options)
    assert isinstance(opt, cls)
    for _ in range(budget):
        x = opt.ask()
        opt.tell(x, f(x))
    return opt
