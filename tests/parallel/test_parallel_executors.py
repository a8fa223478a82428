"""Tests of voot.parallel.executors: one executor interface, serial and process pools."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import pytest
from process_fixtures import child_pids, reaped, survivors

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


# ----- workers exit when their driver dies ---------------------------------------------
@pytest.mark.skipif(not Path("/proc").is_dir() and sys.platform != "darwin", reason="POSIX")
def test_workers_exit_when_the_driver_is_killed(tmp_path: Path) -> None:
    """kill -KILL of a ``voot-bench plan --workers 2`` leaves no worker (nor tracker) behind."""
    argv = [
        *(sys.executable, "-c", "from voot.bench.cli.main import main; raise SystemExit(main())"),
        *("plan", "--out", str(tmp_path / "store"), "--problems", "shekel_chain"),
        *("--dims", "10", "--planners", "uniform_t", "--grid", "default", "--seeds", "50"),
        *("--simulations", "200000", "--workers", "2", "--no-progress"),
    ]
    driver = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    children: set[int] = set()
    with reaped(driver, children):
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline:  # the two workers (and the tracker) are up
            children |= child_pids(driver.pid)
            if len(children) >= 3 or driver.poll() is not None:
                break
            time.sleep(0.2)
        assert driver.poll() is None, "the sweep ended before it could be killed"
        assert len(children) >= 2, f"expected the two workers, found {children}"
        time.sleep(1.0)  # the workers are running their first items
        os.kill(driver.pid, signal.SIGKILL)
        driver.wait(timeout=10)
        left = survivors(children)
        assert not left, f"processes {left} outlived their killed driver"


def test_watch_parent_exits_an_orphan_and_only_an_orphan() -> None:
    """A child watching a pid that is not its parent exits at once; its real parent lives."""
    code = (
        "import os, time\n"
        "from voot.parallel.executors import watch_parent\n"
        "watch_parent(int(os.environ['WATCHED']), interval=0.05)\n"
        "time.sleep(float(os.environ['SLEEP']))\n"
        "raise SystemExit(0)\n"
    )
    start = time.monotonic()
    env = {**os.environ, "WATCHED": "1" if os.getpid() != 1 else "2", "SLEEP": "5"}
    orphan = subprocess.run([sys.executable, "-c", code], env=env, timeout=30)
    assert orphan.returncode == 1 and time.monotonic() - start < 4.0
    env.update(WATCHED=str(os.getpid()), SLEEP="0.3")
    child = subprocess.run([sys.executable, "-c", code], env=env, timeout=30)
    assert child.returncode == 0
