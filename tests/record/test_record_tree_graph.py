"""Tests of voot.record.tree_graph: the search tree as a drawable graph."""

from __future__ import annotations

import numpy as np

from voot.record.tree_graph import (
    BEST_PATH_COLOR,
    DEPTH_SPACING,
    ROOT_COLOR,
    build_tree_graph,
    select_nodes,
)
from voot.tree import MCTS, MCTSConfig
from voot.tree.null_problem import NullProblem


def _tree(n: int = 80) -> MCTS:
    mcts = MCTS(NullProblem(2), MCTSConfig(depth_limit=4), seed=1)
    mcts.search(n)
    return mcts


def test_every_node_edge_and_a_tidy_layout() -> None:
    mcts = _tree()
    path = [node for node, _ in mcts.best_plan()] + [mcts.best_node()]
    g = build_tree_graph(mcts.nodes, mcts.root, path)
    n = len(mcts.nodes)
    assert g.n_total == n and len(g.node_ids) == n and len(g.edges) == n - 1
    assert g.node_ids == [str(i) for i in range(n)]
    assert set(g.edges) == {(str(c.parent.id), str(c.id)) for c in mcts.nodes[1:]}  # type: ignore[union-attr]
    assert g.positions.shape == (n, 2) and g.colors.shape == (n, 3)
    # One row per depth; a parent is centred over its children; leaves do not overlap.
    depths = np.array([node.depth for node in mcts.nodes])
    assert np.allclose(g.positions[:, 1], depths * DEPTH_SPACING)
    for node in mcts.nodes:
        if node.children:
            xs = [g.positions[c.id, 0] for c in node.children]
            assert g.positions[node.id, 0] == np.mean(xs)
    leaves = [node.id for node in mcts.nodes if not node.children]
    assert len(set(g.positions[leaves, 0].tolist())) == len(leaves)
    assert g.colors[0].tolist() == list(ROOT_COLOR)
    for node in path[1:]:
        assert g.colors[node.id].tolist() == list(BEST_PATH_COLOR)
    assert g.labels[0].startswith("#0 V=0")


def test_cut_keeps_the_shallowest_nodes_and_the_best_path() -> None:
    mcts = _tree(120)
    path = [node for node, _ in mcts.best_plan()] + [mcts.best_node()]
    chosen = select_nodes(mcts.nodes, path, 10)
    ids = {n.id for n in chosen}
    assert {n.id for n in path} <= ids
    assert len(ids) <= 10 + len(path)
    for node in chosen:  # closed under "parent of"
        assert node.parent is None or node.parent.id in ids
    shallow = sorted(mcts.nodes, key=lambda n: (n.depth, n.id))[:10]
    assert {n.id for n in shallow} <= ids
    g = build_tree_graph(mcts.nodes, mcts.root, path, max_nodes=10)
    assert len(g.node_ids) == len(ids) and len(g.edges) == len(ids) - 1
    assert g.n_total == len(mcts.nodes)
    assert select_nodes(mcts.nodes, path, 10_000) == mcts.nodes
