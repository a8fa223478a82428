"""Tests of voot.envs.motion.graph_search: A* and the no-path shortcut agree with the search."""

from __future__ import annotations

import numpy as np
from floor_plans import (
    WORKSPACE,
    house_movable,
    house_static,
    random_free_poses,
)

from voot.envs.motion.graph_search import _astar, no_path, search
from voot.envs.motion.planner import BasePlanner


def test_no_path_shortcut_agrees_with_the_search() -> None:
    """no_path says True only where search finds nothing, and plans are unchanged."""
    static, movable = house_static(), house_movable()
    fast = BasePlanner(WORKSPACE, static)
    for radius in (0.45, 0.52):
        poses = random_free_poses(fast, radius, movable, 60, seed=4)
        for k in range(0, len(poses) - 1, 2):
            s, g = poses[k], poses[k + 1]
            path = fast.plan(s, g, radius, movable)
            scene = fast._scene(fast._inflated_radius(radius), tuple(movable))
            if scene.graph is None:
                continue  # the straight line was free: no search
            ends = np.array([[s.x, s.y], [g.x, g.y]])
            r_hit = scene.radius - fast.config.contact_tolerance
            full = search(scene.graph, ends, scene.boxes, r_hit)
            assert no_path(scene, s.x, s.y, g.x, g.y, r_hit) == (full is None)
            assert (path is None) == (full is None)
    # a door too narrow for the disc: start and goal in different components
    blocked = fast.plan((0.0, 0.0, 0.0), (4.5, -1.5, 0.0), 0.55, movable)
    assert blocked is None


def test_astar_finds_the_shortest_sequence_and_breaks_ties_by_node() -> None:
    """Node -1 is the start and -2 the goal; two equal routes: the lower node index wins."""
    adjacency: list[list[tuple[int, float]]] = [
        [(1, 1.0), (2, 1.0), (4, 0.5)],
        [(0, 1.0), (3, 1.0)],
        [(0, 1.0), (3, 1.0)],
        [(1, 1.0), (2, 1.0)],
        [(0, 0.5), (3, 2.0)],
        [],
    ]
    zero = [0.0] * 6
    assert _astar(adjacency, [(0, 1.0)], {3: 1.0}, zero) == [0, 1, 3]
    # the same with an admissible heuristic (graph distance to the goal)
    assert _astar(adjacency, [(0, 1.0)], {3: 1.0}, [3.0, 2.0, 2.0, 1.0, 3.0, 0.0]) == [0, 1, 3]
    # a direct start edge to the goal's neighbour is shorter
    assert _astar(adjacency, [(0, 1.0), (3, 0.5)], {3: 1.0}, zero) == [3]
    # a goal only reachable from a node with no edges: no path
    assert _astar(adjacency, [(0, 1.0)], {5: 1.0}, zero) is None
