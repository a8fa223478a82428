"""Tests of voot.bench.measure.store_speed: the synthetic plan rows and the store's load-time
benchmark."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from voot.bench.measure.store_speed import synthetic_plan_row, time_load
from voot.bench.store import index as store_index
from voot.bench.store.format import check_row
from voot.bench.store.result_store import ResultStore


def test_time_load_measures_a_small_store(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(store_index, "RACY_NS", 0)
    out = time_load(5, 10, repeats=1, path=str(tmp_path / "bench"))
    assert set(out) == {"write", "cold", "warm", "warm_arrays", "verify", "mb"}
    assert all(v >= 0 for v in out.values())
    assert 0 < out["mb"] < 0.01  # five rows of ten steps: a few kB
    assert (tmp_path / "bench" / "store").is_dir()  # a given path is kept


def test_time_load_arguments_and_timings(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(store_index, "RACY_NS", 1_000_000)  # waits 1 ms
    for bad in ((0, 1, 1), (1, 0, 1), (1, 1, 0)):
        with pytest.raises(ValueError, match=">= 1"):
            time_load(*bad)
    began = time.perf_counter()
    out = time_load(1, 1, repeats=1)  # in a temporary directory
    elapsed = time.perf_counter() - began
    assert all(0 <= out[k] <= elapsed for k in ("write", "cold", "warm", "verify"))


def test_time_load_of_a_compact_plan_store(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from voot.bench.store.compact import CompactConfig

    monkeypatch.setattr(store_index, "RACY_NS", 0)
    full = time_load(3, 300, repeats=1, path=str(tmp_path / "a"), plan=True)
    small = time_load(
        3, 300, repeats=1, path=str(tmp_path / "b"), plan=True, compact=CompactConfig()
    )
    assert small["mb"] * 3 < full["mb"]
    assert ResultStore(tmp_path / "b" / "store").compact == CompactConfig()


def test_synthetic_plan_rows_are_valid_and_reproducible() -> None:
    a = synthetic_plan_row(3, 200, np.random.default_rng(5))
    assert check_row(a) is a and a["config"]["seed"] == 3 and a["config"]["simulations"] == 200
    for key in ("best_so_far", "objects_left", "elapsed", "cpu_elapsed", "calls_curve"):
        assert len(a[key]) == 200
    assert np.all(np.diff(a["best_so_far"]) >= 0) and np.all(np.diff(a["calls_curve"]) > 0)
    assert a["wall_time"] == a["elapsed"][-1]
    b = synthetic_plan_row(3, 200, np.random.default_rng(5))
    assert {k: v for k, v in a.items() if k != "finished_at"} == {
        k: v for k, v in b.items() if k != "finished_at"
    }
