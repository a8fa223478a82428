"""The result store: one JSON file per finished run, in a directory with a header.

Every benchmark (the black-box sweep of ``voot-bench bbfo`` now, the tree-search sweeps
of ``voot-bench plan`` later, local or on Ray) writes the same kind of *row*, one per run::

    {
      "schema": 1,
      "run_id": "3f1c...",            # stable hash of kind + config (the seed is in config)
      "kind": "bbfo",                 # "bbfo" | "plan" | ...
      "config": {"function": "shekel", "dim": 20, "method": "voo",
                 "params": {"omega": 0.001}, "budget": 5000, "seed": 7, ...},
      "status": "ok",                 # or "failed"
      "error": null,                  # "ValueError: ..." when failed
      "wall_time": 2.61,              # seconds spent in the run
      "best_so_far": [0.01, 0.01, ...],  # best value after every evaluation
      "versions": {"voot": "0.1.0", "numpy": "2.4.0", "python": "3.11.9"},
      "finished_at": "2025-01-01T12:00:00+00:00",
      ...                             # optional extras (best_x, traceback, ...)
    }

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
  parse, raises :class:`StoreError` naming the file, before anything is written.
  Nothing in this module ever deletes or rewrites a file it did not just create.

* **Checksummed rows.** Every row file ends with a ``"checksum"`` key: ``"sha256:"`` and
  the SHA-256 of the file's bytes as they would be without that key (the row's compact
  JSON), verified on every parse of the file (:func:`row_bytes`, :func:`verify_row_bytes`).
  A row changed in place, even to bytes of the same size with its mtime restored, is a
  :class:`StoreError` naming the file. The index (below) does not re-read unchanged
  files: it keys each one on its size, mtime, *ctime* and inode, and the kernel sets
  ctime to "now" on every write and every ``utime``, so restoring the mtime does not
  hide a change; a changed file is parsed and its checksum verified.
  :meth:`ResultStore.verify` re-hashes every file regardless (a full audit).
* **Old stores.** A store created before checksums (its header has no
  ``"row_checksum"``) still loads: its rows without a checksum are parsed and validated
  as before, and the rows written to it from now on carry one. In a store created with
  ``"row_checksum": "sha256"`` (every new store) a row without a checksum is corrupt.

Loading reads every row file (``json.loads`` on bytes; about 1 s per 100 MB of rows)
once, then keeps an index (a cache of parsed rows; the per-step lists named in
:data:`CURVE_KEYS` are held there as NumPy arrays); :func:`curves` turns rows into a
NumPy array for plotting.
"""

from __future__ import annotations

import datetime as _dt
import functools
import hashlib
import importlib.metadata
import io
import json
import math
import os
import platform
import tempfile
import time
import traceback
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.bench.compact import (
    COMPACT_KEY,
    INTERPOLATED_KEY,
    SAMPLED_KEYS,
    STEP_KEYS,
    CompactConfig,
    check_compact,
    check_roundtrip,
    compact_row,
    expand_row,
)

#: Name written in the header; anything else is a foreign directory.
FORMAT_NAME = "voot-results"
#: Version of the header and row layout. Bump on incompatible changes.
SCHEMA_VERSION = 1
#: Header file name inside the store directory.
HEADER_NAME = "voot-results.json"
#: The row checksum of new stores (recorded in the header as ``row_checksum``).
ROW_CHECKSUM = "sha256"
#: Row key holding the checksum, always the last key of a row file.
CHECKSUM_KEY = "checksum"
_CHECKSUM_HEAD = b',"checksum":"sha256:'
_CHECKSUM_TAIL = b'"}\n'
_CHECKSUM_LEN = len(_CHECKSUM_HEAD) + 64 + len(_CHECKSUM_TAIL)
#: Cache of parsed rows (derived data, rebuilt when missing or unreadable).
INDEX_NAME = ".index-v2.npz"
#: Files changed less than this long (ns) before the index scan are read again at the
#: next load (see :meth:`ResultStore._read_index`): 2 s covers the coarsest file
#: timestamps (FAT's 2 s; ext4 and tmpfs tick in milliseconds).
RACY_NS = 2_000_000_000
#: Folder with one ``<run_id>.json`` per finished run.
RUNS_DIR = "runs"
#: Keys every row must have.
REQUIRED_KEYS = (
    "schema",
    "run_id",
    "kind",
    "config",
    "status",
    "wall_time",
    "best_so_far",
    "versions",
)
#: Allowed values of a row's ``status``.
STATUSES = ("ok", "failed")
#: Row keys holding one number per step (per evaluation or simulation). The index keeps
#: them as float64 arrays; ``best_so_far`` is required, the others optional (``elapsed``:
#: seconds after every simulation, ``cpu_elapsed`` the same in CPU time; ``calls_curve``:
#: simulator calls so far; ``objects_left``: objects still to handle at the best
#: leaf, ``null`` where unknown, which becomes NaN in arrays). A compact store
#: (:mod:`voot.bench.compact`) stores them in a row's ``"compact"`` object instead.
CURVE_KEYS = (*STEP_KEYS, *SAMPLED_KEYS)
#: Curves of whole counts: read back as lists of ``int`` (the index holds float64).
INTEGER_CURVE_KEYS = ("calls_curve",)

Row = dict[str, Any]

_EMPTY: NDArray[np.float64] = np.empty(0, dtype=np.float64)


def _to_list(key: str, curve: NDArray[np.float64]) -> list[float | None]:
    """A curve back as the list its row file holds (NaN -> None except in best_so_far)."""
    if key in INTEGER_CURVE_KEYS and not np.isnan(curve).any():
        return [int(v) for v in curve.tolist()]  # type: ignore[misc]
    values: list[float | None] = curve.tolist()
    if key != "best_so_far" and np.isnan(curve).any():
        values = [None if v is not None and math.isnan(v) else v for v in values]
    return values


class StoreError(ValueError):
    """A result store (or one of its files) is corrupt, foreign or incompatible."""


def _canonical(obj: Any) -> str:
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False)


def make_run_id(kind: str, config: Mapping[str, Any]) -> str:
    """Stable id of a run: the first 20 hex digits of SHA-256 of ``kind`` and ``config``.

    ``config`` must be JSON-serialisable and include the seed. Keys are sorted, so the id
    does not depend on dict order, Python's hash seed or the process.
    """
    return hashlib.sha256(_canonical({"kind": kind, "config": dict(config)}).encode()).hexdigest()[
        :20
    ]


@functools.cache
def versions() -> dict[str, str]:
    """Versions recorded with every row: voot, numpy, python, and scipy and cma if installed.

    Read from the package metadata, so recording them imports nothing heavy.
    """
    import voot

    out = {"voot": voot.__version__, "numpy": np.__version__, "python": platform.python_version()}
    for name in ("scipy", "cma"):
        try:
            out[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:  # pragma: no cover - core dependencies
            continue
    return out


def make_row(
    kind: str,
    config: Mapping[str, Any],
    *,
    status: str,
    wall_time: float,
    best_so_far: Sequence[float] | NDArray[np.float64],
    error: str | None = None,
    **extra: Any,
) -> Row:
    """Assemble a row with its run id, versions and finish time (see the module docstring)."""
    if status not in STATUSES:
        raise ValueError(f"status must be one of {STATUSES}, got {status!r}")
    row: Row = {
        "schema": SCHEMA_VERSION,
        "run_id": make_run_id(kind, config),
        "kind": kind,
        "config": dict(config),
        "status": status,
        "error": error,
        "wall_time": float(wall_time),
        "best_so_far": [float(v) for v in np.asarray(best_so_far, dtype=np.float64)],
        "versions": dict(versions()),
        "finished_at": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
    }
    row.update(extra)
    return row


def failed_row(
    spec: Any,
    error: str,
    *,
    wall_time: float = 0.0,
    best_so_far: Sequence[float] = (),
    **extra: Any,
) -> Row:
    """The row of a run that failed: status ``"failed"``, with what it had recorded."""
    return make_row(
        spec.kind,
        spec.config(),
        status="failed",
        wall_time=wall_time,
        best_so_far=list(best_so_far),
        error=error,
        **extra,
    )


def exception_row(
    spec: Any, exc: Exception, start: float, best: Sequence[float], **extra: Any
) -> Row:
    """The row of a run that raised ``exc`` (called inside its ``except`` block)."""
    return failed_row(
        spec,
        f"{type(exc).__name__}: {exc}",
        wall_time=time.perf_counter() - start,
        best_so_far=best,
        traceback=traceback.format_exc(limit=20),
        **extra,
    )


def row_bytes(row: Row) -> bytes:
    """The bytes of ``row``'s file: its compact JSON with the checksum as the last key.

    The checksum is ``sha256`` of the compact JSON without it (``{...}``), so a reader
    verifies a file from its bytes alone, with no re-serialisation: strip the last key,
    close the brace, hash (:func:`verify_row_bytes`). The file stays plain JSON.
    """
    body = {k: v for k, v in row.items() if k != CHECKSUM_KEY}
    payload = json.dumps(body, separators=(",", ":")).encode()
    digest = hashlib.sha256(payload).hexdigest().encode()
    return payload[:-1] + _CHECKSUM_HEAD + digest + _CHECKSUM_TAIL


def verify_row_bytes(data: bytes, source: str = "row", *, required: bool = True) -> bool:
    """Check the checksum of a row file's bytes; True if it had one.

    Raises :class:`StoreError` naming ``source`` if the checksum does not match the
    bytes, or if there is none and ``required`` (a row of a checksummed store). A file
    without a checksum (an older store's row) passes when not ``required``.
    """
    head = len(data) - _CHECKSUM_LEN
    if head <= 0 or data[head : head + len(_CHECKSUM_HEAD)] != _CHECKSUM_HEAD:
        if required:
            raise StoreError(
                f"{source}: result row without its checksum (rows of this store carry one);"
                " it was changed or truncated: move or delete this file to rerun that run"
            )
        return False
    if not data.endswith(_CHECKSUM_TAIL):
        raise StoreError(f"{source}: result row with a malformed checksum")
    stored = data[head + len(_CHECKSUM_HEAD) : len(data) - len(_CHECKSUM_TAIL)]
    actual = hashlib.sha256(data[:head] + b"}").hexdigest().encode()
    if stored != actual:
        raise StoreError(
            f"{source}: result row changed since it was written (checksum"
            f" {stored.decode(errors='replace')[:12]}..., content {actual.decode()[:12]}...);"
            " move or delete this file to rerun that run"
        )
    return True


def check_row(row: Any, source: str = "row") -> Row:
    """Return ``row`` if it has the row layout, else raise :class:`StoreError` naming ``source``."""
    if not isinstance(row, dict):
        raise StoreError(f"{source}: a row must be a JSON object, got {type(row).__name__}")
    compact = COMPACT_KEY in row
    missing = [k for k in REQUIRED_KEYS if k not in row and not (compact and k == "best_so_far")]
    if missing:
        raise StoreError(f"{source}: not a voot result row (missing keys {missing})")
    if row["schema"] != SCHEMA_VERSION:
        raise StoreError(
            f"{source}: row schema {row['schema']!r}, this voot reads schema {SCHEMA_VERSION}"
        )
    if row["status"] not in STATUSES:
        raise StoreError(f"{source}: status {row['status']!r} is not one of {STATUSES}")
    if compact:
        try:
            check_compact(row[COMPACT_KEY])
        except ValueError as exc:
            raise StoreError(
                f"{source}: corrupt compact result row ({exc}); move or delete this file to"
                " rerun that run"
            ) from None
        if not isinstance(row["config"], dict):
            raise StoreError(f"{source}: 'config' must be an object")
        return row
    if not isinstance(row["config"], dict) or not isinstance(row["best_so_far"], list):
        raise StoreError(f"{source}: 'config' must be an object and 'best_so_far' a list")
    return row


def _current_umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


_UMASK = _current_umask()


def _write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` via a fsynced temporary file and :func:`os.replace`."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        os.chmod(tmp, 0o666 & ~_UMASK)  # mkstemp makes 0600; rows are ordinary files
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    try:  # make the rename itself durable
        dir_fd = os.open(path.parent, os.O_RDONLY)
    except OSError:  # pragma: no cover - e.g. platforms without directory fds
        return
    try:
        os.fsync(dir_fd)
    except OSError:  # pragma: no cover
        pass
    finally:
        os.close(dir_fd)


class ResultStore:
    """A directory of result rows (see the module docstring for layout and guarantees).

    Args:
        path: the store directory.
        create: create the directory and header if ``path`` does not exist or is an
            empty directory. With ``create=False`` a missing store raises
            :class:`StoreError`.
        compact: create a *compact* store (:mod:`voot.bench.compact`): its header keeps
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
        _write_atomic(self.header_path, (json.dumps(header, indent=1) + "\n").encode())

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
        compact store writes the row compact (:func:`~voot.bench.compact.compact_row`), a
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
        _write_atomic(path, row_bytes(row))
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

        With ``arrays`` each curve (:data:`CURVE_KEYS`: ``best_so_far`` and, when present,
        ``elapsed``, ``objects_left`` ...) is a read-only float64 array (no list copy).
        Compact rows come expanded to full length (:func:`~voot.bench.compact.expand_row`:
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

    # ----- index: a cache of parsed rows -----------------------------------------------
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

    def _scan(self) -> list[tuple[str, tuple[int, int, int, int]]]:
        """(file name, (size, mtime_ns, ctime_ns, inode)) of every row file, by name.

        ctime is in the key because nobody but the kernel sets it: an in-place rewrite
        whose mtime was put back with ``utime`` still changes it."""
        if not self.runs_path.is_dir():
            return []
        out = []
        with os.scandir(self.runs_path) as it:
            for e in it:
                if e.name.endswith(".json") and not e.name.startswith(".") and e.is_file():
                    st = e.stat()
                    out.append((e.name, (st.st_size, st.st_mtime_ns, st.st_ctime_ns, st.st_ino)))
        out.sort()
        return out

    def _read_index(self) -> dict[str, tuple[list[int], Row, dict[str, NDArray[np.float64]]]]:
        """The index as ``name -> (stat, row without curves, {curve key: array})``; empty if
        it is missing or unreadable (it is derived data and is then rebuilt).

        Entries of files whose ctime lies within :data:`RACY_NS` of the scan that built
        the index are left out, so that those files are read again: a rewrite right after
        that scan may carry the very same ctime on a file system with coarse timestamps
        (git's "racily clean" entries)."""
        path = self.path / INDEX_NAME
        try:
            with np.load(path, allow_pickle=False) as data:
                meta = json.loads(data["meta"].tobytes())
                columns = {k: (data[f"offsets_{k}"], data[f"values_{k}"]) for k in CURVE_KEYS}
                racy_from = int(data["scanned_ns"][0]) - RACY_NS
            for offsets, values in columns.values():
                if len(meta) + 1 != offsets.size or offsets[-1] != values.size:
                    return {}
                values.setflags(write=False)
            out = {}
            for i, m in enumerate(meta):
                arrays = {}
                for k in m["curves"]:
                    offsets, values = columns[k]
                    arrays[k] = values[offsets[i] : offsets[i + 1]]
                if m["stat"][2] < racy_from:
                    out[m["file"]] = (m["stat"], m["row"], arrays)
            return out
        except (OSError, ValueError, KeyError, TypeError):
            return {}

    def _write_index(
        self,
        entries: list[tuple[str, list[int], Row, dict[str, NDArray[np.float64]]]],
        scanned_ns: int,
    ) -> None:
        meta = [
            {"file": name, "stat": stat, "row": row, "curves": sorted(arrays)}
            for name, stat, row, arrays in entries
        ]
        columns: dict[str, Any] = {}
        for k in CURVE_KEYS:
            parts = [arrays.get(k, _EMPTY) for *_, arrays in entries]
            offsets = np.zeros(len(entries) + 1, dtype=np.int64)
            np.cumsum([p.size for p in parts], out=offsets[1:])
            columns[f"offsets_{k}"] = offsets
            columns[f"values_{k}"] = np.concatenate(parts) if parts else _EMPTY
        buf = io.BytesIO()
        np.savez(
            buf,
            meta=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8),
            scanned_ns=np.array([scanned_ns], dtype=np.int64),
            **columns,
        )
        try:
            _write_atomic(self.path / INDEX_NAME, buf.getvalue())
        except OSError:  # e.g. a read-only copy of a store: loading still works
            pass

    def _load_indexed(self, arrays: bool) -> list[Row]:
        """Rows via the index (:data:`INDEX_NAME`): a cache of every parsed row keyed by its
        file's (size, mtime, ctime, inode). Unchanged files come from the cache; new or
        changed ones are checksum-verified, parsed and validated, and the index is rewritten
        atomically (an index of an older voot, keyed without ctime, is rebuilt once). Row files
        stay the source of truth: deleting the index only costs one slow load."""
        index = self._read_index()
        entries: list[tuple[str, list[int], Row, dict[str, NDArray[np.float64]]]] = []
        changed = False
        scanned_ns = time.time_ns()
        for name, stat in self._scan():
            cached = index.get(name)
            if cached is not None and list(cached[0]) == list(stat):
                entries.append((name, list(stat), cached[1], cached[2]))
                continue
            row = self._read_row(self.runs_path / name)
            found = {}
            for k in CURVE_KEYS:
                if isinstance(row.get(k), list):
                    curve = np.array(row.pop(k), dtype=np.float64)  # None -> NaN
                    curve.setflags(write=False)
                    found[k] = curve
            entries.append((name, list(stat), row, found))
            changed = True
        if changed or len(entries) != len(index):
            self._write_index(entries, scanned_ns)
        out = []
        for _, _, row, found in entries:
            full = dict(row)
            for k, curve in found.items():
                full[k] = curve if arrays else _to_list(k, curve)
            out.append(full)
        return out

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
) -> dict[str, int]:
    """Copy every row of the store ``src`` into the compact store ``dst``.

    ``dst`` is created compact with ``config`` (default :class:`CompactConfig()`) or, if it
    exists, must be a compact store of that config (an interrupted conversion resumes:
    rows already in ``dst`` are kept, the rest copied). Each compacted row is checked to
    expand back to its source (:func:`~voot.bench.compact.check_roundtrip`: step curves bit
    for bit, cost curves at the kept indices) before it is written; ``src`` is only read.
    Run ids are unchanged, so a sweep resumed on ``dst`` skips every copied run.

    Returns:
        ``{"rows": rows in src, "copied": rows written now, "src_bytes": size of src's row
        files, "dst_bytes": size of dst's}``.

    Raises:
        StoreError: ``src`` is not a store or has a corrupt row; ``dst`` is not a compact
            store of ``config``; ``src`` and ``dst`` are one directory.
    """
    source = ResultStore(src, create=False)
    config = config if config is not None else CompactConfig()
    if Path(dst).resolve() == source.path.resolve():
        raise StoreError(f"{dst}: the compact copy must go to another directory than {src}")
    target = ResultStore(dst, compact=config)
    done = {p.stem for p in target.row_files()}
    rows = copied = 0
    for row in source.iter_rows(expand=False):
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

    def size(store: ResultStore) -> int:
        return sum(p.stat().st_size for p in store.row_files())

    return {"rows": rows, "copied": copied, "src_bytes": size(source), "dst_bytes": size(target)}


def curves(rows: Iterable[Row]) -> NDArray[np.float64]:
    """Stack the rows' best-so-far lists into an ``(n_rows, max_len)`` array.

    Shorter curves (smaller budgets) are padded with NaN.
    """
    lists = [r["best_so_far"] for r in rows]
    if not lists:
        return np.empty((0, 0))
    width = max(len(c) for c in lists)
    if all(len(c) == width for c in lists):
        return np.array(lists, dtype=np.float64).reshape(len(lists), width)
    out = np.full((len(lists), width), np.nan)
    for i, c in enumerate(lists):
        out[i, : len(c)] = c
    return out


def synthetic_plan_row(i: int, length: int, rng: np.random.Generator) -> Row:
    """A plan-like row for the store benchmarks: step curves (``best_so_far``,
    ``objects_left``) that change at a few dozen simulations, and cost curves
    (``elapsed``, ``cpu_elapsed``, ``calls_curve``) that rise at every one."""
    jumps = rng.random(length) < min(1.0, 40.0 / length)
    jumps[0] = True
    best = np.cumsum(np.where(jumps, rng.random(length), 0.0)) - 2.0
    left = np.maximum(20 - np.cumsum(jumps), 0).astype(np.float64)
    step = rng.uniform(0.002, 0.02, length)
    elapsed = np.round(np.cumsum(step), 6)
    config = {"problem": "conveyor_v1", "planner": "voot", "simulations": length, "seed": i}
    return make_row(
        "plan",
        config,
        status="ok",
        wall_time=float(elapsed[-1]),
        best_so_far=best,
        objects_left=left.tolist(),
        elapsed=elapsed.tolist(),
        cpu_elapsed=np.round(0.97 * elapsed, 6).tolist(),
        calls_curve=np.cumsum(rng.integers(1, 60, length)).tolist(),
    )


def time_load(
    n_rows: int = 1000,
    length: int = 1000,
    repeats: int = 3,
    path: str | None = None,
    *,
    plan: bool = False,
    compact: CompactConfig | None = None,
) -> dict[str, float]:
    """Seconds to :meth:`ResultStore.load` a store of ``n_rows`` rows, cold and warm.

    Builds the store in a temporary directory (or in ``path``, which must not exist),
    each row a ``bbfo``-like run with a ``length``-step ``best_so_far`` curve. *Cold* is
    the first load (every row file parsed, the index written), *warm* the best of
    ``repeats`` later loads (through the index; ``warm_arrays`` the same with
    ``arrays=True``, as ``voot-bench plot`` reads), of a store at rest (rows written
    within :data:`RACY_NS` of a load are re-read, so the benchmark waits that long
    after writing, outside the timings). Also returns ``write`` (seconds to
    write all rows), ``verify`` (best :meth:`ResultStore.verify`, the full audit) and
    ``mb`` (megabytes of row files).

    With ``plan`` the rows are plan-like (:func:`synthetic_plan_row`: five curves of
    ``length`` entries); with ``compact`` the store is a compact one of that config (its
    loads include expanding every row to full length).
    """
    import shutil

    if n_rows < 1 or length < 1 or repeats < 1:
        raise ValueError("n_rows, length and repeats must be >= 1")
    root = Path(tempfile.mkdtemp(prefix="voot-store-bench-")) if path is None else Path(path)
    try:
        store = ResultStore(root / "store", compact=compact)
        rng = np.random.default_rng(0)
        t0 = time.perf_counter()
        for i in range(n_rows):
            if plan:
                store.write(synthetic_plan_row(i, length, rng))
                continue
            curve = np.maximum.accumulate(rng.standard_normal(length))
            config = {"function": "shekel", "dim": 20, "method": "voo", "seed": i}
            store.write(make_row("bbfo", config, status="ok", wall_time=1.0, best_so_far=curve))
        written = time.perf_counter() - t0
        size = sum(p.stat().st_size for p in store.row_files())
        time.sleep(RACY_NS / 1e9)  # a store at rest: no row is "racily" new at its first load
        t0 = time.perf_counter()
        rows = ResultStore(root / "store", create=False).load()
        cold = time.perf_counter() - t0
        assert len(rows) == n_rows
        warm = warm_arrays = audit = math.inf
        for _ in range(repeats):
            t0 = time.perf_counter()
            ResultStore(root / "store", create=False).load()
            warm = min(warm, time.perf_counter() - t0)
            t0 = time.perf_counter()
            ResultStore(root / "store", create=False).load(arrays=True)
            warm_arrays = min(warm_arrays, time.perf_counter() - t0)
        verify = getattr(store, "verify", None)
        for _ in range(repeats if callable(verify) else 0):
            t0 = time.perf_counter()
            verify()  # type: ignore[misc]
            audit = min(audit, time.perf_counter() - t0)
        return {
            "write": written,
            "cold": cold,
            "warm": warm,
            "warm_arrays": warm_arrays,
            "verify": audit,
            "mb": size / 1e6,
        }
    finally:
        if path is None:
            shutil.rmtree(root, ignore_errors=True)
