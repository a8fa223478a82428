"""Tests of voot.envs.motion.footprint.search (through BasePlanner.plan_footprint)."""

from __future__ import annotations

import itertools
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from voot.envs.motion.footprint.shape import Footprint, FootprintConfig, footprint_hits
from voot.envs.motion.planar import Box2D, path_length, wrap_angle
from voot.envs.motion.planner import BasePlanner, BasePlannerConfig

WS = (0.0, 6.0, 0.0, 4.0)
#: A 1.6 m x 0.6 m robot with its load: its enclosing disc (0.854 m) cannot pass a 1 m door.
BODY = Footprint((Box2D(0.0, 0.0, 0.8, 0.3, 0.0, "body"),))
RADIUS = math.hypot(0.8, 0.3)
CFG = FootprintConfig(xy_step=0.05, headings=36)


def door_wall(width: float) -> list[Box2D]:
    """A wall at x = 3 with a door of ``width`` centred at y = 2."""
    lo, hi = 2.0 - width / 2, 2.0 + width / 2
    return [
        Box2D(3.0, lo / 2, 0.05, lo / 2, 0.0, "wall_s"),
        Box2D(3.0, (4.0 + hi) / 2, 0.05, (4.0 - hi) / 2, 0.0, "wall_n"),
    ]


def planner(width: float, **kwargs: object) -> BasePlanner:
    return BasePlanner(
        WS,
        door_wall(width),
        BasePlannerConfig(footprint=FootprintConfig(**{**CFG.__dict__, **kwargs})),
    )


#: Long axis along the wall at both ends: the robot must turn to pass the door.
START, GOAL = (1.0, 2.0, math.pi / 2), (5.0, 2.0, math.pi / 2)


def shrunk(fp: Footprint, margin: float) -> Footprint:
    return Footprint(
        tuple(Box2D(p.cx, p.cy, p.half_x - margin, p.half_y - margin, p.yaw) for p in fp.parts)
    )


def test_the_footprint_passes_a_door_the_disc_cannot() -> None:
    p = planner(1.0)
    assert p.plan(START, GOAL, RADIUS) is None
    path = p.plan_footprint(START, GOAL, RADIUS, BODY)
    assert path is not None
    w = path.waypoints
    assert tuple(w[0]) == START and tuple(w[-1]) == GOAL
    assert path.length == path_length(w, 1.0)
    walls = door_wall(1.0)
    for q in w:
        assert not footprint_hits(BODY, tuple(q), walls, WS)
    # between waypoints: free up to the lattice's tolerance (one step, one heading step)
    margin = CFG.xy_step * math.sqrt(2) + BODY.reach * CFG.heading_step
    tight = shrunk(BODY, margin)
    crossing = []
    for a, b in itertools.pairwise(w):
        d = float(wrap_angle(b[2] - a[2]))
        for t in np.linspace(0.0, 1.0, 40):
            q = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * d)
            assert not footprint_hits(tight, q, walls, WS)
            if abs(q[0] - 3.0) < 0.05:
                crossing.append(abs(math.cos(q[2])))
    # its long axis crosses the door (diagonally is enough in a 0.1 m wall)
    assert crossing and min(crossing) > 0.6
    # longer than the straight line (it turns), shorter than it plus two quarter turns + 1 m
    assert 4.0 + 0.5 < path.length < 4.0 + math.pi + 1.0


@pytest.mark.parametrize("label_after", [0, 30, 10**9])
def test_no_path_through_a_door_narrower_than_every_heading(label_after: int) -> None:
    p = planner(0.5, label_after=label_after)
    assert p.plan_footprint(START, GOAL, RADIUS, BODY) is None
    assert (
        planner(1.0, label_after=label_after).plan_footprint(START, GOAL, RADIUS, BODY) is not None
    )


def test_disc_path_first_and_option_off() -> None:
    wide = planner(2.5)
    disc = wide.plan(START, GOAL, RADIUS)
    assert disc is not None
    assert wide.plan_footprint(START, GOAL, RADIUS, BODY) == disc
    off = BasePlanner(WS, door_wall(1.0))
    assert off.plan_footprint(START, GOAL, RADIUS, BODY) is None
    with pytest.raises(ValueError, match="footprint is None"):
        off.footprint_search()
    with pytest.raises(ValueError, match="must be a Footprint"):
        planner(1.0).plan_footprint(START, GOAL, RADIUS, "body")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="FootprintConfig"):
        BasePlannerConfig(footprint=0.05)  # type: ignore[arg-type]


def test_colliding_ends_have_no_path() -> None:
    p = planner(1.0)
    assert p.plan_footprint((3.0, 1.0, 0.0), GOAL, RADIUS, BODY) is None  # in the wall
    assert p.plan_footprint(START, (5.5, 2.0, 0.0), RADIUS, BODY) is None  # leaves the workspace
    # a movable box on the goal
    assert (
        p.plan_footprint(START, GOAL, RADIUS, BODY, [Box2D(5.0, 2.0, 0.2, 0.2, 0.0, "box")]) is None
    )


def test_movable_boxes_block_the_door() -> None:
    p = planner(1.0)
    box = Box2D(3.0, 2.0, 0.15, 0.15, 0.0, "plug")
    assert p.plan_footprint(START, GOAL, RADIUS, BODY, [box]) is None
    # the same query without it again (the caches hold the scenes apart)
    assert p.plan_footprint(START, GOAL, RADIUS, BODY) is not None


def _answer() -> str:
    path = planner(1.0).plan_footprint(START, GOAL, RADIUS, BODY)
    assert path is not None
    return f"{path.waypoints.tobytes().hex()} {path.length!r}"


def test_same_path_in_another_process_and_with_warm_caches() -> None:
    here = Path(__file__).resolve()
    code = (
        f"import sys; sys.path[:0] = [{str(here.parent)!r}, {str(here.parents[3])!r}];"
        "from test_footprint_search import _answer; print(_answer())"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    first = _answer()
    assert out.stdout.strip() == first
    p = planner(1.0)
    p.plan_footprint(START, (4.5, 1.0, 1.0), RADIUS, BODY)
    again = p.plan_footprint(START, GOAL, RADIUS, BODY)
    assert again is not None
    assert f"{again.waypoints.tobytes().hex()} {again.length!r}" == first


def test_coarse_first_answers_as_the_lattice_does() -> None:
    """coarse_first: the same "a path exists" answers, every path free, deterministic."""
    plug = Box2D(3.0, 2.0, 0.15, 0.15, 0.0, "plug")
    side = Box2D(4.2, 2.9, 0.3, 0.2, 0.5, "side")
    goals = [GOAL, (4.5, 1.0, 1.0), (5.0, 3.2, 0.0), (1.0, 0.6, 2.5)]
    answers = {False: [], True: []}
    for width in (0.5, 0.62, 0.7, 1.0):
        for coarse in (False, True):
            p = planner(width, coarse_first=coarse)
            if coarse:
                search = p.footprint_search()
                assert search._coarse is not None
                assert search._coarse.lattice.shape == (18, 61, 41)
            for goal in goals:
                for movable in ((), (side,), (plug,)):
                    path = p.plan_footprint(START, goal, RADIUS, BODY, movable)
                    answers[coarse].append(path is not None)
                    if path is None:
                        continue
                    w = path.waypoints
                    assert tuple(w[0]) == START and tuple(w[-1]) == goal
                    obstacles = door_wall(width) + list(movable)
                    for q in w:
                        assert not footprint_hits(BODY, tuple(q), obstacles, WS)
                    again = planner(width, coarse_first=coarse).plan_footprint(
                        START, goal, RADIUS, BODY, movable
                    )
                    assert again is not None and np.array_equal(again.waypoints, w)
    assert answers[True] == answers[False]
    assert 0 < sum(answers[True]) < len(answers[True])


def test_coarse_first_needs_a_lattice_to_halve() -> None:
    with pytest.raises(ValueError, match="coarse_first"):
        FootprintConfig(headings=35, coarse_first=True)
    with pytest.raises(ValueError, match="coarse_first"):
        FootprintConfig(xy_step=0.15, coarse_first=True)
    with pytest.raises(ValueError, match="coarse_first"):
        FootprintConfig(coarse_first=1)  # type: ignore[arg-type]


def test_coarse_first_without_a_hub_reaches_the_start() -> None:
    """The lattice search alone (no disc hub): the coarse path is joined to both ends."""
    from voot.envs.motion.footprint.search import FootprintSearch

    walls = tuple(door_wall(1.0))
    fine = FootprintSearch(WS, walls, CFG)
    coarse = FootprintSearch(WS, walls, FootprintConfig(**{**CFG.__dict__, "coarse_first": True}))
    for start, goal in (
        (START, GOAL),
        ((1.02, 1.97, 1.6), (4.96, 2.04, 1.5)),
        (START, (3.0, 2.0, 0.0)),
    ):
        a, b = fine.plan(start, goal, BODY, ()), coarse.plan(start, goal, BODY, ())
        assert (a is None) == (b is None)
        if b is None:
            continue
        assert tuple(b[0]) == start and tuple(b[-1]) == goal
        for q in b:
            assert not footprint_hits(BODY, tuple(q), walls, WS)
