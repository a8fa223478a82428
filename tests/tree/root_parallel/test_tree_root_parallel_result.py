"""Tests of voot.tree.root_parallel.result: the merged result holds a PlanResult."""

from __future__ import annotations

import functools
import math
from dataclasses import fields, replace

import numpy as np

from voot.tree import PlanResult, make_chain
from voot.tree.root_parallel import RootParallelResult, merge_trees, plan_root_parallel

CHAIN = functools.partial(make_chain, "shekel", 3)


def search(**kwargs: object) -> RootParallelResult:
    args: dict[str, object] = {"seed": 3, "n_trees": 3, "executor": "serial"}
    args.update(kwargs)
    return plan_root_parallel(CHAIN(), "voot", 40, record_info="value", **args)  # type: ignore[arg-type]


def test_the_result_holds_the_merged_plan_and_reads_like_it() -> None:
    res = search()
    assert isinstance(res.plan, PlanResult) and res.plan.mcts is None
    for name in (
        "actions",
        "rewards",
        "bonuses",
        "feasible",
        "best_return",
        "best_leaf_info",
        "best_return_curve",
        "info_curve",
        "best_action",
        "n_simulations",
        "n_nodes",
        "n_steps",
        "n_feasibility_checks",
        "n_node_visits",
    ):
        assert getattr(res, name) is getattr(res.plan, name), name
    assert res.search_time == res.plan.wall_time
    best = res.best_plan
    assert best is res.trees[res.best_tree].plan
    assert res.plan.actions is best.actions and res.plan.best_return == best.best_return
    assert res.plan.n_nodes == sum(t.plan.n_nodes for t in res.trees)
    assert res.decision is not None and np.array_equal(res.plan.best_action, res.decision.action)
    # The plan's fields are not re-declared on the result.
    assert {f.name for f in fields(RootParallelResult)} & {f.name for f in fields(PlanResult)} == {
        "wall_time"
    }


def test_equality_ignores_timings_but_not_the_plan() -> None:
    res = search()
    again = search()
    assert (res == again and res.wall_time != again.wall_time) or res == again
    slower = replace(res, wall_time=res.wall_time + 1.0, plan=replace(res.plan, wall_time=9.0))
    assert slower == res
    other = replace(res, plan=replace(res.plan, n_nodes=res.plan.n_nodes + 1))
    assert other != res
    assert res != object()


def test_merge_trees_in_any_order_and_the_summary() -> None:
    res = search()
    shuffled = merge_trees(list(reversed(res.trees)), res.parallel, res.started, res.wall_time)
    assert shuffled == res
    row = res.summary()
    assert row["best_return"] == res.best_return and row["n_trees"] == 3
    assert row["total_simulations"] == 120 and row["best_return_curve"] == list(
        res.best_return_curve
    )
    x, y = res.curve_by_total_simulations()
    assert x[-1] == 120 and y is res.best_return_curve
    assert res.best_return_at([-1.0])[0] == -math.inf
