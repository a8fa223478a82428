"""Tests of voot.parallel.executors: one executor interface, serial and process pools."""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import pytest

from voot.parallel import Executor, ProcessExecutor, SerialExecutor, in_order, terminate_workers


def nap(seconds: float) -> int:
    """Sleep, then say which process ran (module level: spawned workers import it)."""
    time.sleep(seconds)
    return os.getpid()


def square(x: int) -> int:
    return x * x


def fail_on_three(x: int) -> int:
    if x == 3:
        raise ValueError("three")
    return x


def alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


def test_serial_executor_maps_in_order_in_this_process() -> None:
    ex = SerialExecutor()
    assert isinstance(ex, Executor)
    assert list(ex.map(square, [1, 2, 3])) == [1, 4, 9]
    assert list(ex.map_unordered(square, [3, 2])) == [9, 4]
    assert ex.in_process and ex.name == "serial"
    with ex:
        assert list(ex.map(nap, [0.0])) == [os.getpid()]


class Reversed:
    """A map_unordered that completes the items last first, and records closing."""

    def __init__(self) -> None:
        self.closed = False

    def map_unordered(self, fn: Callable[[Any], Any], items: Sequence[Any]) -> Iterator[Any]:
        try:
            for item in reversed(list(items)):
                yield fn(item)
        finally:
            self.closed = True


def test_in_order_restores_the_items_order_and_closes_the_source() -> None:
    source = Reversed()
    assert list(in_order(source.map_unordered, square, [1, 2, 3, 4])) == [1, 4, 9, 16]
    assert source.closed
    early = Reversed()
    gen = in_order(early.map_unordered, square, [1, 2, 3])
    assert next(gen) == 1  # the last item completes first; the first is yielded first
    gen.close()
    assert early.closed


def test_process_executor_maps_in_order_and_unordered() -> None:
    with ProcessExecutor(max_workers=2) as ex:
        assert isinstance(ex, Executor) and not ex.in_process and ex.workers == 2
        assert list(ex.map(square, range(10))) == [x * x for x in range(10)]
        assert sorted(ex.map_unordered(square, range(10))) == sorted(x * x for x in range(10))
        pool = ex._pool
        assert pool is not None
        assert list(ex.map(square, [5])) == [25]
        assert ex._pool is pool  # kept between maps (keep_alive)
    assert ex._pool is None


def test_an_error_reaches_the_caller() -> None:
    with ProcessExecutor(max_workers=1) as ex, pytest.raises(ValueError, match="three"):
        list(ex.map(fail_on_three, [1, 2, 3, 4]))
    with pytest.raises(ValueError, match="three"):
        list(SerialExecutor().map(fail_on_three, [3]))


def test_close_with_kill_terminates_busy_workers() -> None:
    ex = ProcessExecutor(max_workers=1)
    (pid,) = ex.map(nap, [0.0])
    assert alive(pid)
    assert ex._pool is not None
    ex._pool.submit(nap, 60.0)  # the worker is busy for a minute
    time.sleep(0.2)
    t0 = time.perf_counter()
    ex.close(kill=True)
    assert time.perf_counter() - t0 < 20
    assert ex._pool is None and not alive(pid)
    ex.close()  # closing twice is fine


def test_a_per_call_pool_is_terminated_when_the_caller_stops_early() -> None:
    ex = ProcessExecutor(max_workers=2, keep_alive=False)
    gen = ex.map_unordered(nap, [0.0, 60.0])
    first = next(gen)  # the other worker sleeps for a minute
    assert ex._pool is not None
    pids = list((getattr(ex._pool, "_processes", None) or {}).keys())
    assert first in pids
    t0 = time.perf_counter()
    gen.close()
    assert time.perf_counter() - t0 < 20
    assert ex._pool is None
    assert not any(alive(p) for p in pids)


def test_a_per_call_pool_is_shut_down_after_every_map() -> None:
    ex = ProcessExecutor(max_workers=1, keep_alive=False)
    assert list(ex.map(square, [2, 3])) == [4, 9]
    assert ex._pool is None


def test_terminate_workers_of_a_pool_that_never_started() -> None:
    from concurrent.futures import ProcessPoolExecutor

    pool = ProcessPoolExecutor(max_workers=1)
    terminate_workers(pool)  # no processes yet: nothing to do
    pool.shutdown()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"max_workers": 0}, "max_workers must be"),
        ({"max_workers": True}, "max_workers must be"),
        ({"start_method": "teleport"}, "valid start methods are"),
        ({"max_pending": 0}, "max_pending"),
    ],
)
def test_bad_options(kwargs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        ProcessExecutor(**kwargs)
