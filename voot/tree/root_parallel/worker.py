"""One tree of a root-parallel search: the work item, the worker function, its result.

A :class:`TreeTask` is everything a worker needs to grow tree :math:`k` (the problem or a
factory building it, the configuration, the seed); :func:`run_tree` grows it and returns
a :class:`TreeResult` (its plan, its root statistics for the merge, its timings). Both
pickle, so a task goes to another process or machine as it is.

A factory's problem is built once per worker process and kept in the process's worker
cache (:mod:`voot.parallel.cache`); its initial snapshot is restored before every tree,
so a kept problem searches exactly as a fresh one.
"""

from __future__ import annotations

import functools
import math
import os
import pickle
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from voot.optim.base import FloatArray
from voot.parallel import CACHE_SIZE, clear_worker_cache, worker_cache
from voot.tree.config import MCTSConfig
from voot.tree.mcts import MCTS
from voot.tree.problem import PlanningProblem, problem_bounds
from voot.tree.root_parallel._compare import same, same_fields, same_plan
from voot.tree.root_parallel.merge import RootStats
from voot.tree.search import PlanResult

#: A zero-argument callable that builds the planning problem (in its initial state).
ProblemFactory = Callable[[], PlanningProblem]

#: Objects each process keeps built (problems from factories among them; the least
#: recently used one is dropped): the size of the process's worker cache.
PROBLEM_CACHE_SIZE = CACHE_SIZE


@dataclass(frozen=True)
class TreeTask:
    """One tree's work, sent to a worker (it pickles if the problem source does).

    Attributes:
        index: the tree's index :math:`k`.
        source: the problem, or a zero-argument factory that builds it.
        is_factory: whether ``source`` is a factory.
        root_snapshot: the root state to restore first (problems passed as objects).
        config: the search's configuration.
        n_simulations: simulations of this tree.
        seed: the tree's seed (see :func:`tree_seeds`).
        record_info: a step-info key to record at the best leaf (see :meth:`MCTS.search`).
        keep_tree: return the search object in ``plan.mcts`` (in-process executors only).
        time_limit: stop after this many seconds of search even before ``n_simulations``.
    """

    index: int
    source: Any
    is_factory: bool
    root_snapshot: Any
    config: MCTSConfig
    n_simulations: int
    seed: np.random.SeedSequence
    record_info: str | None = None
    keep_tree: bool = False
    time_limit: float | None = None


@dataclass(frozen=True)
class TreeResult:
    """What one tree found.

    Attributes:
        index: the tree's index :math:`k`.
        seed: its seed.
        plan: its :class:`~voot.tree.PlanResult` (``mcts`` is None unless the tree was
            kept by an in-process executor).
        root: its root statistics (what the merge sees).
        started: ``time.time()`` when its search started (for wall-time alignment).
        elapsed: seconds since its search started, after every simulation.
        pid: the process that ran it.
        cpu_time: CPU seconds its process spent in the search (wall time minus waiting
            for a core, on a shared machine).
    """

    index: int
    seed: np.random.SeedSequence = field(compare=False)
    plan: PlanResult = field(compare=False)
    root: RootStats
    started: float = field(compare=False)
    elapsed: FloatArray = field(compare=False, repr=False)
    pid: int = field(compare=False)
    cpu_time: float = field(default=math.nan, compare=False)

    def __eq__(self, other: object) -> bool:
        """Equal if the seed determines the same tree: timings, process and tree ignored."""
        if not isinstance(other, TreeResult):
            return NotImplemented
        return (
            same_fields(self, other)
            and same(self.seed.entropy, other.seed.entropy)
            and self.seed.spawn_key == other.seed.spawn_key
            and same_plan(self.plan, other.plan)
        )

    __hash__ = None  # type: ignore[assignment]


#: This process's worker cache (:mod:`voot.parallel.cache`), where problems built from
#: factories are kept (under ``("problem", pickled factory)``), beside what other users of
#: the process keep (e.g. environments of ``voot.bench``).
_PROBLEM_CACHE = worker_cache()


def clear_problem_cache() -> None:
    """Forget the problems this process built from factories (this clears the process's
    whole worker cache, :func:`voot.parallel.clear_worker_cache`)."""
    clear_worker_cache()


def _build(factory: ProblemFactory) -> tuple[PlanningProblem, Any]:
    problem = factory()
    return problem, problem.snapshot()


def _problem_of(task: TreeTask) -> tuple[PlanningProblem, Any]:
    """The task's problem and its root snapshot (a factory's problem is kept per process)."""
    if not task.is_factory:
        return task.source, task.root_snapshot
    try:
        key = ("problem", pickle.dumps(task.source))
    except Exception:  # a lambda, a closure: built afresh every time
        return _build(task.source)
    return worker_cache().get(key, functools.partial(_build, task.source))


def prebuild_problem(factory: ProblemFactory) -> None:
    """Build ``factory``'s problem into this process's cache now (a worker initializer)."""
    _problem_of(TreeTask(0, factory, True, None, MCTSConfig(), 1, np.random.SeedSequence(0)))


def run_tree(task: TreeTask) -> TreeResult:
    """Run one tree (the worker function; module-level so that it pickles)."""
    problem, snapshot = _problem_of(task)
    problem.restore(snapshot)
    mcts = MCTS(problem, task.config, seed=task.seed)
    elapsed: list[float] = []
    clock = time.perf_counter
    started = time.time()
    c0 = time.process_time()
    t0 = clock()

    limit = math.inf if task.time_limit is None else task.time_limit

    def tick(_: MCTS, __: int) -> bool:
        t = clock() - t0
        elapsed.append(t)
        return t >= limit

    res = mcts.search(task.n_simulations, callback=tick, record_info=task.record_info)
    cpu = time.process_time() - c0
    bounds = mcts.root.bounds if mcts.root.bounds is not None else problem_bounds(problem)
    root = RootStats.from_node(mcts.root, bounds.lower, bounds.upper)
    problem.restore(snapshot)
    return TreeResult(
        index=task.index,
        seed=task.seed,
        plan=res if task.keep_tree else replace(res, mcts=None),
        root=root,
        started=started,
        elapsed=np.array(elapsed, dtype=np.float64),
        pid=os.getpid(),
        cpu_time=cpu,
    )
