"""The row format of a result store: what one run's row holds, its on-disk names, how a
row becomes bytes (compact JSON ending in a SHA-256 checksum) and is checked when read
back, and :class:`StoreError`, which every store problem raises.

Every benchmark (the black-box sweep of ``voot-bench bbfo``, the tree-search sweeps of
``voot-bench plan``, local or on Ray) writes the same kind of *row*, one per run::

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

A row file ends with a ``"checksum"`` key: ``"sha256:"`` and the SHA-256 of the file's
bytes as they would be without that key (the row's compact JSON), so a reader verifies a
file from its bytes alone (:func:`row_bytes`, :func:`verify_row_bytes`). The store
itself (directory, header, atomic writes, resume) is :mod:`voot.bench.store.result_store`.
"""

from __future__ import annotations

import datetime as _dt
import functools
import hashlib
import importlib.metadata
import json
import platform
import time
import traceback
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.bench.store.compact import COMPACT_KEY, SAMPLED_KEYS, STEP_KEYS, check_compact

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
#: (:mod:`voot.bench.store.compact`) stores them in a row's ``"compact"`` object instead.
CURVE_KEYS = (*STEP_KEYS, *SAMPLED_KEYS)
#: Curves of whole counts: read back as lists of ``int`` (the index holds float64).
INTEGER_CURVE_KEYS = ("calls_curve",)

Row = dict[str, Any]


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
