"""Search of the visibility graph: connect start and goal, A*, and the no-path shortcut.

Given the reduced visibility graph of a query's obstacles
(:mod:`voot.envs.motion.visibility_graph`), :func:`search` connects the start and the goal to
every node they see along a tangent (the same tangency and exact segment tests the
graph's edges passed) and runs A* (:func:`_astar`: Euclidean heuristic, ties broken by
``(f, g, node)``, so the result is deterministic) from the start to the goal; the
polyline is the shortest path in the graph.

Tree search asks many goals from one start, and most of them are unreachable (behind a
closed door, inside a cluttered corner). :func:`no_path` answers those without A*: the
search fails iff no node the goal sees lies in a connected component of a node the start
sees, so the graph's components (:func:`_component_lists`) are computed once per graph
and, per start, the nodes of the components the start sees; the goal is then tested
against those nodes on Python floats (:func:`_sees_any`, the array tests' expressions in
the same order), until one connects. A False answer runs :func:`search` as before, so
every path returned is the one it always was (``tests/envs/motion/test_graph_search.py`` checks
that the two agree).
"""

from __future__ import annotations

import heapq
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.envs.motion.disc_geometry import BoxArrays, _segment_hits_any, segments_hit_any
from voot.envs.motion.visibility_graph import (
    _TANGENT_EPS,
    _box_lists,
    _Graph,
    _Scene,
    _tangent_grid,
)

FloatArray = NDArray[np.float64]

__all__ = ["no_path", "search"]


def search(graph: _Graph, ends: FloatArray, boxes: BoxArrays, r_hit: float) -> FloatArray | None:
    """Connect start and goal to the graph and run A*; the polyline or None."""
    nodes = graph.nodes
    n = len(nodes)
    if n == 0:
        return None
    ux = nodes.pos[None, :, 0] - ends[:, 0:1]
    uy = nodes.pos[None, :, 1] - ends[:, 1:2]
    end_k, node_k = np.nonzero(_tangent_grid(nodes, ux, uy, 1))
    ok = ~segments_hit_any(ends[end_k], nodes.pos[node_k], boxes, r_hit)
    end_k, node_k = end_k[ok], node_k[ok]
    if not (np.any(end_k == 0) and np.any(end_k == 1)):
        return None
    lengths = np.hypot(ux[end_k, node_k], uy[end_k, node_k]).tolist()
    start_edges: list[tuple[int, float]] = []
    goal_edges: dict[int, float] = {}
    for e, v, w in zip(end_k.tolist(), node_k.tolist(), lengths, strict=True):
        if e == 0:
            start_edges.append((v, w))
        else:
            goal_edges[v] = w
    heuristic = np.hypot(ux[1], uy[1]).tolist()
    order = _astar(graph.adjacency(), start_edges, goal_edges, heuristic)
    if order is None:
        return None
    polyline: FloatArray = np.concatenate(
        [ends[:1], nodes.pos[np.array(order, dtype=np.intp)], ends[1:]]
    )
    return polyline


def no_path(scene: _Scene, sx: float, sy: float, gx: float, gy: float, r_hit: float) -> bool:
    """Is it certain that :func:`search` finds no path from ``(sx, sy)`` to ``(gx, gy)``?

    :func:`search` fails iff no node the goal connects to is in a connected component
    of the graph holding a node the start connects to. The components are computed
    once per graph and, per start point, the nodes of the components the start
    connects to (a planning session asks many goals from one start; one connected
    node settles a component); the goal is then tested against those nodes only,
    until one connects. A False answer runs :func:`search` as before, so every path
    returned is the one it always was.
    """
    graph = scene.graph
    assert graph is not None
    nodes = graph.nodes
    if len(nodes) == 0:
        return True
    key = (sx, sy)
    reach = scene.reach.get(key)
    if reach is None:
        if scene.components is None:
            scene.components = _component_lists(graph)
        boxes = _box_lists(scene)
        # the components the start connects to (one connected node is enough)
        seen = [c for c in scene.components if _sees_any(c, sx, sy, boxes, r_hit)]
        reach = tuple(
            [v for c in seen for v in c[f]] if f < 6 else [[0] for c in seen for _ in c[0]]
            for f in range(7)
        )
        scene.reach[key] = reach
        if len(scene.reach) > 16:
            scene.reach.popitem(last=False)
    return not _sees_any(reach, gx, gy, _box_lists(scene), r_hit)


def _astar(
    adjacency: list[list[tuple[int, float]]],
    start_edges: list[tuple[int, float]],
    goal_edges: dict[int, float],
    heuristic: list[float],
) -> list[int] | None:
    """A* from a virtual start to a virtual goal over ``adjacency`` (Euclidean heuristic).

    Node ``-1`` is the start, ``-2`` the goal. Ties are broken by ``(f, g, node)``, so the
    result is deterministic. Returns the node sequence (without start and goal) or None.
    """
    start, goal = -1, -2
    best: dict[int, float] = {start: 0.0}
    parent: dict[int, int] = {}
    heap: list[tuple[float, float, int]] = [(0.0, 0.0, start)]
    closed: set[int] = set()
    while heap:
        _, g, v = heapq.heappop(heap)
        if v == goal:
            path = []
            v = parent[goal]
            while v != start:
                path.append(v)
                v = parent[v]
            path.reverse()
            return path
        if v in closed:
            continue
        closed.add(v)
        for u, w in start_edges if v == start else adjacency[v]:
            ng = g + w
            if ng < best.get(u, math.inf):
                best[u] = ng
                parent[u] = v
                heapq.heappush(heap, (ng + heuristic[u], ng, u))
        if v in goal_edges:
            ng = g + goal_edges[v]
            if ng < best.get(goal, math.inf):
                best[goal] = ng
                parent[goal] = v
                heapq.heappush(heap, (ng, ng, goal))
    return None


def _component_lists(graph: _Graph) -> list[tuple[list[Any], ...]]:
    """The graph's connected components, each as the node lists :func:`_sees_any` takes.

    Union-find over the edges (a property of the graph: no arithmetic involved), then per
    component its nodes' positions, neighbour directions and blocking-box hints.
    """
    n = len(graph.nodes)
    parent = list(range(n))

    def root(v: int) -> int:
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for a, b in zip(graph.i.tolist(), graph.j.tolist(), strict=True):
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    groups: dict[int, list[int]] = {}
    for v in range(n):
        groups.setdefault(root(v), []).append(v)
    nodes = graph.nodes
    cols = (
        nodes.pos[:, 0].tolist(),
        nodes.pos[:, 1].tolist(),
        nodes.to_prev[:, 0].tolist(),
        nodes.to_prev[:, 1].tolist(),
        nodes.to_next[:, 0].tolist(),
        nodes.to_next[:, 1].tolist(),
    )
    shared = [0]  # the box that blocked the last segment from the start, for every node
    return [
        (*([col[v] for v in members] for col in cols), [shared] * len(members))
        for members in groups.values()
    ]


def _sees_any(
    nodes: tuple[list[Any], ...],
    x: float,
    y: float,
    boxes: tuple[list[float], ...],
    radius: float,
) -> bool:
    """Does the point ``(x, y)`` connect to any of ``nodes``, as :func:`search`
    connects an end (tangent at the node, segment clear of every box)?

    ``nodes`` holds the nodes' positions and neighbour directions as lists, and a hint
    per node for :func:`_segment_hits_any` (the box that blocked it last). The tangency
    test is :func:`_tangent_grid`'s expression and the segment test
    :func:`_segment_hits_any`, both on Python floats with the same operations, so each
    pair's answer is the array version's; it stops at the first connected node.
    """
    xs, ys, pxs, pys, nxs, nys, hints = nodes
    for k in range(len(xs)):
        nx_, ny_ = xs[k], ys[k]
        ux = nx_ - x
        uy = ny_ - y
        cross_prev = ux * pys[k] - uy * pxs[k]
        cross_next = ux * nys[k] - uy * nxs[k]
        if not cross_prev * cross_next >= -_TANGENT_EPS * (ux * ux + uy * uy):
            continue
        if not _segment_hits_any(x, y, nx_, ny_, boxes, radius, hints[k]):
            return True
    return False
