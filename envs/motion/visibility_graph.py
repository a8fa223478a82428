"""The reduced visibility graph of a disc among oriented boxes, and how it is built.

The shortest path of a disc among convex obstacles bends only at obstacle corners, so
the base planner (:mod:`voot.envs.motion.planner`) searches a *reduced visibility graph*
(the search itself: :mod:`voot.envs.motion.graph_search`):

1. Each box grown by the disc radius (a rounded rectangle) is enclosed by a polygon whose
   edges are tangent to it: the four straight sides, and ``corner_segments`` segments
   around each rounded corner. Its ``4 * corner_segments`` vertices, pushed out by a
   micrometre (``vertex_margin``), are the graph's nodes, once pruned of those in
   collision or outside the workspace (:meth:`VisibilityGraphs._polygon_nodes`).
2. Two nodes are joined iff the segment between them is *bitangent* (the line through
   each polygon vertex does not separate the vertex's two polygon neighbours,
   :func:`_tangent_grid`; other edges can never be on a shortest path) and
   collision-free (the exact tests of :mod:`voot.envs.motion.disc_geometry`).

The graph of one radius among the static obstacles is cached
(:meth:`VisibilityGraphs._static_graph`) once the radius recurs; the graph of a
``(radius, movable obstacles)`` pair is built on top of it, or, for a radius seen for the first time, in one pass over all obstacles
(:meth:`VisibilityGraphs.build`); both routes give the same graph bit for bit
(``tests/envs/motion/test_visibility_graph.py`` compares). The polygonal corners make a path through
the graph shortest up to a factor of at most ``1 / cos(pi / (4 * corner_segments))``
around corners (1.08 for the default 2), and a gap between two obstacle *corners*
narrower than that factor can be missed; gaps between flat sides, such as doors, are
exact.

This module holds the graph's data (:class:`_Nodes`, :class:`_Graph`, and the
:class:`_Scene` of one query's obstacles that carries it) and its construction; the
planner owns the caches of scenes, and the search reads the graph.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.envs.motion.disc_geometry import (
    _CORNER_SIGNS,
    BoxArrays,
    points_hit_boxes,
    points_inside,
    segments_hit_any,
)

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.intp]
BoolArray = NDArray[np.bool_]


@dataclass(frozen=True, eq=False)
class _Nodes:
    """Graph nodes: positions and unit directions to their two polygon neighbours."""

    pos: FloatArray  # (n, 2)
    to_prev: FloatArray  # (n, 2) unit vector towards the previous polygon vertex
    to_next: FloatArray  # (n, 2) unit vector towards the next polygon vertex

    def __len__(self) -> int:
        return int(self.pos.shape[0])

    def take(self, index: IntArray) -> _Nodes:
        return _Nodes(self.pos[index], self.to_prev[index], self.to_next[index])

    def part(self, start: int, stop: int) -> _Nodes:
        """Nodes ``start`` to ``stop - 1`` (views)."""
        return _Nodes(self.pos[start:stop], self.to_prev[start:stop], self.to_next[start:stop])

    def concat(self, other: _Nodes) -> _Nodes:
        return _Nodes(
            np.concatenate([self.pos, other.pos]),
            np.concatenate([self.to_prev, other.to_prev]),
            np.concatenate([self.to_next, other.to_next]),
        )


@dataclass(eq=False)
class _Graph:
    """Nodes and undirected weighted edges ``(i, j, w)``; adjacency lists built on demand."""

    nodes: _Nodes
    i: IntArray
    j: IntArray
    w: FloatArray
    _adjacency: list[list[tuple[int, float]]] | None = None

    def adjacency(self) -> list[list[tuple[int, float]]]:
        if self._adjacency is None:
            adj: list[list[tuple[int, float]]] = [[] for _ in range(len(self.nodes))]
            for a, b, w in zip(self.i.tolist(), self.j.tolist(), self.w.tolist(), strict=True):
                adj[a].append((b, w))
                adj[b].append((a, w))
            self._adjacency = adj
        return self._adjacency


@dataclass(eq=False)
class _Scene:
    """What one ``(radius, movable)`` pair needs: the obstacle arrays and, once built, the graph."""

    radius: float
    movable: BoxArrays
    boxes: BoxArrays  # static then movable
    graph: _Graph | None = None
    # for the no-path shortcut (voot.envs.motion.graph_search.no_path): the graph's connected
    # components, and per start point the nodes in the components the start sees
    components: list[tuple[list[Any], ...]] | None = None
    reach: OrderedDict[tuple[float, float], tuple[list[Any], ...]] = field(
        default_factory=OrderedDict
    )
    # the boxes as Python lists, for the single-segment test
    lists: tuple[list[float], ...] | None = None


def _box_lists(scene: _Scene) -> tuple[list[float], ...]:
    """The scene's boxes as lists of Python floats (built once per scene)."""
    if scene.lists is None:
        scene.lists = scene.boxes.lists()
    return scene.lists


#: How many radii :meth:`VisibilityGraphs.build` remembers having seen (a radius seen
#: again gets its static graph built and cached).
_RADII_REMEMBERED = 256

#: Lines through a vertex whose sines to both neighbours multiply to more than
#: ``-_TANGENT_EPS`` count as tangent (collinear neighbours, up to rounding, are allowed).
_TANGENT_EPS = 1e-12


def _tangent_grid(nodes: _Nodes, ux: FloatArray, uy: FloatArray, axis: int) -> BoolArray:
    """Tangency at the nodes of a grid of lines with directions ``(ux, uy)``.

    ``axis`` says which grid axis indexes ``nodes``. A line through a convex polygon
    vertex is tangent there iff it does not strictly separate the vertex's two polygon
    neighbours (the product of the two cross products is not negative); only tangent
    lines can carry a shortest path bending at the vertex. The test is invariant under
    ``u -> -u``, so one grid of directions serves both ends of every segment.
    """
    shape = (-1, 1) if axis == 0 else (1, -1)
    px = nodes.to_prev[:, 0].reshape(shape)
    py = nodes.to_prev[:, 1].reshape(shape)
    nx = nodes.to_next[:, 0].reshape(shape)
    ny = nodes.to_next[:, 1].reshape(shape)
    cross_prev = ux * py - uy * px
    cross_next = ux * ny - uy * nx
    result: BoolArray = cross_prev * cross_next >= -_TANGENT_EPS * (ux * ux + uy * uy)
    return result


class VisibilityGraphs:
    """The visibility graphs of one floor plan: built per ``(radius, movable)`` scene, the
    static part cached per radius that recurs.

    Args:
        workspace: ``(xmin, xmax, ymin, ymax)``: nodes must leave the disc inside it.
        static: The static obstacles.
        corner_segments: Tangent segments per rounded corner (``BasePlannerConfig``).
        vertex_margin: How far nodes are pushed out beyond the grown obstacles (metres).
        contact_tolerance: Numerical slack of the collision tests (metres).
        static_cache_size: Number of radii whose static graph is kept.
    """

    def __init__(
        self,
        workspace: tuple[float, float, float, float],
        static: BoxArrays,
        corner_segments: int,
        vertex_margin: float,
        contact_tolerance: float,
        static_cache_size: int,
    ) -> None:
        self.workspace = workspace
        self.corner_segments = corner_segments
        self.vertex_margin = vertex_margin
        self.contact_tolerance = contact_tolerance
        self.static_cache_size = static_cache_size
        self._static = static
        self._template = self._make_template(corner_segments)
        self._static_cache: OrderedDict[float, _Graph] = OrderedDict()
        self._radii_seen: OrderedDict[float, None] = OrderedDict()

    def clear(self) -> None:
        """Forget the cached static graphs and the radii seen."""
        self._static_cache.clear()
        self._radii_seen.clear()

    def _polygon_nodes(self, boxes: BoxArrays, radius: float) -> _Nodes:
        """Vertices of the tangent polygons enclosing the boxes grown by ``radius``.

        Corner ``k`` (signs ``(+,+), (-,+), (-,-), (+,-)``, counter-clockwise) carries ``m``
        vertices at angles ``phi`` mid-way between consecutive tangent lines, at distance
        ``(radius + vertex_margin) / cos(pi / (4 m))`` from the corner. The polygon edge
        after a vertex is the tangent line at ``phi + pi / (4 m)`` (direction
        ``phi + pi / (4 m) + pi / 2``), the edge before it the one at ``phi - pi / (4 m)``.
        """
        if len(boxes) == 0:
            z = np.zeros((0, 2))
            return _Nodes(z, z, z)
        m = self.corner_segments
        corner, unit, to_prev, to_next = self._template
        dist = (radius + self.vertex_margin) / math.cos(math.pi / (4 * m))
        lx = corner[:, 0] * boxes.half[:, 0:1] + dist * unit[:, 0]  # (nb, 4m)
        ly = corner[:, 1] * boxes.half[:, 1:2] + dist * unit[:, 1]
        c = boxes.cos[:, None]
        s = boxes.sin[:, None]
        pos = np.empty((len(boxes), 4 * m, 2))
        pos[..., 0] = boxes.center[:, 0:1] + c * lx - s * ly
        pos[..., 1] = boxes.center[:, 1:2] + s * lx + c * ly
        prev = np.empty_like(pos)
        prev[..., 0] = c * to_prev[:, 0] - s * to_prev[:, 1]
        prev[..., 1] = s * to_prev[:, 0] + c * to_prev[:, 1]
        nxt = np.empty_like(pos)
        nxt[..., 0] = c * to_next[:, 0] - s * to_next[:, 1]
        nxt[..., 1] = s * to_next[:, 0] + c * to_next[:, 1]
        return _Nodes(pos.reshape(-1, 2), prev.reshape(-1, 2), nxt.reshape(-1, 2))

    @staticmethod
    def _make_template(m: int) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Per-vertex corner signs, unit offsets and unit neighbour directions (local frame)."""
        k = np.repeat(np.arange(4), m)
        jj = np.tile(np.arange(m), 4)
        phi = k * (math.pi / 2) + (jj + 0.5) * (math.pi / (2 * m))
        half_step = math.pi / (4 * m)
        unit = np.column_stack([np.cos(phi), np.sin(phi)])
        after = phi + half_step + math.pi / 2
        before = phi - half_step + math.pi / 2
        to_next = np.column_stack([np.cos(after), np.sin(after)])
        to_prev = -np.column_stack([np.cos(before), np.sin(before)])
        return _CORNER_SIGNS[k], unit, to_prev, to_next

    def _free_mask(
        self, owners: BoxArrays, nodes: _Nodes, boxes: BoxArrays, radius: float, r_hit: float
    ) -> BoolArray:
        """Which of the polygon nodes ``nodes`` of the boxes ``owners`` (at ``radius``, as
        :meth:`_polygon_nodes` makes them) lie inside the workspace and clear of ``boxes``
        (for the one-pass build: every obstacle's nodes against every obstacle).

        :func:`points_hit_boxes`'s test, on the node-box pairs that can meet only: the
        ``m`` nodes of a corner lie within ``dist`` of it (their distance from the
        corner), so a corner farther than ``dist + r_hit`` (plus a micrometre for
        rounding) from a box's axis-aligned bounding box along x or y cannot meet the
        box. Each remaining pair's numbers are :func:`points_hit_boxes`'s, so the mask is.
        """
        inside = points_inside(nodes.pos, self.workspace, r_hit)
        if len(boxes) == 0 or len(nodes) == 0:
            return inside
        m = self.corner_segments
        dist = (radius + self.vertex_margin) / math.cos(math.pi / (4 * m))
        kx, ky, _, _ = owners.corners_and_extents
        _, _, ax, ay = boxes.corners_and_extents
        reach = dist + r_hit + 1e-6
        gap_x = np.abs(kx[:, None] - boxes.center[:, 0]) - ax
        gap_y = np.abs(ky[:, None] - boxes.center[:, 1]) - ay
        corner, box = np.nonzero((gap_x < reach) & (gap_y < reach))
        node = ((corner * m)[:, None] + np.arange(m)).ravel()
        box = np.repeat(box, m)
        pos = nodes.pos[node]
        rx = pos[:, 0] - boxes.center[box, 0]
        ry = pos[:, 1] - boxes.center[box, 1]
        c, s = boxes.cos[box], boxes.sin[box]
        lx = rx * c + ry * s
        ly = -rx * s + ry * c
        dx = np.maximum(np.abs(lx) - boxes.half[box, 0], 0.0)
        dy = np.maximum(np.abs(ly) - boxes.half[box, 1], 0.0)
        inside[node[dx * dx + dy * dy < r_hit * r_hit]] = False
        return inside

    def _free_polygon_nodes(self, owners: BoxArrays, boxes: BoxArrays, radius: float) -> _Nodes:
        """The polygon nodes of ``owners`` at ``radius`` clear of ``boxes``.

        Every node-box pair tested (:func:`points_hit_boxes`): the layered build's node
        sets are small enough that the prefilter of :meth:`_free_mask` costs more than it
        saves (measured on the conveyor, whose radii recur).
        """
        nodes = self._polygon_nodes(owners, radius)
        r_hit = radius - self.contact_tolerance
        free = points_inside(nodes.pos, self.workspace, r_hit) & ~points_hit_boxes(
            nodes.pos, boxes, r_hit
        ).any(axis=1)
        return nodes.take(np.flatnonzero(free))

    @staticmethod
    def _candidates(a: _Nodes, b: _Nodes, same: bool) -> tuple[IntArray, IntArray]:
        """Bitangent pairs between node sets ``a`` and ``b`` (``i < j`` if ``same``)."""
        ux = b.pos[None, :, 0] - a.pos[:, 0:1]
        uy = b.pos[None, :, 1] - a.pos[:, 1:2]
        ia, ib = np.nonzero(_tangent_grid(a, ux, uy, 0) & _tangent_grid(b, ux, uy, 1))
        if same:
            upper = ia < ib
            ia, ib = ia[upper], ib[upper]
        return ia, ib

    @staticmethod
    def _keep_free(
        pos: FloatArray, ia: IntArray, ib: IntArray, boxes: BoxArrays, r_hit: float
    ) -> tuple[IntArray, IntArray, FloatArray]:
        """The collision-free edges among ``(ia, ib)`` (indices into ``pos``) and their lengths."""
        pa, pb = pos[ia], pos[ib]
        ok = ~segments_hit_any(pa, pb, boxes, r_hit)
        d = pb[ok] - pa[ok]
        return ia[ok], ib[ok], np.hypot(d[:, 0], d[:, 1])

    def _static_graph(self, radius: float) -> _Graph:
        """Free vertices of the grown static obstacles and their static visibility edges."""
        cached = self._static_cache.get(radius)
        if cached is not None:
            self._static_cache.move_to_end(radius)
            return cached
        r_hit = radius - self.contact_tolerance
        nodes = self._free_polygon_nodes(self._static, self._static, radius)
        ia, ib = self._candidates(nodes, nodes, same=True)
        graph = _Graph(nodes, *self._keep_free(nodes.pos, ia, ib, self._static, r_hit))
        self._static_cache[radius] = graph
        if len(self._static_cache) > self.static_cache_size:
            self._static_cache.popitem(last=False)
        return graph

    def build(self, scene: _Scene) -> _Graph:
        """The visibility graph among the static and movable obstacles of ``scene``.

        Two ways to the same graph (the same nodes, edges, orientations and order, bit
        for bit: every test is elementwise): on top of the static graph of the radius,
        cached for the radii that recur, or, the first time a radius is seen (a carried
        object's disc changes with every grasp, so most radii never recur), in one pass
        over all obstacles, which skips the static graph's own edge tests.
        """
        radius = scene.radius
        if radius not in self._static_cache:
            seen = self._radii_seen
            if radius not in seen:
                seen[radius] = None
                if len(seen) > _RADII_REMEMBERED:
                    seen.popitem(last=False)
                return self._one_pass_graph(scene)
        static = self._static_graph(radius)
        if len(scene.movable) == 0:
            return static
        r_hit = radius - self.contact_tolerance
        # static vertices not covered by a movable obstacle, re-indexed
        covered = points_hit_boxes(static.nodes.pos, scene.movable, r_hit).any(axis=1)
        alive = np.asarray(~covered, dtype=bool)
        new_index = np.cumsum(alive) - 1
        keep = alive[static.i] & alive[static.j]
        base = static.nodes.take(np.flatnonzero(alive))
        mnodes = self._free_polygon_nodes(scene.movable, scene.boxes, radius)
        nodes = base.concat(mnodes)
        nb = len(base)
        # candidate edges: surviving static ones (only the movable obstacles can block
        # them), movable-to-static and movable-to-movable bitangents (all obstacles)
        mi, bj = self._candidates(mnodes, base, same=False)
        mi2, mj2 = self._candidates(mnodes, mnodes, same=True)
        ia = np.concatenate([new_index[static.i[keep]], mi + nb, mi2 + nb])
        ib = np.concatenate([new_index[static.j[keep]], bj, mj2 + nb])
        return _Graph(nodes, *self._keep_free(nodes.pos, ia, ib, scene.boxes, r_hit))

    def _one_pass_graph(self, scene: _Scene) -> _Graph:
        """:meth:`build` without the static graph: the same nodes and edges, in the
        same order (static edges, movable-to-static, movable-to-movable)."""
        r_hit = scene.radius - self.contact_tolerance
        boxes = scene.boxes
        polygon = self._polygon_nodes(boxes, scene.radius)
        free = self._free_mask(boxes, polygon, boxes, scene.radius, r_hit)
        nodes = polygon.take(np.flatnonzero(free))
        # the polygon nodes come box by box, the static boxes first
        nb = int(np.count_nonzero(free[: len(self._static) * 4 * self.corner_segments]))
        # all bitangent pairs i < j at once, then in the layered build's order and
        # orientation: the tangency of a pair does not depend on its orientation (the
        # direction's sign cancels exactly), its segment test may
        i, j = self._candidates(nodes, nodes, same=True)
        movable_i, movable_j = i >= nb, j >= nb
        static_pair = ~movable_j
        mixed = movable_j & ~movable_i
        both = movable_i
        mixed_i, mixed_j = i[mixed], j[mixed]
        order = np.lexsort((mixed_i, mixed_j))  # by movable node, then static node
        ia = np.concatenate([i[static_pair], mixed_j[order], i[both]])
        ib = np.concatenate([j[static_pair], mixed_i[order], j[both]])
        return _Graph(nodes, *self._keep_free(nodes.pos, ia, ib, boxes, r_hit))
