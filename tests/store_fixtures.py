"""Helpers shared by the tests of the result store and the sweeps (not a test module): a
small result row, and a backend interrupted like Ctrl-C."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any

import numpy as np

from voot.bench.store.format import Row, make_row


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


class Interrupting:
    """A serial backend that dies (like Ctrl-C) after ``after`` rows."""

    name = "interrupting"

    def __init__(self, after: int) -> None:
        self.after = after

    def map_unordered(self, fn: Callable[[Any], Row], items: Sequence[Any]) -> Iterator[Row]:
        for i, item in enumerate(items):
            if i == self.after:
                raise KeyboardInterrupt
            yield fn(item)
