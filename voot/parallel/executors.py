"""Executors: where a function runs over many items, in this process or in workers.

One interface (:class:`Executor`) for every parallel job of voot: the runs of a
benchmark sweep (``voot.bench.sweep.engine.run_sweep``) and the trees of a root-parallel search
(``voot.tree.root_parallel.plan_root_parallel``). An executor

* ``map(fn, items)``: yields ``fn(item)`` for every item, **in the items' order**;
* ``map_unordered(fn, items)``: the same results **as they complete** (a sweep writes
  each row as soon as its run finishes);
* ``close(kill=False)``: shuts down what it started; ``kill=True`` terminates worker
  processes instead of letting running items finish (after an error or an interrupt,
  so that no orphan keeps computing). Executors are also context managers: leaving the
  ``with`` block closes them, killing the workers if the block raised.

``fn`` and the items must pickle for executors whose workers are other processes
(``in_process`` is False). Stopping the iteration early (an exception, ``close()`` of
the generator, Ctrl-C) cancels the items that have not started.

Worker processes never outlive their driver: every worker of a :class:`ProcessExecutor`
watches the process that started it and exits as soon as that process is gone, even
when it was killed with SIGKILL and could not shut its pool down (without this, spawned
workers blocked for ever on their task queue, adopted by PID 1, and kept the
multiprocessing resource tracker alive with them). See :func:`watch_parent`.

Implementations: :class:`SerialExecutor` (this process, one item after the other),
:class:`ProcessExecutor` (a pool of local processes) and, in ``voot.bench.sweep.ray_backend``,
``RayBackend`` (actors on a Ray cluster; it needs Ray, so it lives with the benchmarks).
"""

from __future__ import annotations

import contextlib
import itertools
import multiprocessing
import os
import threading
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from typing import Any, Generic, Protocol, TypeVar, runtime_checkable

from voot import validation as V
from voot._workers import single_threaded_children

T = TypeVar("T")
R = TypeVar("R")


@runtime_checkable
class Executor(Protocol):
    """Runs a function over items (see the module docstring for the contract).

    Attributes:
        name: a short name for progress bars and messages (``"serial"``, ``"process"``).
        in_process: True if ``fn`` runs in this process (its results are the very
            objects ``fn`` returned, nothing is pickled).
    """

    name: str
    in_process: bool

    def map(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """``fn(item)`` for every item, in the items' order."""
        ...

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """``fn(item)`` for every item, in completion order."""
        ...

    def close(self, *, kill: bool = False) -> None:
        """Shut down (terminate the workers if ``kill``)."""
        ...


class _Indexed(Generic[T, R]):
    """``fn`` over ``(index, item)`` pairs, returning ``(index, fn(item))``; it pickles
    when ``fn`` does (module level, no closure)."""

    def __init__(self, fn: Callable[[T], R]) -> None:
        self.fn = fn

    def __call__(self, pair: tuple[int, T]) -> tuple[int, R]:
        index, item = pair
        return index, self.fn(item)


def in_order(
    map_unordered: Callable[..., Iterable[tuple[int, R]]],
    fn: Callable[[T], R],
    items: Iterable[T],
) -> Iterator[R]:
    """``map`` from a ``map_unordered``: results yielded in the items' order.

    Each result waits in a buffer until every earlier one has come back, so the first
    result may come later than with ``map_unordered``; the work is the same.
    """
    results = map_unordered(_Indexed(fn), list(enumerate(items)))
    buffer: dict[int, R] = {}
    following = 0
    try:
        for index, value in results:
            buffer[index] = value
            while following in buffer:
                yield buffer.pop(following)
                following += 1
    finally:
        close = getattr(results, "close", None)
        if callable(close):  # a generator: cancel what has not started
            close()


class SerialExecutor:
    """Runs every item in this process, one after the other, in order (tests, debugging,
    one core, or work that is already parallel one level up)."""

    name = "serial"
    in_process = True

    def map(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        for item in items:
            yield fn(item)

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """The same as :meth:`map` (items complete in order here)."""
        return self.map(fn, items)

    def close(self, *, kill: bool = False) -> None:
        """Nothing to shut down."""

    def __enter__(self) -> SerialExecutor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def terminate_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's worker processes now (what they were running is lost)."""
    terminate = getattr(pool, "terminate_workers", None)  # Python >= 3.14
    if callable(terminate):
        terminate()
        return
    processes = getattr(pool, "_processes", None) or {}
    for process in list(processes.values()):
        with contextlib.suppress(Exception):
            process.terminate()


#: Seconds between two looks of a worker at its parent (see :func:`watch_parent`).
PARENT_POLL_SECONDS = 0.25


def watch_parent(parent_pid: int, interval: float = PARENT_POLL_SECONDS) -> threading.Thread:
    """Exit this process (``os._exit``) soon after the process ``parent_pid`` is gone.

    A daemon thread compares ``os.getppid()`` with ``parent_pid`` every ``interval``
    seconds: when the parent dies its children are re-parented (to PID 1 or a
    subreaper), so the two differ. Portable where ``getppid`` reports the current
    parent (POSIX); on Windows, where it keeps the original pid, the thread also asks
    whether that process still exists. ``prctl(PR_SET_PDEATHSIG)`` was not used: Linux
    sends that signal when the parent *thread* that started the worker ends, and pool
    workers may be started from a short-lived thread. The cost is one system call per
    interval; the work of an item is not interrupted while the parent lives.
    ``os._exit`` skips ``atexit`` handlers and the queue feeder threads, which would
    block on a parent that is no longer there.
    """

    def gone() -> bool:
        if os.getppid() != parent_pid:
            return True
        if os.name == "nt":  # pragma: no cover - getppid keeps the original pid there
            try:
                os.kill(parent_pid, 0)
            except OSError:
                return True
        return False

    def watch() -> None:
        while True:
            time.sleep(interval)
            if gone():
                os._exit(1)

    thread = threading.Thread(target=watch, name="voot-watch-parent", daemon=True)
    thread.start()
    return thread


def _init_worker(
    parent_pid: int, initializer: Callable[..., object] | None, *initargs: object
) -> None:
    """Every pool worker's initializer: watch the parent, then the user's initializer."""
    watch_parent(parent_pid)
    if initializer is not None:
        initializer(*initargs)


_END = object()


class ProcessExecutor:
    """A pool of local worker processes (a :class:`~concurrent.futures.ProcessPoolExecutor`).

    Args:
        max_workers: worker processes (default ``os.cpu_count()``).
        start_method: ``"spawn"`` (default: a fresh interpreter per worker, nothing of the
            parent's state leaks in; slower to start), ``"forkserver"`` or ``"fork"``.
        initializer: run as ``initializer(*initargs)`` in every worker when it starts,
            e.g. to build a MuJoCo problem into the worker's cache
            (:mod:`voot.parallel.cache`) before the first, timed, item.
        initargs: the initializer's arguments.
        max_pending: items submitted ahead of completion (default ``4 * max_workers``;
            bounds the memory of huge sweeps).
        keep_alive: keep the pool (its workers and what they cached) from one ``map`` to
            the next until :meth:`close` (default). False: every ``map`` starts a pool
            and shuts it down when it ends.

    Worker processes start on demand, get one BLAS/OpenMP thread each
    (:func:`voot._workers.single_threaded_children`) and exit by themselves when this
    process dies (:func:`watch_parent`). When an item raises or the
    caller stops early, the items not started are cancelled; a per-call pool
    (``keep_alive=False``) is then terminated at once, a kept pool lives on until
    :meth:`close` (``with`` blocks close it with ``kill=True`` on an exception).
    """

    name = "process"
    in_process = False

    def __init__(
        self,
        max_workers: int | None = None,
        start_method: str = "spawn",
        initializer: Callable[..., object] | None = None,
        initargs: tuple[Any, ...] = (),
        *,
        max_pending: int | None = None,
        keep_alive: bool = True,
    ) -> None:
        n = (os.cpu_count() or 1) if max_workers is None else max_workers
        n = V.integer(n, "max_workers", 1)
        valid = multiprocessing.get_all_start_methods()
        if start_method not in valid:
            raise ValueError(
                f"unknown start method {start_method!r}; valid start methods are: {', '.join(valid)}"
            )
        V.optional_integer(max_pending, "max_pending", 1)
        self.max_workers = n
        self.start_method = start_method
        self.initializer = initializer
        self.initargs = tuple(initargs)
        self.max_pending = max_pending if max_pending is not None else 4 * n
        self.keep_alive = bool(keep_alive)
        self._pool: ProcessPoolExecutor | None = None

    @property
    def workers(self) -> int:
        """The number of worker processes (``max_workers``)."""
        return self.max_workers

    def _submit(self, fn: Callable[[T], R], item: T) -> Future[R]:
        # Workers start on demand at submit(): the thread variables are set around it.
        with single_threaded_children():
            if self._pool is None:
                self._pool = ProcessPoolExecutor(
                    max_workers=self.max_workers,
                    mp_context=multiprocessing.get_context(self.start_method),
                    initializer=_init_worker,
                    initargs=(os.getpid(), self.initializer, *self.initargs),
                )
            return self._pool.submit(fn, item)

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """Submit up to ``max_pending`` items ahead, yield results as they complete (an
        item's exception is raised when its result comes)."""
        todo = iter(list(items))
        pending: set[Future[R]] = set()
        completed = False
        try:
            for item in itertools.islice(todo, self.max_pending):
                pending.add(self._submit(fn, item))
            while pending:
                done, pending = wait(pending, return_when=FIRST_COMPLETED)
                for fut in done:
                    following = next(todo, _END)
                    if following is not _END:
                        pending.add(self._submit(fn, following))  # type: ignore[arg-type]
                    yield fut.result()
            completed = True
        finally:
            for fut in pending:
                fut.cancel()
            if not self.keep_alive:
                self.close(kill=not completed)

    def map(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """Results in the items' order (see :func:`in_order`)."""
        return in_order(self.map_unordered, fn, items)

    def warm_up(self) -> None:
        """Start every worker process now (so that a timed ``map`` does not pay for it)."""
        list(self.map_unordered(_pid, [None] * (2 * self.max_workers)))

    def close(self, *, kill: bool = False) -> None:
        """Shut the pool down (its workers and what they cached go).

        Args:
            kill: terminate the workers instead of letting running items finish.
        """
        pool, self._pool = self._pool, None
        if pool is None:
            return
        if kill:
            terminate_workers(pool)
        pool.shutdown(wait=True, cancel_futures=True)

    def __enter__(self) -> ProcessExecutor:
        return self

    def __exit__(self, exc_type: object, *exc: object) -> None:
        self.close(kill=exc_type is not None)


def _pid(_: object) -> int:
    time.sleep(0.05)  # keep this worker busy so that the next item starts another one
    return os.getpid()
