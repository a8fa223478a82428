"""Tests of voot.bench.store.lock: one writer per store (a second one refused with the
holder named, in-process and between two real ``voot-bench plan`` processes), a lock left
by a killed writer taken over, and every store writer (sweep, compact) going through it."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from store_fixtures import row

from voot.bench.store.format import StoreError
from voot.bench.store.lock import (
    LOCK_NAME,
    StoreBusyError,
    WriterLock,
    describe_holder,
)
from voot.bench.store.result_store import ResultStore, compact_store
from voot.bench.sweep.bbfo import build_specs
from voot.bench.sweep.engine import run_sweep


def test_a_second_lock_is_refused_with_the_holder_named(tmp_path: Path) -> None:
    store = ResultStore(tmp_path / "r")
    with store.writing():
        holder = json.loads((store.path / LOCK_NAME).read_text())
        assert holder["pid"] == os.getpid() and holder["host"] == socket.gethostname()
        assert holder["started"] and holder["command"]
        # another object on the same store, in this very process, is a second writer
        with pytest.raises(StoreBusyError, match=f"pid {os.getpid()} on host") as info:
            WriterLock(store.path).acquire()
        assert info.value.holder == holder
        assert isinstance(info.value, StoreError)  # the CLI reports it as a store error
        with pytest.raises(StoreBusyError):
            ResultStore(store.path).writing().__enter__()
    # released: the file is gone and the next writer gets the lock
    assert not (store.path / LOCK_NAME).exists()
    with WriterLock(store.path) as lock:
        assert lock.held and lock.stale is None
    assert not lock.held


def test_nested_writing_on_one_store_reuses_its_lock(tmp_path: Path) -> None:
    store = ResultStore(tmp_path / "r")
    with store.writing() as outer, store.writing() as inner:
        assert inner is outer
    assert not outer.held and not (store.path / LOCK_NAME).exists()


def test_a_lock_file_of_a_dead_writer_is_stale_and_taken_over(tmp_path: Path) -> None:
    store = ResultStore(tmp_path / "r")
    dead = {"pid": 999_999_999, "host": "gone", "started": "then", "command": "voot-bench plan"}
    (store.path / LOCK_NAME).write_text(json.dumps(dead))  # left by a writer that crashed
    with store.writing() as lock:
        assert lock.stale == dead
        assert json.loads((store.path / LOCK_NAME).read_text())["pid"] == os.getpid()


def test_sweeps_and_compact_refuse_a_store_that_is_being_written(tmp_path: Path) -> None:
    specs = build_specs(["shekel"], [3], ["voo"], range(2), budget=5, grid="default")
    store = ResultStore(tmp_path / "r")
    store.write(row(1))
    with WriterLock(store.path):
        with pytest.raises(StoreBusyError):
            run_sweep(specs, ResultStore(store.path), progress=False)
        assert len(store) == 1  # refused before anything ran or was written
    target = tmp_path / "compact"
    compact_store(store.path, target)
    with WriterLock(target), pytest.raises(StoreBusyError):
        compact_store(store.path, target)
    summary = run_sweep(specs, store, progress=False)  # lock free again: the sweep runs
    assert summary.ran == 2


def test_describe_holder_of_an_unrecorded_holder() -> None:
    assert "not recorded" in describe_holder({})


def _plan(out: Path, seeds: int, simulations: int) -> list[str]:
    return [
        *(sys.executable, "-m", "voot.bench.cli.main", "plan", "--out", str(out)),
        *("--problems", "shekel_chain", "--dims", "3", "--planners", "doot"),
        *("--seeds", str(seeds), "--simulations", str(simulations), "--grid", "default"),
        *("--workers", "1", "--no-progress"),
    ]


@pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="POSIX")
def test_two_plan_processes_on_one_out(tmp_path: Path) -> None:
    """A second ``voot-bench plan`` on a store being written exits with the first named;
    after the first is killed, the lock it left is taken over and the sweep completes
    with every run once."""
    out = tmp_path / "r"
    first = subprocess.Popen(
        _plan(out, 40, 400), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    try:
        lock = out / LOCK_NAME
        deadline = time.monotonic() + 60
        holder: dict = {}
        while time.monotonic() < deadline and first.poll() is None:
            try:
                holder = json.loads(lock.read_text())
                break
            except (OSError, ValueError):
                time.sleep(0.02)
        assert holder.get("pid") == first.pid, "the first sweep never took the lock"
        second = subprocess.run(_plan(out, 40, 400), capture_output=True, text=True, timeout=60)
        assert second.returncode == 2
        assert "another voot-bench process is writing this store" in second.stderr
        assert f"pid {first.pid} on host {socket.gethostname()}" in second.stderr
        assert "plan --out" in second.stderr  # the holder's command line
        assert first.poll() is None  # the refusal did not disturb the first sweep
        os.kill(first.pid, signal.SIGKILL)
        first.wait(timeout=30)
    finally:
        if first.poll() is None:
            first.kill()
            first.wait()
    assert lock.exists()  # a killed writer leaves its file, but not its lock
    before = len(ResultStore(out))
    third = subprocess.run(_plan(out, 4, 50), capture_output=True, text=True, timeout=120)
    assert third.returncode == 0, third.stderr
    assert f"pid {first.pid}" in third.stderr and "took over the writer lock" in third.stderr
    assert not lock.exists()
    rows = ResultStore(out).load(status=None)
    assert len({r["run_id"] for r in rows}) == len(rows) >= 4
    assert len(rows) >= before


def test_a_lock_that_is_a_folder_is_a_store_error_naming_it(tmp_path: Path) -> None:
    store = ResultStore(tmp_path / "r")
    (store.path / LOCK_NAME).mkdir()
    with pytest.raises(StoreError, match=f"{LOCK_NAME}: the store's writer lock cannot be opened"):
        WriterLock(store.path).acquire()
    assert (store.path / LOCK_NAME).is_dir()  # left for the user to look at


def test_the_cli_reports_a_lock_folder_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from cli_fixtures import PLAN_TINY, assert_refused

    store = ResultStore(tmp_path / "r")
    (store.path / LOCK_NAME).mkdir()
    argv = ["plan", "--out", str(store.path), *PLAN_TINY]
    assert_refused(argv, tmp_path, capsys, "writer lock cannot be opened (a folder)")
