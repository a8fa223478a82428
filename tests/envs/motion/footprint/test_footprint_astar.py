"""Tests of voot.envs.motion.footprint.astar: the compiled A* returns the reference's paths."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from voot.envs.motion.footprint.astar import hypot_table, numba_available
from voot.envs.motion.footprint.search import FootprintSearch
from voot.envs.motion.footprint.shape import Footprint, FootprintConfig
from voot.envs.motion.planar import Box2D, Pose2D
from voot.envs.motion.planner import BasePlanner, BasePlannerConfig, _DiscHub

pytestmark = pytest.mark.skipif(not numba_available(), reason="numba is not installed")

WS = (0.0, 6.0, 0.0, 4.0)
BODY = Footprint((Box2D(0.0, 0.0, 0.8, 0.3, 0.0, "body"), Box2D(0.6, 0.0, 0.2, 0.5, 0.3, "arm")))
RADIUS = math.hypot(0.8, 0.5)
CFG = FootprintConfig(xy_step=0.05, headings=36)
WALLS = (
    Box2D(3.0, 0.7, 0.05, 0.7, 0.0, "wall_s"),
    Box2D(3.0, 3.2, 0.05, 0.8, 0.0, "wall_n"),
    Box2D(1.5, 3.0, 0.4, 0.2, 0.4, "table"),
)
BOXES = (
    Box2D(4.2, 2.9, 0.3, 0.2, 0.5, "side"),
    Box2D(2.2, 1.0, 0.25, 0.25, 0.0, "crate"),
    Box2D(3.0, 2.3, 0.1, 0.1, 0.0, "plug"),
)
QUERIES = [
    ((1.0, 2.0, 0.0), (4.5, 1.0, 1.0)),
    ((1.0, 0.8, 2.5), (5.0, 2.0, 0.0)),
    ((1.0, 2.0, 0.0), (5.2, 2.0, math.pi / 2)),
    ((4.5, 1.0, 1.0), (5.0, 2.0, 0.0)),
]


def _search(engine: str, **kwargs: object) -> FootprintSearch:
    return FootprintSearch(WS, WALLS, replace(CFG, engine=engine, **kwargs))  # type: ignore[arg-type]


def _answers(engine: str, **kwargs: object) -> list[tuple[str | None, int]]:
    """Each query's waypoints (bytes) and expansions, among growing sets of boxes."""
    s = _search(engine, **kwargs)
    out = []
    for n in range(len(BOXES) + 1):
        for start, goal in QUERIES:
            path = s.plan(start, goal, BODY, BOXES[:n])
            out.append((None if path is None else path.tobytes().hex(), s.last_expansions))
    return out


@pytest.mark.parametrize(
    "kwargs",
    [
        {},
        {"lazy_tile": 0},
        {"lazy_tile": 3},
        {"label_after": 40},
        {"heuristic_weight": 1.0},
        {"coarse_first": True},
        {"heuristic": "geodesic"},
        {"heuristic": "geodesic", "label_after": 40},
        {"heuristic": "geodesic", "coarse_first": True},
    ],
)
def test_compiled_and_python_give_the_same_paths_and_expansions(kwargs: dict[str, object]) -> None:
    compiled = _answers("compiled", **kwargs)
    assert compiled == _answers("python", **kwargs)
    # the queries are not trivial: paths and "no path" both occur, with many expansions
    assert any(p is None for p, _ in compiled) and any(p is not None for p, _ in compiled)
    assert max(e for _, e in compiled) > 100


def test_no_path_is_proved_by_labelling() -> None:
    """The crate shuts the west room in: the labelling ends the search in both engines."""
    for engine in ("compiled", "python"):
        s = _search(engine, label_after=25)
        assert s.plan(*QUERIES[0], BODY, BOXES[:2]) is None
        assert s.last_expansions == 25


def _planner_answers(engine: str, heuristic: str = "euclidean") -> list[str | None]:
    """Queries through BasePlanner (the disc hub stops the search early)."""
    footprint = replace(CFG, engine=engine, heuristic=heuristic)
    p = BasePlanner(WS, list(WALLS), BasePlannerConfig(footprint=footprint))
    out = []
    for boxes in ((), BOXES[:1], BOXES[:2]):
        for start, goal in QUERIES:
            path = p.plan_footprint(start, goal, RADIUS, BODY, list(boxes))
            out.append(None if path is None else path.waypoints.tobytes().hex())
    return out


@pytest.mark.parametrize("heuristic", ["euclidean", "geodesic"])
def test_the_disc_hub_gives_the_same_paths(heuristic: str) -> None:
    compiled = _planner_answers("compiled", heuristic)
    assert compiled == _planner_answers("python", heuristic)
    assert any(p is not None for p in compiled)


class _AskHub:
    """A hub without ``disc_data``: the compiled loop asks it position by position."""

    def __init__(self, hub: _DiscHub) -> None:
        self.is_free = hub.is_free
        self.connect = hub.connect


def test_a_hub_without_disc_data_is_asked_and_gives_the_same_paths() -> None:
    p = BasePlanner(WS, list(WALLS), BasePlannerConfig(footprint=CFG))
    compiled, python = _search("compiled"), _search("python")
    answers = []
    for boxes in ((), BOXES[:1]):
        for start, goal in QUERIES:
            s_hub = _DiscHub(p, Pose2D(*start), RADIUS, boxes)
            a = compiled.plan(start, goal, BODY, boxes, _AskHub(s_hub))  # type: ignore[arg-type]
            b = python.plan(start, goal, BODY, boxes, s_hub)
            assert (a is None) == (b is None) and (a is None or a.tobytes() == b.tobytes())
            answers.append(a is not None)
    assert any(answers)


@settings(max_examples=25, deadline=None)
@given(
    st.lists(st.floats(0.3, 5.7), min_size=2, max_size=2),
    st.lists(st.floats(0.3, 3.7), min_size=2, max_size=2),
    st.lists(st.floats(-math.pi, math.pi), min_size=2, max_size=2),
    st.integers(0, len(BOXES)),
)
def test_random_queries_give_the_same_paths(
    xs: list[float], ys: list[float], ths: list[float], n: int
) -> None:
    start, goal = (xs[0], ys[0], ths[0]), (xs[1], ys[1], ths[1])
    answers: dict[tuple[str, str], tuple[bytes | None, int]] = {}
    for heuristic in ("euclidean", "geodesic"):
        for engine in ("compiled", "python"):
            key = (engine, heuristic)
            s = _SEARCHES.setdefault(key, _search(engine, heuristic=heuristic))
            path = s.plan(start, goal, BODY, BOXES[:n])
            answers[key] = (None if path is None else path.tobytes(), s.last_expansions)
    assert answers["compiled", "euclidean"] == answers["python", "euclidean"]
    assert answers["compiled", "geodesic"] == answers["python", "geodesic"]
    # the heuristics change the path, never whether there is one
    assert (answers["compiled", "euclidean"][0] is None) == (
        answers["compiled", "geodesic"][0] is None
    )


_SEARCHES: dict[tuple[str, str], FootprintSearch] = {}


def test_geodesic_answers_a_walled_off_goal_without_searching() -> None:
    """A static wall shuts the east half: no path, found before any expansion; the
    straight-line heuristic proves it only by labelling."""
    shut = (*WALLS, Box2D(3.0, 1.9, 0.05, 0.6, 0.0, "door"))
    start, goal = QUERIES[0]
    for engine in ("compiled", "python"):
        geo = FootprintSearch(WS, shut, replace(CFG, engine=engine, heuristic="geodesic"))
        assert geo.plan(start, goal, BODY, ()) is None and geo.last_expansions == 0
        line = FootprintSearch(WS, shut, replace(CFG, engine=engine, label_after=30))
        assert line.plan(start, goal, BODY, ()) is None and line.last_expansions == 30


def test_heuristic_is_validated() -> None:
    with pytest.raises(ValueError, match=r"heuristic must be one of \('euclidean', 'geodesic'\)"):
        FootprintConfig(heuristic="manhattan")


def test_thehypot_table_is_cpythons() -> None:
    table = hypot_table(7, 5)
    assert table.shape == (7, 5)
    assert all(table[a, b] == math.hypot(a, b) for a in range(7) for b in range(5))


def test_engine_is_validated() -> None:
    with pytest.raises(ValueError, match=r"engine must be one of \('compiled', 'python'\)"):
        FootprintConfig(engine="numba")


def test_compiled_in_a_fresh_process_with_a_cache_dir(tmp_path: Path) -> None:
    """A new process (its own compile or the disk cache) answers as this one, without warnings."""
    here = Path(__file__).resolve()
    code = (
        "import warnings; warnings.simplefilter('error');"
        f"import sys; sys.path[:0] = [{str(here.parent)!r}, {str(here.parents[4])!r}];"
        "from test_footprint_astar import _answers; print(_answers('compiled'))"
    )
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    for _ in range(2):  # the second run loads the cache written by the first
        out = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
        )
        assert out.stdout.strip() == repr(_answers("python"))
    assert any(tmp_path.rglob("kernels.*.nbi"))


def test_compiled_without_a_cache_location() -> None:
    """No writable cache (numba finds no locator): compiled in the process, no warning."""
    here = Path(__file__).resolve()
    code = (
        "import warnings; warnings.simplefilter('error');"
        f"import sys; sys.path[:0] = [{str(here.parent)!r}, {str(here.parents[4])!r}];"
        "from test_footprint_astar import _answers; print(_answers('compiled'))"
    )
    # ZipCacheLocator alone finds no place for a module outside a zip file
    env = {**os.environ, "NUMBA_CACHE_LOCATOR_CLASSES": "ZipCacheLocator"}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert out.stdout.strip() == repr(_answers("python"))
