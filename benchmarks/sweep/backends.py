"""The backends of benchmark sweeps: where runs execute, chosen by name.

A backend is any :class:`voot.parallel.Executor`; a sweep uses its ``map_unordered``
(rows in completion order, each written as soon as its run finishes) and its ``name``.
:func:`make_backend` builds one from the command line's ``--backend``: ``serial``
(:data:`SerialBackend`, this process), ``process`` (:class:`ProcessBackend`, a local pool
per sweep) or ``ray`` (:class:`voot.bench.sweep.ray_backend.RayBackend`, imported only then,
since it needs Ray). The same executors run the trees of root-parallel search.
"""

from __future__ import annotations

from voot import validation as V
from voot.parallel import Executor, ProcessExecutor, SerialExecutor

#: Where runs execute: any :class:`voot.parallel.Executor` (the sweep uses its
#: ``map_unordered``, rows in completion order, and its ``name``). A backend must not drop
#: rows: when the consumer stops early (exception, Ctrl-C) it cancels what has not
#: started. ``fn`` and the items must be picklable for backends that run elsewhere.
Backend = Executor

#: Runs everything in this process, in order (for tests, debugging, one core).
SerialBackend = SerialExecutor


class ProcessBackend(ProcessExecutor):
    """A local process pool of ``workers`` processes, started by every
    ``map_unordered`` and shut down when it ends (its workers terminated if it was
    interrupted): a :class:`voot.parallel.ProcessExecutor` with ``keep_alive=False``.

    Args:
        workers: number of processes (default ``os.cpu_count()``).
        start_method: multiprocessing start method; ``"spawn"`` (default) gives every
            worker a fresh interpreter, so nothing of the parent's state leaks into runs.
        max_pending: runs submitted ahead of completion (bounds memory on huge sweeps).
    """

    def __init__(
        self,
        workers: int | None = None,
        start_method: str = "spawn",
        max_pending: int | None = None,
    ) -> None:
        if workers is not None:
            V.integer(workers, "workers", 1)
        super().__init__(workers, start_method, max_pending=max_pending, keep_alive=False)


BACKENDS: tuple[str, ...] = ("process", "serial", "ray")


def make_backend(
    name: str = "process",
    workers: int | None = None,
    *,
    address: str | None = None,
    max_tries: int | None = None,
) -> Backend:
    """A backend by name: ``process`` (a local pool; one worker runs in this process),
    ``serial`` or ``ray`` (:class:`voot.bench.sweep.ray_backend.RayBackend`; ``address`` of an
    existing cluster, e.g. ``"auto"``, and ``max_tries`` per run)."""
    if name != "ray" and (address is not None or max_tries is not None):
        raise ValueError("address and max_tries apply to the ray backend only (--backend ray)")
    if name == "process":
        if workers == 1:
            return SerialBackend()
        return ProcessBackend(workers)
    if name == "serial":
        return SerialBackend()
    if name == "ray":
        from voot.bench.sweep.ray_backend import DEFAULT_MAX_TRIES, RayBackend

        return RayBackend(
            workers,
            address=address,
            max_tries=DEFAULT_MAX_TRIES if max_tries is None else max_tries,
        )
    raise ValueError(f"unknown backend {name!r}; valid backends are: {', '.join(BACKENDS)}")
