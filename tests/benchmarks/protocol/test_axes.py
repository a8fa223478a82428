"""Tests of voot.bench.protocol.axes: the three x axes and the honest common grid of a cost axis."""

from __future__ import annotations

import numpy as np
import pytest

from voot.bench.protocol.axes import (
    AXES,
    AXIS_NAMES,
    get_axis,
    has_axis_data,
    on_cost_grid,
    read_steps,
)

NAN = np.nan


def test_the_three_axes_and_their_files() -> None:
    assert AXIS_NAMES == ("simulations", "calls", "cpu")
    assert get_axis("calls").key == "calls_curve" and get_axis("cpu").key == "cpu_elapsed"
    assert get_axis("simulations").key is None
    assert len({a.png for a in AXES.values()}) == 3
    assert "pre-checks" in get_axis("calls").caption
    with pytest.raises(ValueError, match="valid axes are: simulations, calls, cpu"):
        get_axis("wall")


def test_read_steps_carries_forward_and_never_extrapolates() -> None:
    values = np.array([[1.0, 2.0, 5.0], [0.0, 4.0, 4.0]])
    x = np.array([[10.0, 20.0, 30.0], [5.0, 6.0, 100.0]])
    grid = np.array([4.0, 5.0, 15.0, 29.9, 30.0, 31.0, 100.0, 101.0])
    out = read_steps(values, x, grid)
    # seed 0: nothing before its first simulation, the last value up to its end, then none
    assert np.array_equal(out[0], [NAN, NAN, 1.0, 2.0, 5.0, NAN, NAN, NAN], equal_nan=True)
    assert np.array_equal(out[1], [NAN, 0.0, 4.0, 4.0, 4.0, 4.0, 4.0, NAN], equal_nan=True)


def test_read_steps_checks_its_input() -> None:
    with pytest.raises(ValueError, match="same shape"):
        read_steps(np.zeros((1, 2)), np.zeros((1, 3)), np.zeros(2))
    with pytest.raises(ValueError, match="must not decrease"):
        read_steps(np.zeros((1, 2)), np.array([[2.0, 1.0]]), np.zeros(2))
    # unknown (NaN) x entries are skipped, a row of them gives no value
    out = read_steps(
        np.array([[1.0, 2.0], [3.0, 4.0]]), np.array([[1.0, NAN], [NAN, NAN]]), np.array([1.0, 2.0])
    )
    assert np.array_equal(out, [[1.0, NAN], [NAN, NAN]], equal_nan=True)


def test_on_cost_grid_spans_every_seed_and_masks_where_few_remain() -> None:
    values = np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0], [7.0, 8.0]])
    x = np.array([[1.0, 2.0], [1.0, 4.0], [1.0, 6.0], [NAN, NAN]])  # the last seed lacks x
    grid, samples = on_cost_grid(values, x, points=6, min_share=0.5, hold_final=False)
    assert grid[0] == 1.0 and grid[-1] == 6.0 and samples.shape == (3, 6)
    count = (~np.isnan(samples)).sum(axis=0)
    # past x = 4 only one of three seeds is left: below half, nothing is drawn there
    assert np.all(count[grid <= 4.0] >= 2) and np.all(count[grid > 4.0] == 0)
    # by default a finished seed keeps its final value: all three contribute to the end
    _, held = on_cost_grid(values, x, points=6, min_share=0.5)
    assert np.array_equal(held[:, -1], [2.0, 4.0, 6.0])
    _, all_kept = on_cost_grid(values, x, points=6, min_share=0.0, hold_final=False)
    assert (~np.isnan(all_kept[:, -1])).sum() == 1  # the last seed alone at the end
    assert has_axis_data(x).tolist() == [True, True, True, False]


def test_on_cost_grid_without_data_and_bad_options() -> None:
    grid, samples = on_cost_grid(np.zeros((2, 3)), np.full((2, 3), NAN))
    assert grid.size == 0 and samples.size == 0
    with pytest.raises(ValueError, match="points"):
        on_cost_grid(np.zeros((1, 2)), np.ones((1, 2)), points=1)
    with pytest.raises(ValueError, match="min_share"):
        on_cost_grid(np.zeros((1, 2)), np.ones((1, 2)), min_share=1.5)
