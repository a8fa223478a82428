"""Tests of voot.bench.sweep.ray_reaper: the watchdog of a driver's local Ray instance.

No Ray here: a stand-in driver starts the reaper and one child process (as ``ray.init``
starts Ray's), then is killed or ends normally.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time

import pytest

psutil = pytest.importorskip("psutil")

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

DRIVER = """
import subprocess, sys, time
from voot.bench.sweep.ray_reaper import RayReaper
child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
reaper = RayReaper(interval=0.1, grace=1.0)
print(child.pid, reaper.process.pid, int(reaper.ready), flush=True)
if sys.argv[1] == "normal":
    time.sleep(0.5)
    reaper.done()
    print("done", flush=True)
else:
    time.sleep(60)
"""


def _start(mode: str) -> tuple[subprocess.Popen[str], int, int]:
    driver = subprocess.Popen(
        [sys.executable, "-c", DRIVER, mode], stdout=subprocess.PIPE, text=True
    )
    assert driver.stdout is not None
    child, reaper, ready = (int(v) for v in driver.stdout.readline().split())
    assert ready == 1, "the reaper did not report that it recorded the driver's children"
    return driver, child, reaper


def _gone(pid: int, timeout: float) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            if psutil.Process(pid).status() == psutil.STATUS_ZOMBIE:
                return True
        except psutil.NoSuchProcess:
            return True
        time.sleep(0.1)
    return False


def _cleanup(*pids: int) -> None:
    for pid in pids:
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)


def test_a_killed_driver_has_its_descendants_stopped() -> None:
    driver, child, reaper = _start("killed")
    try:
        time.sleep(0.5)  # the reaper has recorded the child
        os.kill(driver.pid, signal.SIGKILL)
        driver.wait(timeout=10)
        assert _gone(child, 8.0), "the killed driver's child outlived it"
        assert _gone(reaper, 8.0), "the reaper did not exit"
    finally:
        _cleanup(driver.pid, child, reaper)


def test_a_normal_end_touches_nothing() -> None:
    driver, child, reaper = _start("normal")
    try:
        assert driver.stdout is not None and driver.stdout.readline().strip() == "done"
        assert _gone(reaper, 5.0)
        driver.wait(timeout=10)
        time.sleep(0.3)
        assert not _gone(child, 0.0), "the reaper stopped a process after a normal end"
    finally:
        _cleanup(driver.pid, child, reaper)


def test_options_are_checked() -> None:
    from voot.bench.sweep.ray_reaper import RayReaper

    with pytest.raises(ValueError, match="interval"):
        RayReaper(interval=0.0)
    with pytest.raises(ValueError, match="grace"):
        RayReaper(grace=-1.0)
