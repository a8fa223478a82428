"""Equality of root-parallel results "up to what a seed determines".

The results hold numpy arrays (whose ``==`` is elementwise) and timings (which differ
between two runs of the same seed), so dataclass equality does not fit: these helpers
compare arrays, mappings and sequences exactly (NaN equal to NaN) and leave out the
fields marked ``compare=False``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import fields
from typing import Any

import numpy as np

from voot.tree.search import PlanResult


def same(a: object, b: object) -> bool:
    """Equality through arrays, mappings and sequences (NaN equals NaN)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if not (isinstance(a, np.ndarray) and isinstance(b, np.ndarray)) or a.shape != b.shape:
            return False
        return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc" and b.dtype.kind in "fc"))
    if isinstance(a, Mapping) or isinstance(b, Mapping):
        return (
            isinstance(a, Mapping)
            and isinstance(b, Mapping)
            and list(a) == list(b)
            and all(same(a[k], b[k]) for k in a)
        )
    if isinstance(a, list | tuple) or isinstance(b, list | tuple):
        return (
            type(a) is type(b)
            and len(a) == len(b)  # type: ignore[arg-type]
            and all(same(x, y) for x, y in zip(a, b, strict=True))  # type: ignore[call-overload]
        )
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


def same_fields(a: Any, b: Any) -> bool:
    """Dataclasses ``a`` and ``b`` agree on every field compared by ``==``."""
    return type(a) is type(b) and all(
        same(getattr(a, f.name), getattr(b, f.name)) for f in fields(a) if f.compare
    )


#: The fields of a :class:`PlanResult` that a seed determines (not timings, not the tree).
PLAN_FIELDS = tuple(f.name for f in fields(PlanResult) if f.name not in ("wall_time", "mcts"))


def same_plan(a: PlanResult, b: PlanResult) -> bool:
    """Plans agree on every field a seed determines (:data:`PLAN_FIELDS`)."""
    return all(same(getattr(a, f), getattr(b, f)) for f in PLAN_FIELDS)
