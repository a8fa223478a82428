"""A watchdog that stops the local Ray instance of a driver that was killed.

``ray.init()`` in a driver starts a private instance: the GCS server, the raylet, a
log monitor, the dashboard and runtime-env agents and the actors' worker processes. Ray
ties the GCS, raylet and workers to the driver, but after a ``kill -KILL`` of the driver
the dashboard and runtime-env agents were seen staying alive (Ray 2.60), re-parented to
PID 1, until killed by hand. The process-pool backend's workers watch their parent
(:func:`voot.parallel.executors.watch_parent`); Ray's processes cannot be given that
thread, so :class:`RayReaper` watches from outside:

* the driver starts it right after its ``ray.init()`` started the instance, as a child
  process (``python -m voot.bench.sweep.ray_reaper <driver pid>``) reading a pipe from the
  driver, and waits until the reaper has recorded the instance's processes (about
  half a second, once per sweep);
* every ``interval`` seconds the reaper records the driver's descendants (pid and start
  time, so a reused pid is never taken for one of them);
* when the pipe ends without the driver saying ``done`` (the driver is gone: its end of
  the pipe was closed by the kernel), the reaper sends ``SIGTERM`` to every recorded
  process still alive, ``SIGKILL`` to those alive ``grace`` seconds later, and exits;
* on a normal end the driver shuts Ray down, writes ``done`` and the reaper exits
  without touching anything.

It ignores ``SIGINT`` (a Ctrl-C of the terminal reaches the whole process group; the
driver handles it and then ends the pipe). It only ever signals processes that were
the driver's descendants while the driver lived. Needs ``psutil`` (in the ``ray``
extra); without it the backend warns that nothing watches the instance.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import threading
from typing import IO, Any

from voot import validation as V

#: Seconds between two records of the driver's descendants.
POLL_SECONDS = 0.5
#: Seconds between ``SIGTERM`` and ``SIGKILL`` of the processes left behind.
GRACE_SECONDS = 3.0
#: What the driver writes to the reaper's pipe on a normal end.
DONE = b"done\n"
#: What the reaper writes back once it has recorded the driver's descendants.
READY = b"ready\n"


def _descendants(psutil: Any, pid: int, me: int) -> dict[int, float]:
    """``{pid: start time}`` of ``pid``'s descendants (not this process)."""
    try:
        children = psutil.Process(pid).children(recursive=True)
    except psutil.Error:
        return {}
    out: dict[int, float] = {}
    for child in children:
        with contextlib.suppress(psutil.Error):
            if child.pid != me:
                out[child.pid] = child.create_time()
    return out


def _still_ours(psutil: Any, pid: int, started: float) -> Any:
    """The process ``pid`` if it is the one recorded (same start time) and alive."""
    try:
        proc = psutil.Process(pid)
        if proc.create_time() != started or proc.status() == psutil.STATUS_ZOMBIE:
            return None
        return proc
    except psutil.Error:
        return None


def reap(
    driver: int,
    pipe: IO[bytes],
    interval: float = POLL_SECONDS,
    grace: float = GRACE_SECONDS,
    ready: IO[bytes] | None = None,
) -> int:
    """The reaper's loop (see the module docstring); returns the processes it signalled.

    ``ready`` gets :data:`READY` once the driver's descendants are first recorded.
    """
    import psutil

    me = os.getpid()
    seen: dict[int, float] = {}
    ended = threading.Event()
    done = [False]

    def read() -> None:
        data = b""
        with contextlib.suppress(OSError, ValueError):
            while chunk := pipe.read(1):
                data += chunk
                if data.endswith(DONE):
                    done[0] = True
                    break
        ended.set()

    threading.Thread(target=read, name="voot-ray-reaper-pipe", daemon=True).start()
    seen.update(_descendants(psutil, driver, me))
    if ready is not None:  # the driver waits for this before it goes on
        with contextlib.suppress(OSError, ValueError):
            ready.write(READY)
            ready.flush()
            ready.close()
    while not ended.wait(interval):
        seen.update(_descendants(psutil, driver, me))
    if done[0]:
        return 0
    seen.update(_descendants(psutil, driver, me))  # the driver may still be exiting
    left = [p for pid, t in seen.items() if (p := _still_ours(psutil, pid, t)) is not None]
    for proc in left:
        with contextlib.suppress(psutil.Error):
            proc.terminate()
    _, alive = psutil.wait_procs(left, timeout=grace)
    for proc in alive:
        with contextlib.suppress(psutil.Error):
            proc.kill()
    return len(left)


class RayReaper:
    """The driver's handle on its reaper process (see the module docstring).

    Args:
        interval: seconds between two records of the driver's descendants.
        grace: seconds between ``SIGTERM`` and ``SIGKILL`` of what is left behind.

    Attributes:
        process: the reaper process.
        ready: whether it reported that it recorded the driver's descendants.
    """

    def __init__(self, interval: float = POLL_SECONDS, grace: float = GRACE_SECONDS) -> None:
        self.interval = V.positive(interval, "interval")
        self.grace = V.positive(grace, "grace", allow_zero=True)
        self.process = subprocess.Popen(
            [
                *(sys.executable, "-m", "voot.bench.sweep.ray_reaper", str(os.getpid())),
                *(repr(self.interval), repr(self.grace)),
            ],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        # wait until it has recorded the instance's processes: a driver killed earlier
        # would leave them unrecorded
        assert self.process.stdout is not None
        with self.process.stdout as answer:
            self.ready = answer.readline() == READY

    def done(self) -> None:
        """The instance was shut down normally: let the reaper exit without reaping."""
        stdin = self.process.stdin
        if stdin is not None:
            with contextlib.suppress(OSError, ValueError):
                stdin.write(DONE)
                stdin.flush()
            with contextlib.suppress(OSError, ValueError):
                stdin.close()
        try:
            self.process.wait(timeout=5.0 + 2 * self.interval)
        except subprocess.TimeoutExpired:  # pragma: no cover - it reads the pipe at once
            self.process.kill()
            self.process.wait()


def main(argv: list[str]) -> int:
    """``python -m voot.bench.sweep.ray_reaper DRIVER_PID [INTERVAL GRACE]``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    driver = int(argv[0])
    interval = float(argv[1]) if len(argv) > 1 else POLL_SECONDS
    grace = float(argv[2]) if len(argv) > 2 else GRACE_SECONDS
    reap(driver, sys.stdin.buffer, interval, grace, ready=sys.stdout.buffer)
    return 0


if __name__ == "__main__":  # pragma: no cover - run as the reaper process
    raise SystemExit(main(sys.argv[1:]))
