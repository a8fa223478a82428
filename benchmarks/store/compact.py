r"""Compact result rows: per-simulation curves stored small enough to ship with the repository.

A plan row at full resolution holds several per-simulation lists, 2,000-3,000 numbers
each; a protocol of ~1,500 runs is then ~100 MB of JSON. A *compact* row keeps the same
row with those lists replaced by one ``"compact"`` object, one entry per curve, in one of
two codecs:

* ``"steps"`` (**exact**), for the step functions of the simulation index
  (:data:`STEP_KEYS`: ``best_so_far``, ``objects_left``), which change only when a
  better leaf is found: only the change points, the indices ``at`` (the first is 0) and
  the values from there on. Expanding repeats each value up to the next change point,
  which gives back the very same floats (JSON keeps a float's shortest repr exactly).
* ``"sampled"`` (**reduced**), for the monotone cost curves (:data:`SAMPLED_KEYS`:
  ``elapsed``, ``cpu_elapsed``, ``calls_curve``): the values at about
  :attr:`CompactConfig.points` indices, log-spaced (``spacing="log"``: dense at the
  start, where the curves bend) or evenly spaced (``"linear"``), always with the first
  and the **last** index, so the final value (total seconds, total calls) is exact.
  Expanding interpolates linearly in the simulation index between kept points; the
  expanded row lists these keys in ``"interpolated"``. A curve with a NaN, or no longer
  than the points kept, is stored with the exact ``steps`` codec instead.

Each entry is ``{"codec": ..., "n": length, "at": [...], "values": [...]}`` (NaN as
``null``). Every other key of the row (the config, the final numbers, the best plan)
is kept as it is, so the run id, status and final values never change. The result store
(:mod:`voot.bench.store.result_store`) writes compact rows when its header says so and expands them on
every read (:func:`expand_row`), so compact and full rows are interchangeable for every
reader (plots, selection, tables, resume).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot import validation as V

#: Version of the compact layout (in the store header and in every compact row).
COMPACT_VERSION = 1
#: Row key holding the compact curves.
COMPACT_KEY = "compact"
#: Key of an expanded row listing the curves that were interpolated (not exact).
INTERPOLATED_KEY = "interpolated"
#: Curves that are step functions of the simulation index: stored exactly.
STEP_KEYS: tuple[str, ...] = ("best_so_far", "objects_left")
#: Monotone cost curves: stored at reduced resolution, first and last value exact.
SAMPLED_KEYS: tuple[str, ...] = ("elapsed", "cpu_elapsed", "calls_curve")
#: The codecs of a compact curve.
CODECS: tuple[str, ...] = ("steps", "sampled")
#: Spacings of the kept indices of a sampled curve.
SPACINGS: tuple[str, ...] = ("log", "linear")
#: Default number of indices kept per sampled curve.
DEFAULT_POINTS = 100


@dataclass(frozen=True)
class CompactConfig:
    """How a compact store reduces its cost curves (persisted in the store's header).

    Attributes:
        points: indices kept per sampled curve (before de-duplication; plus the first
            and the last). At least 2.
        spacing: ``"log"`` (log-spaced simulation indices) or ``"linear"``.
    """

    points: int = DEFAULT_POINTS
    spacing: str = "log"

    def __post_init__(self) -> None:
        V.integer(self.points, "points", 2)
        if self.spacing not in SPACINGS:
            raise ValueError(
                f"unknown spacing {self.spacing!r}; valid spacings are: {', '.join(SPACINGS)}"
            )

    def to_dict(self) -> dict[str, Any]:
        """The header's ``"compact"`` entry."""
        return {"version": COMPACT_VERSION, "points": self.points, "spacing": self.spacing}

    @classmethod
    def from_dict(cls, data: Any) -> CompactConfig:
        """The config of a header's ``"compact"`` entry (ValueError if it is not one)."""
        if not isinstance(data, Mapping):
            raise ValueError(f"'compact' must be an object, got {type(data).__name__}")
        if data.get("version") != COMPACT_VERSION:
            raise ValueError(
                f"compact layout version {data.get('version')!r}; this voot reads version"
                f" {COMPACT_VERSION}"
            )
        return cls(points=data.get("points", DEFAULT_POINTS), spacing=data.get("spacing", "log"))


def kept_indices(n: int, config: CompactConfig) -> NDArray[np.int64]:
    """The indices a sampled curve of length ``n`` keeps: sorted, unique, 0 and ``n - 1``."""
    if n <= 0:
        return np.empty(0, dtype=np.int64)
    if config.spacing == "log":
        idx = np.rint(np.geomspace(1.0, float(n), config.points)).astype(np.int64) - 1
    else:
        idx = np.rint(np.linspace(0.0, float(n - 1), config.points)).astype(np.int64)
    return np.unique(np.concatenate([[0, n - 1], np.clip(idx, 0, n - 1)]))


def _json_values(values: NDArray[np.float64]) -> list[float | None]:
    out: list[float | None] = values.tolist()
    if np.isnan(values).any():
        out = [None if v is not None and math.isnan(v) else v for v in out]
    return out


def _changes(values: NDArray[np.float64]) -> NDArray[np.int64]:
    """Indices where ``values`` differs from the entry before it (0 always; NaN == NaN)."""
    if values.size == 0:
        return np.empty(0, dtype=np.int64)
    a, b = values[1:], values[:-1]
    same = (a == b) | (np.isnan(a) & np.isnan(b))
    return np.concatenate([[0], np.flatnonzero(~same) + 1]).astype(np.int64)


def encode_curve(key: str, values: Any, config: CompactConfig) -> dict[str, Any] | None:
    """The compact entry of curve ``key`` (None if ``values`` is not a 1-D list of numbers)."""
    try:
        arr = np.array(values, dtype=np.float64)  # None -> NaN
    except (TypeError, ValueError):
        return None
    if arr.ndim != 1:
        return None
    n = int(arr.size)
    if key in SAMPLED_KEYS and not np.isnan(arr).any() and n > config.points:
        at = kept_indices(n, config)
        codec = "sampled"
    else:
        at = _changes(arr)
        codec = "steps"
    return {"codec": codec, "n": n, "at": at.tolist(), "values": _json_values(arr[at])}


def compact_row(row: Mapping[str, Any], config: CompactConfig) -> dict[str, Any]:
    """``row`` with its curves (:data:`STEP_KEYS`, :data:`SAMPLED_KEYS`) in compact form.

    A row that is already compact is returned unchanged (as a copy)."""
    out = dict(row)
    if COMPACT_KEY in out:
        return out
    curves: dict[str, Any] = {}
    for key in (*STEP_KEYS, *SAMPLED_KEYS):
        if key in out and isinstance(out[key], list | np.ndarray):
            entry = encode_curve(key, out[key], config)
            if entry is not None:
                curves[key] = entry
                del out[key]
    out[COMPACT_KEY] = {"version": COMPACT_VERSION, "curves": curves}
    return out


def check_compact(data: Any) -> None:
    """Raise ValueError (saying what is wrong) unless ``data`` is a row's valid ``"compact"``."""
    if not isinstance(data, Mapping) or not isinstance(data.get("curves"), Mapping):
        raise ValueError("'compact' must be an object with a 'curves' object")
    if data.get("version") != COMPACT_VERSION:
        raise ValueError(
            f"compact row version {data.get('version')!r}; this voot reads {COMPACT_VERSION}"
        )
    if "best_so_far" not in data["curves"]:
        raise ValueError("compact row without its 'best_so_far' curve")
    for key, entry in data["curves"].items():
        if not isinstance(entry, Mapping):
            raise ValueError(f"compact curve {key!r} must be an object")
        codec = entry.get("codec")
        if codec not in CODECS:
            raise ValueError(
                f"compact curve {key!r}: unknown codec {codec!r}; valid codecs are:"
                f" {', '.join(CODECS)}"
            )
        n, at, values = entry.get("n"), entry.get("at"), entry.get("values")
        if not isinstance(n, int) or isinstance(n, bool) or n < 0:
            raise ValueError(f"compact curve {key!r}: 'n' must be an integer >= 0, got {n!r}")
        if not isinstance(at, list) or not isinstance(values, list) or len(at) != len(values):
            raise ValueError(
                f"compact curve {key!r}: 'at' and 'values' must be lists of one length"
            )
        if n == 0:
            if at:
                raise ValueError(f"compact curve {key!r}: points given for an empty curve")
            continue
        if not all(isinstance(i, int) and not isinstance(i, bool) for i in at):
            raise ValueError(f"compact curve {key!r}: 'at' must hold integers")
        rising = all(b > a for a, b in itertools.pairwise(at))
        if not at or at[0] != 0 or at[-1] > n - 1 or not rising:
            raise ValueError(
                f"compact curve {key!r}: 'at' must rise strictly from 0 to at most n - 1 = {n - 1}"
            )
        if codec == "sampled" and at[-1] != n - 1:
            raise ValueError(f"compact curve {key!r}: a sampled curve must keep its last index")
        if not all(
            v is None or (isinstance(v, int | float) and not isinstance(v, bool)) for v in values
        ):
            raise ValueError(f"compact curve {key!r}: 'values' must hold numbers or null")


def decode_curve(entry: Mapping[str, Any]) -> NDArray[np.float64]:
    """The full-length curve of a compact entry (exact for ``steps``, interpolated for
    ``sampled``), as a float64 array (``null`` -> NaN)."""
    n = int(entry["n"])
    at = np.asarray(entry["at"], dtype=np.int64)
    values = np.array(entry["values"], dtype=np.float64)
    if n == 0:
        return np.empty(0, dtype=np.float64)
    if entry["codec"] == "sampled":
        return np.interp(np.arange(n, dtype=np.float64), at.astype(np.float64), values)
    return np.repeat(values, np.diff(np.append(at, n)))


def is_compact(row: Mapping[str, Any]) -> bool:
    """Whether ``row`` is in compact form."""
    return COMPACT_KEY in row


def expand_row(row: Mapping[str, Any], *, arrays: bool = False) -> dict[str, Any]:
    """A compact row back as a full row (a full row is returned as a copy, unchanged).

    Step curves come back exactly; sampled curves interpolated, and then listed under
    :data:`INTERPOLATED_KEY`. With ``arrays`` the curves are read-only float64 arrays,
    else lists (NaN as None except in ``best_so_far``, as a full row's file holds them).
    """
    out = dict(row)
    data = out.pop(COMPACT_KEY, None)
    if data is None:
        return out
    interpolated = []
    for key, entry in data["curves"].items():
        curve = decode_curve(entry)
        if entry["codec"] == "sampled" and len(entry["at"]) < entry["n"]:
            interpolated.append(key)
        if arrays:
            curve.setflags(write=False)
            out[key] = curve
        elif key == "best_so_far":
            out[key] = curve.tolist()
        else:
            out[key] = _json_values(curve)
    if interpolated:
        out[INTERPOLATED_KEY] = sorted(interpolated)
    return out


def check_roundtrip(row: Mapping[str, Any], compact: Mapping[str, Any]) -> None:
    """Raise ValueError unless ``compact`` expands to ``row``: every step curve bit for bit,
    every sampled curve at its kept indices (so its first and last value), every other key
    equal. The self-check of a conversion (:func:`voot.bench.store.result_store.compact_store`)."""
    full = expand_row(compact, arrays=True)
    curves = compact.get(COMPACT_KEY, {}).get("curves", {})
    for key, value in row.items():
        if key not in curves:
            if full.get(key) != value:
                raise ValueError(f"row {row.get('run_id')}: key {key!r} changed in compaction")
            continue
        want = np.array(value, dtype=np.float64)
        got = np.asarray(full[key])
        if curves[key]["codec"] == "sampled":
            at = np.asarray(curves[key]["at"], dtype=np.int64)
            want, got = want[at], got[at]
        if want.shape != got.shape or not np.array_equal(want, got, equal_nan=True):
            raise ValueError(f"row {row.get('run_id')}: curve {key!r} changed in compaction")
