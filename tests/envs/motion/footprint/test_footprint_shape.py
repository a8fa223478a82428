"""Tests of voot.envs.motion.footprint.shape: the oriented footprint and its lattice occupancy."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voot.envs.motion.footprint.shape import (
    Footprint,
    FootprintConfig,
    FootprintLattice,
    bound_boxes,
    footprint_hits,
)
from voot.envs.motion.planar import Box2D

WS = (0.0, 4.0, 0.0, 3.0)
#: A long robot: a 1.6 m x 0.6 m rectangle about the planned point, plus a small arm.
LONG = Footprint((Box2D(0.0, 0.0, 0.8, 0.3, 0.0, "body"), Box2D(0.5, 0.2, 0.1, 0.15, 0.3, "arm")))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"xy_step": 0.0}, "xy_step"),
        ({"xy_step": 0.5}, "xy_step"),
        ({"headings": 4}, "headings"),
        ({"heading_weight": 1}, "unexpected"),
        ({"heuristic_weight": 0.5}, "heuristic_weight"),
        ({"static_cache_size": 0}, "static_cache_size"),
        ({"label_after": -1}, "label_after"),
    ],
)
def test_config_validation(kwargs: dict, match: str) -> None:
    with pytest.raises((ValueError, TypeError), match=match):
        FootprintConfig(**kwargs)


def test_footprint_needs_boxes() -> None:
    with pytest.raises(ValueError, match="one or more Box2D"):
        Footprint(())
    with pytest.raises(ValueError, match="one or more Box2D"):
        Footprint(((0.0, 0.0),))  # type: ignore[arg-type]


def test_footprint_pose_and_reach() -> None:
    world = LONG.at(1.0, 2.0, math.pi / 2)
    assert world[0].cx == pytest.approx(1.0) and world[0].cy == pytest.approx(2.0)
    assert world[1].cx == pytest.approx(1.0 - 0.2) and world[1].cy == pytest.approx(2.5)
    assert world[1].yaw == pytest.approx(math.pi / 2 + 0.3)
    corners = np.concatenate([p.corners() for p in LONG.parts])
    assert LONG.reach == pytest.approx(float(np.hypot(corners[:, 0], corners[:, 1]).max()))


def test_hits_turns_with_the_heading() -> None:
    wall = Box2D(2.0, 1.5, 0.05, 1.5, 0.0, "wall")
    # 0.5 m from the wall: the long side along x reaches it, along y it does not
    assert footprint_hits(LONG, (1.45, 1.5, 0.0), [wall])
    assert not footprint_hits(LONG, (1.45, 1.5, math.pi / 2), [wall])
    # the workspace counts when given
    assert footprint_hits(LONG, (0.5, 1.5, 0.0), [], WS)
    assert not footprint_hits(LONG, (0.5, 1.5, math.pi / 2), [], WS)


def test_lattice_occupancy_is_the_exact_test_at_every_lattice_pose() -> None:
    """Vectorised windows agree with the scalar separating-axis test pose by pose."""
    cfg = FootprintConfig(xy_step=0.1, headings=24)
    lat = FootprintLattice(WS, cfg)
    rng = np.random.default_rng(3)
    boxes = tuple(
        Box2D(float(rng.uniform(0.5, 3.5)), float(rng.uniform(0.5, 2.5)),
              float(rng.uniform(0.05, 0.4)), float(rng.uniform(0.05, 0.4)),
              float(rng.uniform(-3, 3)), f"b{k}")
        for k in range(4)
    ) + bound_boxes(WS)  # fmt: skip
    occ = lat.occupancy(LONG, boxes)
    assert occ.shape == (24, lat.nx, lat.ny)
    assert 0.05 < occ.mean() < 0.95
    for _ in range(3000):
        k, i, j = int(rng.integers(24)), int(rng.integers(lat.nx)), int(rng.integers(lat.ny))
        assert occ[k, i, j] == footprint_hits(LONG, lat.pose(k, i, j), boxes[:4], WS)


def test_each_part_window_misses_no_pose() -> None:
    """Each rectangle is tested on its own window only: every lattice pose still agrees.

    A small part at the planned point and a far one (1.2 m out) beside one small box:
    checked exhaustively, so a window cut too tight for either part shows up.
    """
    far = Footprint(
        (Box2D(0.0, 0.0, 0.1, 0.1, 0.0, "base"), Box2D(1.2, -0.3, 0.2, 0.05, 0.7, "load"))
    )
    lat = FootprintLattice(WS, FootprintConfig(xy_step=0.1, headings=24))
    box = Box2D(2.05, 1.45, 0.12, 0.3, 0.4, "box")
    window = lat.blocked_window(far, box)
    assert window is not None
    occ = lat.occupancy(far, (box,))
    assert occ.any()
    for k in range(lat.nk):
        for i in range(lat.nx):
            for j in range(lat.ny):
                assert occ[k, i, j] == footprint_hits(far, lat.pose(k, i, j), [box])


def test_nearest_lattice_pose() -> None:
    lat = FootprintLattice(WS, FootprintConfig(xy_step=0.1, headings=36))
    assert lat.nearest(0.26, 0.04, math.radians(-4.0)) == (0, 3, 0)
    assert lat.nearest(0.26, 0.04, math.radians(-6.0)) == (35, 3, 0)
    assert lat.nearest(-0.2, 1.0, 0.0) is None
    assert lat.pose(18, 1, 2) == (pytest.approx(0.1), pytest.approx(0.2), pytest.approx(-math.pi))


def test_the_compiled_engine_without_numba_says_how_to_do_without(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "numba" else real(name, *a)
    )
    ws = (0.0, 2.0, 0.0, 2.0)
    with pytest.raises(ImportError, match='engine="python" runs the same search'):
        FootprintLattice(ws, FootprintConfig(xy_step=0.1, headings=16))
    FootprintLattice(ws, FootprintConfig(xy_step=0.1, headings=16, engine="python"))
