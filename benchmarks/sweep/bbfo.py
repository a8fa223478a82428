"""The black-box optimisation sweep of the paper's Figure 3, resumable and parallel.

A sweep is a grid of functions x dimensions x optimisers (each with its hyperparameter
grid) x seeds. :func:`build_specs` turns the grid into :class:`RunSpec` values,
:func:`run_spec` runs one and returns its result row (see :mod:`voot.bench.store.result_store`), and
:func:`run_sweep` runs every spec not yet in a :class:`~voot.bench.store.result_store.ResultStore` on a
backend (:mod:`voot.bench.sweep.backends`: in-process, a local process pool, or Ray), writing
each row as soon as its run finishes. The
planning sweep (:mod:`voot.bench.sweep.plan`) runs through the same :func:`run_sweep`.

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

import functools
import hashlib
import itertools
import math
import sys
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol, TypeVar

import numpy as np
from threadpoolctl import threadpool_limits

from voot import validation as V
from voot.bench.store.format import (  # failed_row, exception_row: re-exported
    Row,
    StoreError,
    exception_row,
    failed_row,  # noqa: F401 - re-exported (voot.bench.sweep.bbfo.failed_row)
    make_row,
    make_run_id,
)
from voot.bench.store.lock import describe_holder
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.backends import (  # re-exported: voot.bench.sweep.bbfo.make_backend ...
    BACKENDS,  # noqa: F401
    Backend,
    ProcessBackend,  # noqa: F401
    SerialBackend,
    make_backend,  # noqa: F401
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
#: Hyperparameter grids: each method's ``paper_grid()``, or its defaults only.
GRIDS: tuple[str, ...] = ("paper", "default")
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


def name_key(name: str) -> int:
    """A process-independent 32-bit integer for a name (SHA-256 based)."""
    return int.from_bytes(hashlib.sha256(name.encode()).digest()[:4], "little")


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
class RunSpec:
    """One black-box optimisation run: ``method`` with ``params`` on ``function`` in ``dim``
    dimensions, ``budget`` evaluations, ``seed``, on test-function ``instance`` (0: the
    paper's function).

    ``params`` holds only the hyperparameters set by the grid (sorted ``(name, value)``
    pairs); the rest are the method's defaults.
    """

    function: str
    dim: int
    method: str
    params: tuple[tuple[str, Any], ...]
    budget: int
    seed: int
    instance: int = 0

    kind: ClassVar[str] = "bbfo"

    @property
    def params_dict(self) -> dict[str, Any]:
        return dict(self.params)

    def config(self) -> dict[str, Any]:
        """The row's ``config`` (JSON-serialisable; hashed into the run id).

        ``"instance"`` is there only when nonzero (instance 0 keeps the run ids it had
        before instances existed)."""
        config: dict[str, Any] = {
            "function": self.function,
            "dim": self.dim,
            "method": self.method,
            "params": self.params_dict,
            "budget": self.budget,
            "seed": self.seed,
            "protocol": PROTOCOL,
        }
        if self.instance:
            config["instance"] = self.instance
        return config

    @property
    def run_id(self) -> str:
        return make_run_id(self.kind, self.config())


def method_grid(method: str, grid: str = "paper") -> list[dict[str, Any]]:
    """Hyperparameter settings of ``method``: every combination of its ``paper_grid()``
    (``grid="paper"``) or just the defaults (``grid="default"``, one empty dict).

    Raises:
        ValueError: unknown method or grid, or the method's module cannot be imported
            (not implemented yet); the message lists the valid choices.
    """
    if grid not in GRIDS:
        raise ValueError(f"unknown grid {grid!r}; valid grids are: {', '.join(GRIDS)}")
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


def _check_int_list(values: Iterable[Any], what: str, minimum: int) -> list[int]:
    out = V.integers(values, what, minimum)
    if not out:
        raise ValueError(f"no {what} given")
    return out


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
    dim_list = _check_int_list(dims, "dims", 1)
    seed_list = _check_int_list(seeds, "seeds", 0)
    method_list = [normalize_method(m) for m in methods]
    if not method_list:
        raise ValueError("no methods given")
    if not (V.is_number(budget_scale) and 0 < budget_scale < math.inf):  # type: ignore[operator]
        raise ValueError(f"budget_scale must be > 0 and finite, got {budget_scale!r}")
    if budget is not None:
        _check_int_list([budget], "budget", 1)
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
        for dim in dict.fromkeys(dim_list):
            get_function(function, dim, instance)
    specs: list[RunSpec] = []
    for function in dict.fromkeys(funcs):
        for dim in dict.fromkeys(dim_list):
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
                    for seed in dict.fromkeys(seed_list):
                        specs.append(RunSpec(function, dim, method, items, int(n), seed, instance))
    return specs


def _jsonable(value: Any) -> Any:
    if isinstance(value, str | int | float | bool) or value is None:
        return value
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    return repr(value)


_Spec = TypeVar("_Spec")
_Out = TypeVar("_Out")


def one_blas_thread(run: Callable[[_Spec], _Out]) -> Callable[[_Spec], _Out]:
    """Run ``run(spec)`` with one BLAS/OpenMP thread, in whatever process executes it.

    Results of the GP-based optimisers differ in their last bits between BLAS thread
    counts, so a run is bit-identical across processes and machines only at a fixed
    count; one thread also keeps parallel runs from oversubscribing the cores.
    """

    @functools.wraps(run)
    def wrapper(spec: _Spec) -> _Out:
        with threadpool_limits(limits=1):
            return run(spec)

    return wrapper


@one_blas_thread
def run_spec(spec: RunSpec) -> Row:
    """Run one spec and return its row (status ``"failed"`` with the error on exception)."""
    from voot.functions import get_function

    start = time.perf_counter()
    best: list[float] = []
    try:
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
        best = np.maximum.accumulate(opt.values).tolist()
        best_x = opt.best_x
        return make_row(
            spec.kind,
            spec.config(),
            status="ok",
            wall_time=time.perf_counter() - start,
            best_so_far=best,
            best_x=None if best_x is None else best_x.tolist(),
            method_config={k: _jsonable(v) for k, v in config.to_dict().items()},
        )
    except Exception as exc:
        return exception_row(spec, exc, start, best)


#: The run function of each spec kind (``RunSpec.kind`` -> :func:`run_spec`); modules
#: defining other kinds add theirs with :func:`register_runner` when imported (e.g.
#: :mod:`voot.bench.sweep.plan`: ``"plan"`` -> ``run_plan_spec``). Unpickling a spec in a
#: worker imports its module, so the worker knows its run function too.
RUNNERS: dict[str, Callable[[Any], Row]] = {}


def register_runner(kind: str, run: Callable[[Any], Row]) -> None:
    """Make :func:`run_any` run specs of ``kind`` with ``run``."""
    RUNNERS[kind] = run


def run_any(spec: Any) -> Row:
    """Run a spec of any registered kind (:data:`RUNNERS`): :func:`run_spec` for a
    :class:`RunSpec`, :func:`voot.bench.sweep.plan.run_plan_spec` for a plan spec."""
    run = RUNNERS.get(getattr(spec, "kind", None))  # type: ignore[arg-type]
    if run is None:
        raise TypeError(
            f"cannot run a {type(spec).__name__}; expected a spec of a registered kind"
            f" ({', '.join(sorted(RUNNERS))}), e.g. a RunSpec or a PlanSpec"
        )
    return run(spec)


register_runner(RunSpec.kind, run_spec)


def describe_config(config: Mapping[str, Any]) -> str:
    """A one-line description of a run from its row's ``config`` (any kind)."""
    params = config.get("params") or {}
    text = ", ".join(f"{k}={params[k]}" for k in sorted(params)) or "default"
    if "planner" in config:
        from voot.bench.protocol.problems import problem_label

        label = problem_label(str(config.get("problem")), config.get("env_kwargs"))
        if config.get("dim") is not None:
            label += f"-{config['dim']}D"
        return f"{config.get('planner')} [{text}] on {label} seed {config.get('seed')}"
    instance = instance_of(config)
    return (
        f"{config.get('method')} [{text}] on {config.get('function')}-{config.get('dim')}D"
        + (f" instance {instance}" if instance else "")
        + f" seed {config.get('seed')}"
    )


# ----- the sweep -----------------------------------------------------------------------
class Spec(Protocol):
    """What the sweep needs of a run's spec (:class:`RunSpec`, a plan spec)."""

    @property
    def kind(self) -> str: ...

    @property
    def seed(self) -> int: ...

    @property
    def run_id(self) -> str: ...

    def config(self) -> dict[str, Any]: ...


S = TypeVar("S", bound=Spec)


@dataclass
class SweepSummary:
    """What :func:`run_sweep` did."""

    total: int = 0
    skipped: int = 0
    ran: int = 0
    failed: int = 0
    failed_errors: list[str] = field(default_factory=list)

    def __str__(self) -> str:
        text = (
            f"{self.total} runs: {self.skipped} already in the store, {self.ran} ran"
            f" ({self.failed} failed)"
        )
        if self.failed_errors:
            text += "\nfirst failures:\n  " + "\n  ".join(self.failed_errors[:5])
        return text


def execution_order(specs: Sequence[S]) -> list[S]:
    """Seed-major order, shuffled (deterministically) within each seed.

    Every block of one seed holds the same mix of cheap and costly runs, so the progress
    bar's time estimate is fair from the start, and an interrupted sweep leaves complete
    seeds rather than complete methods.
    """
    rng = np.random.default_rng(0)
    by_seed: dict[int, list[S]] = {}
    for s in specs:
        by_seed.setdefault(s.seed, []).append(s)
    out: list[S] = []
    for seed in sorted(by_seed):
        block = by_seed[seed]
        out.extend(block[i] for i in rng.permutation(len(block)))
    return out


def pending_specs(specs: Sequence[S], store: ResultStore, *, retry_failed: bool = True) -> list[S]:
    """The specs whose run is not finished in ``store`` (duplicates removed).

    A run with an ``"ok"`` row is finished. With ``retry_failed=False`` a run with a
    ``"failed"`` row counts as finished too.
    """
    rows = store.load(status=None, arrays=True, expand=False)
    done = {r["run_id"] for r in rows if r["status"] == "ok" or not retry_failed}
    unique: dict[str, S] = {}
    for s in specs:
        unique.setdefault(s.run_id, s)
    return [s for rid, s in unique.items() if rid not in done]


def _progress_bar(total: int, enabled: bool, desc: str) -> Any:
    if not enabled or total == 0:  # nothing to run: no bar (tqdm would draw it twice)
        return None
    try:
        from tqdm import tqdm
    except ImportError:  # pragma: no cover - tqdm is in the [bench] extra
        return None
    return tqdm(
        total=total, desc=desc, unit="run", file=sys.stderr, smoothing=0.05, dynamic_ncols=True
    )


def run_sweep(
    specs: Sequence[S],
    store: ResultStore,
    backend: Backend | None = None,
    *,
    progress: bool = True,
    retry_failed: bool = True,
    run: Callable[[Any], Row] = run_any,
) -> SweepSummary:
    """Run every spec not finished in ``store``, writing each row as its run finishes.

    Interrupting (Ctrl-C, an exception, a kill) loses only the runs in flight; calling
    again with the same specs resumes. The sweep holds the store's writer lock
    (:meth:`~voot.bench.store.result_store.ResultStore.writing`) from before it reads what is finished
    until its last row is written: a second sweep on the same store raises
    :class:`~voot.bench.store.lock.StoreBusyError` naming this one, before running anything.
    """
    with store.writing() as lock:
        if lock.stale:
            print(
                f"{store.path}: took over the writer lock of a sweep that did not release it"
                f" ({describe_holder(lock.stale)}; no longer running)",
                file=sys.stderr,
            )
        return _run_pending(specs, store, backend, progress, retry_failed, run)


def _run_pending(
    specs: Sequence[S],
    store: ResultStore,
    backend: Backend | None,
    progress: bool,
    retry_failed: bool,
    run: Callable[[Any], Row],
) -> SweepSummary:
    """The body of :func:`run_sweep`, under the store's writer lock."""
    backend = backend if backend is not None else SerialBackend()
    unique = {s.run_id for s in specs}
    todo = execution_order(pending_specs(specs, store, retry_failed=retry_failed))
    summary = SweepSummary(total=len(unique), skipped=len(unique) - len(todo))
    bar = _progress_bar(
        len(todo), progress, f"{specs[0].kind if specs else 'sweep'} ({backend.name})"
    )
    rows = backend.map_unordered(run, todo)
    try:
        for row in rows:
            write_row(store, row)
            summary.ran += 1
            if row["status"] != "ok":
                summary.failed += 1
                summary.failed_errors.append(
                    f"{describe_config(row['config'])}: {row.get('error')}"
                )
            if bar is not None:
                bar.update(1)
                if summary.failed:
                    bar.set_postfix(failed=summary.failed, refresh=False)
    finally:
        close = getattr(rows, "close", None)
        if close is not None:  # a generator backend: cancel what has not started
            close()
        if bar is not None:
            bar.close()
    return summary


def write_row(store: ResultStore, row: Row) -> None:
    """Write ``row`` into ``store``; a write the file system refuses stops the sweep.

    A full disk (``ENOSPC``), a quota or an I/O error while writing a row is a
    :class:`~voot.bench.store.format.StoreError` naming the store, the run and the cause
    (not a traceback, and not a failed row: the run itself did not fail). The store's
    atomic write leaves no part of that row behind (its temporary file is removed), so
    the store stays loadable with every row written before; the same command, run again
    once there is room, redoes that run and those not yet finished, and no other.
    """
    try:
        store.write(row)
    except OSError as exc:
        cause = exc.strerror or type(exc).__name__
        raise StoreError(
            f"{store.path}: could not write the row of run {row.get('run_id')!r}"
            f" ({cause}); the sweep stopped. The rows written before are kept; free the"
            " space (or fix the cause) and run the same command again to resume"
        ) from exc


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


def params_key(params: Mapping[str, Any]) -> str:
    """A short stable label of a hyperparameter setting (``"omega=0.001"``; ``"default"``)."""
    if not params:
        return "default"
    return ", ".join(f"{k}={params[k]}" for k in sorted(params))
