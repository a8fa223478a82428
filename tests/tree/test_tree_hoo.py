"""Tests of voot.tree.hoo: the HOO bandit used by HOOT."""

from __future__ import annotations

import numpy as np
import pytest

from voot.optim.base import Bounds
from voot.tree import HOO, HOOConfig


def _run(hoo: HOO, f: object, n: int) -> None:
    for _ in range(n):
        cell, _ = hoo.select()
        hoo.update(cell, f(hoo.point(cell)))  # type: ignore[operator]


def test_hoo_concentrates_on_the_optimum() -> None:
    c = np.array([0.3, -0.5])
    hoo = HOO(Bounds.cube(-1.0, 1.0, 2), HOOConfig(v1=1.0, rho=0.5), np.random.default_rng(0))
    _run(hoo, lambda x: 1.0 - float(np.sum((x - c) ** 2)), 400)
    best = hoo.point(hoo.best_cell())
    assert np.linalg.norm(best - c) < 0.15
    # Cells are split ever finer around the optimum.
    depths = [hoo.depth(k) for k in range(1, hoo.n_cells)]
    assert max(depths) >= 6


def test_points_lie_in_their_cells_and_children_halve_the_parent() -> None:
    hoo = HOO(Bounds([0.0, 0.0], [4.0, 1.0]), HOOConfig(), np.random.default_rng(1))
    _run(hoo, lambda x: float(x[0]), 50)
    for k in range(1, hoo.n_cells):
        lo, hi = hoo.cell_bounds(k)
        if hoo._x[k] is not None:
            x = hoo.point(k)
            assert np.all(lo <= x) and np.all(x <= hi)
    lo1, hi1 = hoo.cell_bounds(1)
    lo2, hi2 = hoo.cell_bounds(2)
    assert np.allclose(hi1 - lo1, [2.0, 1.0]) and np.allclose(hi2 - lo2, [2.0, 1.0])


def test_truncation_replays_cells_at_max_depth() -> None:
    hoo = HOO(Bounds.cube(0.0, 1.0, 1), HOOConfig(max_depth=2), np.random.default_rng(0))
    new = 0
    for _ in range(40):
        cell, is_new = hoo.select()
        new += is_new
        assert hoo.depth(cell) <= 2
        hoo.update(cell, float(hoo.point(cell)[0]))
    assert new == 6  # 2 cells at depth 1, 4 at depth 2, then only replays


def test_center_points_are_deterministic() -> None:
    hoo = HOO(Bounds.cube(0.0, 1.0, 1), HOOConfig(point="center"), np.random.default_rng(0))
    cell, _ = hoo.select()
    assert hoo.point(cell)[0] in (0.25, 0.75)


def test_redraw_stays_in_the_cell() -> None:
    hoo = HOO(Bounds.cube(0.0, 1.0, 3), HOOConfig(), np.random.default_rng(0))
    cell, _ = hoo.select()
    lo, hi = hoo.cell_bounds(cell)
    x = hoo.redraw(cell)
    assert np.all(lo <= x) and np.all(x <= hi)


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("v1", -1.0),
        ("rho", 1.0),
        ("rho", 0.0),
        ("exploration", float("inf")),
        ("max_depth", 0),
        ("point", "corner"),
    ],
)
def test_bad_config(field: str, value: object) -> None:
    with pytest.raises(ValueError, match=field):
        HOOConfig(**{field: value})  # type: ignore[arg-type]
