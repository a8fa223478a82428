"""The black-box optimisation sweep of the paper's Figure 3, resumable and parallel.

A sweep is a grid of functions x dimensions x optimisers (each with its hyperparameter
grid) x seeds. :func:`build_specs` turns the grid into :class:`RunSpec` values,
:func:`run_spec` runs one and returns its result row (see :mod:`voot.bench.store.result_store`);
:func:`voot.bench.sweep.engine.run_sweep` runs the specs not yet in a store, as it runs
the planning sweep's (:mod:`voot.bench.sweep.plan`).

The protocol of one run (``PROTOCOL = 1``):

* **Budget** (paper): 500 evaluations for d = 3 and for Griewank, 5000 for Shekel-20D,
  1000 otherwise (:func:`paper_budget`), optionally scaled for quick sweeps.
* **Common initial point** (paper: "all algorithms evaluate the same initial point"): the
  first point of every run of a (function, dim, seed) is uniform in the function's box,
  drawn from ``default_rng(SeedSequence([key("initial-point"), seed, key(function), dim]))``
  (:func:`initial_point`), so it is the same for every method and hyperparameter.
* **Optimiser seed**: ``SeedSequence([seed, key(function), dim, key(method)])``
  (:func:`optimizer_seed`). The hyperparameters are deliberately not in it: every
  grid point of a method sees the same random stream (common random numbers), which
  makes the selection of :mod:`voot.bench.protocol.select` less noisy.
  ``key(name)`` is the first 4 bytes of SHA-256 of the name (never Python's ``hash``,
  which changes between processes).
* **Record**: the best value so far after every evaluation, the wall time and the best
  point; an exception inside the run gives a row with status ``"failed"`` and the error.
* **Instance** (not in the paper): ``instance = 0`` runs the paper's functions;
  ``instance = k >= 1`` runs :func:`voot.functions.get_function` instance ``k``, the
  function with its optimum moved off the box centre (same box, so the same initial point
  and optimiser seed). A nonzero instance is part of the row's ``config`` (so of the run
  id); instance 0 is left out of it, so the paper sweep's run ids are unchanged
  (:func:`instance_of` reads a missing one as 0).

Same spec -> bit-identical ``best_so_far``, in any process and on any backend.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from voot import validation as V
from voot.bench.store.format import Row
from voot.bench.sweep.engine import (
    SpecBase,
    check_grid,
    int_list,
    jsonable,
    name_key,
    one_blas_thread,
    params_key,
    register_runner,
    timed_row,
)
from voot.optim.base import FloatArray
from voot.optim.registry import make_config, make_optimizer, normalize_method, optimizer_class

#: Version of the run protocol (initial point and seeding rules); part of every run id.
PROTOCOL = 1
#: The paper's test functions (Figure 3 rows).
PAPER_FUNCTIONS: tuple[str, ...] = ("griewank", "rastrigin", "shekel")
#: The paper's dimensions (Figure 3 columns).
PAPER_DIMS: tuple[int, ...] = (3, 10, 20)
#: The optimisers compared in Figure 3, in plotting order.
PAPER_METHODS: tuple[str, ...] = (
    "voo",
    "doo",
    "soo",
    "rand_doo",
    "gp_ucb",
    "cmaes",
    "random",
    "rembo",
    "bamsoo",
)
#: Seeds per configuration in the paper.
PAPER_SEEDS = 20
#: Methods the paper did not run in low dimensions: method -> smallest dimension run.
#: ("We also omit testing REMBO in problems with 3-dimensional search spaces.")
MIN_DIM: dict[str, int] = {"rembo": 4}


def paper_budget(function: str, dim: int) -> int:
    """Evaluations per run in the paper: 500 for d = 3 and Griewank, 5000 for Shekel-20D,
    1000 otherwise."""
    if dim <= 3 or function == "griewank":
        return 500
    if function == "shekel" and dim >= 20:
        return 5000
    return 1000


def initial_point(
    function: str, dim: int, seed: int, lower: FloatArray, upper: FloatArray
) -> FloatArray:
    """The first point of every run of ``(function, dim, seed)``: uniform in the box."""
    ss = np.random.SeedSequence(
        [name_key("initial-point"), int(seed), name_key(function), int(dim)]
    )
    rng = np.random.default_rng(ss)
    return lower + rng.random(int(dim)) * (upper - lower)


def instance_of(config: Mapping[str, Any]) -> int:
    """The test-function instance of a row's ``config`` (0, the paper's, when absent)."""
    return int(config.get("instance") or 0)


def optimizer_seed(seed: int, function: str, dim: int, method: str) -> np.random.SeedSequence:
    """Seed of the optimiser of a run (the same for every hyperparameter of ``method``)."""
    return np.random.SeedSequence([int(seed), name_key(function), int(dim), name_key(method)])


@dataclass(frozen=True)
class RunSpec(SpecBase):
    """One black-box optimisation run: ``method`` with ``params`` on ``function`` in ``dim``
    dimensions, ``budget`` evaluations, ``seed``, on test-function ``instance`` (0: the
    paper's function).

    ``params`` holds only the hyperparameters set by the grid (sorted ``(name, value)``
    pairs); the rest are the method's defaults. The row's ``config`` has
    ``"instance"`` only when nonzero (instance 0 keeps the run ids it had before
    instances existed).
    """

    function: str
    dim: int
    method: str
    params: tuple[tuple[str, Any], ...]
    budget: int
    seed: int
    instance: int = 0

    kind: ClassVar[str] = "bbfo"
    protocol: ClassVar[int] = PROTOCOL
    optional_fields: ClassVar[tuple[str, ...]] = ("instance",)


def method_grid(method: str, grid: str = "paper") -> list[dict[str, Any]]:
    """Hyperparameter settings of ``method``: every combination of its ``paper_grid()``
    (``grid="paper"``) or just the defaults (``grid="default"``, one empty dict).

    Raises:
        ValueError: unknown method or grid, or the method's module cannot be imported
            (not implemented yet); the message lists the valid choices.
    """
    check_grid(grid)
    key = normalize_method(method)
    try:
        cls = optimizer_class(key)
    except ImportError as exc:
        raise ValueError(
            f"method {key!r} is registered but cannot be imported ({exc}); leave it out"
            " with --methods"
        ) from None
    if grid == "default":
        return [{}]
    axes = cls.config_class.paper_grid()
    if not axes:
        return [{}]
    names = sorted(axes)
    combos = itertools.product(*(list(axes[n]) for n in names))
    return [dict(zip(names, values, strict=True)) for values in combos]


def check_functions(functions: Iterable[str]) -> list[str]:
    """Lower-cased function names, each checked against ``available_functions()``."""
    from voot.functions import available_functions

    valid = list(available_functions())
    out = []
    for name in functions:
        key = str(name).strip().lower()
        if key not in valid:
            raise ValueError(
                f"unknown function {name!r}; valid functions are: {', '.join(sorted(valid))}"
            )
        out.append(key)
    if not out:
        raise ValueError("no functions given")
    return out


def build_specs(
    functions: Sequence[str] = PAPER_FUNCTIONS,
    dims: Sequence[int] = PAPER_DIMS,
    methods: Sequence[str] = PAPER_METHODS,
    seeds: Iterable[int] = range(PAPER_SEEDS),
    *,
    grid: str = "paper",
    budget_scale: float = 1.0,
    budget: int | None = None,
    instance: int = 0,
    fixed: Mapping[str, Any] | None = None,
) -> list[RunSpec]:
    """Every run of the sweep, in grid order (function, dim, method, params, seed).

    Args:
        functions: test function names (default: the paper's three).
        dims: dimensions (default: 3, 10, 20).
        methods: registry names of the optimisers (default: the paper's nine).
        seeds: seeds (default: 0..19).
        grid: ``"paper"`` (each method's ``paper_grid()``) or ``"default"``.
        budget_scale: multiplies :func:`paper_budget` (rounded, at least 1).
        budget: a fixed budget for every run instead (overrides ``budget_scale``).
        instance: test-function instance: 0 for the paper's functions, k >= 1 for
            :func:`voot.functions.get_function` instance k (optimum off the box centre).
        fixed: hyperparameters set in every run on top of the grid (e.g.
            ``{"sampler": "gaussian"}`` for VOO); they become part of every setting's
            ``params``, so of its run id and label, and override a grid axis of the same
            name.

    Raises:
        ValueError: also when a method does not accept a ``fixed`` parameter (the
            message is the method's own, naming its valid fields).

    Methods listed in :data:`MIN_DIM` are skipped below their smallest dimension.
    """
    funcs = check_functions(functions)
    dim_list = int_list(dims, "dims", 1)
    seed_list = int_list(seeds, "seeds", 0)
    method_list = [normalize_method(m) for m in methods]
    if not method_list:
        raise ValueError("no methods given")
    if not (V.is_number(budget_scale) and 0 < budget_scale < math.inf):  # type: ignore[operator]
        raise ValueError(f"budget_scale must be > 0 and finite, got {budget_scale!r}")
    if budget is not None:
        int_list([budget], "budget", 1)
    instance = V.integer(instance, "instance", 0, hint="0 = the paper's functions")
    extra = dict(fixed or {})
    grids = {m: method_grid(m, grid) for m in dict.fromkeys(method_list)}
    if extra:
        for method, settings in grids.items():
            grids[method] = list(
                {params_key(s): s for s in ({**p, **extra} for p in settings)}.values()
            )
            for params in grids[method]:
                try:
                    make_config(method, **params)
                except (TypeError, ValueError) as exc:
                    raise ValueError(f"{method} with {params_key(params)}: {exc}") from None
    from voot.functions import get_function

    for function in dict.fromkeys(funcs):  # e.g. Shekel exists in 3, 10 and 20 dimensions only
        for dim in dim_list:
            get_function(function, dim, instance)
    specs: list[RunSpec] = []
    for function in dict.fromkeys(funcs):
        for dim in dim_list:
            n = (
                budget
                if budget is not None
                else max(1, round(paper_budget(function, dim) * budget_scale))
            )
            for method in grids:
                if dim < MIN_DIM.get(method, 0):
                    continue
                for params in grids[method]:
                    items = tuple(sorted(params.items()))
                    for seed in seed_list:
                        specs.append(RunSpec(function, dim, method, items, int(n), seed, instance))
    return specs


@one_blas_thread
def run_spec(spec: RunSpec) -> Row:
    """Run one spec and return its row (status ``"failed"`` with the error on exception)."""
    return timed_row(spec, lambda: _run_fields(spec))


def _run_fields(spec: RunSpec) -> dict[str, Any]:
    """Run ``spec``: its row's fields (``best_so_far``, ``best_x``, ``method_config``)."""
    from voot.functions import get_function

    f = get_function(spec.function, spec.dim, spec.instance)
    bounds = f.bounds
    x0 = initial_point(spec.function, spec.dim, spec.seed, bounds.lower, bounds.upper)
    config = make_config(spec.method, **spec.params_dict)
    opt = make_optimizer(
        spec.method,
        bounds,
        seed=optimizer_seed(spec.seed, spec.function, spec.dim, spec.method),
        initial_point=x0,
        config=config,
    )
    for _ in range(spec.budget):
        x = opt.ask()
        opt.tell(x, float(f(x)))
    best_x = opt.best_x
    return {
        "best_so_far": np.maximum.accumulate(opt.values).tolist(),
        "best_x": None if best_x is None else best_x.tolist(),
        "method_config": {k: jsonable(v) for k, v in config.to_dict().items()},
    }


def describe_config(config: Mapping[str, Any]) -> str:
    """A one-line description of a black-box run from its row's ``config``."""
    params = config.get("params") or {}
    instance = instance_of(config)
    return (
        f"{config.get('method')} [{params_key(params)}] on"
        f" {config.get('function')}-{config.get('dim')}D"
        + (f" instance {instance}" if instance else "")
        + f" seed {config.get('seed')}"
    )


register_runner(RunSpec.kind, run_spec, describe_config)


def summarize_specs(specs: Sequence[RunSpec]) -> str:
    """One line per (function, dim, instance): budget and number of runs per method."""
    cells: dict[tuple[str, int, int, int], dict[str, int]] = {}
    for s in specs:
        counts = cells.setdefault((s.function, s.dim, s.instance, s.budget), {})
        counts[s.method] = counts.get(s.method, 0) + 1
    lines = []
    for (function, dim, instance, budget), counts in cells.items():
        per = ", ".join(f"{m} {n}" for m, n in counts.items())
        tag = f" instance {instance}" if instance else ""
        lines.append(f"{function}-{dim}D{tag} budget {budget}: {per}")
    return "\n".join(lines)
