r"""The merge at the root: the trees' root statistics -> one root action.

:class:`RootStats` is what each tree reports of its root (actions, :math:`\hat Q`, visits,
feasibility, the action box); :func:`merge_roots` applies a :class:`~.config.MergeRule`
(``max_q``, ``most_visited``, ``vote``; see :mod:`voot.tree.root_parallel` for the exact
rules and their tie-breaking) and returns a :class:`MergeDecision` saying what it chose
and why.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from voot.optim.base import FloatArray
from voot.tree.node import Node
from voot.tree.root_parallel._compare import same_fields
from voot.tree.root_parallel.config import MergeRule, RootParallelConfig, merge_rule


@dataclass(frozen=True)
class RootStats:
    """A tree's root edges, as the merge needs them.

    Attributes:
        actions: ``(m, d)`` tried root actions, in the order they were tried.
        q: :math:`\\hat Q` of each (``m``).
        n: visit count of each (``m``).
        feasible: whether each was feasible (``m``).
        lower, upper: the root's action box (``d`` each), for the ``vote`` distance.
    """

    actions: FloatArray
    q: FloatArray
    n: np.ndarray[Any, np.dtype[np.int64]]
    feasible: np.ndarray[Any, np.dtype[np.bool_]]
    lower: FloatArray
    upper: FloatArray

    def __post_init__(self) -> None:
        lo = np.array(self.lower, dtype=np.float64).reshape(-1)
        hi = np.array(self.upper, dtype=np.float64).reshape(-1)
        if lo.shape != hi.shape or lo.size == 0 or not np.all(hi > lo):
            raise ValueError(
                f"root box must have lower < upper in every dimension, got {lo} and {hi}"
            )
        d = lo.size
        acts = np.array(self.actions, dtype=np.float64)
        if acts.size == 0:
            acts = acts.reshape(0, d)
        if acts.ndim != 2 or acts.shape[1] != d:
            raise ValueError(f"root actions must be an (m, {d}) array, got shape {acts.shape}")
        m = acts.shape[0]
        q = np.array(self.q, dtype=np.float64).reshape(-1)
        n = np.array(self.n, dtype=np.int64).reshape(-1)
        feasible = np.array(self.feasible, dtype=bool).reshape(-1)
        for name, arr in (("q", q), ("n", n), ("feasible", feasible)):
            if arr.shape != (m,):
                raise ValueError(
                    f"root {name} must have {m} entries (one per action), got {arr.shape}"
                )
        for name, arr in (("actions", acts), ("q", q), ("n", n), ("feasible", feasible)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        lo.setflags(write=False)
        hi.setflags(write=False)
        object.__setattr__(self, "lower", lo)
        object.__setattr__(self, "upper", hi)

    @classmethod
    def from_node(cls, node: Node, lower: ArrayLike, upper: ArrayLike) -> RootStats:
        """The statistics of a tree node (the root) whose action box is ``[lower, upper]``."""
        d = np.asarray(lower).size
        return cls(
            actions=np.array(node.actions, dtype=np.float64).reshape(-1, d),
            q=np.array(node.q, dtype=np.float64),
            n=np.array(node.n, dtype=np.int64),
            feasible=np.array(node.feasible, dtype=bool),
            lower=np.asarray(lower, dtype=np.float64),
            upper=np.asarray(upper, dtype=np.float64),
        )

    @property
    def n_actions(self) -> int:
        return int(self.q.size)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RootStats):
            return NotImplemented
        return same_fields(self, other)

    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True)
class MergeDecision:
    """The merged root action and why it was chosen.

    Attributes:
        rule: the merge rule.
        tree: the tree whose root edge was chosen.
        edge: the edge's index at that tree's root.
        action: the chosen root action.
        q: its :math:`\\hat Q`.
        visits: its visit count.
        score: what the rule maximised: :math:`\\hat Q` (``max_q``), visits
            (``most_visited``) or the neighbourhood's summed visits :math:`V` (``vote``).
        members: ``(tree, edge)`` of the candidates that voted for it (``vote``; the
            chosen edge alone otherwise).
        members_best_q: the best :math:`\\hat Q` among the members.
        members_mean_q: the members' visit-weighted mean :math:`\\hat Q`.
        n_candidates: the number of root edges the rule chose among.
    """

    rule: MergeRule
    tree: int
    edge: int
    action: FloatArray
    q: float
    visits: int
    score: float
    members: tuple[tuple[int, int], ...]
    members_best_q: float
    members_mean_q: float
    n_candidates: int

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, MergeDecision):
            return NotImplemented
        return same_fields(self, other)

    __hash__ = None  # type: ignore[assignment]

    def to_dict(self) -> dict[str, Any]:
        """Plain values for a results row."""
        return {
            "rule": self.rule.value,
            "tree": self.tree,
            "edge": self.edge,
            "action": self.action.tolist(),
            "q": self.q,
            "visits": self.visits,
            "score": self.score,
            "members": [list(m) for m in self.members],
            "members_best_q": self.members_best_q,
            "members_mean_q": self.members_mean_q,
            "n_candidates": self.n_candidates,
        }


def normalized_distances(
    x: FloatArray, y: FloatArray, lower: FloatArray, upper: FloatArray
) -> FloatArray:
    """:math:`\\delta` between the rows of ``x`` and ``y`` (an ``(len(x), len(y))`` array):
    root-mean-square coordinate difference in units of the box's widths."""
    width = np.asarray(upper, dtype=np.float64) - np.asarray(lower, dtype=np.float64)
    zx = np.asarray(x, dtype=np.float64) / width
    zy = np.asarray(y, dtype=np.float64) / width
    diff = zx[:, None, :] - zy[None, :, :]
    out: FloatArray = np.sqrt(np.mean(diff * diff, axis=2))
    return out


#: Rows of the vote's pairwise distances computed at once (bounds its memory).
_VOTE_BLOCK = 512


def merge_roots(
    roots: Sequence[RootStats],
    rule: MergeRule | str = MergeRule.MAX_Q,
    vote_radius: float = 0.1,
) -> MergeDecision | None:
    """The merged root action of ``roots`` (one per tree, in tree order); None if no
    tree's root has an action. See the module docstring for the rules.

    Raises:
        ValueError: unknown rule, bad radius, or roots with different action boxes (the
            trees did not search the same root state).
    """
    rule = merge_rule(rule)
    RootParallelConfig(n_trees=max(1, len(roots)), merge=rule, vote_radius=vote_radius)
    if not roots:
        return None
    first = roots[0]
    for k, r in enumerate(roots):
        if not (np.array_equal(r.lower, first.lower) and np.array_equal(r.upper, first.upper)):
            raise ValueError(
                f"tree {k}'s root box [{r.lower}, {r.upper}] differs from tree 0's"
                f" [{first.lower}, {first.upper}]: the trees must search the same root state"
                " (does the problem factory always build the same initial state?)"
            )
    tree_idx = np.concatenate(
        [np.full(r.n_actions, k, dtype=np.int64) for k, r in enumerate(roots)]
    )
    edge_idx = np.concatenate([np.arange(r.n_actions, dtype=np.int64) for r in roots])
    if tree_idx.size == 0:
        return None
    actions = np.concatenate([r.actions for r in roots], axis=0)
    q = np.concatenate([r.q for r in roots])
    n = np.concatenate([r.n for r in roots])
    feasible = np.concatenate([r.feasible for r in roots])
    keep = np.flatnonzero(feasible) if feasible.any() else np.arange(q.size)
    tree_idx, edge_idx = tree_idx[keep], edge_idx[keep]
    actions, q, n = actions[keep], q[keep], n[keep]
    m = q.size
    if rule is MergeRule.VOTE:
        neighbours = np.zeros((m, m), dtype=bool)
        limit = float(vote_radius)
        for s in range(0, m, _VOTE_BLOCK):
            block = normalized_distances(
                actions[s : s + _VOTE_BLOCK], actions, first.lower, first.upper
            )
            neighbours[s : s + _VOTE_BLOCK] = block <= limit
        np.fill_diagonal(neighbours, True)
        score = neighbours.astype(np.int64) @ n
        primary, secondary = score.astype(np.float64), q
    elif rule is MergeRule.MOST_VISITED:
        primary, secondary = n.astype(np.float64), q
    else:
        primary, secondary = q, np.zeros(m)
    # Lexicographic maximum of (primary, secondary), the lowest (tree, edge) on ties:
    # candidates are in (tree, edge) order, so np.lexsort's stable order gives the first.
    order = np.lexsort((-secondary, -primary))
    best = int(order[0])
    if rule is MergeRule.VOTE:
        members = np.flatnonzero(neighbours[best])
    else:
        members = np.array([best])
    w = n[members].astype(np.float64)
    mq = q[members]
    finite = np.isfinite(mq)
    if finite.any() and w[finite].sum() > 0:
        mean_q = float(np.sum(w[finite] * mq[finite]) / np.sum(w[finite]))
    else:
        mean_q = float(np.max(mq))
    return MergeDecision(
        rule=rule,
        tree=int(tree_idx[best]),
        edge=int(edge_idx[best]),
        action=actions[best].copy(),
        q=float(q[best]),
        visits=int(n[best]),
        score=float(primary[best]),
        members=tuple((int(tree_idx[j]), int(edge_idx[j])) for j in members),
        members_best_q=float(np.max(mq)),
        members_mean_q=mean_q,
        n_candidates=int(m),
    )
