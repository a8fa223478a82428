r"""Selection rules: how a node chooses the action of a visit, and what it learns from it.

A tree search (:class:`voot.tree.MCTS`) visits a node and asks its rule for an edge: an
existing action to go down, or a new one, which the rule obtains from the search
(:meth:`MCTS.new_action` with the node's sampler, or :meth:`MCTS.add_action` with a
point of its own). Every rule has the same small interface (:class:`SelectionRule`), so
the search has one loop, one feasibility-retry loop and no rule-specific switches:

``reevaluate`` (:class:`Reevaluate`)
    Paper Algorithm 2: re-evaluate the newest action until it has been tried
    :math:`1 + w\,\kappa_r^h` times at relative depth :math:`h`, then sample a new one.
``progressive_widening`` (:class:`ProgressiveWidening`)
    A new action when :math:`|A(s)| \le k\,N(s)^\alpha`, else UCB over feasible actions
    (or, with ``widening="authors"``, the original's inverted linear test: UCB when
    :math:`|A(s)| \le k\,N(s)`, else a new action).
``hoo`` (:class:`HOOSelection`)
    A HOO bandit over the action box chooses every action and is told every return.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Protocol

import numpy as np

from voot.optim.base import FloatArray
from voot.tree.config import MCTSConfig, Selection, Widening
from voot.tree.node import Node

if TYPE_CHECKING:  # pragma: no cover
    from voot.tree.hoo import HOO
    from voot.tree.mcts import MCTS


class SelectionRule(Protocol):
    """What the search needs from a selection rule.

    Attributes:
        tells_sampler: whether the node's sampler is told each new action's first value
            and every change of :math:`\\hat Q` (the optimiser samplers); False when the
            rule learns from :meth:`observe` instead (HOO).
    """

    tells_sampler: bool

    def select(self, search: MCTS, node: Node, depth: int) -> int:
        """The edge of ``node`` to follow at relative depth ``depth`` (maybe a new one)."""
        ...

    def observe(self, node: Node, edge: int, ret: float) -> None:
        """A simulation's return ``ret`` went through ``node``'s ``edge``."""
        ...


class Reevaluate:
    """Paper Algorithm 2: re-evaluate the newest action, then ask for a new one."""

    tells_sampler = True

    def __init__(self, config: MCTSConfig) -> None:
        self.config = config
        self.horizon = config.depth_limit
        self._budget: list[float] = []

    def budget(self, depth: int) -> float:
        """Re-evaluations allowed at relative depth ``depth``: ``w * kappa_r**depth``."""
        budget = self._budget
        while len(budget) <= depth:
            budget.append(self.config.reevaluations * self.config.kappa_r ** len(budget))
        return budget[depth]

    def select(self, search: MCTS, node: Node, depth: int) -> int:
        k = len(node.actions)
        H = self.horizon
        if (
            k
            and node.n_feasible
            and node.feasible[k - 1]
            and not node.children[k - 1].terminal
            and not (node.n_terminal_children and self.config.terminal_child_forces_new)
            and (H is None or depth != H - 1)
            and node.reevaluations < self.budget(depth)
        ):
            node.reevaluations += 1
            return k - 1
        node.reevaluations = 0
        return search.new_action(node)

    def observe(self, node: Node, edge: int, ret: float) -> None:
        pass


class ProgressiveWidening:
    """Progressive widening with UCB among the feasible actions."""

    tells_sampler = True

    def __init__(self, config: MCTSConfig) -> None:
        self.config = config
        self.authors = config.widening is Widening.AUTHORS

    def widens(self, n_actions: int, visits: int) -> bool:
        """Whether a node with ``n_actions`` tried actions and ``visits`` visits adds one.

        Standard: :math:`|A| \\le k N^\\alpha`; the authors' code: :math:`|A| > k N`.
        """
        cfg = self.config
        if self.authors:
            return n_actions > cfg.pw_k * visits
        return n_actions <= cfg.pw_k * visits**cfg.pw_alpha

    def select(self, search: MCTS, node: Node, depth: int) -> int:
        k = len(node.actions)
        cfg = self.config
        if (
            k == 0
            or node.n_feasible == 0
            or (node.n_terminal_children and cfg.terminal_child_forces_new)
            or self.widens(k, node.visits)
        ):
            return search.new_action(node)
        return self.ucb(node)

    def ucb(self, node: Node) -> int:
        """argmax over feasible edges of :math:`\\hat Q + c\\sqrt{\\ln N / n}` (first on ties)."""
        q = np.array(node.q)
        n = np.array(node.n, dtype=np.float64)
        score = q + self.config.ucb_c * np.sqrt(math.log(max(node.visits, 1)) / n)
        if node.n_feasible < len(node.q):
            score[~np.array(node.feasible)] = -np.inf
        return int(np.argmax(score))

    def observe(self, node: Node, edge: int, ret: float) -> None:
        pass


class HOOSelection:
    """HOOT: the node's HOO bandit (its sampler) chooses every action and learns every return."""

    tells_sampler = False

    def select(self, search: MCTS, node: Node, depth: int) -> int:
        search.goto(node)
        hoo: HOO = search.sampler(node)
        cell, is_new = hoo.select()
        if not is_new:
            return node.tag_to_edge[cell]

        def redraw(previous: FloatArray) -> FloatArray:
            return hoo.redraw(cell).copy()

        i = search.add_action(node, hoo.point(cell).copy(), redraw)
        node.tags.append(cell)
        node.tag_to_edge[cell] = i
        return i

    def observe(self, node: Node, edge: int, ret: float) -> None:
        node.sampler.update(node.tags[edge], ret)


def make_selection(config: MCTSConfig) -> SelectionRule:
    """The rule named by ``config.selection``."""
    sel = Selection(config.selection)
    if sel is Selection.REEVALUATE:
        return Reevaluate(config)
    if sel is Selection.PROGRESSIVE_WIDENING:
        return ProgressiveWidening(config)
    return HOOSelection()
