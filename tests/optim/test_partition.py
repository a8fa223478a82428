"""Tests of voot.optim._partition's split points near the float limits (the cells
themselves are tested through DOO and SOO: test_doo.py, test_soo.py, test_bamsoo.py)."""

from __future__ import annotations

import math

import pytest

from voot.optim._partition import _between


def _exact(lo: float, hi: float, t: float) -> float:
    """``lo + t (hi - lo)`` computed at a quarter of the scale, where nothing overflows."""
    return 4.0 * ((1.0 - t) * (lo / 4.0) + t * (hi / 4.0))


@pytest.mark.parametrize(
    ("lo", "hi"),
    [(-1.7e308, 1.7e308), (1e308, 1.7e308), (-1.7e308, -1e308), (-8e307, 1.6e308)],
)
@pytest.mark.parametrize("t", [1.0 / 3.0, 0.5, 2.0 / 3.0])
def test_split_points_near_the_float_limits_are_where_they_belong(
    lo: float, hi: float, t: float
) -> None:
    """Where the usual formula overflows (``2 lo + hi``, ``lo + hi``), the fallback gives
    the point a fraction ``t`` of the way, not merely some finite point of the box (a
    clamped wrong value would still be finite and inside, so the cells would be wrong
    silently)."""
    v = _between(lo, hi, t)
    assert math.isfinite(v) and lo <= v <= hi
    assert v == pytest.approx(_exact(lo, hi, t), rel=1e-12, abs=1e293)


@pytest.mark.parametrize("t", [1.0 / 3.0, 0.5, 2.0 / 3.0])
def test_ordinary_split_points_are_the_partitions_own_formulas(t: float) -> None:
    """Bit for bit the formulas the partition always used (v0/v1 cells unchanged)."""
    lo, hi = -0.3, 1.7
    expected = {1.0 / 3.0: (2.0 * lo + hi) / 3.0, 0.5: 0.5 * (lo + hi)}.get(
        t, (lo + 2.0 * hi) / 3.0
    )
    assert _between(lo, hi, t) == expected
