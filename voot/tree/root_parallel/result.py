r"""The merged result of a root-parallel search, and the merge of the trees' results.

:func:`merge_trees` combines the :class:`~voot.tree.root_parallel.worker.TreeResult` of
every tree into a :class:`RootParallelResult`: the merged root action
(:func:`~voot.tree.root_parallel.merge.merge_roots`), the best tree's plan, and the
best-return curve :math:`B_K(i) = \max_k B^{(k)}(i)`. The result holds that merged plan
as a :class:`~voot.tree.PlanResult` (``plan``), so it reads like a single tree's result
(``res.best_return``, ``res.best_return_curve`` ... are the plan's), plus what only
root-parallel search has: the trees, the merge decision, the timings of the call.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar, overload

import numpy as np
from numpy.typing import ArrayLike

from voot.optim.base import FloatArray
from voot.tree.root_parallel._compare import same_fields, same_plan
from voot.tree.root_parallel.config import RootParallelConfig
from voot.tree.root_parallel.merge import MergeDecision, merge_roots
from voot.tree.root_parallel.worker import TreeResult
from voot.tree.search import PlanResult

T = TypeVar("T")


class _PlanField(Generic[T]):
    """A read-only attribute of :class:`RootParallelResult` that is its merged plan's field
    ``source`` (by default the attribute's own name)."""

    def __init__(self, source: str = "") -> None:
        self.source = source

    def __set_name__(self, owner: type, name: str) -> None:
        self.source = self.source or name

    @overload
    def __get__(self, result: None, owner: type) -> _PlanField[T]: ...
    @overload
    def __get__(self, result: RootParallelResult, owner: type) -> T: ...
    def __get__(self, result: RootParallelResult | None, owner: type) -> _PlanField[T] | T:
        if result is None:
            return self
        return getattr(result.plan, self.source)  # type: ignore[no-any-return]


@dataclass(frozen=True)
class RootParallelResult:
    """The outcome of a root-parallel search.

    Attributes:
        parallel: the root-parallel options.
        trees: every tree's result, in tree order.
        decision: the merge decision (None if no root has an action).
        best_tree: the tree holding the best plan (highest best return; lowest on ties).
        plan: the merged plan, a :class:`~voot.tree.PlanResult`: the best tree's plan
            (``actions``, ``rewards``, ``bonuses``, ``feasible``, ``best_return``,
            ``best_leaf_info``) with the merged root action as ``best_action``, the merged
            curves (``best_return_curve``: :math:`B_K(i) = \\max_k B^{(k)}(i)`,
            ``i = 1 .. N``; ``info_curve``: at each index, ``info[record_info]`` of the tree
            best at that index, lowest on ties, if asked), ``n_simulations`` per tree
            (:math:`N`; the longest tree's), the sums over trees of ``n_nodes``,
            ``n_steps``, ``n_feasibility_checks`` and ``n_node_visits``, and the trees'
            search seconds summed as ``wall_time``.
        total_simulations: simulations of all trees.
        started: ``time.time()`` at the start of the call.
        wall_time: seconds of the whole call (workers, transfer and merge included).
        cpu_time: the trees' CPU seconds summed.

    The plan's fields are also read-only attributes of the result, under the names a
    single tree's result uses (``res.best_return`` is ``res.plan.best_return``):

    | attribute | what |
    | --- | --- |
    | ``best_action`` | the merged root action (None if no root has an action) |
    | ``actions`` | the best plan's actions (the best tree's) |
    | ``rewards`` | the best plan's rewards (goal bonus excluded) |
    | ``bonuses`` | the best plan's goal bonuses |
    | ``feasible`` | whether each action of the best plan was feasible |
    | ``best_return`` | the best plan's return (the best tree's) |
    | ``best_leaf_info`` | the step info of the best plan's last action |
    | ``best_return_curve`` | :math:`B_K(i) = \\max_k B^{(k)}(i)`, ``i = 1 .. N`` |
    | ``info_curve`` | ``info[record_info]`` of the tree best at each index (if asked) |
    | ``n_simulations`` | simulations per tree (:math:`N`; the longest tree's) |
    | ``n_nodes`` | nodes of all trees |
    | ``n_steps`` | simulator steps of all trees |
    | ``n_feasibility_checks`` | feasibility checks of all trees |
    | ``n_node_visits`` | node visits of all trees |
    | ``search_time`` | the plan's ``wall_time``: the trees' search seconds summed (compute, not wall time) |
    """

    parallel: RootParallelConfig
    trees: tuple[TreeResult, ...]
    decision: MergeDecision | None
    best_tree: int
    plan: PlanResult = field(compare=False)  # compared by __eq__, timings left out
    total_simulations: int
    started: float = field(compare=False)
    wall_time: float = field(compare=False)
    cpu_time: float = field(default=math.nan, compare=False)

    def __eq__(self, other: object) -> bool:
        """Equal if everything a seed determines is equal (timings are ignored)."""
        if not isinstance(other, RootParallelResult):
            return NotImplemented
        return same_fields(self, other) and same_plan(self.plan, other.plan)

    __hash__ = None  # type: ignore[assignment]

    # ----- the merged plan's fields, read-only under their old names (table above) -----
    best_action = _PlanField[FloatArray | None]()
    actions = _PlanField[tuple[FloatArray, ...]]()
    rewards = _PlanField[FloatArray]()
    bonuses = _PlanField[FloatArray]()
    feasible = _PlanField[tuple[bool, ...]]()
    best_return = _PlanField[float]()
    best_leaf_info = _PlanField[Mapping[str, Any]]()
    best_return_curve = _PlanField[FloatArray]()
    info_curve = _PlanField[tuple[Any, ...] | None]()
    n_simulations = _PlanField[int]()
    n_nodes = _PlanField[int]()
    n_steps = _PlanField[int]()
    n_feasibility_checks = _PlanField[int]()
    n_node_visits = _PlanField[int]()
    search_time = _PlanField[float]("wall_time")

    # ----- views over the trees ---------------------------------------------------------
    @property
    def n_trees(self) -> int:
        return len(self.trees)

    @property
    def best_plan(self) -> PlanResult:
        """The best tree's own :class:`~voot.tree.PlanResult` (its own curve and counts,
        not the merged ones)."""
        return self.trees[self.best_tree].plan

    @property
    def tree_best_returns(self) -> FloatArray:
        """Each tree's best return."""
        return np.array([t.plan.best_return for t in self.trees], dtype=np.float64)

    def curve_by_total_simulations(self) -> tuple[np.ndarray[Any, np.dtype[np.int64]], FloatArray]:
        """``(K i, B_K(i))``: the merged curve against the simulations of all trees."""
        x = self.n_trees * np.arange(1, self.best_return_curve.size + 1, dtype=np.int64)
        return x, self.best_return_curve

    def best_return_at(self, seconds: ArrayLike) -> FloatArray:
        """The best return known ``seconds`` after the call started (wall clock).

        Tree :math:`k`'s simulation :math:`i` counts once its worker finished it, at
        ``trees[k].started - started + trees[k].elapsed[i]``; the result is the maximum
        over trees of their best return by then (:math:`-\\infty` before any). Workers'
        clocks must agree (one machine, or synchronised hosts).
        """
        t = np.asarray(seconds, dtype=np.float64)
        out = np.full(t.shape, -math.inf)
        for tree in self.trees:
            done = (tree.started - self.started) + tree.elapsed
            curve = tree.plan.best_return_curve
            count = np.searchsorted(done, t, side="right")
            value = np.where(count > 0, curve[np.maximum(count - 1, 0)], -math.inf)
            out = np.maximum(out, value)
        return out

    def summary(self) -> dict[str, Any]:
        """Plain values for a results row (curves as lists)."""
        return {
            **self.parallel.to_dict(),
            "best_return": self.best_return,
            "best_tree": self.best_tree,
            "plan_length": len(self.actions),
            "best_action": None if self.best_action is None else self.best_action.tolist(),
            "decision": None if self.decision is None else self.decision.to_dict(),
            "tree_best_returns": self.tree_best_returns.tolist(),
            "n_simulations": self.n_simulations,
            "total_simulations": self.total_simulations,
            "n_nodes": self.n_nodes,
            "n_steps": self.n_steps,
            "n_feasibility_checks": self.n_feasibility_checks,
            "n_node_visits": self.n_node_visits,
            "wall_time": self.wall_time,
            "search_time": self.search_time,
            "cpu_time": self.cpu_time,
            "best_return_curve": self.best_return_curve.tolist(),
        }


def merge_trees(
    trees: Sequence[TreeResult], parallel: RootParallelConfig, started: float, wall_time: float
) -> RootParallelResult:
    """Combine the trees' results (in any order) into a :class:`RootParallelResult`.

    Raises:
        RuntimeError: the results are not exactly one per tree ``0 .. K-1``.
    """
    ordered = sorted(trees, key=lambda t: t.index)
    if [t.index for t in ordered] != list(range(parallel.n_trees)):
        raise RuntimeError(
            f"expected one result for each of trees 0..{parallel.n_trees - 1}, got indices"
            f" {[t.index for t in ordered]}"
        )
    decision = merge_roots([t.root for t in ordered], parallel.merge, parallel.vote_radius)
    returns = [t.plan.best_return for t in ordered]
    best_tree = int(np.argmax(returns))  # first on ties
    best = ordered[best_tree].plan
    length = max(t.plan.best_return_curve.size for t in ordered)
    curves = np.full((len(ordered), length), -math.inf)
    for k, t in enumerate(ordered):
        c = t.plan.best_return_curve
        if c.size:
            curves[k, : c.size] = c
            curves[k, c.size :] = c[-1]  # a tree that stopped early keeps its best
    curve = curves.max(axis=0) if length else np.empty(0)
    info_curve: tuple[Any, ...] | None = None
    if all(t.plan.info_curve is not None for t in ordered) and length:
        leaders = np.argmax(curves, axis=0)
        infos = [t.plan.info_curve or () for t in ordered]
        info_curve = tuple(
            infos[k][min(i, len(infos[k]) - 1)] if infos[k] else None
            for i, k in enumerate(leaders.tolist())
        )
    plan = PlanResult(
        actions=best.actions,
        rewards=best.rewards,
        bonuses=best.bonuses,
        feasible=best.feasible,
        best_return=float(best.best_return),
        best_return_curve=curve,
        info_curve=info_curve,
        best_action=None if decision is None else decision.action.copy(),
        best_leaf_info=best.best_leaf_info,
        n_simulations=length,
        n_nodes=sum(t.plan.n_nodes for t in ordered),
        n_steps=sum(t.plan.n_steps for t in ordered),
        n_feasibility_checks=sum(t.plan.n_feasibility_checks for t in ordered),
        n_node_visits=sum(t.plan.n_node_visits for t in ordered),
        wall_time=sum(t.plan.wall_time for t in ordered),
    )
    return RootParallelResult(
        parallel=parallel,
        trees=tuple(ordered),
        decision=decision,
        best_tree=best_tree,
        plan=plan,
        total_simulations=sum(t.plan.n_simulations for t in ordered),
        started=started,
        wall_time=wall_time,
        cpu_time=sum(t.cpu_time for t in ordered),
    )
