"""Normalised action units: the affine map between ``[-1, 1]^d`` and parameter ranges.

Every env's actions are vectors in ``[-1, 1]^d`` (one fixed box for gymnasium's checkers
and for the planners); each operator maps them affinely to its parameters' ranges
(:func:`denormalize`, inverse :func:`normalize`). :func:`denormalize_floats` computes the
same numbers on Python floats for the pre-screens, which read the parameters one by one.
The ranges' arrays are built once per ranges (a step maps an action every time).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]


def denormalize(a: FloatArray, ranges: Sequence[tuple[float, float]]) -> FloatArray:
    """Map ``a`` in ``[-1, 1]^d`` to the box ``ranges`` (``d`` pairs ``(low, high)``)."""
    lo, width = _range_arrays(ranges)
    out: FloatArray = lo + 0.5 * (a + 1.0) * width
    return out


#: ``(low, high - low)`` arrays of the ranges :func:`denormalize` has seen.
_RANGE_ARRAYS: dict[tuple[tuple[float, float], ...], tuple[FloatArray, FloatArray]] = {}


def _range_arrays(ranges: Sequence[tuple[float, float]]) -> tuple[FloatArray, FloatArray]:
    """The read-only ``low`` and ``high - low`` arrays of ``ranges`` (built once per ranges)."""
    try:
        hit = _RANGE_ARRAYS.get(ranges)  # type: ignore[call-overload]
    except TypeError:  # not hashable (lists)
        hit = None
    if hit is None:
        key = tuple((r[0], r[1]) for r in ranges)
        lo = np.array([r[0] for r in key], dtype=np.float64)
        hi = np.array([r[1] for r in key], dtype=np.float64)
        width = hi - lo
        lo.setflags(write=False)
        width.setflags(write=False)
        if len(_RANGE_ARRAYS) >= 64:
            _RANGE_ARRAYS.clear()
        hit = _RANGE_ARRAYS[key] = (lo, width)
    return hit


def denormalize_floats(a: Sequence[float], ranges: Sequence[tuple[float, float]]) -> list[float]:
    """:func:`denormalize` on Python floats: the same numbers, without the arrays.

    Each entry is ``low + 0.5 * (a + 1.0) * (high - low)``, the IEEE operations numpy
    applies elementwise, in its order; for the envs' pre-screens, which read the
    parameters one by one.
    """
    lo, width = _range_lists(ranges)
    return [lo_i + 0.5 * (a_i + 1.0) * w_i for lo_i, a_i, w_i in zip(lo, a, width, strict=True)]


#: ``(low, high - low)`` lists of the ranges :func:`denormalize_floats` has seen.
_RANGE_LISTS: dict[Any, tuple[list[float], list[float]]] = {}


def _range_lists(ranges: Sequence[tuple[float, float]]) -> tuple[list[float], list[float]]:
    """:func:`_range_arrays` as lists of Python floats (the same numbers)."""
    try:
        hit = _RANGE_LISTS.get(ranges)
    except TypeError:  # not hashable (lists)
        lo, width = _range_arrays(ranges)
        return lo.tolist(), width.tolist()
    if hit is None:
        lo, width = _range_arrays(ranges)
        hit = (lo.tolist(), width.tolist())
        if len(_RANGE_LISTS) >= 64:
            _RANGE_LISTS.clear()
        _RANGE_LISTS[ranges] = hit
    return hit


def normalize(x: ArrayLike, ranges: Sequence[tuple[float, float]]) -> FloatArray:
    """Inverse of :func:`denormalize`: parameters in the paper's units to ``[-1, 1]^d``."""
    lo = np.array([r[0] for r in ranges], dtype=np.float64)
    hi = np.array([r[1] for r in ranges], dtype=np.float64)
    out: FloatArray = 2.0 * (np.asarray(x, dtype=np.float64) - lo) / (hi - lo) - 1.0
    return out


def padded_parameters(values: FloatArray, shape: tuple[int, ...]) -> dict[str, Any]:
    """A step info's ``parameters`` and ``parameters_mask``: ``values`` (an operator's
    parameters in the paper's units) padded with zeros to ``shape``, the env's widest
    operator's, and True where an entry is one of them.

    Every step's info then has the same keys, shapes and dtypes whatever the node (a
    kitchen place has 3 parameters, a pick 6), as gymnasium's vector envs need to stack
    them; ``info["parameters"][info["parameters_mask"]]`` gives the operator's own. Zeros,
    not NaN: gymnasium's checks compare infos for equality (a NaN equals nothing, so
    ``check_env`` would find two identical resets different).
    """
    out = np.zeros(shape)
    mask = np.zeros(shape, dtype=bool)
    where = tuple(slice(0, n) for n in values.shape)
    out[where] = values
    mask[where] = True
    return {"parameters": out, "parameters_mask": mask}
