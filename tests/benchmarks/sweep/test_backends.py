"""Tests of voot.bench.sweep.backends: sweep backends are voot.parallel executors, and no worker
process outlives its driver (killed, terminated or raising)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from process_fixtures import child_pids, reaped, survivors

from voot.bench.sweep import backends
from voot.parallel import Executor, ProcessExecutor, SerialExecutor


def double(x: int) -> int:
    return 2 * x


def test_backends_are_executors() -> None:
    assert backends.SerialBackend is SerialExecutor
    process = backends.make_backend("process", 2)
    assert isinstance(process, backends.ProcessBackend) and isinstance(process, ProcessExecutor)
    assert isinstance(process, Executor) and process.name == "process"
    assert not process.keep_alive and process.workers == 2 and process.max_pending == 8
    assert sorted(process.map_unordered(double, [1, 2, 3])) == [2, 4, 6]
    assert process._pool is None  # a pool per call, shut down when it ends
    assert isinstance(backends.make_backend("serial"), Executor)
    assert backends.BACKENDS == ("process", "serial", "ray")


def test_bad_workers_are_named_as_the_sweep_names_them() -> None:
    with pytest.raises(ValueError, match=r"^workers must be an integer >= 1, got 0"):
        backends.ProcessBackend(workers=0)


def test_ray_options_need_the_ray_backend() -> None:
    with pytest.raises(ValueError, match="apply to the ray backend only"):
        backends.make_backend("serial", max_tries=2)


# ----- no worker outlives its driver ---------------------------------------------------
# A ``voot-bench plan`` on 2 worker processes whose driver raises an exception it does
# not handle 3 s in, while both workers are in the middle of long runs.
_RAISING_PLAN = r"""
import json, os, signal, sys
from voot.bench.cli.main import main

def broken(signum, frame):
    raise RuntimeError("the driver broke")

signal.signal(signal.SIGALRM, broken)
signal.alarm(3)
sys.exit(main(json.loads(os.environ["VOOT_ARGV"])))
"""


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
@pytest.mark.parametrize("end", ["SIGKILL", "SIGTERM", "raises"])
def test_no_worker_outlives_its_driver(tmp_path: Path, end: str) -> None:
    """The driver of a process-backend sweep is killed (SIGKILL), terminated (SIGTERM, as
    by a job scheduler) or raises: within a few seconds none of its worker processes (nor
    the multiprocessing resource tracker) is left."""
    pytest.importorskip("psutil")
    argv = [
        *("plan", "--out", str(tmp_path / "store"), "--problems", "shekel_chain"),
        *("--dims", "3", "--planners", "doot", "--grid", "default", "--seeds", "40"),
        *("--simulations", "1000000", "--workers", "2"),
        "--no-progress",
    ]
    code = (
        _RAISING_PLAN
        if end == "raises"
        else "from voot.bench.cli.main import main; raise SystemExit(main())"
    )
    command = [sys.executable, "-c", code, *([] if end == "raises" else argv)]
    env = {**os.environ, "VOOT_ARGV": json.dumps(argv)}
    log = tmp_path / "stderr.txt"  # not a pipe: a surviving worker would hold it open
    with log.open("wb") as fh:
        driver = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=fh)
    seen: set[int] = set()
    with reaped(driver, seen):
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and driver.poll() is None:
            seen |= child_pids(driver.pid, recursive=True)  # the workers (and tracker)
            if end != "raises" and len(seen) >= 3:
                break
            time.sleep(0.05)
        assert len(seen) >= 2, f"expected the two workers, found {seen}"
        if end != "raises":
            assert driver.poll() is None, "the sweep ended before it could be stopped"
            time.sleep(1.0)  # the workers are running their first runs
            driver.send_signal(getattr(signal, end))
        driver.wait(timeout=30)  # stopped, it does not wait for the runs (~10 min each)
        err = log.read_text()
        if end == "raises":
            assert driver.returncode == 1 and "RuntimeError: the driver broke" in err
        elif end == "SIGTERM":
            assert driver.returncode == 130, err  # handled as an interrupt
        left = survivors(seen)
        assert not left, f"processes {left} outlived their driver ({end})"
