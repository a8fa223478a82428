"""A result store as a table: a pandas DataFrame and a Parquet file, one row per run.

For analysis outside voot (pandas, polars, DuckDB, R's arrow, a spreadsheet of the
finals) a store (:class:`~voot.bench.store.result_store.ResultStore`) becomes a table:

* one **row per run**, in the store's order (by run id), compact rows expanded;
* the run's identity and outcome first: ``run_id``, ``kind``, ``status``, ``error``,
  ``wall_time``, ``finished_at``;
* the **config flattened**: one column per config key (``problem``, ``planner``,
  ``seed``, ``simulations`` ... or ``function``, ``dim``, ``method``, ``budget`` ...); a
  config key that is also a row key is prefixed ``config_``;
* the **curves** (:data:`~voot.bench.store.format.CURVE_KEYS`: ``best_so_far``,
  ``objects_left``, ``elapsed``, ``cpu_elapsed``, ``calls_curve``) as list columns of
  float64, one number per step (an unknown value, ``null`` in the row, is NaN); a run
  without a curve has a null there;
* every other row key (``best_return``, ``simulator_calls``, ``versions`` ...) as a
  column, sorted by name.

A column's type follows its values over all the selected runs: numbers are float64
(int64 when every value is a whole ``int`` and none is missing), strings are strings,
booleans booleans, lists of numbers list columns of float64, lists of strings list
columns of strings; anything else (objects such as ``params``, ``env_kwargs``,
``versions``; nested lists; a mix of types) is its canonical JSON text (keys sorted), so
``json.loads`` gives it back. The Parquet file has exactly these columns and types, and
the same store always gives the same bytes (no timestamps or paths are written).

pandas and pyarrow are the ``bench`` extra; they are imported when a table is made, and
without them :func:`require_table_libs` raises an :class:`ImportError` naming the extra.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voot.bench.store.format import CURVE_KEYS, STATUSES, Row, StoreError
from voot.bench.store.result_store import ResultStore

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa

#: How to install what a table needs.
INSTALL_HINT = 'pip install -e ".[bench]"  (or: pip install "voot[bench]")'
#: The leading columns, in this order (every row has them).
HEAD_COLUMNS: tuple[str, ...] = ("run_id", "kind", "status", "error", "wall_time", "finished_at")
#: Row keys that are not columns: ``config`` is flattened, ``schema`` is the same for all.
_NOT_COLUMNS = frozenset({"config", "schema"})
#: Prefix of a config key that is also a row key.
CONFIG_PREFIX = "config_"
#: Parquet compression of :func:`write_parquet` (deterministic, read by every Arrow).
COMPRESSION = "zstd"

#: Column types: their pandas dtype (None: object) and their Arrow type's name.
_TYPES: dict[str, tuple[str | None, str]] = {
    "int": ("int64", "int64"),
    "float": ("float64", "float64"),
    "bool": ("boolean", "bool_"),
    "str": (None, "string"),
    "floats": (None, "float64"),  # list column
    "strs": (None, "string"),  # list column
    "json": (None, "string"),
}


def require_table_libs() -> tuple[Any, Any]:
    """The ``pandas`` and ``pyarrow`` modules, or an :class:`ImportError` naming the extra."""
    try:
        import pandas
        import pyarrow
    except ImportError as exc:
        raise ImportError(
            f"a store as a table needs pandas and pyarrow, which are not installed ({exc});"
            f" install the bench extra: {INSTALL_HINT}"
        ) from None
    return pandas, pyarrow


@dataclass(frozen=True)
class Column:
    """One column of a store's table: its name, type (a key of ``_TYPES``) and values
    (Python objects, None where missing)."""

    name: str
    type: str
    values: list[Any]


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


def _type_of(values: Sequence[Any], curve: bool) -> str:
    """The column type of ``values`` (see the module docstring)."""
    present = [v for v in values if v is not None]
    if curve and all(isinstance(v, list) for v in present):
        return "floats"
    if not present:
        return "str"
    if all(isinstance(v, bool) for v in present):
        return "bool"
    if all(isinstance(v, int) and not isinstance(v, bool) for v in present):
        return "int" if len(present) == len(values) else "float"
    if all(_is_number(v) for v in present):
        return "float"
    if all(isinstance(v, str) for v in present):
        return "str"
    if all(isinstance(v, list) for v in present):
        items = [x for v in present for x in v]
        if all(x is None or _is_number(x) for x in items):
            return "floats"
        if all(isinstance(x, str) for x in items):
            return "strs"
    return "json"


def _cell(value: Any, kind: str) -> Any:
    """``value`` as the column type ``kind`` holds it."""
    if value is None:
        return float("nan") if kind == "float" else None
    if kind == "float":
        return float(value)
    if kind == "floats":
        return [float("nan") if x is None else float(x) for x in value]
    if kind == "json":
        return json.dumps(value, sort_keys=True, separators=(",", ":"))
    return value


def _names(rows: Sequence[Row]) -> tuple[list[str], list[str], list[str]]:
    """The config keys (in order of first appearance), the curves present and the other
    row keys (sorted) of ``rows``."""
    config: dict[str, None] = {}
    extra: set[str] = set()
    for row in rows:
        config.update(dict.fromkeys(row["config"]))
        extra.update(row)
    curves = [k for k in CURVE_KEYS if k in extra]
    rest = sorted(extra - set(HEAD_COLUMNS) - set(CURVE_KEYS) - _NOT_COLUMNS)
    return list(config), curves, rest


def table_columns(rows: Sequence[Row]) -> list[Column]:
    """The columns of the table of ``rows`` (see the module docstring), in order."""
    config, curves, rest = _names(rows)
    row_keys = {*HEAD_COLUMNS, *curves, *rest}
    sources: list[tuple[str, list[Any], bool]] = [
        (k, [r.get(k) for r in rows], False) for k in HEAD_COLUMNS
    ]
    sources += [
        (CONFIG_PREFIX + k if k in row_keys else k, [r["config"].get(k) for r in rows], False)
        for k in config
    ]
    sources += [(k, [r.get(k) for r in rows], True) for k in curves]
    sources += [(k, [r.get(k) for r in rows], False) for k in rest]
    out = []
    for name, values, curve in sources:
        kind = _type_of(values, curve)
        out.append(Column(name, kind, [_cell(v, kind) for v in values]))
    return out


def _open(store_or_path: ResultStore | str | os.PathLike[str]) -> ResultStore:
    if isinstance(store_or_path, ResultStore):
        return store_or_path
    return ResultStore(store_or_path, create=False)


def store_rows(
    store_or_path: ResultStore | str | os.PathLike[str],
    kind: str | None = None,
    status: str | None = None,
) -> list[Row]:
    """The rows of a store (``kind`` and ``status``: None for any), compact rows expanded.

    Raises:
        StoreError: the path is not a result store, or has a corrupt row.
        ValueError: ``status`` is not a row status, or the store has no run of ``kind``.
    """
    if status is not None and status not in STATUSES:
        raise ValueError(f"unknown status {status!r}; valid statuses are: {', '.join(STATUSES)}")
    store = _open(store_or_path)
    rows = store.load(status=None)
    if kind is not None:
        kinds = sorted({r["kind"] for r in rows})
        if kind not in kinds:
            raise ValueError(
                f"{store.path}: no runs of kind {kind!r}; the store has"
                f" {', '.join(repr(k) for k in kinds) if kinds else 'no runs'}"
            )
    return [
        r
        for r in rows
        if (kind is None or r["kind"] == kind) and (status is None or r["status"] == status)
    ]


def store_frame(
    store_or_path: ResultStore | str | os.PathLike[str],
    kind: str | None = None,
    status: str | None = None,
) -> pd.DataFrame:
    """A result store as a pandas DataFrame, one row per run (see the module docstring).

    Args:
        store_or_path: a :class:`~voot.bench.store.result_store.ResultStore` or its directory.
        kind: only runs of this kind (``"plan"``, ``"bbfo"``); None for all.
        status: only runs of this status (``"ok"``, ``"failed"``); None for all.

    Raises:
        ImportError: pandas or pyarrow is missing (names the ``bench`` extra).
        StoreError: the path is not a result store, or has a corrupt row.
        ValueError: an unknown status, or a kind the store has no run of.
    """
    pd, _ = require_table_libs()
    columns = table_columns(store_rows(store_or_path, kind, status))
    data = {
        c.name: pd.Series(c.values, dtype=_TYPES[c.type][0] or object, name=c.name) for c in columns
    }
    return pd.DataFrame(data, columns=[c.name for c in columns])


def store_table(
    store_or_path: ResultStore | str | os.PathLike[str],
    kind: str | None = None,
    status: str | None = None,
) -> pa.Table:
    """The same table as :func:`store_frame`, as a pyarrow Table (the Parquet file's)."""
    _, pa = require_table_libs()
    columns = table_columns(store_rows(store_or_path, kind, status))
    arrays, fields = [], []
    for c in columns:
        arrow = getattr(pa, _TYPES[c.type][1])()
        if c.type in ("floats", "strs"):
            arrow = pa.list_(arrow)
        values = c.values  # a missing number is null in Arrow, NaN inside a curve stays NaN
        if c.type == "float":
            values = [None if math.isnan(v) else v for v in values]
        arrays.append(pa.array(values, type=arrow))
        fields.append(pa.field(c.name, arrow))
    return pa.Table.from_arrays(arrays, schema=pa.schema(fields))


def write_parquet(
    store_or_path: ResultStore | str | os.PathLike[str],
    path: str | os.PathLike[str],
    kind: str | None = None,
    status: str | None = None,
) -> int:
    """Write the table of a store (:func:`store_frame`) to the Parquet file ``path``;
    the number of rows written.

    The file is written to a temporary name beside ``path`` and moved into place, so a
    failed export leaves no partial file. The same store gives the same bytes. Read it
    back with ``pandas.read_parquet(path)`` (a curve cell is then a NumPy array).

    Raises:
        StoreError: ``path`` is a directory; and the errors of :func:`store_frame`.
    """
    require_table_libs()
    import pyarrow.parquet as pq

    out = Path(path)
    if out.is_dir():
        raise StoreError(f"{out}: is a directory; give the Parquet file to write")
    table = store_table(store_or_path, kind, status)
    tmp = out.with_name(f".{out.name}.tmp")
    try:
        pq.write_table(table, tmp, compression=COMPRESSION)
        os.replace(tmp, out)
    finally:
        tmp.unlink(missing_ok=True)
    return int(table.num_rows)
