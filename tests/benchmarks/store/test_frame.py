"""Tests of voot.bench.store.frame: a store as a DataFrame and a Parquet file (one row per
run, config flattened, curves as list columns), round trips on a full and a compact store,
the committed protocol store, bad input, and the same bytes for the same store."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from plan_fixtures import kitchen_rows, with_costs
from store_fixtures import row

from voot.bench.cli.main import main
from voot.bench.store import frame
from voot.bench.store.compact import CompactConfig
from voot.bench.store.format import StoreError
from voot.bench.store.result_store import ResultStore

pd = pytest.importorskip("pandas")
pa = pytest.importorskip("pyarrow")
pq = pytest.importorskip("pyarrow.parquet")

PROTOCOL = Path(__file__).resolve().parents[3] / "docs" / "data" / "protocol-v1"


def plan_store(path: Path, compact: CompactConfig | None = None) -> ResultStore:
    """A store of the kitchen plan rows (costs on half of them, so curves are missing on
    the rest), two bbfo rows and a failed one."""
    store = ResultStore(path, compact=compact)
    for i, r in enumerate(kitchen_rows()):
        store.write(with_costs(r, 3, 0.01) if i % 2 else r)
    store.write(row(1))
    store.write(row(2))
    store.write(row(3, status="failed"))
    return store


def test_one_row_per_run_with_the_config_flattened(tmp_path: Path) -> None:
    store = plan_store(tmp_path / "s")
    df = frame.store_frame(store)
    rows = store.load(status=None)
    assert len(df) == len(rows) == len(store)
    assert list(df.run_id) == [r["run_id"] for r in rows]
    assert list(df.columns[:6]) == list(frame.HEAD_COLUMNS)
    plan = frame.store_frame(store.path, kind="plan")
    assert set(plan.kind) == {"plan"} and len(plan) == 12
    assert {"problem", "planner", "seed", "params", "env_kwargs", "simulations"} <= set(
        plan.columns
    )
    assert plan.seed.dtype == np.int64 and plan.wall_time.dtype == np.float64
    voot = plan[plan.planner == "voot"]
    assert (
        sorted(json.loads(p).get("omega", 0) for p in voot.params)
        == [0] * 3 + [0.1] * 3 + [0.3] * 3
    )
    # curves are lists of float64, one per run; a run without one has None
    for r, curve, calls in zip(rows, df.best_so_far, df.calls_curve, strict=True):
        assert isinstance(curve, list) and curve == [float(v) for v in r["best_so_far"]]
        assert calls is None if "calls_curve" not in r else calls == r["calls_curve"]
    # objects_left's nulls are NaN
    left = plan.objects_left[(plan.seed == 0) & (plan.params == '{"omega":0.1}')].iloc[0]
    assert math.isnan(left[0]) and left[1:] == [3.0, 1.0, 0.0]
    # status: only the failed one
    failed = frame.store_frame(store, status="failed")
    assert list(failed.error) == ["ValueError: boom"] and failed.best_so_far.iloc[0] == []


def test_the_parquet_file_reads_back_as_the_frame(tmp_path: Path) -> None:
    store = plan_store(tmp_path / "s")
    out = tmp_path / "runs.parquet"
    assert frame.write_parquet(store, out) == len(store)
    df = frame.store_frame(store)
    back = pd.read_parquet(out)
    assert list(back.columns) == list(df.columns) and len(back) == len(df)
    for name in df.columns:
        for a, b in zip(df[name], back[name], strict=True):
            if isinstance(a, list):
                assert np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True), name
            elif isinstance(a, float) and math.isnan(a):
                assert b is None or math.isnan(b), name
            else:
                assert a == b or (a is None and pd.isna(b)), name
    schema = pq.read_schema(out)
    curve = schema.field("best_so_far").type
    assert pa.types.is_list(curve) and curve.value_type == pa.float64()
    assert schema.field("seed").type == pa.int64() and schema.field("params").type == pa.string()


def test_a_compact_store_gives_the_rows_expanded(tmp_path: Path) -> None:
    full = plan_store(tmp_path / "full")
    small = plan_store(tmp_path / "small", compact=CompactConfig(points=2))
    a, b = frame.store_frame(full), frame.store_frame(small)
    assert list(a.run_id) == list(b.run_id) and list(a.best_so_far) == list(b.best_so_far)
    assert "interpolated" in b.columns and "interpolated" not in a.columns
    frame.write_parquet(small, tmp_path / "small.parquet")
    assert pq.read_metadata(tmp_path / "small.parquet").num_rows == len(small)


def test_the_same_store_gives_the_same_bytes(tmp_path: Path) -> None:
    store = plan_store(tmp_path / "s")
    frame.write_parquet(store, tmp_path / "a.parquet")
    frame.write_parquet(store.path, tmp_path / "b.parquet")
    assert (tmp_path / "a.parquet").read_bytes() == (tmp_path / "b.parquet").read_bytes()
    assert not list(tmp_path.glob(".*.tmp"))


def test_the_committed_protocol_store() -> None:
    store = ResultStore(PROTOCOL, create=False)
    df = frame.store_frame(store, kind="plan")
    assert len(df) == len(store) and df.run_id.is_unique
    assert set(df.problem) >= {"voot/KitchenClearing-v1", "voot/ConveyorPacking-v1"}
    assert (df.best_so_far.map(len) == df.simulations).all()


def test_bad_input_is_a_clear_error(tmp_path: Path) -> None:
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "a.txt").write_text("hello")
    with pytest.raises(StoreError, match="not a voot result store"):
        frame.store_frame(tmp_path / "notes")
    with pytest.raises(StoreError, match="no voot result store"):
        frame.store_frame(tmp_path / "missing")
    assert not (tmp_path / "missing").exists()
    store = plan_store(tmp_path / "s")
    with pytest.raises(ValueError, match=r"no runs of kind 'plans'; the store has 'bbfo', 'plan'"):
        frame.store_frame(store, kind="plans")
    with pytest.raises(ValueError, match="unknown status 'good'"):
        frame.store_frame(store, status="good")
    with pytest.raises(StoreError, match="is a directory"):
        frame.write_parquet(store, tmp_path)


def test_a_missing_extra_names_it(monkeypatch: pytest.MonkeyPatch) -> None:
    import builtins

    real = builtins.__import__

    def no_pandas(name: str, *args: object, **kwargs: object) -> object:
        if name == "pandas":
            raise ImportError("No module named 'pandas'")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_pandas)
    with pytest.raises(ImportError, match=r"pandas and pyarrow.*the bench extra"):
        frame.require_table_libs()


def test_export_command(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    store = plan_store(tmp_path / "s")
    out = tmp_path / "plan.parquet"
    argv = ["export", str(store.path), "--parquet", str(out), "--kind", "plan", "--status", "ok"]
    assert main(argv) == 0
    assert capsys.readouterr().out == f"12 runs of {store.path} written to {out}\n"
    assert set(pd.read_parquet(out).kind) == {"plan"}
    assert main(["export", str(tmp_path / "nothing"), "--parquet", str(out)]) == 2
    assert "voot-bench: error:" in capsys.readouterr().err
