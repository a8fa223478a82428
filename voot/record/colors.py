r"""Colours of sampled actions: :math:`\hat Q` through a colour map, infeasible ones apart.

The paper's Figure 5 colours the placements sampled at a node by their value. Here a
node's feasible actions are scaled to :math:`[0, 1]` by the minimum and maximum
:math:`\hat Q` among them (at the moment they are drawn) and mapped through *viridis*
(dark purple = lowest, yellow = highest); infeasible actions get one fixed colour. Pure
numpy, vectorised, no matplotlib.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: Viridis sampled at 0, 1/8, ..., 1 (sRGB, 0-255); linear interpolation in between.
VIRIDIS_ANCHORS: NDArray[np.float64] = np.array(
    [
        [68, 1, 84],
        [71, 44, 122],
        [59, 81, 139],
        [44, 113, 142],
        [33, 144, 141],
        [39, 173, 129],
        [92, 200, 99],
        [170, 220, 50],
        [253, 231, 37],
    ],
    dtype=np.float64,
)

#: Default colour of infeasible actions (light grey: outside the colour map).
INFEASIBLE_COLOR: tuple[int, int, int] = (170, 170, 170)


def check_color(color: object, name: str) -> tuple[int, int, int]:
    """An RGB triple of integers in [0, 255], or a ValueError naming ``name``."""
    if (
        not isinstance(color, Sequence)
        or isinstance(color, str)
        or len(color) != 3
        or not all(
            isinstance(c, int | np.integer) and not isinstance(c, bool) and 0 <= c <= 255
            for c in color
        )
    ):
        raise ValueError(f"{name} must be three integers in [0, 255] (R, G, B), got {color!r}")
    return (int(color[0]), int(color[1]), int(color[2]))


def colormap(t: ArrayLike) -> NDArray[np.uint8]:
    """Viridis colours ``(n, 3)`` uint8 of values ``t`` in [0, 1] (clipped; NaN -> 0)."""
    x = np.nan_to_num(np.clip(np.asarray(t, dtype=np.float64), 0.0, 1.0), nan=0.0)
    grid = np.linspace(0.0, 1.0, len(VIRIDIS_ANCHORS))
    out = np.empty((*x.shape, 3), dtype=np.float64)
    for c in range(3):
        out[..., c] = np.interp(x, grid, VIRIDIS_ANCHORS[:, c])
    return np.rint(out).astype(np.uint8)


def value_colors(
    q: ArrayLike,
    feasible: ArrayLike,
    infeasible_color: tuple[int, int, int] = INFEASIBLE_COLOR,
) -> NDArray[np.uint8]:
    r"""Colours ``(n, 3)`` of actions with values ``q`` and feasibility flags ``feasible``.

    Feasible actions: viridis of :math:`(\hat Q - \min) / (\max - \min)` over the finite
    feasible values (all at the top of the map when they are equal); a non-finite
    :math:`\hat Q` (not backed up yet) counts as the minimum. Infeasible actions:
    ``infeasible_color``.
    """
    qv = np.asarray(q, dtype=np.float64).reshape(-1)
    ok = np.asarray(feasible, dtype=bool).reshape(-1)
    if qv.shape != ok.shape:
        raise ValueError(f"q and feasible must have the same length, got {qv.size} and {ok.size}")
    out = np.empty((qv.size, 3), dtype=np.uint8)
    out[:] = infeasible_color
    if ok.any():
        vals = qv[ok]
        finite = np.isfinite(vals)
        if finite.any():
            lo, hi = float(vals[finite].min()), float(vals[finite].max())
            span = hi - lo
            t = (vals - lo) / span if span > 0 else np.ones_like(vals)
            t[~finite] = 0.0
        else:
            t = np.zeros_like(vals)
        out[ok] = colormap(t)
    return out
