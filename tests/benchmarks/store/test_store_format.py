"""Tests of voot.bench.store.format: run ids, rows (ok, failed, from an exception), their
checksummed bytes, the row check and curves."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import numpy as np
import pytest
from store_fixtures import row

from voot.bench.store import format as store_format
from voot.bench.store.format import StoreError, check_row, curves, make_row, make_run_id


def test_run_id_is_stable_and_order_independent() -> None:
    a = make_run_id("bbfo", {"x": 1, "seed": 2, "params": {"a": 0.1, "b": 2}})
    b = make_run_id("bbfo", {"params": {"b": 2, "a": 0.1}, "seed": 2, "x": 1})
    assert a == b and len(a) == 20
    assert a != make_run_id("bbfo", {"x": 1, "seed": 3, "params": {"a": 0.1, "b": 2}})
    assert a != make_run_id("plan", {"x": 1, "seed": 2, "params": {"a": 0.1, "b": 2}})
    code = (
        "from voot.bench.store.format import make_run_id;"
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


def test_run_ids_refuse_non_json_numbers() -> None:
    with pytest.raises(ValueError):
        make_run_id("bbfo", {"x": float("nan")})


def test_check_row_and_make_row_validation() -> None:
    with pytest.raises(StoreError, match="JSON object"):
        check_row([1, 2])
    with pytest.raises(StoreError, match="status"):
        check_row(dict(row(1), status="meh"))
    with pytest.raises(ValueError, match="status"):
        make_row("bbfo", {}, status="done", wall_time=0.0, best_so_far=[])


def test_check_row_returns_the_row_and_checks_both_types() -> None:
    r = row(1)
    assert check_row(r) is r
    for bad in (dict(r, config=[1]), dict(r, best_so_far=(1.0,))):
        with pytest.raises(StoreError, match="'config' must be an object"):
            check_row(bad)


class _Spec:
    kind = "bbfo"

    def config(self) -> dict:
        return {"function": "f", "dim": 2, "seed": 7}


def test_failed_and_exception_rows() -> None:
    spec = _Spec()
    r = store_format.failed_row(spec, "RuntimeError: no", note=1)
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
        r = store_format.exception_row(spec, exc, start, [1.0, 2.0], extra="x")
    elapsed = time.perf_counter() - start
    assert r["status"] == "failed" and r["error"] == "ValueError: boom"
    assert 0.0 <= r["wall_time"] <= elapsed
    assert r["best_so_far"] == [1.0, 2.0] and r["extra"] == "x"
    assert "ValueError: boom" in r["traceback"]


def test_verify_row_bytes_edge_cases() -> None:
    verify = store_format.verify_row_bytes
    good = store_format.row_bytes(row(1))
    assert verify(good) is True
    plain = json.dumps(row(1)).encode() + b"\n"
    with pytest.raises(StoreError, match="without its checksum"):
        verify(plain)  # required by default
    assert verify(plain, required=False) is False
    zeros = b"0" * 64
    only = store_format._CHECKSUM_HEAD + zeros + store_format._CHECKSUM_TAIL  # nothing before it
    assert verify(only, required=False) is False
    with pytest.raises(StoreError, match="changed since"):
        verify(b"{" + only, required=False)  # one byte of body: a (wrong) checksum


def test_curves_pads_with_nan() -> None:
    c = curves([{"best_so_far": [1.0, 2.0, 3.0]}, {"best_so_far": [5.0]}])
    assert c.shape == (2, 3)
    assert np.array_equal(c[0], [1.0, 2.0, 3.0])
    assert c[1, 0] == 5.0 and np.isnan(c[1, 1:]).all()
    assert curves([]).shape == (0, 0)


def test_curves_of_equal_length() -> None:
    c = curves([{"best_so_far": [1.0, 2.0]}, {"best_so_far": [3.0, 4.0]}])
    assert c.tolist() == [[1.0, 2.0], [3.0, 4.0]]


def test_row_bytes_replaces_an_earlier_checksum() -> None:
    """A row read back (or copied) with its checksum key is re-serialised without it: the
    file carries exactly one checksum, of the content."""
    r = row(1)
    stale = dict(r, **{store_format.CHECKSUM_KEY: "0" * 64})
    assert store_format.row_bytes(stale) == store_format.row_bytes(r)
    assert store_format.verify_row_bytes(store_format.row_bytes(stale))


def test_check_row_of_a_compact_row() -> None:
    """A compact row keeps its curves under the compact key, so it may lack best_so_far;
    a full row may not, and either needs a config object."""
    from voot.bench.store.compact import CompactConfig, compact_row

    compact = compact_row(row(1), CompactConfig())
    assert store_format.COMPACT_KEY in compact and "best_so_far" not in compact
    assert check_row(compact) is compact
    with pytest.raises(StoreError, match="'config' must be an object"):
        check_row(dict(compact, config=[1]))
    full = {k: v for k, v in row(1).items() if k != "best_so_far"}
    with pytest.raises(StoreError, match=r"missing keys \['best_so_far'\]"):
        check_row(full)
