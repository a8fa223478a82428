"""A small result row shared by the tests of voot.bench.store.result_store, store_format and
store_index (a helper, not a test module)."""

from __future__ import annotations

import numpy as np

from voot.bench.store.format import make_row


def row(i: int, status: str = "ok", n: int = 5, kind: str = "bbfo") -> dict:
    best: list[float] = (
        np.maximum.accumulate(np.arange(n, dtype=float) + i).tolist() if status == "ok" else []
    )
    return make_row(
        kind,
        {"function": "f", "dim": 3, "seed": i},
        status=status,
        wall_time=0.5,
        best_so_far=best,
        error=None if status == "ok" else "ValueError: boom",
    )
