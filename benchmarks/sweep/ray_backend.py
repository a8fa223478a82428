"""Run a sweep on Ray: a local Ray instance or an existing cluster (``--backend ray``).

:class:`RayBackend` is a :class:`voot.parallel.Executor` (so a
:class:`~voot.bench.sweep.backends.Backend`): the same runs, the same rows, the same store as the
local backends; only where the runs execute changes. Its ``map`` (results in order,
exceptions raised) serves any function, e.g. the trees of
:func:`voot.tree.root_parallel.plan_root_parallel` (``executor=RayBackend(...)``).

* **Workers keep their models.** The backend starts one long-lived actor per CPU (or
  ``workers``); each runs one run at a time in its own process, so what a run loads
  once per process stays loaded for the next run on that actor: the environments made
  by :func:`voot.bench.protocol.problems.cached_env` (MuJoCo models, scenes), imported modules.
* **Dead workers are retried.** If an actor's process dies during a run (a crash, the
  out-of-memory killer, a lost node), the actor is replaced and the run resubmitted, up
  to ``max_tries`` tries in all; then the run gets a ``"failed"`` row naming the error
  and the number of tries, and the sweep goes on. An exception *inside* a run is not a
  death: the run function turns it into a failed row itself (as on every backend).
* **Nothing finished is lost.** Rows come back to the driver, which writes them to the
  store as they arrive (atomically, :mod:`voot.bench.store.result_store`); interrupting the driver
  kills the actors, and rerunning the same command resumes.

Connecting: ``address=None`` starts a private local instance with ``workers`` CPUs and
shuts it down afterwards; ``address="auto"`` (or ``"ray://host:10001"``, or
``"host:6379"``) joins a running cluster started with ``ray start --head``, whose nodes
must have the same voot installed. If Ray is already initialised in this process (e.g.
a test fixture), the backend uses that instance and leaves it running.

**A killed driver leaves no local instance behind.** With the instance it started
itself, the backend also starts a :class:`~voot.bench.sweep.ray_reaper.RayReaper`: if the
driver dies without shutting Ray down (``kill -KILL``, the out-of-memory killer), the
reaper stops what is left of that instance (Ray's agents outlived the driver otherwise).
A cluster joined by ``address`` is never touched.
"""

from __future__ import annotations

import collections
import contextlib
import dataclasses
import logging
import os
import socket
import warnings
from collections.abc import Callable, Generator, Iterator, Sequence
from typing import Any, TypeVar, cast

from voot import validation as V
from voot.bench.store.format import Row, failed_row

#: Tries per run when its worker dies (the first try included).
DEFAULT_MAX_TRIES = 3

T = TypeVar("T")
R = TypeVar("R")


@dataclasses.dataclass(frozen=True)
class _Failure:
    """Why an item has no result: a message, the exception, the tries made, and whether
    the worker died (``lost``) rather than the function raised."""

    message: str
    error: BaseException
    tries: int
    lost: bool


class _Worker:
    """The actor: runs one run at a time in its own, long-lived process."""

    def run(self, fn: Callable[[Any], Any], item: Any) -> Any:
        return fn(item)

    def where(self) -> tuple[str, int]:
        """(host name, process id) of this worker."""
        return socket.gethostname(), os.getpid()


def _lost_errors() -> tuple[type[BaseException], ...]:
    """Ray's exceptions that mean "the worker (or its node) died", not "the run raised"."""
    import ray.exceptions as rex

    names = (
        "RayActorError",  # ActorDiedError, ActorUnavailableError
        "WorkerCrashedError",
        "NodeDiedError",
        "ObjectLostError",  # OwnerDiedError ...
        "LocalRayletDiedError",
    )
    return tuple(getattr(rex, n) for n in names if hasattr(rex, n))


class RayBackend:
    """Runs items on a pool of Ray actors (see the module docstring).

    Args:
        workers: number of actors (one CPU each); default: every CPU of the instance.
        address: None to start a local instance, else a cluster address (``"auto"``).
        max_tries: tries per run when its worker dies (>= 1).
        init_options: extra keywords of ``ray.init`` (when this backend starts Ray).
        on_lost: ``on_lost(item, error, tries=n)`` makes the row of a run whose worker
            died ``max_tries`` times (default :func:`voot.bench.store.format.failed_row`).
        reap_on_driver_death: with a local instance this backend starts, run a
            :class:`~voot.bench.sweep.ray_reaper.RayReaper` that stops the instance if the
            driver dies without shutting it down (needs ``psutil``).
    """

    name = "ray"
    in_process = False

    def __init__(
        self,
        workers: int | None = None,
        *,
        address: str | None = None,
        max_tries: int = DEFAULT_MAX_TRIES,
        init_options: dict[str, Any] | None = None,
        on_lost: Callable[..., Row] = failed_row,
        reap_on_driver_death: bool = True,
    ) -> None:
        V.optional_integer(workers, "workers", 1)
        V.integer(max_tries, "max_tries", 1)
        if address is not None and (not isinstance(address, str) or not address.strip()):
            raise ValueError(f"address must be a Ray address such as 'auto', got {address!r}")
        self.workers = workers
        self.address = address
        self.max_tries = max_tries
        self.init_options = dict(init_options or {})
        self.on_lost = on_lost
        if not isinstance(reap_on_driver_death, bool):
            raise ValueError(
                f"reap_on_driver_death must be True or False, got {reap_on_driver_death!r}"
            )
        self.reap_on_driver_death = reap_on_driver_death
        #: The reaper of the local instance being run (None when none is).
        self.reaper: Any = None
        #: Runs resubmitted after a worker died, in the last :meth:`map_unordered`.
        self.retries = 0

    def _init(self) -> bool:
        """Initialise Ray if needed; True if this call started (and must stop) it."""
        try:
            import ray
        except ImportError:
            raise ValueError(
                "the ray backend needs Ray: pip install 'voot[ray]' (or pip install ray)"
            ) from None
        if ray.is_initialized():
            return False
        options: dict[str, Any] = {
            "include_dashboard": False,
            "log_to_driver": False,
            "logging_level": logging.WARNING,
        }
        if self.address is None:
            options["num_cpus"] = self.workers
        else:
            options["address"] = self.address
        options.update(self.init_options)
        try:
            ray.init(**options)
        except ConnectionError as exc:
            raise ValueError(
                f"cannot reach a Ray cluster at {self.address!r} ({exc}); start one with"
                " 'ray start --head' or leave out --address for a local instance"
            ) from None
        if self.address is None and "address" not in self.init_options:
            self._start_reaper()
        return True

    def _start_reaper(self) -> None:
        """Watch the local instance just started (see :mod:`voot.bench.sweep.ray_reaper`)."""
        if not self.reap_on_driver_death:
            return
        try:
            import psutil  # noqa: F401
        except ImportError:
            warnings.warn(
                "psutil is not installed: if this driver is killed, nothing stops its local"
                " Ray instance (pip install psutil, or 'voot[ray]')",
                RuntimeWarning,
                stacklevel=3,
            )
            return
        from voot.bench.sweep.ray_reaper import RayReaper

        self.reaper = RayReaper()

    def _shutdown(self) -> None:
        """Shut down the local instance this backend started, then release its reaper."""
        import ray

        try:
            ray.shutdown()
        finally:
            reaper, self.reaper = self.reaper, None
            if reaper is not None:
                reaper.done()

    def _outcomes(
        self, fn: Callable[[T], R], items: Sequence[T]
    ) -> Generator[tuple[int, Any, _Failure | None], None, None]:
        """``(index, result, None)`` for every item as it completes, or ``(index, None,
        failure)`` when its worker died ``max_tries`` times or ``fn`` raised."""
        if not items:
            return
        import ray

        started = self._init()
        lost = _lost_errors()
        actors: list[Any] = []
        self.retries = 0
        try:
            total = int(ray.cluster_resources().get("CPU", 1))
            n = min(self.workers or max(total, 1), len(items))
            actor_class = ray.remote(num_cpus=1, max_restarts=0, max_task_retries=0)(_Worker)
            actors = [actor_class.remote() for _ in range(n)]
            queue = collections.deque(range(len(items)))
            tries = [0] * len(items)
            idle = list(range(n))
            in_flight: dict[Any, tuple[int, int]] = {}
            while queue or in_flight:
                while idle and queue:
                    a, i = idle.pop(), queue.popleft()
                    tries[i] += 1
                    in_flight[actors[a].run.remote(fn, items[i])] = (a, i)
                done, _ = ray.wait(list(in_flight), num_returns=1)
                ref = done[0]
                a, i = in_flight.pop(ref)
                try:
                    value = ray.get(ref)
                except lost as exc:
                    with contextlib.suppress(Exception):
                        ray.kill(actors[a], no_restart=True)
                    actors[a] = actor_class.remote()
                    idle.append(a)
                    if tries[i] < self.max_tries:
                        self.retries += 1
                        queue.appendleft(i)
                        continue
                    reason = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
                    message = (
                        f"{type(exc).__name__}: the worker died in each of {tries[i]} tries"
                        + (f" (last: {reason})" if reason else "")
                    )
                    yield i, None, _Failure(message, exc, tries[i], lost=True)
                    continue
                except ray.exceptions.RayTaskError as exc:  # the run function itself raised
                    idle.append(a)
                    cause = exc.cause if exc.cause is not None else exc
                    yield (
                        i,
                        None,
                        _Failure(f"{type(cause).__name__}: {cause}", cause, tries[i], lost=False),
                    )
                    continue
                idle.append(a)
                if tries[i] > 1 and isinstance(value, dict):
                    value["tries"] = tries[i]
                yield i, value, None
        finally:
            for actor in actors:
                with contextlib.suppress(Exception):
                    ray.kill(actor, no_restart=True)
            if started:
                self._shutdown()

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """Results (rows) as their runs complete; a run whose worker died ``max_tries``
        times, or whose function raised, gets the row ``on_lost(item, error, tries=n)``
        instead (so ``fn`` should be a run function returning rows; use :meth:`map` for
        other functions)."""
        for i, row, failure in self._outcomes(fn, items):
            if failure is not None:
                yield cast(R, self.on_lost(items[i], failure.message, tries=failure.tries))
            else:
                yield row

    def map(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[R]:
        """Results in the items' order (any function, e.g. root-parallel trees); an
        item's exception is raised (a lost worker: a RuntimeError)."""
        buffer: dict[int, R] = {}
        following = 0
        outcomes = self._outcomes(fn, items)
        try:
            for i, value, failure in outcomes:
                if failure is not None:
                    if not failure.lost:
                        raise failure.error
                    raise RuntimeError(failure.message) from failure.error
                buffer[i] = value
                while following in buffer:
                    yield buffer.pop(following)
                    following += 1
        finally:
            outcomes.close()

    def close(self, *, kill: bool = False) -> None:
        """Nothing to shut down: the actors live for one ``map`` call (and Ray with them,
        if that call started it)."""

    def __enter__(self) -> RayBackend:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
