"""A node of the search tree: a state and the actions tried from it (the tree's edges).

Edges are stored on their parent as parallel lists (action, reward, bonus, feasible,
child, :math:`\\hat Q`, visit count), which is what the search touches at every visit;
plain Python lists are the fastest containers for that scalar work.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from voot.optim.base import Bounds, FloatArray


class Node:
    """One state of the search tree.

    Attributes:
        id: index in :attr:`voot.tree.MCTS.nodes` (creation order).
        parent: the parent node (None at the root).
        edge: index of the action of ``parent`` that leads here (-1 at the root).
        depth: number of actions from the tree's root.
        discount: :math:`\\gamma^{\\text{depth}}`.
        path_return: discounted sum of rewards (goal bonus excluded) from the root here.
        snapshot: the problem's snapshot of this state (None for terminal or infeasible
            states, which are never expanded).
        bounds: the action box of this state (set when the node first samples).
        terminal: the action leading here ended the episode.
        infeasible: the action leading here was infeasible (the rollout stopped here).
        info: the problem's step info of the action leading here.
        actions, rewards, bonuses, feasible, children, q, n: the edges, in the order
            they were tried (``q`` is :math:`\\hat Q`, ``n`` the visit count).
        visits: number of simulations through this node (:math:`N(s)`).
        n_feasible: number of feasible edges.
        n_commit_actions: number of edges that count towards root commitment
            (``MCTSConfig.commit_min_reward``).
        n_terminal_children: number of edges leading to a terminal state.
        reevaluations: re-evaluations of the newest action since it was added.
        sampler: the node's action sampler (created at its first new action).
        tags: per-edge sampler data (the HOO cell of each edge).
    """

    __slots__ = (
        "actions",
        "bonuses",
        "bounds",
        "children",
        "depth",
        "discount",
        "edge",
        "feasible",
        "id",
        "infeasible",
        "info",
        "n",
        "n_commit_actions",
        "n_feasible",
        "n_terminal_children",
        "parent",
        "path_return",
        "q",
        "reevaluations",
        "rewards",
        "sampler",
        "snapshot",
        "tag_to_edge",
        "tags",
        "terminal",
        "visits",
    )

    def __init__(
        self,
        id: int,
        parent: Node | None,
        edge: int,
        depth: int,
        discount: float,
        path_return: float,
        snapshot: Any,
        terminal: bool = False,
        infeasible: bool = False,
        info: Mapping[str, Any] | None = None,
    ) -> None:
        self.id = id
        self.parent = parent
        self.edge = edge
        self.depth = depth
        self.discount = discount
        self.path_return = path_return
        self.snapshot = snapshot
        self.bounds: Bounds | None = None
        self.terminal = terminal
        self.infeasible = infeasible
        self.info: Mapping[str, Any] = info if info is not None else {}
        self.actions: list[FloatArray] = []
        self.rewards: list[float] = []
        self.bonuses: list[float] = []
        self.feasible: list[bool] = []
        self.children: list[Node] = []
        self.q: list[float] = []
        self.n: list[int] = []
        self.tags: list[int] = []
        self.tag_to_edge: dict[int, int] = {}
        self.visits = 0
        self.n_feasible = 0
        self.n_commit_actions = 0
        self.n_terminal_children = 0
        self.reevaluations = 0
        self.sampler: Any = None

    @property
    def n_actions(self) -> int:
        return len(self.actions)

    @property
    def is_leaf(self) -> bool:
        return not self.children

    @property
    def expandable(self) -> bool:
        """Whether actions can be tried from here (not terminal, not infeasible)."""
        return not (self.terminal or self.infeasible)

    def q_values(self) -> FloatArray:
        """:math:`\\hat Q` of every edge as an array."""
        return np.array(self.q, dtype=np.float64)

    def action_array(self) -> FloatArray:
        """The tried actions as an ``(n, d)`` array (``(0, 0)`` if none)."""
        return np.array(self.actions) if self.actions else np.empty((0, 0))

    def best_edge(self, feasible_only: bool = True) -> int:
        """Index of the edge with the highest :math:`\\hat Q` (first on ties); -1 if none.

        With ``feasible_only`` infeasible edges are skipped unless every edge is infeasible.
        """
        best, best_q = -1, -math.inf
        use_feasible = feasible_only and self.n_feasible > 0
        for i, q in enumerate(self.q):
            if use_feasible and not self.feasible[i]:
                continue
            if best < 0 or q > best_q:
                best, best_q = i, q
        return best

    def most_visited_edge(self, feasible_only: bool = True) -> int:
        """Index of the most visited edge (higher :math:`\\hat Q`, then first, on ties)."""
        best = -1
        use_feasible = feasible_only and self.n_feasible > 0
        for i, n in enumerate(self.n):
            if use_feasible and not self.feasible[i]:
                continue
            if best < 0 or n > self.n[best] or (n == self.n[best] and self.q[i] > self.q[best]):
                best = i
        return best

    def path(self) -> list[tuple[Node, int]]:
        """``(ancestor, edge)`` pairs from the tree's root down to this node."""
        out: list[tuple[Node, int]] = []
        node = self
        while node.parent is not None:
            out.append((node.parent, node.edge))
            node = node.parent
        out.reverse()
        return out

    def subtree(self) -> Iterator[Node]:
        """This node and its descendants, depth first (parents before children)."""
        stack = [self]
        while stack:
            node = stack.pop()
            yield node
            stack.extend(reversed(node.children))

    def __repr__(self) -> str:
        kind = "terminal" if self.terminal else "infeasible" if self.infeasible else "state"
        return (
            f"Node(id={self.id}, depth={self.depth}, {kind}, actions={len(self.actions)},"
            f" visits={self.visits}, path_return={self.path_return:.6g})"
        )
