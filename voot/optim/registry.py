"""Optimisers by name, and the one-call :func:`maximize` convenience."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from voot import validation as V
from voot.optim.base import Bounds, FloatArray, Optimizer, OptimizerConfig

#: name -> "module:ClassName"; modules are imported on first use.
_REGISTRY: dict[str, str] = {
    "voo": "voot.optim.voo:VOO",
    "doo": "voot.optim.doo:DOO",
    "rand_doo": "voot.optim.doo:RandDOO",
    "soo": "voot.optim.soo:SOO",
    "gp_ucb": "voot.optim.gp_ucb:GPUCB",
    "cmaes": "voot.optim.cmaes:CMAES",
    "random": "voot.optim.random_search:RandomSearch",
    "rembo": "voot.optim.rembo:REMBO",
    "bamsoo": "voot.optim.bamsoo:BaMSOO",
}


def available_methods() -> list[str]:
    """Names accepted by :func:`make_optimizer` and :func:`maximize`."""
    return sorted(_REGISTRY)


def normalize_method(method: str) -> str:
    """Lower-case and map ``-`` to ``_`` (``"RAND-DOO"`` -> ``"rand_doo"``); check it exists."""
    return V.registered_name(method, _REGISTRY, "method")


def optimizer_class(method: str) -> type[Optimizer]:
    """The optimiser class registered under ``method``."""
    module_name, class_name = _REGISTRY[normalize_method(method)].split(":")
    cls = getattr(importlib.import_module(module_name), class_name)
    assert issubclass(cls, Optimizer)
    return cls


def make_config(method: str, **options: Any) -> OptimizerConfig:
    """Build ``method``'s config from keyword options (unknown keys raise ValueError)."""
    cls = optimizer_class(method).config_class
    V.config_options(cls, options, f"method {method!r}")
    return cls(**options)


def make_optimizer(
    method: str,
    bounds: Bounds | ArrayLike,
    *,
    seed: int | np.random.SeedSequence | None = None,
    initial_point: ArrayLike | None = None,
    config: OptimizerConfig | None = None,
    **options: Any,
) -> Optimizer:
    """Instantiate optimiser ``method`` on ``bounds``.

    Options are either a ready ``config`` or keyword fields of the method's config.
    """
    cls = optimizer_class(method)
    if config is not None and options:
        raise ValueError("pass either config= or keyword options, not both")
    cfg = config if config is not None else make_config(method, **options)
    return cls(bounds, config=cfg, seed=seed, initial_point=initial_point)


@dataclass(frozen=True)
class MaximizeResult:
    """Outcome of :func:`maximize`.

    ``best_so_far[i]`` is the best value among the first ``i + 1`` evaluations (the
    anytime curve of the paper's Figure 3).
    """

    best_x: FloatArray
    best_value: float
    best_so_far: FloatArray
    xs: FloatArray
    values: FloatArray
    method: str

    @property
    def n_evaluations(self) -> int:
        return int(self.values.size)


def maximize(
    f: Callable[[FloatArray], float],
    bounds: Bounds | ArrayLike,
    method: str = "voo",
    budget: int = 100,
    seed: int | None = None,
    initial_point: ArrayLike | None = None,
    **options: Any,
) -> MaximizeResult:
    """Maximise ``f`` over ``bounds`` with ``budget`` evaluations of ``method``.

    >>> from voot.optim import maximize
    >>> res = maximize(lambda x: -float((x**2).sum()), [[-1, 1]] * 3, budget=200, seed=0)
    >>> res.best_value > -0.1
    True
    """
    key = normalize_method(method)
    V.integer(budget, "budget", 1)
    V.seed(seed)
    opt = make_optimizer(key, bounds, seed=seed, initial_point=initial_point, **options)
    for _ in range(int(budget)):
        x = opt.ask()
        opt.tell(x, float(f(x)))
    values = opt.values.copy()
    return MaximizeResult(
        best_x=np.asarray(opt.best_x),
        best_value=opt.best_value,
        best_so_far=np.maximum.accumulate(values),
        xs=opt.xs.copy(),
        values=values,
        method=key,
    )
