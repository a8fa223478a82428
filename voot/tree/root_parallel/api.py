"""The entry point of root-parallel search: :func:`plan_root_parallel`.

It checks the options, resolves the executor (a name or an object; see
:mod:`voot.parallel`), builds one :class:`~voot.tree.root_parallel.worker.TreeTask` per
tree, maps :func:`~voot.tree.root_parallel.worker.run_tree` over them and merges the
results (:func:`~voot.tree.root_parallel.result.merge_trees`).
"""

from __future__ import annotations

import math
import os
import pickle
import time
from collections.abc import Callable, Iterable, Sequence
from typing import Any, TypeVar

import numpy as np

from voot import validation as V
from voot.parallel import Executor, ProcessExecutor, SerialExecutor
from voot.tree.config import MCTSConfig, planner_config
from voot.tree.problem import PlanningProblem
from voot.tree.root_parallel.config import MergeRule, RootParallelConfig, tree_seeds
from voot.tree.root_parallel.result import RootParallelResult, merge_trees
from voot.tree.root_parallel.worker import ProblemFactory, TreeTask, run_tree
from voot.tree.search import check_n_simulations

T = TypeVar("T")
R = TypeVar("R")

#: What runs the trees: any :class:`voot.parallel.Executor` (or, duck-typed, any object
#: with ``map(fn, items)`` or ``map_unordered(fn, items)``).
TreeExecutor = Executor
#: The local process pool of root-parallel search (kept between searches until closed).
LocalProcessExecutor = ProcessExecutor
#: Executor names accepted by :func:`plan_root_parallel`.
EXECUTORS = ("process", "serial")

__all__ = [
    "EXECUTORS",
    "LocalProcessExecutor",
    "SerialExecutor",
    "TreeExecutor",
    "plan_root_parallel",
]


def plan_root_parallel(
    problem: PlanningProblem | ProblemFactory,
    planner: str | MCTSConfig = "voot",
    n_simulations: int = 1000,
    seed: int | np.random.SeedSequence | None = 0,
    *,
    n_trees: int = 2,
    merge: MergeRule | str = MergeRule.MAX_Q,
    vote_radius: float = 0.1,
    executor: str | TreeExecutor | Any = "process",
    max_workers: int | None = None,
    record_info: str | None = None,
    keep_trees: bool = False,
    time_limit: float | None = None,
    **options: Any,
) -> RootParallelResult:
    """Root-parallel search: ``n_trees`` independent trees, merged at the root.

    Args:
        problem: the planning problem (its current state is the root), or a zero-argument
            factory that builds it in the root state (for problems that do not pickle, or
            not cheaply, e.g. MuJoCo environments; it must build the same state every call).
        planner: a planner name or an :class:`~voot.tree.MCTSConfig` (every tree's).
        n_simulations: simulations *per tree* (:math:`N`; the trees run :math:`K N` in all).
        seed: the base seed; tree :math:`k` gets ``tree_seeds(seed, K)[k]``.
        n_trees: :math:`K`.
        merge: the root merge rule (``max_q``, ``most_visited``, ``vote``).
        vote_radius: the ``vote`` neighbourhood radius (see
            :class:`~voot.tree.root_parallel.config.RootParallelConfig`).
        executor: ``"process"`` (a :class:`~voot.parallel.ProcessExecutor` of
            ``min(K, max_workers or os.cpu_count())`` workers for this call only; pass your
            own to keep it between calls), ``"serial"``, or any
            :class:`~voot.parallel.Executor` (e.g. ``voot.bench.sweep.ray_backend.RayBackend``),
            or any object with ``map(fn, items)`` (or ``map_unordered``), e.g. a
            :class:`concurrent.futures.Executor`.
        max_workers: worker processes of ``executor="process"``.
        record_info: a step-info key recorded at each tree's best leaf (see
            :meth:`voot.tree.MCTS.search`) and merged into ``info_curve``.
        keep_trees: keep each tree's search object in ``trees[k].plan.mcts``; only with
            an in-process executor (``"serial"``).
        time_limit: seconds of search after which each tree stops, even before
            ``n_simulations`` (an anytime planner with a deadline). With a time limit the
            result depends on the machine's speed and load: it is *not* deterministic.
        **options: :class:`~voot.tree.MCTSConfig` fields overriding the planner's.

    Without ``time_limit`` the merged result depends only on the problem, the
    configuration and ``seed``: not on the executor, the number of workers, or the order
    in which trees finish.

    >>> from voot.tree.null_problem import NullProblem
    >>> res = plan_root_parallel(NullProblem(dim=2), "voot", 20, seed=0, n_trees=3,
    ...                          executor="serial", depth_limit=3)
    >>> res.best_return_curve.shape, res.total_simulations
    ((20,), 60)
    """
    n = check_n_simulations(n_simulations)
    parallel = RootParallelConfig(n_trees=n_trees, merge=merge, vote_radius=vote_radius)
    config = _search_config(planner, options)
    _check_search_options(record_info, keep_trees, time_limit)
    is_factory = not _is_problem(problem)
    if is_factory and not callable(problem):
        raise ValueError(
            f"problem must be a PlanningProblem (snapshot, restore, step, action_bounds) or a"
            f" zero-argument factory building one; got {type(problem).__name__}"
        )
    runner, own_pool = _resolve_executor(executor, max_workers, parallel.n_trees)
    in_process = bool(getattr(runner, "in_process", False))
    if keep_trees and not in_process:
        raise ValueError(
            "keep_trees=True needs an in-process executor (executor='serial'): a tree built"
            " in another process is not sent back"
        )
    root_snapshot = None
    if not is_factory:
        root_snapshot = problem.snapshot()  # type: ignore[union-attr]
        if not in_process:
            _check_pickles(problem)
    tasks = [
        TreeTask(
            index=k,
            source=problem,
            is_factory=is_factory,
            root_snapshot=root_snapshot,
            config=config,
            n_simulations=n,
            seed=s,
            record_info=record_info,
            keep_tree=keep_trees,
            time_limit=None if time_limit is None else float(time_limit),
        )
        for k, s in enumerate(tree_seeds(seed, parallel.n_trees))
    ]
    started = time.time()
    t0 = time.perf_counter()
    failed = True
    try:
        results = list(_map(runner, run_tree, tasks))
        failed = False
    finally:
        if own_pool is not None:
            own_pool.close(kill=failed)
        if not is_factory:
            problem.restore(root_snapshot)  # type: ignore[union-attr]
    return merge_trees(results, parallel, started, time.perf_counter() - t0)


def _search_config(planner: str | MCTSConfig, options: dict[str, Any]) -> MCTSConfig:
    """Every tree's configuration: the planner's, with ``options`` overriding."""
    if isinstance(planner, MCTSConfig):
        return planner.replace(**options) if options else planner
    return planner_config(planner, **options)


def _is_problem(obj: object) -> bool:
    return all(
        callable(getattr(obj, m, None)) for m in ("snapshot", "restore", "step", "action_bounds")
    )


def _check_search_options(record_info: object, keep_trees: object, time_limit: object) -> None:
    """Raise a ValueError naming the first bad option."""
    if record_info is not None and not isinstance(record_info, str):
        raise ValueError(
            f"record_info must be a step-info key (a string) or None, got {record_info!r}"
        )
    if not isinstance(keep_trees, bool):
        raise ValueError(f"keep_trees must be True or False, got {keep_trees!r}")
    if time_limit is not None and (
        isinstance(time_limit, bool)
        or not isinstance(time_limit, int | float)
        or not math.isfinite(time_limit)
        or time_limit <= 0
    ):
        raise ValueError(f"time_limit must be a number of seconds > 0 or None, got {time_limit!r}")


def _resolve_executor(
    executor: Any, max_workers: int | None, n_trees: int
) -> tuple[Any, ProcessExecutor | None]:
    """The executor to run the trees on, and the pool this call owns (closes) if any."""
    if max_workers is not None and executor != "process":
        raise ValueError("max_workers applies to executor='process' only")
    if not isinstance(executor, str):
        return executor, None
    if executor == "serial":
        return SerialExecutor(), None
    if executor == "process":
        V.optional_integer(max_workers, "max_workers", 1)
        pool = ProcessExecutor(min(n_trees, max_workers or os.cpu_count() or 1))
        return pool, pool
    raise ValueError(
        f"unknown executor {executor!r}; valid executors are: {', '.join(EXECUTORS)}"
        " (or an object with map(fn, items))"
    )


def _check_pickles(problem: object) -> None:
    """A problem sent to worker processes must pickle (else: say to pass a factory)."""
    try:
        pickle.dumps(problem)
    except Exception as exc:
        raise ValueError(
            f"{type(problem).__name__} cannot be sent to worker processes ({exc});"
            " pass a zero-argument factory that builds it, or executor='serial'"
        ) from None


def _map(executor: Any, fn: Callable[[T], R], items: Sequence[T]) -> Iterable[R]:
    """``executor.map(fn, items)``, or its ``map_unordered`` (the merge sorts the trees)."""
    mapper = getattr(executor, "map", None)
    if not callable(mapper):
        mapper = getattr(executor, "map_unordered", None)
    if not callable(mapper):
        raise ValueError(
            f"executor must be one of {', '.join(EXECUTORS)} or an object with"
            f" map(fn, items) (or map_unordered(fn, items)); got {type(executor).__name__}"
        )
    return mapper(fn, items)  # type: ignore[no-any-return]
