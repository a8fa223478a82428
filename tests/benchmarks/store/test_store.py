"""Tests of voot.bench.store.result_store: the ResultStore (header, rows, foreign data, checksums, old
and compact stores, resume) and compact_store."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from store_fixtures import row

from voot.bench.measure.store_speed import synthetic_plan_row
from voot.bench.store.format import (
    HEADER_NAME,
    StoreError,
    row_bytes,
    verify_row_bytes,
)
from voot.bench.store.result_store import ResultStore, compact_store


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


def test_row_files_carry_a_checksum_that_is_dropped_on_read(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    r = row(1)
    path = s.write(r)
    data = path.read_bytes()
    assert json.loads(data)["checksum"].startswith("sha256:")
    assert data == row_bytes(r) and verify_row_bytes(data)
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


def test_header_run_id_paths_and_a_missing_runs_folder(tmp_path: Path) -> None:
    s = ResultStore(tmp_path / "r")
    assert s.header["format"] == "voot-results" and s.checksums_required
    assert s.row_path("abc") == s.runs_path / "abc.json"
    for bad in ("", "a/b", "a\\b", "a.b", " abc", "abc\n"):
        with pytest.raises(ValueError, match="invalid run id"):
            s.row_path(bad)
    s.runs_path.rmdir()
    assert s.row_files() == []


def test_repr_and_an_empty_runs_folder(tmp_path: Path) -> None:
    s = ResultStore(tmp_path)
    assert repr(s) == f"ResultStore({str(tmp_path)!r})"
    s.runs_path.rmdir()
    assert s.load() == []


def plan_rows(n: int, length: int = 600) -> list[dict]:
    rng = np.random.default_rng(1)
    return [synthetic_plan_row(i, length, rng) for i in range(n)]


def test_a_compact_store_writes_compact_rows_and_reads_them_back_full(tmp_path: Path) -> None:
    from voot.bench.store.compact import CompactConfig

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
    from voot.bench.store.compact import CompactConfig

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
    from voot.bench.store.compact import CompactConfig

    store = ResultStore(tmp_path / "c", compact=CompactConfig())
    path = store.write(plan_rows(1)[0])
    row = json.loads(path.read_bytes())
    row.pop("checksum")
    row["compact"]["curves"]["elapsed"]["codec"] = "zip"
    path.write_bytes(row_bytes(row))  # a valid checksum over bad content
    with pytest.raises(StoreError, match=rf"{path.name}.*corrupt compact.*steps, sampled"):
        store.load()
    row["compact"]["curves"]["elapsed"]["codec"] = "sampled"
    data = row_bytes(row)
    path.write_bytes(data.replace(b'"n":600', b'"n":601', 1))  # valid layout, wrong checksum
    with pytest.raises(StoreError, match="changed since it was written"):
        ResultStore(tmp_path / "c").verify()


def test_compact_store_converts_resumes_and_keeps_the_source(tmp_path: Path) -> None:
    from voot.bench.store.compact import CompactConfig

    src = ResultStore(tmp_path / "src")
    rows = plan_rows(3)
    for r in rows:
        src.write(r)
    src.write(row(9, status="failed"))
    before = {p.name: p.read_bytes() for p in src.row_files()}
    out = compact_store(tmp_path / "src", tmp_path / "dst")
    assert (
        out["rows"] == out["copied"] == out["dst_rows"] == 4
        and out["dst_bytes"] * 5 < out["src_bytes"]
    )
    assert {p.name: p.read_bytes() for p in src.row_files()} == before
    dst = ResultStore(tmp_path / "dst")
    assert dst.compact == CompactConfig()
    assert {r["run_id"] for r in dst.load(status=None)} == {p.stem for p in src.row_files()}
    assert len(dst.load(status="failed")) == 1
    (dst.runs_path / f"{rows[0]['run_id']}.json").unlink()  # as if interrupted before it
    again = compact_store(tmp_path / "src", tmp_path / "dst")
    assert again["copied"] == 1 and again["rows"] == 4
    # a compact source copies as it is into the same settings, and is refused for others
    assert compact_store(tmp_path / "dst", tmp_path / "dst2")["copied"] == 4
    with pytest.raises(StoreError, match="same settings"):
        compact_store(tmp_path / "dst", tmp_path / "dst3", CompactConfig(points=5))
    with pytest.raises(StoreError, match="another directory"):
        compact_store(tmp_path / "src", tmp_path / "src")
    with pytest.raises(StoreError, match="full-resolution"):
        compact_store(tmp_path / "dst", tmp_path / "src")
    with pytest.raises(StoreError, match="no voot result store"):
        compact_store(tmp_path / "missing", tmp_path / "dst4")


def test_compact_store_copies_only_the_given_run_ids(tmp_path: Path) -> None:
    src = ResultStore(tmp_path / "src")
    rows = plan_rows(3)
    for r in rows:
        src.write(r)
    wanted = {rows[0]["run_id"], rows[2]["run_id"], "not-in-src"}
    out = compact_store(tmp_path / "src", tmp_path / "dst", run_ids=wanted)
    assert out["rows"] == out["copied"] == out["dst_rows"] == 2
    assert {p.stem for p in ResultStore(tmp_path / "dst").row_files()} == wanted - {"not-in-src"}
    assert compact_store(tmp_path / "src", tmp_path / "dst", run_ids=wanted)["copied"] == 0


def test_a_store_is_created_with_its_missing_parent_folders(tmp_path: Path) -> None:
    store = ResultStore(tmp_path / "results" / "kitchen" / "v1")
    assert store.header_path.is_file() and store.runs_path.is_dir() and len(store) == 0
