"""Helpers shared by the tests of the result store and the sweeps (not a test module): a
small result row, a backend interrupted like Ctrl-C, and a real sweep killed and resumed."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from voot.bench.store.format import Row, make_row
from voot.bench.store.result_store import ResultStore


def row(i: int, status: str = "ok", n: int = 5, kind: str = "bbfo") -> dict:
    best: list[float] = (
        np.maximum.accumulate(np.arange(n, dtype=float) + i).tolist() if status == "ok" else []
    )
    return make_row(
        kind,
        {"function": "f", "dim": 3, "seed": i},
        status=status,
        wall_time=0.5,
        best_so_far=best,
        error=None if status == "ok" else "ValueError: boom",
    )


class Interrupting:
    """A serial backend that dies (like Ctrl-C) after ``after`` rows."""

    name = "interrupting"

    def __init__(self, after: int) -> None:
        self.after = after

    def map_unordered(self, fn: Callable[[Any], Row], items: Sequence[Any]) -> Iterator[Row]:
        for i, item in enumerate(items):
            if i == self.after:
                raise KeyboardInterrupt
            yield fn(item)


def killed_and_resumed(argv: Sequence[str], out: Path, rows: int) -> tuple[ResultStore, set[str]]:
    """Run ``voot-bench ARGV`` (a sweep into the store ``out``) in a fresh interpreter,
    SIGKILL it once ``rows`` rows are on disk, then run it again to its end.

    Checks that the killed sweep left at least ``rows`` rows, that the second run succeeds
    and says they were already in the store, and that it left them byte for byte; returns
    the store and the names of the row files written before the kill.
    """
    args = [sys.executable, "-m", "voot.bench.cli.main", *argv]
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    runs = out / "runs"
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and proc.poll() is None:
        if runs.is_dir() and sum(1 for _ in runs.glob("[!.]*.json")) >= rows:
            break
        time.sleep(0.02)
    if proc.poll() is None:
        os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    store = ResultStore(out)
    before = {p.name: p.read_bytes() for p in store.row_files()}
    assert len(before) >= rows
    done = subprocess.run(args, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert f"{len(before)} already in the store" in done.stdout
    for name, data in before.items():
        assert (store.runs_path / name).read_bytes() == data
    return store, set(before)
