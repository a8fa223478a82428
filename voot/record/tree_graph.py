"""The search tree as a graph for rerun's graph view: nodes, edges, a tidy layout, colours.

The viewer's force layout is slow and messy for thousands of nodes, so positions are
given: leaves side by side in depth-first order, a parent centred over its children,
one row per depth. Huge trees are cut to the ``max_nodes`` shallowest nodes (breadth
first) plus the best path. Nothing here imports rerun; :func:`log_tree` does the logging.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.record.colors import INFEASIBLE_COLOR
from voot.tree.node import Node

#: Colours of graph nodes (RGB).
STATE_COLOR = (90, 140, 220)
TERMINAL_COLOR = (80, 200, 120)
BEST_PATH_COLOR = (255, 165, 0)
ROOT_COLOR = (255, 255, 255)

#: Layout spacing (graph-view units) between leaves and between depths.
LEAF_SPACING = 12.0
DEPTH_SPACING = 60.0


@dataclass(frozen=True)
class TreeGraph:
    """A drawable snapshot of a search tree.

    Attributes:
        node_ids: node ids as strings (rerun graph node ids), in creation order.
        edges: ``(parent id, child id)`` pairs.
        positions: ``(n, 2)`` layout positions (x along leaves, y down the depths).
        colors: ``(n, 3)`` uint8 colours (root, best path, terminal, infeasible, state).
        labels: per node ``#id V=<path return> N=<visits>``.
        n_total: nodes in the tree (``len(node_ids) < n_total`` when it was cut).
    """

    node_ids: list[str]
    edges: list[tuple[str, str]]
    positions: NDArray[np.float64]
    colors: NDArray[np.uint8]
    labels: list[str]
    n_total: int


def select_nodes(nodes: Sequence[Node], best_path: Sequence[Node], max_nodes: int) -> list[Node]:
    """The nodes to draw: all if few enough, else the shallowest ``max_nodes`` plus ``best_path``.

    The result is closed under "parent of" (every chosen node's ancestors are chosen) and
    sorted by id.
    """
    if len(nodes) <= max_nodes:
        return list(nodes)
    order = sorted(nodes, key=lambda n: (n.depth, n.id))[:max_nodes]
    chosen = {n.id: n for n in order}
    for n in best_path:
        while n is not None and n.id not in chosen:
            chosen[n.id] = n
            n = n.parent  # type: ignore[assignment]
    return [chosen[i] for i in sorted(chosen)]


def build_tree_graph(
    nodes: Sequence[Node],
    root: Node,
    best_path: Sequence[Node] = (),
    max_nodes: int = 2000,
    infeasible_color: tuple[int, int, int] = INFEASIBLE_COLOR,
) -> TreeGraph:
    """The :class:`TreeGraph` of the tree below ``root`` (``nodes``: all nodes, by id)."""
    chosen = select_nodes(nodes, best_path, max_nodes)
    index = {n.id: k for k, n in enumerate(chosen)}
    n = len(chosen)
    x = np.zeros(n)
    y = np.array([node.depth for node in chosen], dtype=np.float64) * DEPTH_SPACING
    # Depth-first order restricted to the chosen nodes: leaves get consecutive x.
    dfs: list[int] = []
    stack = [root]
    while stack:
        node = stack.pop()
        k = index.get(node.id)
        if k is None:
            continue
        dfs.append(k)
        stack.extend(reversed(node.children))
    kids: list[list[int]] = [[] for _ in range(n)]
    for k, node in enumerate(chosen):
        p = node.parent
        if p is not None and p.id in index:
            kids[index[p.id]].append(k)
    leaf = 0
    for k in dfs:
        if not kids[k]:
            x[k] = leaf * LEAF_SPACING
            leaf += 1
    for k in reversed(dfs):  # children before parents
        if kids[k]:
            x[k] = x[kids[k]].mean()
    colors = np.empty((n, 3), dtype=np.uint8)
    colors[:] = STATE_COLOR
    on_path = {node.id for node in best_path}
    for k, node in enumerate(chosen):
        if node.infeasible:
            colors[k] = infeasible_color
        elif node.terminal:
            colors[k] = TERMINAL_COLOR
        if node.id in on_path:
            colors[k] = BEST_PATH_COLOR
    if root.id in index:
        colors[index[root.id]] = ROOT_COLOR
    ids = [str(node.id) for node in chosen]
    edges = [
        (str(node.parent.id), str(node.id))
        for node in chosen
        if node.parent is not None and node.parent.id in index
    ]
    labels = [f"#{node.id} V={node.path_return:.4g} N={node.visits}" for node in chosen]
    return TreeGraph(ids, edges, np.column_stack([x, y]), colors, labels, len(nodes))


def log_tree(rec: Any, entity: str, graph: TreeGraph) -> None:
    """Log ``graph`` at ``entity`` of the rerun recording ``rec`` (at its current time)."""
    import rerun as rr

    rec.log(
        entity,
        rr.GraphNodes(
            graph.node_ids,
            positions=graph.positions,
            colors=graph.colors,
            labels=graph.labels,
            show_labels=False,
        ),
        rr.GraphEdges(graph.edges, graph_type="directed"),
    )
