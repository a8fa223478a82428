"""Helpers for tests that run code in other processes (not a test module itself): a run
compared with the same run in a fresh interpreter, and the child processes of a driver
that must not outlive it (psutil if installed, else /proc)."""

from __future__ import annotations

import contextlib
import os
import pickle
import signal
import subprocess
import sys
import time
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any


def run_pickled(
    script: str, payload: Any, timeout: float = 120, env: Mapping[str, str] | None = None
) -> Any:
    """Run ``script`` in a fresh Python with ``payload`` pickled on its stdin; what it
    pickles on its stdout, unpickled. ``env``: variables set for the child."""
    proc = subprocess.run(
        [sys.executable, "-c", script],
        input=pickle.dumps(payload),
        capture_output=True,
        check=True,
        timeout=timeout,
        env=None if env is None else {**os.environ, **env},
    )
    return pickle.loads(proc.stdout)


def child_pids(pid: int, recursive: bool = False) -> set[int]:
    """The pids of ``pid``'s child processes (``recursive``: and theirs, with psutil)."""
    try:
        import psutil
    except ImportError:
        out = set()
        for entry in Path("/proc").iterdir():
            if entry.name.isdigit():
                try:
                    stat = (entry / "stat").read_text()
                except OSError:
                    continue
                if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                    out.add(int(entry.name))
        return out
    try:
        return {c.pid for c in psutil.Process(pid).children(recursive=recursive)}
    except psutil.NoSuchProcess:
        return set()


def is_alive(pid: int) -> bool:
    """Whether process ``pid`` exists and is not a zombie."""
    try:
        import psutil
    except ImportError:
        stat = Path(f"/proc/{pid}/stat")
        try:
            return stat.read_text().rsplit(")", 1)[1].split()[0] != "Z"
        except OSError:
            return False
    try:
        return psutil.Process(pid).status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def survivors(pids: set[int], seconds: float = 8.0) -> list[int]:
    """The processes of ``pids`` still alive after waiting up to ``seconds`` for them."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and any(is_alive(p) for p in pids):
        time.sleep(0.1)
    return [p for p in pids if is_alive(p)]


@contextlib.contextmanager
def reaped(driver: subprocess.Popen, pids: set[int]) -> Iterator[None]:
    """On leaving, kill ``driver`` if it still runs and every process of ``pids`` (the
    driver's own children, filled in by the caller, by pid) that is still alive."""
    try:
        yield
    finally:
        if driver.poll() is None:
            driver.kill()
            driver.wait()
        for pid in pids:
            if is_alive(pid):
                with contextlib.suppress(ProcessLookupError):
                    os.kill(pid, signal.SIGKILL)
