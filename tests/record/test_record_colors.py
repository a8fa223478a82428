"""Tests of voot.record.colors: value colours of sampled actions."""

from __future__ import annotations

import numpy as np
import pytest

from voot.record.colors import (
    INFEASIBLE_COLOR,
    VIRIDIS_ANCHORS,
    check_color,
    colormap,
    value_colors,
)


def test_colormap_ends_middle_and_clipping() -> None:
    c = colormap([0.0, 1.0, 0.5, -3.0, 7.0, np.nan])
    assert c.dtype == np.uint8 and c.shape == (6, 3)
    assert c[0].tolist() == VIRIDIS_ANCHORS[0].tolist()
    assert c[1].tolist() == VIRIDIS_ANCHORS[-1].tolist()
    assert c[2].tolist() == VIRIDIS_ANCHORS[4].tolist()
    assert c[3].tolist() == c[0].tolist() and c[5].tolist() == c[0].tolist()
    assert c[4].tolist() == c[1].tolist()
    # Brightness grows along the map (viridis is perceptually ordered).
    t = np.linspace(0, 1, 50)
    assert np.all(np.diff(colormap(t).astype(float).sum(axis=1)) >= -3)


def test_value_colors_scale_feasible_and_mark_infeasible() -> None:
    q = np.array([1.0, 3.0, 2.0, 100.0, -np.inf])
    feasible = np.array([True, True, True, False, True])
    c = value_colors(q, feasible)
    assert c[3].tolist() == list(INFEASIBLE_COLOR)  # highest value, but infeasible
    assert c[0].tolist() == VIRIDIS_ANCHORS[0].tolist()  # lowest feasible
    assert c[1].tolist() == VIRIDIS_ANCHORS[-1].tolist()  # highest feasible
    assert c[2].tolist() == VIRIDIS_ANCHORS[4].tolist()  # halfway
    assert c[4].tolist() == VIRIDIS_ANCHORS[0].tolist()  # not backed up yet: the bottom
    same = value_colors([2.0, 2.0], [True, True])
    assert same.tolist() == [VIRIDIS_ANCHORS[-1].tolist()] * 2
    none = value_colors([1.0, 2.0], [False, False], (1, 2, 3))
    assert none.tolist() == [[1, 2, 3], [1, 2, 3]]
    assert value_colors([], []).shape == (0, 3)
    with pytest.raises(ValueError, match="same length"):
        value_colors([1.0, 2.0], [True])


def test_check_color() -> None:
    assert check_color((1, 2, 3), "c") == (1, 2, 3)
    assert check_color([np.int64(255), 0, 0], "c") == (255, 0, 0)
    for bad in ((1, 2), (1, 2, 256), (1.0, 2, 3), "red", (True, 0, 0), None):
        with pytest.raises(ValueError, match="infeasible_color must be three integers"):
            check_color(bad, "infeasible_color")
