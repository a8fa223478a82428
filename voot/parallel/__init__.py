"""Parallel execution for every part of voot: sweeps and root-parallel search alike.

Two concepts, one module each:

* :mod:`voot.parallel.executors`: the :class:`Executor` interface (map a picklable
  function over items; results in the items' order or as they complete; a shutdown that
  terminates worker processes) with a :class:`SerialExecutor` and a
  :class:`ProcessExecutor`. ``voot.bench.sweep.ray_backend.RayBackend`` implements the same
  interface on a Ray cluster.
* :mod:`voot.parallel.cache`: :class:`WorkerCache`, the one small LRU of expensive
  objects (environments, planning problems) that each worker process keeps between
  work items.

This layer sits beside :mod:`voot._workers`, below :mod:`voot.tree` and
:mod:`voot.bench`, so that both use it; it imports nothing of voot above it (and needs
no MuJoCo, no Ray).
"""

from voot.parallel.cache import (
    CACHE_SIZE,
    WorkerCache,
    clear_worker_cache,
    worker_cache,
)
from voot.parallel.executors import (
    Executor,
    ProcessExecutor,
    SerialExecutor,
    in_order,
    terminate_workers,
)

__all__ = [
    "CACHE_SIZE",
    "Executor",
    "ProcessExecutor",
    "SerialExecutor",
    "WorkerCache",
    "clear_worker_cache",
    "in_order",
    "terminate_workers",
    "worker_cache",
]
