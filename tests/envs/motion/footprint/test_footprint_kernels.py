"""Tests of voot.envs.motion.footprint.kernels: each kernel against the Python it copies."""

from __future__ import annotations

import heapq
import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from voot.envs.motion.footprint.astar import numba_available
from voot.envs.motion.footprint.shape import Footprint, FootprintConfig, FootprintLattice
from voot.envs.motion.planar import Box2D
from voot.envs.motion.planner import BasePlanner

pytestmark = pytest.mark.skipif(not numba_available(), reason="numba is not installed")

WS = (0.0, 4.0, 0.0, 3.0)
FP = Footprint(
    (
        Box2D(0.0, 0.0, 0.35, 0.3, 0.0, "base"),
        Box2D(0.5, 0.1, 0.25, 0.05, 0.2, "arm"),
        Box2D(0.8, 0.1, 0.2, 0.15, -0.4, "load"),
    )
)


def test_the_heap_pops_as_heapq_with_ties() -> None:
    from voot.envs.motion.footprint import kernels as K

    rng = np.random.default_rng(3)
    entries = [(float(f), int(v)) for f, v in zip(rng.integers(0, 20, 400) / 4.0,
                                                   rng.permutation(400), strict=True)]  # fmt: skip
    keys, vals = np.empty(400), np.empty(400, dtype=np.int64)
    n = 0
    heap: list[tuple[float, int]] = []
    for f, v in entries:
        n = K._push(keys, vals, n, f, v)
        heapq.heappush(heap, (f, v))
    out = []
    while n:
        out.append((float(keys[0]), int(vals[0])))
        n = K._pop(keys, vals, n)
    assert out == [heapq.heappop(heap) for _ in range(len(out))] and len(out) == 400


@settings(max_examples=30, deadline=None)
@given(
    st.floats(-0.5, 4.5),
    st.floats(-0.5, 3.5),
    st.floats(0.02, 0.6),
    st.floats(0.02, 0.6),
    st.floats(-math.pi, math.pi),
)
def test_blocked_window_compiled_is_numpys(
    cx: float, cy: float, hx: float, hy: float, yaw: float
) -> None:
    cfg = FootprintConfig(xy_step=0.05, headings=24, engine="python")
    box = Box2D(cx, cy, hx, hy, yaw, "box")
    ref = FootprintLattice(WS, cfg).blocked_window(FP, box)
    got = FootprintLattice(WS, replace(cfg, engine="compiled")).blocked_window(FP, box)
    if ref is None or got is None:
        assert ref is None and got is None
        return
    assert ref[:4] == got[:4]
    assert np.array_equal(ref[4], got[4])


def test_the_disc_test_is_the_planners() -> None:
    from voot.envs.motion.footprint import kernels as K

    walls = [Box2D(2.0, 1.0, 0.05, 1.0, 0.3, "wall"), Box2D(1.0, 2.4, 0.4, 0.2, 1.0, "table")]
    probe = BasePlanner(WS, walls).disc_probe([Box2D(3.0, 2.0, 0.2, 0.3, 0.0, "box")])
    r_hit, boxes = probe.blocked_data(0.45)
    par = np.array([1.0, 1.0, r_hit, *WS])
    rng = np.random.default_rng(0)
    answers = []
    for x, y in rng.uniform((-0.2, -0.2), (4.2, 3.2), (3000, 2)).tolist():
        answers.append(K._disc_free(x, y, par, boxes))
        assert answers[-1] == (not probe.blocked(x, y, 0.45))
    assert 0 < sum(answers) < len(answers)
    par[1] = 0.0  # the start is not free: no position is
    assert K._disc_free(1.0, 1.0, par, boxes) == 0


def test_tile_lists_name_exactly_the_boxes_whose_window_meets_each_tile() -> None:
    from voot.envs.motion.footprint import kernels as K

    rng = np.random.default_rng(5)
    nx, ny, side = 70, 53, 1 << K.TILE_SHIFT
    wins = np.zeros((12, 2, 4), dtype=np.int64)
    for b in range(12):
        i0, j0 = int(rng.integers(0, nx)), int(rng.integers(0, ny))
        wins[b, 0] = (i0, min(nx, i0 + int(rng.integers(0, 40))), j0,
                      min(ny, j0 + int(rng.integers(1, 40))))  # fmt: skip
    out = K.tile_lists(wins, nx, ny)
    nty = out[0]
    for t in range(out[1]):
        ti, tj = divmod(t, nty)
        listed = sorted(out[out[2 + t] : out[3 + t]].tolist())
        meets = [
            b for b in range(12)
            if wins[b, 0, 0] < wins[b, 0, 1] and wins[b, 0, 2] < wins[b, 0, 3]
            and wins[b, 0, 0] < (ti + 1) * side and wins[b, 0, 1] > ti * side
            and wins[b, 0, 2] < (tj + 1) * side and wins[b, 0, 3] > tj * side
        ]  # fmt: skip
        assert listed == meets
    assert any(wins[b, 0, 0] >= wins[b, 0, 1] for b in range(12))  # an empty window too


def test_dense_tables_give_the_same_paths_after_many_searches() -> None:
    """Searches that share the g and move tables (never cleared) answer as fresh ones."""
    from voot.envs.motion.footprint.search import FootprintSearch

    cfg = FootprintConfig(xy_step=0.1, headings=24)
    walls = (Box2D(2.0, 0.8, 0.05, 0.8, 0.0, "wall"),)
    shared = FootprintSearch(WS, walls, cfg)
    goals = [(3.0, 0.9, 1.57), (3.0, 2.2, 0.0), (2.5, 2.0, -1.57), (3.2, 0.5, 0.3)]
    found = 0
    for goal in goals * 2:
        a = shared.plan((1.0, 2.0, 0.0), goal, FP, ())
        b = FootprintSearch(WS, walls, cfg).plan((1.0, 2.0, 0.0), goal, FP, ())
        assert (a is None and b is None) or (
            a is not None and b is not None and np.array_equal(a, b)
        )
        found += a is not None
    assert found == 4  # two goals reached, each twice; two refused
