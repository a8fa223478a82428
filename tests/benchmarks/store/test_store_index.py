"""Tests of voot.bench.store.index: atomic writes (file modes, a failed rename) and the
index (a cache of parsed rows: changes, damage, racy files, ctime, curves as arrays)."""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from store_fixtures import row

from voot.bench.store import format as store_format
from voot.bench.store import index as store_index
from voot.bench.store.format import StoreError, make_row
from voot.bench.store.index import INDEX_NAME
from voot.bench.store.result_store import ResultStore


def test_write_is_atomic_when_replace_fails(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    s = ResultStore(tmp_path)
    r = row(1)

    def broken_replace(src: str, dst: str) -> None:
        raise OSError("disk on fire")

    monkeypatch.setattr(store_index.os, "replace", broken_replace)
    with pytest.raises(OSError, match="disk on fire"):
        s.write(r)
    monkeypatch.undo()
    # no row, and no temporary file left behind
    assert list((tmp_path / "runs").iterdir()) == []
    assert s.load(status=None) == []


def test_row_files_are_ordinary_files(tmp_path: Path) -> None:
    path = ResultStore(tmp_path).write(row(1))
    assert path.stat().st_mode & 0o777 == 0o666 & ~store_index._UMASK
    assert ResultStore(tmp_path).write(row(1)) == path  # kept, and its path returned


def test_index_cache_tracks_changes_and_survives_damage(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    for i in range(3):
        s.write(row(i))
    first = s.load(status=None)
    assert (tmp_path / INDEX_NAME).exists()
    assert s.load(status=None) == first  # from the index
    failed = row(7, status="failed")
    s.write(failed)
    assert len(s.load(status=None)) == 4
    s.write(row(7))  # replaces the failed row: the index must notice
    assert s.get(failed["run_id"])["status"] == "ok"
    assert [r["status"] for r in s.load(status=None)].count("failed") == 0
    (tmp_path / INDEX_NAME).write_bytes(b"garbage")
    assert s.load(status=None) == ResultStore(tmp_path).load(status=None)
    assert len(s.load(status=None)) == 4
    (tmp_path / INDEX_NAME).unlink()
    assert len(s.load(status=None)) == 4


@pytest.mark.parametrize("keep", [0.0, 0.01, 0.3, 0.5, 0.9, 0.999])
def test_an_index_cut_at_any_byte_is_rebuilt(tmp_path: Path, keep: float) -> None:
    """A crash (or a file system without atomic renames) may leave the index cut short:
    an empty file made np.load raise EOFError and a cut one BadZipFile, which escaped."""
    s = ResultStore(tmp_path)
    for i in range(3):
        s.write(row(i))
    expected = s.load(status=None)
    data = (tmp_path / INDEX_NAME).read_bytes()
    (tmp_path / INDEX_NAME).write_bytes(data[: int(len(data) * keep)])
    assert store_index.read_index(tmp_path) == {}
    assert ResultStore(tmp_path).load(status=None) == expected
    assert (tmp_path / INDEX_NAME).read_bytes() != data[: int(len(data) * keep)]  # rebuilt


def test_extra_curves_are_indexed_as_arrays(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    r = _plan_row(objects_initial=7, calls_curve=[3, 40, 41], cpu_elapsed=[0.1, 0.2, 0.4])
    s.write(r)
    s.write(row(1))  # a row without the optional curves
    for _ in range(2):  # parsed, then from the index
        plan, bbfo = sorted(s.load(arrays=True), key=lambda x: x["kind"] != "plan")
        assert np.array_equal(plan["elapsed"], [0.1, 0.25, 0.5])
        assert np.isnan(plan["objects_left"][0]) and plan["objects_left"][1:].tolist() == [6, 4]
        assert plan["objects_initial"] == 7 and "elapsed" not in bbfo
        as_lists = next(x for x in s.load() if x["kind"] == "plan")
        assert as_lists["objects_left"] == [None, 6.0, 4.0]  # as in the row file
        assert plan["calls_curve"].tolist() == [3.0, 40.0, 41.0]
        assert as_lists["calls_curve"] == [3, 40, 41]  # whole counts read back as int
        assert all(type(v) is int for v in as_lists["calls_curve"])
        assert as_lists == s.get(r["run_id"])
    assert store_format.CURVE_KEYS[0] == "best_so_far"


def test_nan_in_best_so_far_stays_nan(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    s.write(make_row("bbfo", {"seed": 0}, status="ok", wall_time=0.0, best_so_far=[np.nan, 1.0]))
    for _ in range(2):
        (r,) = s.load()
        assert np.isnan(r["best_so_far"][0]) and r["best_so_far"][1] == 1.0


def _tamper_in_place(path: Path, old: bytes, new: bytes) -> None:
    """Overwrite ``old`` with ``new`` (same size) inside ``path``, then restore its mtime."""
    assert len(old) == len(new)
    st = path.stat()
    data = path.read_bytes()
    at = data.index(old)
    with open(path, "r+b") as fh:  # same file, same inode, same size
        fh.seek(at)
        fh.write(new)
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))
    after = path.stat()
    assert (after.st_size, after.st_mtime_ns, after.st_ino) == (
        st.st_size,
        st.st_mtime_ns,
        st.st_ino,
    )


@pytest.mark.parametrize("wait_out_racy_window", [False, True])
def test_a_row_changed_in_place_with_its_mtime_restored_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, wait_out_racy_window: bool
) -> None:
    s = ResultStore(tmp_path)
    r = row(3)
    path = s.write(r)
    s.write(row(4))
    assert len(s.load()) == 2  # the index now holds both rows
    if wait_out_racy_window:  # the row is "at rest": only its ctime can tell the change
        monkeypatch.setattr(store_index, "RACY_NS", 0)
        time.sleep(0.05)  # longer than a tick of the coarsest Linux timestamps
    _tamper_in_place(path, b'"best_so_far":[3.0,', b'"best_so_far":[9.0,')
    with pytest.raises(StoreError, match=rf"{r['run_id']}\.json: result row changed since"):
        s.load()
    with pytest.raises(StoreError, match="changed since it was written"):
        ResultStore(tmp_path).get(r["run_id"])
    with pytest.raises(StoreError, match="changed since it was written"):
        s.verify()
    assert b"[9.0," in path.read_bytes()  # reported, never rewritten


def _plan_row(**extra: Any) -> dict:
    """A three-simulation plan row with elapsed times, objects left and ``extra``."""
    return make_row(
        "plan",
        {"problem": "kitchen", "seed": 0},
        status="ok",
        wall_time=1.0,
        best_so_far=[0.0, 1.0, 1.5],
        elapsed=[0.1, 0.25, 0.5],
        objects_left=[None, 6, 4],
        **extra,
    )


def _count_reads(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    reads: list[str] = []
    read_row = ResultStore._read_row

    def counting(self: ResultStore, path: Path) -> dict:
        reads.append(path.name)
        return read_row(self, path)

    monkeypatch.setattr(ResultStore, "_read_row", counting)
    return reads


def test_the_index_serves_files_at_rest_and_rereads_racy_ones(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    s = ResultStore(tmp_path)
    for r in [row(0), row(1, status="failed"), _plan_row(), row(2)]:
        s.write(r)
    reads = _count_reads(monkeypatch)
    first = s.load(status=None)
    assert len(reads) == 4
    # written just now (within RACY_NS of the scan): read again at the next load
    assert s.load(status=None) == first and len(reads) == 8
    monkeypatch.setattr(store_index, "RACY_NS", 0)  # now every file is at rest
    s.load(status=None)  # rebuilds the index with a later scan time
    del reads[:]
    for arrays in (False, True):
        again = s.load(status=None, arrays=arrays)
        assert reads == []  # all from the index
        if not arrays:
            assert again == first
    plan = next(r for r in again if r["kind"] == "plan")
    assert plan["elapsed"].tolist() == [0.1, 0.25, 0.5]
    for r in again:
        assert not r["best_so_far"].flags.writeable
    # an index whose curve values do not match its offsets is rebuilt, not trusted
    with np.load(tmp_path / INDEX_NAME) as data:
        cols = dict(data)
    cols["values_best_so_far"] = cols["values_best_so_far"][:-1]
    np.savez(tmp_path / INDEX_NAME, **cols)
    assert s.load(status=None) == first and len(reads) == 4
    # curves parsed from the files are read-only too
    (tmp_path / INDEX_NAME).unlink()
    assert all(not r["best_so_far"].flags.writeable for r in s.load(arrays=True))
