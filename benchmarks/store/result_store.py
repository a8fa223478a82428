"""The result store: one JSON file per finished run, in a directory with a header.

Every benchmark (``voot-bench bbfo``, ``voot-bench plan``, local or on Ray) writes one
*row* per run (its format: :mod:`voot.bench.store.format`) into a :class:`ResultStore`.

Layout on disk (chosen over an append-only JSONL because a rename is atomic on every
POSIX file system, so there is no recovery rule to get wrong)::

    RESULTS/
      voot-results.json      header: {"format": "voot-results", "schema": 1, ...}
      runs/<run_id>.json     one row per finished run

Guarantees:

* **Atomic rows.** A row is written to a hidden temporary file in ``runs/``, flushed and
  fsynced, then moved into place with :func:`os.replace`. A reader sees either the whole
  row or no row; a sweep killed mid-write leaves at most a stray ``.tmp`` file, which
  readers ignore.
* **Resume.** A sweep asks :meth:`ResultStore.finished_ids` and runs only the rest, so an
  interrupted sweep restarted with the same command skips every finished run and loses
  none. A run that *failed* (status ``"failed"``) is not finished: it is retried by
  default and its row replaced by the new outcome, because a failure is usually a bug
  fixed since.
* **Never clobber foreign data.** A directory that exists, is not empty and has no
  header, a header of another format or a newer schema, or a row file that does not
  parse, raises :class:`~voot.bench.store.format.StoreError` naming the file, before
  anything is written. Nothing in this module ever deletes or rewrites a file it did not
  just create.

* **Checksummed rows.** Every row file ends with a ``"checksum"`` key, verified on every
  parse of the file (:mod:`voot.bench.store.format`). A row changed in place, even to
  bytes of the same size with its mtime restored, is a ``StoreError`` naming the file.
  The index (:mod:`voot.bench.store.index`) does not re-read unchanged files: it keys
  each one on its size, mtime, *ctime* and inode, and the kernel sets ctime to "now" on
  every write and every ``utime``, so restoring the mtime does not hide a change; a
  changed file is parsed and its checksum verified. :meth:`ResultStore.verify` re-hashes
  every file regardless (a full audit).
* **One writer.** A sweep (:func:`~voot.bench.sweep.engine.run_sweep`, so ``plan``, ``bbfo``,
  ``ablation``) and :func:`compact_store` write inside :meth:`ResultStore.writing`, which
  holds the store's writer lock (:mod:`voot.bench.store.lock`): a second writer of the
  same directory is refused with the holder's pid, host, start time and command, and a
  lock left by a killed writer is taken over (the kernel released it).
* **Old stores.** A store created before checksums (its header has no
  ``"row_checksum"``) still loads: its rows without a checksum are parsed and validated
  as before, and the rows written to it from now on carry one. In a store created with
  ``"row_checksum": "sha256"`` (every new store) a row without a checksum is corrupt.

Loading reads every row file (``json.loads`` on bytes; about 1 s per 100 MB of rows)
once, then keeps an index (a cache of parsed rows; the per-step lists named in
:data:`~voot.bench.store.format.CURVE_KEYS` are held there as NumPy arrays);
:func:`~voot.bench.store.format.curves` turns rows into a NumPy array for plotting.
:func:`compact_store` copies a store into a compact one (:mod:`voot.bench.store.compact`).
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import json
import os
from collections.abc import Collection, Iterator
from pathlib import Path
from typing import Any

from voot.bench.store.compact import (
    COMPACT_KEY,
    INTERPOLATED_KEY,
    CompactConfig,
    check_roundtrip,
    compact_row,
    expand_row,
)
from voot.bench.store.format import (
    CHECKSUM_KEY,
    FORMAT_NAME,
    HEADER_NAME,
    ROW_CHECKSUM,
    RUNS_DIR,
    SCHEMA_VERSION,
    Row,
    StoreError,
    check_row,
    row_bytes,
    verify_row_bytes,
    versions,
)
from voot.bench.store.index import load_indexed, write_atomic
from voot.bench.store.lock import WriterLock


class ResultStore:
    """A directory of result rows (see the module docstring for layout and guarantees).

    Args:
        path: the store directory.
        create: create the directory and header if ``path`` does not exist or is an
            empty directory. With ``create=False`` a missing store raises
            :class:`StoreError`.
        compact: create a *compact* store (:mod:`voot.bench.store.compact`): its header keeps
            this config and every row is written compact, whoever opens it later. For an
            existing store it must be None or the store's own config.

    Raises:
        StoreError: ``path`` is a file, a non-empty directory without header, or has a
            header of another format or schema; ``compact`` given for an existing store
            with another (or no) compact config.
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        *,
        create: bool = True,
        compact: CompactConfig | None = None,
    ) -> None:
        self.path = Path(path)
        self.header_path = self.path / HEADER_NAME
        self.runs_path = self.path / RUNS_DIR
        if self.path.exists() and not self.path.is_dir():
            raise StoreError(f"{self.path}: is a file, not a voot result store directory")
        if not self.header_path.exists():
            if self.path.is_dir() and any(self.path.iterdir()):
                raise StoreError(
                    f"{self.path}: directory is not empty and has no {HEADER_NAME}, so it is"
                    " not a voot result store; refusing to write into it (choose another"
                    " --out directory)"
                )
            if not create:
                raise StoreError(f"{self.path}: no voot result store here (no {HEADER_NAME})")
            self._create(compact)
        self.header = self._read_header()
        if compact is not None and compact != self.compact:
            what = (
                "a full-resolution store"
                if self.compact is None
                else f"compact with {self.compact}"
            )
            raise StoreError(
                f"{self.path}: this store is {what}, not compact with {compact}; use it"
                " without --compact, or convert it into a new store with voot-bench compact"
            )
        self.runs_path.mkdir(exist_ok=True)
        self._lock: WriterLock | None = None

    @contextlib.contextmanager
    def writing(self) -> Iterator[WriterLock]:
        """Hold the store's writer lock for the block (:class:`~voot.bench.store.lock.WriterLock`).

        Raises :class:`~voot.bench.store.lock.StoreBusyError` (a :class:`StoreError`)
        naming the holder if another process (or another :class:`ResultStore` object)
        writes the store. Nested use on this object reuses the lock it holds.
        """
        if self._lock is not None:
            yield self._lock
            return
        lock = WriterLock(self.path).acquire()
        self._lock = lock
        try:
            yield lock
        finally:
            self._lock = None
            lock.release()

    # ----- header ---------------------------------------------------------------------
    def _create(self, compact: CompactConfig | None = None) -> None:
        self.path.mkdir(parents=True, exist_ok=True)
        header = {
            "format": FORMAT_NAME,
            "schema": SCHEMA_VERSION,
            "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
            "created_by": dict(versions()),
            "row_checksum": ROW_CHECKSUM,
        }
        if compact is not None:
            header[COMPACT_KEY] = compact.to_dict()
        write_atomic(self.header_path, (json.dumps(header, indent=1) + "\n").encode())

    def _read_header(self) -> dict[str, Any]:
        try:
            header = json.loads(self.header_path.read_bytes())
        except (OSError, ValueError) as exc:
            raise StoreError(f"{self.header_path}: corrupt store header ({exc})") from None
        if not isinstance(header, dict) or header.get("format") != FORMAT_NAME:
            raise StoreError(
                f"{self.header_path}: not a voot result store header (expected format"
                f" {FORMAT_NAME!r}); refusing to use {self.path}"
            )
        schema = header.get("schema")
        if schema != SCHEMA_VERSION:
            raise StoreError(
                f"{self.header_path}: store schema {schema!r}, but this voot reads and writes"
                f" schema {SCHEMA_VERSION}; use a matching voot version or another directory"
            )
        checksum = header.get("row_checksum")
        if checksum not in (None, ROW_CHECKSUM):
            raise StoreError(
                f"{self.header_path}: row checksum {checksum!r}, this voot knows"
                f" {ROW_CHECKSUM!r} (or none, for stores written before checksums)"
            )
        #: Whether every row must carry a checksum (stores created with checksums).
        self.checksums_required = checksum == ROW_CHECKSUM
        #: How rows are compacted on write (None: a full-resolution store).
        self.compact: CompactConfig | None = None
        if COMPACT_KEY in header:
            try:
                self.compact = CompactConfig.from_dict(header[COMPACT_KEY])
            except ValueError as exc:
                raise StoreError(f"{self.header_path}: bad compact settings ({exc})") from None
        return header

    # ----- rows -----------------------------------------------------------------------
    def row_path(self, run_id: str) -> Path:
        """Where the row of ``run_id`` lives."""
        if not run_id or any(c in run_id for c in "/\\.") or run_id != run_id.strip():
            raise ValueError(f"invalid run id {run_id!r}")
        return self.runs_path / f"{run_id}.json"

    def write(self, row: Row) -> Path:
        """Atomically write ``row`` and return its path.

        An earlier *failed* row of the same run id is replaced. A finished (``"ok"``) row
        is never replaced: the store keeps it and the call returns its path. An existing
        file that does not parse raises :class:`StoreError` and is left as it is. A
        compact store writes the row compact (:func:`~voot.bench.store.compact.compact_row`), a
        full store writes a compact row expanded.
        """
        check_row(row)
        if self.compact is not None:
            row = compact_row({k: v for k, v in row.items() if k != INTERPOLATED_KEY}, self.compact)
        else:
            row = expand_row(row)
        path = self.row_path(str(row["run_id"]))
        if path.exists() and self._read_row(path)["status"] == "ok":
            return path
        write_atomic(path, row_bytes(row))
        return path

    def _read_row(self, path: Path) -> Row:
        """The row in ``path``: parsed, validated, checksum verified (its key dropped)."""
        try:
            data = path.read_bytes()
            row = json.loads(data)
        except (OSError, ValueError) as exc:
            raise StoreError(
                f"{path}: corrupt result row ({exc}); move or delete this file to rerun that run"
            ) from None
        check_row(row, str(path))
        verify_row_bytes(data, str(path), required=self.checksums_required)
        row.pop(CHECKSUM_KEY, None)
        if path.stem != row["run_id"]:
            raise StoreError(f"{path}: file name does not match its run_id {row['run_id']!r}")
        return row

    def row_files(self) -> list[Path]:
        """Row files in a stable (sorted) order, ignoring temporary files."""
        if not self.runs_path.is_dir():
            return []
        with os.scandir(self.runs_path) as it:
            names = sorted(
                e.name
                for e in it
                if e.name.endswith(".json") and not e.name.startswith(".") and e.is_file()
            )
        return [self.runs_path / n for n in names]

    def iter_rows(self, *, expand: bool = True) -> Iterator[Row]:
        """Every row read from its file, validated (compact rows expanded unless not
        ``expand``); raises :class:`StoreError` on the first corrupt file. (:meth:`load`
        is faster: it reuses the index.)"""
        for path in self.row_files():
            row = self._read_row(path)
            yield expand_row(row) if expand else row

    def load(
        self,
        kind: str | None = None,
        status: str | None = "ok",
        *,
        arrays: bool = False,
        expand: bool = True,
    ) -> list[Row]:
        """All rows of ``kind`` (any if None) with ``status`` (any if None), in file order.

        With ``arrays`` each curve (:data:`~voot.bench.store.format.CURVE_KEYS`: ``best_so_far`` and, when present,
        ``elapsed``, ``objects_left`` ...) is a read-only float64 array (no list copy).
        Compact rows come expanded to full length (:func:`~voot.bench.store.compact.expand_row`:
        step curves exact, cost curves interpolated and named in ``"interpolated"``), so
        readers see no difference; ``expand=False`` leaves them compact (e.g. to resume,
        which needs only run ids). Rows are read through the index (see
        :meth:`_load_indexed`), so only row files written or changed since the last load
        are parsed.
        """
        rows = [
            r
            for r in self._load_indexed(arrays)
            if (kind is None or r["kind"] == kind) and (status is None or r["status"] == status)
        ]
        if expand:
            rows = [expand_row(r, arrays=arrays) if COMPACT_KEY in r else r for r in rows]
        return rows

    def verify(self) -> int:
        """Re-read every row file and verify its checksum and layout; the number of rows.

        A full audit, independent of the index: it costs reading and hashing every byte
        of the store and parsing it (about 0.16 s for 1,000 rows of 1,000 steps). Raises
        :class:`StoreError` on the first bad file.
        """
        n = 0
        for path in self.row_files():
            self._read_row(path)
            n += 1
        return n

    def _load_indexed(self, arrays: bool) -> list[Row]:
        """Every row through the index (:func:`voot.bench.store.index.load_indexed`)."""
        return load_indexed(self.path, self.runs_path, self._read_row, arrays)

    def get(self, run_id: str) -> Row | None:
        """The row of ``run_id``, or None."""
        path = self.row_path(run_id)
        return expand_row(self._read_row(path)) if path.exists() else None

    def finished_ids(self, kind: str | None = None) -> set[str]:
        """Run ids with an ``"ok"`` row: a resumed sweep skips these."""
        rows = self.load(kind=kind, status="ok", arrays=True, expand=False)
        return {r["run_id"] for r in rows}

    def __len__(self) -> int:
        return len(self.row_files())

    def __repr__(self) -> str:
        return f"ResultStore({str(self.path)!r})"


def compact_store(
    src: str | os.PathLike[str],
    dst: str | os.PathLike[str],
    config: CompactConfig | None = None,
    *,
    run_ids: Collection[str] | None = None,
) -> dict[str, int]:
    """Copy every row of the store ``src`` (only those of ``run_ids``, if given) into the
    compact store ``dst``.

    ``dst`` is created compact with ``config`` (default :class:`CompactConfig()`) or, if it
    exists, must be a compact store of that config (an interrupted conversion resumes:
    rows already in ``dst`` are kept, the rest copied). Each compacted row is checked to
    expand back to its source (:func:`~voot.bench.store.compact.check_roundtrip`: step curves bit
    for bit, cost curves at the kept indices) before it is written; ``src`` is only read.
    Run ids are unchanged, so a sweep resumed on ``dst`` skips every copied run.

    Returns:
        ``{"rows": rows in src (of ``run_ids``), "copied": rows written now, "dst_rows": rows in dst after
        (more than ``rows`` when src was merged into a store with other runs),
        "src_bytes": size of src's row files, "dst_bytes": size of dst's}``.

    Raises:
        StoreError: ``src`` is not a store or has a corrupt row; ``dst`` is not a compact
            store of ``config``; ``src`` and ``dst`` are one directory.
    """
    source = ResultStore(src, create=False)
    config = config if config is not None else CompactConfig()
    if Path(dst).resolve() == source.path.resolve():
        raise StoreError(f"{dst}: the compact copy must go to another directory than {src}")
    target = ResultStore(dst, compact=config)
    with target.writing():
        rows, copied = _copy_rows(source, target, config, run_ids)

    def size(files: list[Path]) -> int:
        return sum(p.stat().st_size for p in files)

    dst_files = target.row_files()
    return {
        "rows": rows,
        "copied": copied,
        "dst_rows": len(dst_files),
        "src_bytes": size(source.row_files()),
        "dst_bytes": size(dst_files),
    }


def _copy_rows(
    source: ResultStore,
    target: ResultStore,
    config: CompactConfig,
    run_ids: Collection[str] | None = None,
) -> tuple[int, int]:
    """Copy the rows of ``source`` (of ``run_ids``, if given) not yet in ``target`` compact
    (see :func:`compact_store`); ``(rows in source of run_ids, rows copied)``."""
    done = {p.stem for p in target.row_files()}
    rows = copied = 0
    for row in source.iter_rows(expand=False):
        if run_ids is not None and row["run_id"] not in run_ids:
            continue
        rows += 1
        if row["run_id"] in done:
            continue
        if COMPACT_KEY in row:  # already compact: re-compacting would sample interpolations
            if source.compact != config:
                raise StoreError(
                    f"{source.path}: a compact store of {source.compact}; it can be copied"
                    f" only into a compact store of the same settings, not {config}"
                )
            target.write(row)
            copied += 1
            continue
        full = row
        small = compact_row(full, config)
        try:
            check_roundtrip(full, small)
        except ValueError as exc:  # pragma: no cover - a bug in the codecs
            raise StoreError(f"{source.path}: {exc}") from None
        target.write(small)
        copied += 1
    return rows, copied
