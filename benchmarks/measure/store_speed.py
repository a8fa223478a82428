"""The store's size and speed benchmark (``voot-bench measure store-speed``): synthetic plan-like
rows (:func:`synthetic_plan_row`) and the time to write, load and verify a store of them,
full or compact (:func:`time_load`; measured numbers in docs/stores.md)."""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

import numpy as np

from voot.bench.store import index as store_index
from voot.bench.store.compact import CompactConfig
from voot.bench.store.format import Row, make_row
from voot.bench.store.result_store import ResultStore


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
    within :data:`~voot.bench.store.index.RACY_NS` of a load are re-read, so the benchmark
    waits that long after writing, outside the timings). Also returns ``write`` (seconds to
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
        time.sleep(
            store_index.RACY_NS / 1e9
        )  # a store at rest: no row is "racily" new at its first load
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
