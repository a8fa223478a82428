"""Crash tests of the result store: a real ``voot-bench plan`` SIGKILLed at deterministic
points (after k rows, in the middle of writing a row, in the middle of a search, in the
middle of writing the index), resumed each time with the same command, ends with the
store an uninterrupted run writes, row for row; and a hypothesis property test: any
interleaving of writes from one or two writers, crashes (a row or index file cut at any
byte) and resumes leaves a consistent store.

Rows are compared without :data:`TIMING_KEYS`, the only fields that differ between two
runs of one spec: they measure the run (wall and CPU clocks, the finish time), and the
checksum covers them.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from store_fixtures import row

from voot.bench.store.format import StoreError, row_bytes
from voot.bench.store.index import INDEX_NAME
from voot.bench.store.lock import LOCK_NAME, StoreBusyError, WriterLock
from voot.bench.store.result_store import ResultStore

#: Row fields that differ between two runs of the same spec (so not compared): the wall
#: time of the run and of its search, the per-simulation wall and CPU clocks, the finish
#: time, and the checksum (it covers those bytes).
TIMING_KEYS = frozenset(
    {"wall_time", "search_time", "elapsed", "cpu_elapsed", "finished_at", "checksum"}
)

# A ``voot-bench plan`` that SIGKILLs itself at the point named by VOOT_CRASH (JSON):
#   ["rows", k]        right after its k-th row file is in place (k >= 1),
#   ["mid-write", k]   while writing its k-th row: half the bytes in the temporary file,
#   ["mid-search", k, j] in its k-th run, after simulation j,
#   ["index", k]       while writing the index for the k-th time: half of it written.
# It patches this process only (the sweep runs serially, --workers 1).
_CRASHING_PLAN = r"""
import json, os, signal, sys
import voot.bench.store.result_store as store_mod
import voot.bench.store.index as index_mod
from voot.bench.cli.main import main
from voot.tree.mcts import MCTS

point = json.loads(os.environ["VOOT_CRASH"])
kind, k = point[0], int(point[1])
counts = {"row": 0, "index": 0, "run": 0}
original_write = index_mod.write_atomic

def die():
    os.kill(os.getpid(), signal.SIGKILL)

def half_written(path, data):
    with open(path.parent / f".{path.name}.crash{os.getpid()}.tmp", "wb") as fh:
        fh.write(data[: len(data) // 2])
        fh.flush()
        os.fsync(fh.fileno())
    die()

def row_write(path, data):
    if path.parent.name != "runs":  # the header
        return original_write(path, data)
    counts["row"] += 1
    if kind == "mid-write" and counts["row"] == k:
        half_written(path, data)
    original_write(path, data)
    if kind == "rows" and counts["row"] == k:
        die()

def index_write(path, data):
    counts["index"] += 1
    if kind == "index" and counts["index"] == k:
        half_written(path, data)
    original_write(path, data)

store_mod.write_atomic = row_write
index_mod.write_atomic = index_write
iterate = MCTS.iterate

def crashing_iterate(self, n, *args, **kw):
    counts["run"] += 1
    for i in iterate(self, n, *args, **kw):
        if kind == "mid-search" and counts["run"] == k and i == int(point[2]):
            die()
        yield i

MCTS.iterate = crashing_iterate
sys.exit(main(json.loads(os.environ["VOOT_ARGV"])))
"""


def _plan_args(out: Path, problem: Sequence[str], simulations: int, seeds: int) -> list[str]:
    return [
        *("plan", "--out", str(out), "--problems", *problem),
        *("--simulations", str(simulations), "--seeds", str(seeds)),
        *("--workers", "1", "--no-progress"),
    ]


def _crash(args: list[str], point: list[Any]) -> int:
    env = {**os.environ, "VOOT_CRASH": json.dumps(point), "VOOT_ARGV": json.dumps(args)}
    done = subprocess.run(
        [sys.executable, "-c", _CRASHING_PLAN], env=env, capture_output=True, timeout=300
    )
    return done.returncode


def _plan(args: list[str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "voot.bench.cli.main", *args],
        capture_output=True,
        text=True,
        timeout=300,
    )


def _comparable(store: ResultStore) -> dict[str, dict[str, Any]]:
    """Every row of ``store`` by run id, without :data:`TIMING_KEYS`."""
    out = {}
    for path in store.row_files():
        data = json.loads(path.read_bytes())
        out[data["run_id"]] = {k: v for k, v in data.items() if k not in TIMING_KEYS}
    return out


def _crash_and_resume(
    tmp_path: Path, problem: Sequence[str], simulations: int, seeds: int, points: list[list[Any]]
) -> None:
    reference_out, out = tmp_path / "reference", tmp_path / "crashed"
    reference = _plan(_plan_args(reference_out, problem, simulations, seeds))
    assert reference.returncode == 0, reference.stderr
    expected = _comparable(ResultStore(reference_out, create=False))
    args = _plan_args(out, problem, simulations, seeds)
    kept: dict[str, bytes] = {}
    for point in points:
        code = _crash(args, point)
        assert code == -signal.SIGKILL, f"{point}: the sweep was not killed (exit {code})"
        store = ResultStore(out, create=False)
        now = {p.name: p.read_bytes() for p in store.row_files()}
        for name, data in kept.items():  # a crash never changes a finished row
            assert now[name] == data, f"{point}: {name} changed"
        kept = now
        assert set(_comparable(store)) < set(expected)
    assert (out / LOCK_NAME).exists()  # the last crash left its lock file, not its lock
    final = _plan(args)
    assert final.returncode == 0, final.stderr
    assert f"{len(kept)} already in the store" in final.stdout
    store = ResultStore(out, create=False)
    assert store.verify() == len(expected)
    for name, data in kept.items():
        assert (store.runs_path / name).read_bytes() == data
    got = _comparable(store)
    assert got.keys() == expected.keys()
    for run_id, row_ in expected.items():
        assert got[run_id] == row_, run_id
    assert {r["run_id"] for r in store.load()} == set(expected)
    strays = sorted(p.name for p in store.runs_path.iterdir() if p.name.endswith(".tmp"))
    assert strays  # the half-written temporary files are still there, and ignored
    assert not (out / LOCK_NAME).exists()


#: Crash points of one sweep, in order (each counted within its own process).
POINTS: list[list[Any]] = [
    ["rows", 5],  # after 5 rows
    ["mid-write", 3],  # 3 more rows, then killed half-way through writing the 4th
    ["mid-search", 4, 7],  # in the 4th run, after its 8th simulation
    ["index", 1],  # at the start, while rewriting the index
    ["rows", 9],
]


def test_killed_v1_sweep_resumes_to_the_uninterrupted_store(tmp_path: Path) -> None:
    """kitchen v1, voot and pw_uct (their paper grids: 36 runs of 20 simulations)."""
    _crash_and_resume(tmp_path, ["kitchen_v1", "--planners", "voot", "pw_uct"], 20, 3, POINTS)


def test_killed_chain_sweep_resumes_to_the_uninterrupted_store(tmp_path: Path) -> None:
    """The same on a Shekel chain (a fast version without MuJoCo)."""
    problem = ["shekel_chain", "--dims", "3", "--planners", "voot", "doot"]
    _crash_and_resume(tmp_path, problem, 30, 4, POINTS)


# ----- the property test ---------------------------------------------------------------
#: One step of a history: write row i by writer w, crash while writing row i by writer w
#: with the file cut after a fraction of its bytes, cut the index, or resume (reopen).
_step = st.one_of(
    st.tuples(st.just("write"), st.integers(0, 4), st.integers(0, 1), st.booleans()),
    st.tuples(st.just("crash"), st.integers(0, 4), st.integers(0, 1), st.floats(0, 1)),
    st.tuples(st.just("cut-index"), st.floats(0, 1)),
    st.tuples(st.just("cut-row"), st.integers(0, 4), st.floats(0, 0.999)),
    st.tuples(st.just("resume"), st.integers(0, 1)),
)


def _cut(path: Path, fraction: float) -> None:
    data = path.read_bytes()
    path.write_bytes(data[: int(len(data) * fraction)])


@settings(max_examples=100, deadline=None)
@given(history=st.lists(_step, max_size=25))
def test_any_interleaving_of_writes_crashes_and_resumes_is_consistent(
    tmp_path_factory: pytest.TempPathFactory, history: list[tuple[Any, ...]]
) -> None:
    """The model: ``ok[i]`` is the finished row i (the first one written: a finished row
    is never replaced), ``failed`` the ids whose last row failed. After every step the
    store loads exactly the finished rows, once each, with their bytes, or refuses with
    a StoreError naming the one corrupt file (a row cut by a crash the atomic write
    cannot have made, e.g. a disk that lied about fsync); moving that file away resumes."""
    root = tmp_path_factory.mktemp("prop") / "store"
    writers = [ResultStore(root), ResultStore(root)]
    ok: dict[int, bytes] = {}
    failed: set[int] = set()

    def new_row(i: int, status: str) -> dict[str, Any]:
        return row(i, status=status)

    for step in history:
        kind = step[0]
        if kind == "write":
            _, i, w, success = step
            store = writers[w]
            path = store.row_path(new_row(i, "ok")["run_id"])
            try:
                with store.writing():
                    store.write(new_row(i, "ok" if success else "failed"))
            except StoreError:
                assert path.exists()  # refused only because that row file is corrupt
                continue
            if success and i not in ok:
                ok[i] = path.read_bytes()
                failed.discard(i)
            elif not success and i not in ok:
                failed.add(i)
        elif kind == "crash":  # killed mid-write: a cut temporary file, the lock left
            _, i, w, fraction = step
            data = row_bytes(new_row(i, "ok"))
            tmp = writers[w].runs_path / f".{i}.json.crash{len(history)}.tmp"
            tmp.write_bytes(data[: int(len(data) * fraction)])
            (root / LOCK_NAME).write_text(json.dumps({"pid": 1, "host": "h"}))
        elif kind == "cut-index":
            if (root / INDEX_NAME).exists():
                _cut(root / INDEX_NAME, step[1])
        elif kind == "cut-row":
            _, i, fraction = step
            if i in ok:
                path = writers[0].row_path(new_row(i, "ok")["run_id"])
                _cut(path, fraction)
                with pytest.raises(StoreError, match=path.name):
                    ResultStore(root).load(status=None)
                path.unlink()  # what the message says to do; the run is rerun
                del ok[i]
        else:  # resume: a new process opens the store
            writers[step[1]] = ResultStore(root)
        loaded = ResultStore(root).load(status=None)
        ids = [r["run_id"] for r in loaded]
        assert len(ids) == len(set(ids))  # every row once
        finished = {r["run_id"] for r in loaded if r["status"] == "ok"}
        assert finished == {new_row(i, "ok")["run_id"] for i in ok}
        for i, data in ok.items():
            assert writers[0].row_path(new_row(i, "ok")["run_id"]).read_bytes() == data
        assert {r["run_id"] for r in loaded if r["status"] == "failed"} == {
            new_row(i, "failed")["run_id"] for i in failed - set(ok)
        }
        lock = WriterLock(root)
        with lock:  # a crashed writer never leaves the store locked
            pass


def test_a_busy_store_refuses_writes_through_a_second_store_object(tmp_path: Path) -> None:
    a, b = ResultStore(tmp_path / "s"), ResultStore(tmp_path / "s")
    with a.writing(), pytest.raises(StoreBusyError):
        b.writing().__enter__()
