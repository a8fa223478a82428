"""The files under a result store's rows: atomic writes and the index.

* **Atomic writes** (:func:`write_atomic`): every file of a store (header, rows, index)
  is written to a hidden temporary file in its folder, flushed and fsynced, then moved
  into place with :func:`os.replace`, so a reader sees the whole file or none.
* **The index** (:data:`INDEX_NAME`, :func:`load_indexed`): a cache of every parsed row,
  its curves (:data:`~voot.bench.store.format.CURVE_KEYS`) as NumPy arrays, keyed by its
  file's (size, mtime, ctime, inode). A load parses only the row files written or
  changed since the index was written and rewrites the index atomically; the row files
  stay the source of truth (a missing or unreadable index is rebuilt, at the cost of one
  slow load). ctime is in the key because nobody but the kernel sets it: an in-place
  rewrite whose mtime was put back with ``utime`` still changes it.
"""

from __future__ import annotations

import io
import json
import math
import os
import tempfile
import time
import zipfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.bench.store.format import CURVE_KEYS, INTEGER_CURVE_KEYS, Row

#: Cache of parsed rows (derived data, rebuilt when missing or unreadable).
INDEX_NAME = ".index-v2.npz"
#: Files changed less than this long (ns) before the index scan are read again at the
#: next load (see :func:`read_index`): 2 s covers the coarsest file
#: timestamps (FAT's 2 s; ext4 and tmpfs tick in milliseconds).
RACY_NS = 2_000_000_000

_EMPTY: NDArray[np.float64] = np.empty(0, dtype=np.float64)


def _to_list(key: str, curve: NDArray[np.float64]) -> list[float | None]:
    """A curve back as the list its row file holds (NaN -> None except in best_so_far)."""
    if key in INTEGER_CURVE_KEYS and not np.isnan(curve).any():
        return [int(v) for v in curve.tolist()]  # type: ignore[misc]
    values: list[float | None] = curve.tolist()
    if key != "best_so_far" and np.isnan(curve).any():
        values = [None if v is not None and math.isnan(v) else v for v in values]
    return values


def _current_umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


_UMASK = _current_umask()


def write_atomic(path: Path, data: bytes) -> None:
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


#: One index entry: (file name, its stat key, the row without its curves, {curve: array}).
Entry = tuple[str, list[int], Row, dict[str, NDArray[np.float64]]]


def scan_rows(runs_path: Path) -> list[tuple[str, tuple[int, int, int, int]]]:
    """(file name, (size, mtime_ns, ctime_ns, inode)) of every row file in ``runs_path``,
    by name.

    ctime is in the key because nobody but the kernel sets it: an in-place rewrite
    whose mtime was put back with ``utime`` still changes it."""
    if not runs_path.is_dir():
        return []
    out = []
    with os.scandir(runs_path) as it:
        for e in it:
            if e.name.endswith(".json") and not e.name.startswith(".") and e.is_file():
                st = e.stat()
                out.append((e.name, (st.st_size, st.st_mtime_ns, st.st_ctime_ns, st.st_ino)))
    out.sort()
    return out


def read_index(
    store_path: Path,
) -> dict[str, tuple[list[int], Row, dict[str, NDArray[np.float64]]]]:
    """The index of the store at ``store_path`` as ``name -> (stat, row without curves,
    {curve key: array})``; empty if it is missing or unreadable (it is derived data and
    is then rebuilt).

    Entries of files whose ctime lies within :data:`RACY_NS` of the scan that built
    the index are left out, so that those files are read again: a rewrite right after
    that scan may carry the very same ctime on a file system with coarse timestamps
    (git's "racily clean" entries)."""
    path = store_path / INDEX_NAME
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
    except (OSError, ValueError, KeyError, TypeError, IndexError, EOFError, zipfile.BadZipFile):
        # a cut or garbled index (a crash of a file system without atomic renames, an
        # edit): np.load raises EOFError for an empty file, BadZipFile for a cut one
        return {}


def write_index(store_path: Path, entries: list[Entry], scanned_ns: int) -> None:
    """Write the index of ``entries`` (the scan began at ``scanned_ns``) atomically; a
    store that cannot be written (e.g. a read-only copy) keeps its old index or none."""
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
        write_atomic(store_path / INDEX_NAME, buf.getvalue())
    except OSError:  # e.g. a read-only copy of a store: loading still works
        pass


def load_indexed(
    store_path: Path, runs_path: Path, read_row: Callable[[Path], Row], arrays: bool
) -> list[Row]:
    """Every row of the store, via the index (:data:`INDEX_NAME`): a cache of every parsed
    row keyed by its file's (size, mtime, ctime, inode). Unchanged files come from the
    cache; new or changed ones are read with ``read_row`` (checksum-verified, parsed and
    validated), and the index is rewritten atomically (an index of an older voot, keyed
    without ctime, is rebuilt once). Row files stay the source of truth: deleting the
    index only costs one slow load. With ``arrays`` the curves are read-only float64
    arrays, else lists as in the row files."""
    index = read_index(store_path)
    entries: list[Entry] = []
    changed = False
    scanned_ns = time.time_ns()
    for name, stat in scan_rows(runs_path):
        cached = index.get(name)
        if cached is not None and list(cached[0]) == list(stat):
            entries.append((name, list(stat), cached[1], cached[2]))
            continue
        row = read_row(runs_path / name)
        found = {}
        for k in CURVE_KEYS:
            if isinstance(row.get(k), list):
                curve = np.array(row.pop(k), dtype=np.float64)  # None -> NaN
                curve.setflags(write=False)
                found[k] = curve
        entries.append((name, list(stat), row, found))
        changed = True
    if changed or len(entries) != len(index):
        write_index(store_path, entries, scanned_ns)
    out = []
    for _, _, row, found in entries:
        full = dict(row)
        for k, curve in found.items():
            full[k] = curve if arrays else _to_list(k, curve)
        out.append(full)
    return out
