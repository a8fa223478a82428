"""Screenshots of rerun's own viewer showing a recording, taken without a display.

:func:`viewer_screenshots` starts the native viewer that ships with ``rerun-sdk``
headless (``rerun --headless``: no window, rendered off-screen by ``wgpu``), opens a
``.rrd`` file in it, moves the time cursor, and saves the whole viewer and/or single
views as PNG files through rerun's viewer-control API
(:class:`rerun.experimental.ViewerClient`, experimental in rerun 0.41). The viewer
process is ended afterwards.

The viewer needs a graphics adapter: a GPU, or a software one such as Mesa's lavapipe
(Vulkan on the CPU; Debian/Ubuntu: ``apt-get install mesa-vulkan-drivers``). Without
one the viewer does not start and a RuntimeError says so; draw the images from the
recorded data instead (:mod:`voot.record.figure5`).
"""

from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

#: Graphics backends of the native viewer (``rerun --renderer``).
RENDERERS = ("vulkan", "gl")


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def rerun_executable() -> str:
    """The ``rerun`` binary next to this Python (a venv's), else the one on ``PATH``."""
    here = Path(sys.executable).parent / "rerun"
    if here.exists():
        return str(here)
    found = shutil.which("rerun")
    if found is None:
        raise RuntimeError("found no 'rerun' executable; pip install rerun-sdk")
    return found


def viewer_screenshots(
    recording: str | os.PathLike[str],
    outputs: Mapping[str | None, str | os.PathLike[str]],
    *,
    timeline: str | None = None,
    sequence: int | None = None,
    window_size: tuple[int, int] = (1400, 850),
    renderer: str = "vulkan",
    timeout: float = 60.0,
    settle: float = 1.0,
) -> dict[str | None, Path]:
    """Open ``recording`` in a headless rerun viewer and save screenshots of it.

    Args:
        recording: the ``.rrd`` file (with the blueprint it carries).
        outputs: view name -> PNG path; the name None means the whole viewer window.
            View names are those of the recording's blueprint (e.g. ``"Scene and
            sampled actions"``).
        timeline: the timeline to show (default: the blueprint's).
        sequence: the time cursor on it (default: where the viewer puts it).
        window_size: the viewer's size in logical points (screenshots are at the
            viewer's pixel scale, 2x on a headless viewer).
        renderer: the graphics backend, ``vulkan`` or ``gl``.
        timeout: seconds to wait for the viewer to start and to load the file.
        settle: seconds to wait after moving the time cursor, before the screenshots.

    Returns:
        The written files by view name.

    Raises:
        ValueError: bad arguments, a missing file, or a view name the recording's
            layout does not have (the valid names are listed).
        RuntimeError: the viewer did not start (no graphics adapter?) or load the file.
    """
    path = Path(recording).resolve()
    if not path.is_file():
        raise ValueError(f"no recording at {str(path)!r}")
    if not outputs:
        raise ValueError("outputs must name at least one screenshot (view name or None -> file)")
    if renderer not in RENDERERS:
        raise ValueError(f"renderer must be one of {', '.join(RENDERERS)}; got {renderer!r}")
    w, h = (int(v) for v in window_size)
    if not (320 <= w <= 4096 and 240 <= h <= 4096):
        raise ValueError(f"window_size must be within 320..4096 x 240..4096, got {window_size}")
    if sequence is not None and timeline is None:
        raise ValueError("sequence needs the timeline it is on")
    from rerun.experimental import ViewerClient

    port = _free_port()
    fd, log_name = tempfile.mkstemp(prefix="rerun-viewer-", suffix=".log")
    log_path = Path(log_name)
    with os.fdopen(fd, "w") as log:
        proc = subprocess.Popen(
            [
                rerun_executable(),
                "--headless",
                "--port",
                str(port),
                "--window-size",
                f"{w}x{h}",
                "--hide-welcome-screen",
                "--renderer",
                renderer,
            ],
            stdout=log,
            stderr=subprocess.STDOUT,
            # its own process group: ``rerun`` may be a Python launcher whose child is
            # the viewer, and both must end with it
            start_new_session=True,
        )
    try:
        client = _connect(ViewerClient, port, proc, timeout, log_path)
        client.open(str(path))
        views = _wait_loaded(client, timeout)
        if timeline is not None:
            if sequence is None:
                client.set_time(timeline, play_state="paused")
            else:
                client.set_time(timeline, sequence=int(sequence), play_state="paused")
        time.sleep(settle)
        written: dict[str | None, Path] = {}
        for name, out in outputs.items():
            target = Path(out).resolve()
            target.parent.mkdir(parents=True, exist_ok=True)
            view_id = None
            if name is not None:
                if name not in views:
                    raise ValueError(f"the recording has no view {name!r}; views: {sorted(views)}")
                view_id = views[name]
            client.save_screenshot(str(target), view_id=view_id)
            written[name] = target
        return written
    finally:
        _end(proc)
        log_path.unlink(missing_ok=True)


def _end(proc: subprocess.Popen[bytes]) -> None:
    """End the viewer's process group (the launcher and the viewer it started)."""
    try:
        os.killpg(proc.pid, signal.SIGTERM)
    except ProcessLookupError:
        pass
    try:
        proc.wait(10)
    except subprocess.TimeoutExpired:  # pragma: no cover - a hung viewer
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(10)


def _connect(
    client_class: Any, port: int, proc: subprocess.Popen[bytes], timeout: float, log_path: Path
) -> Any:
    """Wait until the viewer answers on ``port``; a RuntimeError if it died or timed out."""
    deadline = time.monotonic() + timeout
    url = f"rerun+http://127.0.0.1:{port}/proxy"
    while True:
        if proc.poll() is not None:
            tail = log_path.read_text(errors="replace").strip().splitlines()[-3:]
            raise RuntimeError(
                "the rerun viewer exited before answering (no graphics adapter? install a"
                " GPU driver or Mesa's lavapipe, mesa-vulkan-drivers): " + " | ".join(tail)
            )
        try:
            client = client_class.connect(url)
            client.get_state()
            return client
        except Exception as exc:  # not up yet
            if time.monotonic() > deadline:
                raise RuntimeError(f"the rerun viewer did not answer within {timeout} s") from exc
            time.sleep(0.5)


def _wait_loaded(client: Any, timeout: float) -> dict[str, str]:
    """Wait until the viewer has loaded everything; its views by name -> id."""
    deadline = time.monotonic() + timeout
    while True:
        state = client.get_state()
        if not state.loading and state.recordings and state.views:
            return {v.name: v.view_id for v in state.views}
        if time.monotonic() > deadline:
            raise RuntimeError(f"the rerun viewer did not load the recording within {timeout} s")
        time.sleep(0.5)
