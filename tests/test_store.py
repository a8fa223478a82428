"""Tests of voot.bench.store: atomic rows, resume data, refusal to touch foreign files."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from voot.bench import store as store_mod
from voot.bench.store import (
    HEADER_NAME,
    INDEX_NAME,
    ResultStore,
    StoreError,
    check_row,
    curves,
    make_row,
    make_run_id,
)


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


def test_new_store_has_header_and_empty_runs(tmp_path: Path) -> None:
    s = ResultStore(tmp_path / "r")
    header = json.loads((tmp_path / "r" / HEADER_NAME).read_text())
    assert header["format"] == "voot-results" and header["schema"] == 1
    assert (tmp_path / "r" / "runs").is_dir()
    assert len(s) == 0 and s.load() == []
    # reopening an existing store works and keeps the header
    assert ResultStore(tmp_path / "r").header == s.header


def test_empty_existing_directory_becomes_a_store(tmp_path: Path) -> None:
    ResultStore(tmp_path)
    assert (tmp_path / HEADER_NAME).exists()


def test_row_round_trip_and_fields(tmp_path: Path) -> None:
    s = ResultStore(tmp_path / "r")
    r = row(3)
    path = s.write(r)
    assert path.name == f"{r['run_id']}.json"
    got = s.get(r["run_id"])
    assert got == r
    assert got["versions"]["numpy"] == np.__version__ and "voot" in got["versions"]
    assert got["best_so_far"] == [3.0, 4.0, 5.0, 6.0, 7.0]
    assert s.get("0" * 20) is None


def test_run_id_is_stable_and_order_independent() -> None:
    a = make_run_id("bbfo", {"x": 1, "seed": 2, "params": {"a": 0.1, "b": 2}})
    b = make_run_id("bbfo", {"params": {"b": 2, "a": 0.1}, "seed": 2, "x": 1})
    assert a == b and len(a) == 20
    assert a != make_run_id("bbfo", {"x": 1, "seed": 3, "params": {"a": 0.1, "b": 2}})
    assert a != make_run_id("plan", {"x": 1, "seed": 2, "params": {"a": 0.1, "b": 2}})
    code = (
        "from voot.bench.store import make_run_id;"
        "print(make_run_id('bbfo', {'x': 1, 'seed': 2, 'params': {'a': 0.1, 'b': 2}}))"
    )
    other = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "PYTHONHASHSEED": "123"},
    )
    assert other.stdout.strip() == a


def test_failed_replaced_by_ok_but_ok_never_replaced(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    failed = row(1, status="failed")
    s.write(failed)
    assert s.get(failed["run_id"])["status"] == "failed"
    ok = row(1)
    assert ok["run_id"] == failed["run_id"]
    s.write(ok)
    assert s.get(ok["run_id"])["status"] == "ok"
    before = s.row_path(ok["run_id"]).read_bytes()
    s.write(failed)  # a finished run is never lost ...
    other_ok = dict(ok, wall_time=99.0)
    s.write(other_ok)  # ... nor redone
    assert s.row_path(ok["run_id"]).read_bytes() == before


def test_write_is_atomic_when_replace_fails(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    s = ResultStore(tmp_path)
    r = row(1)

    def broken_replace(src: str, dst: str) -> None:
        raise OSError("disk on fire")

    monkeypatch.setattr(store_mod.os, "replace", broken_replace)
    with pytest.raises(OSError, match="disk on fire"):
        s.write(r)
    monkeypatch.undo()
    # no row, and no temporary file left behind
    assert list((tmp_path / "runs").iterdir()) == []
    assert s.load(status=None) == []


def test_stray_temp_file_from_a_killed_writer_is_ignored(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    s.write(row(1))
    (tmp_path / "runs" / ".abc.json.x1y2.tmp").write_text('{"half": ')
    (tmp_path / "runs" / ".hidden.json").write_text("{")
    rows = s.load()
    assert [r["config"]["seed"] for r in rows] == [1]
    assert len(s) == 1


def test_corrupt_row_names_the_file_and_is_not_overwritten(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    r = row(1)
    path = s.write(r)
    path.write_text('{"schema": 1, "run_id": ')  # truncated by some other tool
    with pytest.raises(StoreError, match=str(path)):
        s.load()
    with pytest.raises(StoreError, match="corrupt"):
        s.write(r)
    assert path.read_text() == '{"schema": 1, "run_id": '


def test_foreign_json_row_is_rejected(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    bad = tmp_path / "runs" / "abcdef.json"
    bad.write_text(json.dumps({"hello": "world"}))
    with pytest.raises(StoreError, match=r"abcdef\.json.*missing keys"):
        s.load()
    assert json.loads(bad.read_text()) == {"hello": "world"}


def test_foreign_directory_is_refused_and_untouched(tmp_path: Path) -> None:
    (tmp_path / "notes.txt").write_text("mine")
    with pytest.raises(StoreError, match="not a voot result store"):
        ResultStore(tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]
    assert (tmp_path / "notes.txt").read_text() == "mine"


def test_foreign_or_newer_header_is_refused(tmp_path: Path) -> None:
    (tmp_path / HEADER_NAME).write_text(json.dumps({"format": "something-else", "schema": 1}))
    with pytest.raises(StoreError, match=HEADER_NAME):
        ResultStore(tmp_path)
    (tmp_path / HEADER_NAME).write_text(json.dumps({"format": "voot-results", "schema": 99}))
    with pytest.raises(StoreError, match="schema 99"):
        ResultStore(tmp_path)
    (tmp_path / HEADER_NAME).write_text("{not json")
    with pytest.raises(StoreError, match="corrupt store header"):
        ResultStore(tmp_path)
    assert (tmp_path / HEADER_NAME).read_text() == "{not json"
    assert not (tmp_path / "runs").exists()


def test_file_path_and_missing_store(tmp_path: Path) -> None:
    f = tmp_path / "results.json"
    f.write_text("[]")
    with pytest.raises(StoreError, match="is a file"):
        ResultStore(f)
    with pytest.raises(StoreError, match="no voot result store"):
        ResultStore(tmp_path / "missing", create=False)
    assert not (tmp_path / "missing").exists()


def test_load_filters_and_arrays(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    for i in range(4):
        s.write(row(i))
    s.write(row(10, status="failed"))
    s.write(row(20, kind="plan"))
    assert len(s.load()) == 5
    assert len(s.load(kind="bbfo")) == 4
    assert len(s.load(status=None)) == 6
    assert [r["status"] for r in s.load(status="failed")] == ["failed"]
    arr = s.load(kind="bbfo", arrays=True)
    assert all(isinstance(r["best_so_far"], np.ndarray) for r in arr)
    with pytest.raises(ValueError):
        arr[0]["best_so_far"][0] = 1.0  # read-only views of the index
    assert s.finished_ids(kind="bbfo") == {r["run_id"] for r in s.load(kind="bbfo")}


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


def test_check_row_and_make_row_validation() -> None:
    with pytest.raises(StoreError, match="JSON object"):
        check_row([1, 2])
    with pytest.raises(StoreError, match="status"):
        check_row(dict(row(1), status="meh"))
    with pytest.raises(ValueError, match="status"):
        make_row("bbfo", {}, status="done", wall_time=0.0, best_so_far=[])


def test_curves_pads_with_nan() -> None:
    c = curves([{"best_so_far": [1.0, 2.0, 3.0]}, {"best_so_far": [5.0]}])
    assert c.shape == (2, 3)
    assert np.array_equal(c[0], [1.0, 2.0, 3.0])
    assert c[1, 0] == 5.0 and np.isnan(c[1, 1:]).all()
    assert curves([]).shape == (0, 0)


def test_extra_curves_are_indexed_as_arrays(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    r = make_row(
        "plan",
        {"problem": "kitchen", "seed": 0},
        status="ok",
        wall_time=1.0,
        best_so_far=[0.0, 1.0, 1.5],
        elapsed=[0.1, 0.25, 0.5],
        objects_left=[None, 6, 4],
        objects_initial=7,
        calls_curve=[3, 40, 41],
        cpu_elapsed=[0.1, 0.2, 0.4],
    )
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
    assert store_mod.CURVE_KEYS[0] == "best_so_far"


# ----- rows changed in place: the checksum -----------------------------------------------
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
        monkeypatch.setattr(store_mod, "RACY_NS", 0)
        time.sleep(0.05)  # longer than a tick of the coarsest Linux timestamps
    _tamper_in_place(path, b'"best_so_far":[3.0,', b'"best_so_far":[9.0,')
    with pytest.raises(StoreError, match=rf"{r['run_id']}\.json: result row changed since"):
        s.load()
    with pytest.raises(StoreError, match="changed since it was written"):
        ResultStore(tmp_path).get(r["run_id"])
    with pytest.raises(StoreError, match="changed since it was written"):
        s.verify()
    assert b"[9.0," in path.read_bytes()  # reported, never rewritten


def test_row_files_carry_a_checksum_that_is_dropped_on_read(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    r = row(1)
    path = s.write(r)
    data = path.read_bytes()
    assert json.loads(data)["checksum"].startswith("sha256:")
    assert data == store_mod.row_bytes(r) and store_mod.verify_row_bytes(data)
    assert s.get(r["run_id"]) == r and s.load() == [r]
    assert json.loads((tmp_path / HEADER_NAME).read_text())["row_checksum"] == "sha256"
    assert s.verify() == 1


def test_a_row_without_its_checksum_is_refused_in_a_checksummed_store(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    r = row(2)
    path = s.write(r)
    path.write_bytes(json.dumps(r, separators=(",", ":")).encode() + b"\n")  # stripped
    with pytest.raises(StoreError, match="without its checksum"):
        s.load()


def test_an_old_store_without_checksums_still_loads(tmp_path: Path) -> None:
    """A store written before checksums: header without row_checksum, plain JSON rows."""
    s = ResultStore(tmp_path)
    header = json.loads((tmp_path / HEADER_NAME).read_text())
    del header["row_checksum"]
    (tmp_path / HEADER_NAME).write_text(json.dumps(header))
    old = [row(i) for i in range(3)]
    for r in old:
        (tmp_path / "runs" / f"{r['run_id']}.json").write_bytes(
            json.dumps(r, separators=(",", ":")).encode() + b"\n"
        )
    s = ResultStore(tmp_path)
    assert not s.checksums_required
    by_id = sorted(old, key=lambda r: r["run_id"])
    assert s.load() == by_id
    new = row(5)
    assert b'"checksum":"sha256:' in s.write(new).read_bytes()  # new rows carry one
    assert len(s.load()) == 4 and s.verify() == 4


def test_time_load_measures_a_small_store(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(store_mod, "RACY_NS", 0)
    out = store_mod.time_load(5, 10, repeats=1, path=str(tmp_path / "bench"))
    assert set(out) == {"write", "cold", "warm", "warm_arrays", "verify", "mb"}
    assert all(v >= 0 for v in out.values())
    assert 0 < out["mb"] < 0.01  # five rows of ten steps: a few kB
    assert (tmp_path / "bench" / "store").is_dir()  # a given path is kept


# ----- failed rows, checksum edge cases, file modes ---------------------------------------
class _Spec:
    kind = "bbfo"

    def config(self) -> dict:
        return {"function": "f", "dim": 2, "seed": 7}


def test_failed_and_exception_rows() -> None:
    spec = _Spec()
    r = store_mod.failed_row(spec, "RuntimeError: no", note=1)
    check_row(r)
    assert (r["status"], r["error"], r["wall_time"], r["best_so_far"], r["note"]) == (
        "failed",
        "RuntimeError: no",
        0.0,
        [],
        1,
    )
    assert r["run_id"] == make_run_id("bbfo", spec.config())
    start = time.perf_counter()
    try:
        raise ValueError("boom")
    except ValueError as exc:
        r = store_mod.exception_row(spec, exc, start, [1.0, 2.0], extra="x")
    elapsed = time.perf_counter() - start
    assert r["status"] == "failed" and r["error"] == "ValueError: boom"
    assert 0.0 <= r["wall_time"] <= elapsed
    assert r["best_so_far"] == [1.0, 2.0] and r["extra"] == "x"
    assert "ValueError: boom" in r["traceback"]


def test_run_ids_refuse_non_json_numbers() -> None:
    with pytest.raises(ValueError):
        make_run_id("bbfo", {"x": float("nan")})


def test_check_row_returns_the_row_and_checks_both_types() -> None:
    r = row(1)
    assert check_row(r) is r
    for bad in (dict(r, config=[1]), dict(r, best_so_far=(1.0,))):
        with pytest.raises(StoreError, match="'config' must be an object"):
            check_row(bad)


def test_verify_row_bytes_edge_cases() -> None:
    verify = store_mod.verify_row_bytes
    good = store_mod.row_bytes(row(1))
    assert verify(good) is True
    plain = json.dumps(row(1)).encode() + b"\n"
    with pytest.raises(StoreError, match="without its checksum"):
        verify(plain)  # required by default
    assert verify(plain, required=False) is False
    zeros = b"0" * 64
    only = store_mod._CHECKSUM_HEAD + zeros + store_mod._CHECKSUM_TAIL  # nothing before it
    assert verify(only, required=False) is False
    with pytest.raises(StoreError, match="changed since"):
        verify(b"{" + only, required=False)  # one byte of body: a (wrong) checksum


def test_row_files_are_ordinary_files(tmp_path: Path) -> None:
    path = ResultStore(tmp_path).write(row(1))
    assert path.stat().st_mode & 0o777 == 0o666 & ~store_mod._UMASK
    assert ResultStore(tmp_path).write(row(1)) == path  # kept, and its path returned


def test_nan_in_best_so_far_stays_nan(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    s.write(make_row("bbfo", {"seed": 0}, status="ok", wall_time=0.0, best_so_far=[np.nan, 1.0]))
    for _ in range(2):
        (r,) = s.load()
        assert np.isnan(r["best_so_far"][0]) and r["best_so_far"][1] == 1.0


def test_header_run_id_paths_and_a_missing_runs_folder(tmp_path: Path) -> None:
    s = ResultStore(tmp_path / "r")
    assert s.header["format"] == "voot-results" and s.checksums_required
    assert s.row_path("abc") == s.runs_path / "abc.json"
    for bad in ("", "a/b", "a\\b", "a.b", " abc", "abc\n"):
        with pytest.raises(ValueError, match="invalid run id"):
            s.row_path(bad)
    s.runs_path.rmdir()
    assert s.row_files() == []


# ----- the index: used for files at rest, validated, read-only arrays ----------------------
def _plan_row() -> dict:
    return make_row(
        "plan",
        {"problem": "kitchen", "seed": 0},
        status="ok",
        wall_time=1.0,
        best_so_far=[0.0, 1.0, 1.5],
        elapsed=[0.1, 0.25, 0.5],
        objects_left=[None, 6, 4],
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
    monkeypatch.setattr(store_mod, "RACY_NS", 0)  # now every file is at rest
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


def test_repr_curves_of_equal_length_and_an_empty_runs_folder(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    assert repr(s) == f"ResultStore({str(tmp_path)!r})"
    c = curves([{"best_so_far": [1.0, 2.0]}, {"best_so_far": [3.0, 4.0]}])
    assert c.tolist() == [[1.0, 2.0], [3.0, 4.0]]
    s.runs_path.rmdir()
    assert s.load() == []


def test_time_load_arguments_and_timings(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(store_mod, "RACY_NS", 1_000_000)  # waits 1 ms
    for bad in ((0, 1, 1), (1, 0, 1), (1, 1, 0)):
        with pytest.raises(ValueError, match=">= 1"):
            store_mod.time_load(*bad)
    began = time.perf_counter()
    out = store_mod.time_load(1, 1, repeats=1)  # in a temporary directory
    elapsed = time.perf_counter() - began
    assert all(0 <= out[k] <= elapsed for k in ("write", "cold", "warm", "verify"))


# ----- compact stores -----------------------------------------------------------------------
def plan_rows(n: int, length: int = 600) -> list[dict]:
    rng = np.random.default_rng(1)
    return [store_mod.synthetic_plan_row(i, length, rng) for i in range(n)]


def test_a_compact_store_writes_compact_rows_and_reads_them_back_full(tmp_path: Path) -> None:
    from voot.bench.compact import CompactConfig

    rows = plan_rows(4)
    full = ResultStore(tmp_path / "full")
    small = ResultStore(tmp_path / "small", compact=CompactConfig(points=20))
    for r in rows:
        full.write(r)
        small.write(r)
    size = sum(p.stat().st_size for p in small.row_files())
    assert size * 5 < sum(p.stat().st_size for p in full.row_files())
    header = json.loads((tmp_path / "small" / HEADER_NAME).read_bytes())
    assert header["compact"] == {"version": 1, "points": 20, "spacing": "log"}
    assert small.verify() == 4
    for loaded in (
        small.load(),
        small.load(),
        list(small.iter_rows()),
        [small.get(rows[0]["run_id"])],
    ):
        for r in loaded:
            assert r is not None
            want = next(w for w in rows if w["run_id"] == r["run_id"])
            assert r["best_so_far"] == want["best_so_far"]
            assert r["objects_left"] == want["objects_left"]
            assert r["elapsed"][-1] == want["elapsed"][-1] and len(r["elapsed"]) == 600
            assert r["interpolated"] == ["calls_curve", "cpu_elapsed", "elapsed"]
    arrays = small.load(arrays=True)
    assert all(isinstance(r["calls_curve"], np.ndarray) for r in arrays)
    raw = small.load(expand=False)
    assert all("compact" in r and "best_so_far" not in r for r in raw)
    assert small.finished_ids() == {r["run_id"] for r in rows}
    # an expanded row written into a full store keeps its mark; into the compact one: kept
    other = ResultStore(tmp_path / "other")
    other.write(small.load()[0])
    assert "interpolated" in other.load()[0] and "compact" not in other.load()[0]


def test_compact_settings_persist_and_a_mismatch_is_refused(tmp_path: Path) -> None:
    from voot.bench.compact import CompactConfig

    ResultStore(tmp_path / "c", compact=CompactConfig())
    assert ResultStore(tmp_path / "c").compact == CompactConfig()
    assert ResultStore(tmp_path / "c", compact=CompactConfig()).compact == CompactConfig()
    with pytest.raises(StoreError, match="voot-bench compact"):
        ResultStore(tmp_path / "c", compact=CompactConfig(points=7))
    ResultStore(tmp_path / "f")
    with pytest.raises(StoreError, match="full-resolution store"):
        ResultStore(tmp_path / "f", compact=CompactConfig())
    header = tmp_path / "c" / HEADER_NAME
    data = json.loads(header.read_bytes())
    data["compact"]["spacing"] = "cubic"
    header.write_text(json.dumps(data))
    with pytest.raises(StoreError, match=r"bad compact settings.*log, linear"):
        ResultStore(tmp_path / "c")


def test_a_corrupt_compact_row_is_a_store_error_naming_the_file(tmp_path: Path) -> None:
    from voot.bench.compact import CompactConfig

    store = ResultStore(tmp_path / "c", compact=CompactConfig())
    path = store.write(plan_rows(1)[0])
    row = json.loads(path.read_bytes())
    row.pop("checksum")
    row["compact"]["curves"]["elapsed"]["codec"] = "zip"
    path.write_bytes(store_mod.row_bytes(row))  # a valid checksum over bad content
    with pytest.raises(StoreError, match=rf"{path.name}.*corrupt compact.*steps, sampled"):
        store.load()
    row["compact"]["curves"]["elapsed"]["codec"] = "sampled"
    data = store_mod.row_bytes(row)
    path.write_bytes(data.replace(b'"n":600', b'"n":601', 1))  # valid layout, wrong checksum
    with pytest.raises(StoreError, match="changed since it was written"):
        ResultStore(tmp_path / "c").verify()


def test_compact_store_converts_resumes_and_keeps_the_source(tmp_path: Path) -> None:
    from voot.bench.compact import CompactConfig

    src = ResultStore(tmp_path / "src")
    rows = plan_rows(3)
    for r in rows:
        src.write(r)
    src.write(row(9, status="failed"))
    before = {p.name: p.read_bytes() for p in src.row_files()}
    out = store_mod.compact_store(tmp_path / "src", tmp_path / "dst")
    assert out["rows"] == out["copied"] == 4 and out["dst_bytes"] * 5 < out["src_bytes"]
    assert {p.name: p.read_bytes() for p in src.row_files()} == before
    dst = ResultStore(tmp_path / "dst")
    assert dst.compact == CompactConfig()
    assert {r["run_id"] for r in dst.load(status=None)} == {p.stem for p in src.row_files()}
    assert len(dst.load(status="failed")) == 1
    (dst.runs_path / f"{rows[0]['run_id']}.json").unlink()  # as if interrupted before it
    again = store_mod.compact_store(tmp_path / "src", tmp_path / "dst")
    assert again["copied"] == 1 and again["rows"] == 4
    # a compact source copies as it is into the same settings, and is refused for others
    assert store_mod.compact_store(tmp_path / "dst", tmp_path / "dst2")["copied"] == 4
    with pytest.raises(StoreError, match="same settings"):
        store_mod.compact_store(tmp_path / "dst", tmp_path / "dst3", CompactConfig(points=5))
    with pytest.raises(StoreError, match="another directory"):
        store_mod.compact_store(tmp_path / "src", tmp_path / "src")
    with pytest.raises(StoreError, match="full-resolution"):
        store_mod.compact_store(tmp_path / "dst", tmp_path / "src")
    with pytest.raises(StoreError, match="no voot result store"):
        store_mod.compact_store(tmp_path / "missing", tmp_path / "dst4")


def test_time_load_of_a_compact_plan_store(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from voot.bench.compact import CompactConfig

    monkeypatch.setattr(store_mod, "RACY_NS", 0)
    full = store_mod.time_load(3, 300, repeats=1, path=str(tmp_path / "a"), plan=True)
    small = store_mod.time_load(
        3, 300, repeats=1, path=str(tmp_path / "b"), plan=True, compact=CompactConfig()
    )
    assert small["mb"] * 3 < full["mb"]
    assert ResultStore(tmp_path / "b" / "store").compact == CompactConfig()
