"""Tests of voot.envs.motion.visibility_graph: bitangent pruning, the two build routes, caches."""

from __future__ import annotations

import numpy as np
import pytest
from floor_plans import (
    WORKSPACE,
    house_movable,
    house_static,
    random_free_poses,
)

import voot.envs.motion.graph_search as gs
import voot.envs.motion.visibility_graph as vg
from voot.envs.motion.disc_geometry import (
    BoxArrays,
    points_hit_boxes,
    points_inside,
)
from voot.envs.motion.planar import Box2D, Pose2D
from voot.envs.motion.planner import BasePlanner, BasePlannerConfig
from voot.envs.motion.visibility_graph import _box_lists, _Graph, _Scene


def test_bitangent_pruning_keeps_shortest_paths(monkeypatch: pytest.MonkeyPatch) -> None:
    """The reduced visibility graph gives the same lengths as the full one."""
    static, movable = house_static(), house_movable()
    queries = []
    for radius in (0.3, 0.45):
        planner = BasePlanner(WORKSPACE, static)
        starts = random_free_poses(planner, radius, movable, 15, seed=3)
        goals = random_free_poses(planner, radius, movable, 15, seed=4)
        queries += [(s, g, radius) for s, g in zip(starts, goals, strict=True)]
    reduced = BasePlanner(WORKSPACE, static)
    lengths = [reduced.plan(s, g, r, movable) for s, g, r in queries]
    # every pair a candidate, in the graph and where the search connects its ends
    for module in (vg, gs):
        monkeypatch.setattr(
            module,
            "_tangent_grid",
            lambda nodes, ux, uy, axis: np.ones(np.broadcast(ux, uy).shape, dtype=bool),
        )
    full = BasePlanner(WORKSPACE, static)
    multi = 0
    for (s, g, r), a in zip(queries, lengths, strict=True):
        b = full.plan(s, g, r, movable)
        assert (a is None) == (b is None)
        if a is not None and b is not None:
            assert a.length == pytest.approx(b.length, abs=1e-9)
            multi += len(a.waypoints) > 2
    assert multi >= 3


def _graph_arrays(graph: _Graph) -> list[bytes]:
    nodes = graph.nodes
    return [a.tobytes() for a in (nodes.pos, nodes.to_prev, nodes.to_next, graph.i, graph.j)] + [
        graph.w.tobytes()
    ]


@pytest.mark.parametrize("movable_count", [0, 1, 4, 10])
def test_one_pass_graph_is_the_graph_on_the_static_one(movable_count: int) -> None:
    """Both routes of VisibilityGraphs.build give the same nodes and edges, bit for bit."""
    static, movable = house_static(), tuple(house_movable()[:movable_count])
    planner = BasePlanner(WORKSPACE, static)
    for radius in (0.3, 0.4137, 0.52, 0.61):
        scene = planner._scene(radius, movable)
        one_pass = planner._graphs._one_pass_graph(scene)
        static_graph = planner._graphs._static_graph(radius)  # cached: the second route now
        layered = planner._graphs.build(scene)
        assert planner._graphs._static_cache[radius] is static_graph
        assert len(one_pass.i) > 0
        assert _graph_arrays(one_pass) == _graph_arrays(layered)


def test_free_mask_is_the_full_point_box_test() -> None:
    """The corner prefilter of _free_mask drops only pairs that cannot meet."""
    rng = np.random.default_rng(8)
    static = house_static()
    planner = BasePlanner(WORKSPACE, static, BasePlannerConfig(corner_segments=3))
    freed = covered = 0
    for k in range(40):
        movable = [
            Box2D(
                *rng.uniform((-1.8, -3.8), (5.8, 3.8)),
                *rng.uniform(0.05, 0.5, 2),
                float(rng.uniform(-3, 3)),
                f"m{i}",
            )
            for i in range(int(rng.integers(0, 8)))
        ]
        boxes = BoxArrays.from_boxes(static + movable)
        owners = BoxArrays.from_boxes(movable) if k % 2 else boxes
        radius = float(rng.uniform(0.05, 1.5))
        r_hit = radius - planner.config.contact_tolerance
        nodes = planner._graphs._polygon_nodes(owners, radius)
        mask = planner._graphs._free_mask(owners, nodes, boxes, radius, r_hit)
        full = points_inside(nodes.pos, WORKSPACE, r_hit) & ~points_hit_boxes(
            nodes.pos, boxes, r_hit
        ).any(axis=1)
        assert mask.tolist() == full.tolist()
        freed += int(full.sum())
        covered += int((~full).sum())
    assert freed > 100 and covered > 100


def test_a_radius_seen_again_gets_its_static_graph_cached() -> None:
    planner = BasePlanner(WORKSPACE, house_static())
    movable = house_movable()
    s, g = Pose2D(-1.5, 1.0, 0.0), Pose2D(4.5, -1.5, 0.0)  # through the kitchen door
    first = planner.plan(s, g, 0.3, movable[:3])
    assert first is not None and len(first.waypoints) > 2
    assert list(planner._graphs._static_cache) == []  # first sight of the radius: one pass
    second = planner.plan(s, g, 0.3, movable[:2])
    assert list(planner._graphs._static_cache) == [0.3]
    assert second is not None
    planner.clear_caches()
    assert planner.plan(s, g, 0.3, movable[:3]) == first


def test_scene_lists_are_the_boxes_as_floats_built_once() -> None:
    boxes = BoxArrays.from_boxes(house_static())
    scene = _Scene(0.5, BoxArrays.from_boxes([]), boxes)
    first = _box_lists(scene)
    assert first == boxes.lists() and _box_lists(scene) is first
    assert len(first) == 7 and len(first[0]) == len(boxes)
