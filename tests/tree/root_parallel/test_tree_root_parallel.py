"""Tests of voot.tree.root_parallel: K independent trees merged at the root."""

from __future__ import annotations

import functools
import math
import pickle
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import numpy as np
import pytest

from voot.tree import MCTS, chain_planner_options, make_chain, plan, planner_config
from voot.tree.null_problem import NullProblem
from voot.tree.root_parallel import (
    LocalProcessExecutor,
    MergeRule,
    RootParallelConfig,
    RootStats,
    SerialExecutor,
    TreeExecutor,
    clear_problem_cache,
    merge_roots,
    normalized_distances,
    plan_root_parallel,
    tree_seeds,
)

#: A cheap chain with infeasible actions, a bonus and step info.
CHAIN = functools.partial(make_chain, "shekel", 3)
CONFIG = planner_config(
    "voot",
    **{**chain_planner_options("shekel", 3), "reevaluations": 3},
    feasibility_retries=5,
)


def chain_plan(**kwargs: Any) -> Any:
    args: dict[str, Any] = {"n_simulations": 60, "seed": 7, "n_trees": 3, "executor": "serial"}
    args.update(kwargs)
    return plan_root_parallel(args.pop("problem", CHAIN()), CONFIG, **args)


# ----- seeds ---------------------------------------------------------------------------------
def test_tree_seeds_are_spawned_and_do_not_depend_on_the_number_of_trees() -> None:
    four = tree_seeds(3, 4)
    assert [s.spawn_key for s in four] == [(0,), (1,), (2,), (3,)]
    assert all(s.entropy == 3 for s in four)
    two = tree_seeds(3, 2)
    for a, b in zip(two, four, strict=False):
        assert np.array_equal(a.generate_state(4), b.generate_state(4))
    assert not np.array_equal(four[0].generate_state(4), four[1].generate_state(4))
    base = np.random.SeedSequence(3)
    first = tree_seeds(base, 2)
    again = tree_seeds(base, 2)  # the passed sequence is not advanced
    assert base.n_children_spawned == 0
    assert [s.spawn_key for s in first] == [s.spawn_key for s in again] == [(0,), (1,)]
    with pytest.raises(ValueError, match="n_trees"):
        tree_seeds(0, 0)


# ----- K = 1 is a plain search -----------------------------------------------------------------
@pytest.mark.parametrize("merge", ["max_q", "most_visited"])
def test_one_tree_equals_a_plain_search_with_the_derived_seed(merge: str) -> None:
    cfg = CONFIG.replace(final_action=merge)
    rp = plan_root_parallel(CHAIN(), cfg, 80, seed=5, n_trees=1, merge=merge, executor="serial")
    ref = MCTS(CHAIN(), cfg, seed=tree_seeds(5, 1)[0]).search(80)
    assert np.array_equal(rp.best_return_curve, ref.best_return_curve)
    assert rp.best_return == ref.best_return
    assert ref.best_action is not None and rp.best_action is not None
    assert np.array_equal(rp.best_action, ref.best_action)
    assert len(rp.actions) == len(ref.actions)
    assert all(np.array_equal(a, b) for a, b in zip(rp.actions, ref.actions, strict=True))
    assert (rp.n_steps, rp.n_nodes, rp.total_simulations) == (ref.n_steps, ref.n_nodes, 80)
    # ... and not the search seeded with the base seed itself.
    other = plan(CHAIN(), cfg, 80, seed=5)
    assert not np.array_equal(other.best_return_curve, rp.best_return_curve)


# ----- determinism -----------------------------------------------------------------------------
class Shuffled:
    """An executor that returns results in a scrambled order (as a pool may)."""

    def __init__(self, order: Callable[[int], list[int]]) -> None:
        self.order = order

    def map(self, fn: Callable[[Any], Any], items: Sequence[Any]) -> list[Any]:
        results = [fn(item) for item in items]
        return [results[i] for i in self.order(len(results))]


class UnorderedOnly:
    """A voot.bench-style backend: map_unordered only, results last-first."""

    def map_unordered(self, fn: Callable[[Any], Any], items: Sequence[Any]) -> Iterator[Any]:
        for item in reversed(list(items)):
            yield fn(item)


@pytest.mark.parametrize("merge", ["max_q", "most_visited", "vote"])
def test_result_does_not_depend_on_completion_order(merge: str) -> None:
    ref = chain_plan(merge=merge, record_info="value")
    rng = np.random.default_rng(0)
    for executor in (
        Shuffled(lambda n: list(reversed(range(n)))),
        Shuffled(lambda n: rng.permutation(n).tolist()),
        UnorderedOnly(),
    ):
        got = chain_plan(merge=merge, record_info="value", executor=executor)
        assert got == ref
        assert [t.index for t in got.trees] == [0, 1, 2]
    assert isinstance(SerialExecutor(), TreeExecutor)
    # Different seeds give different trees (the comparison can fail).
    assert chain_plan(merge=merge, seed=8) != ref


def test_serial_and_process_pool_give_identical_results() -> None:
    """The problem object in-process, a factory in two spawned workers: the same result."""
    serial = chain_plan(merge="vote", record_info="value", n_trees=4)
    with LocalProcessExecutor(max_workers=2) as pool:
        parallel = chain_plan(
            problem=CHAIN, merge="vote", record_info="value", n_trees=4, executor=pool
        )
        again = chain_plan(
            problem=CHAIN, merge="vote", record_info="value", n_trees=4, executor=pool
        )
    assert parallel == serial == again
    assert parallel.decision == serial.decision
    assert len({t.pid for t in parallel.trees}) >= 1
    assert all(t.pid == serial.trees[0].pid for t in serial.trees)
    # The one-shot default pool, with a pickled problem object.
    assert chain_plan(executor="process", merge="vote", record_info="value", n_trees=4) == serial


def test_a_serial_factory_is_built_once_and_restored_for_every_tree() -> None:
    calls: list[int] = []

    def factory() -> Any:
        calls.append(1)
        return CHAIN()

    clear_problem_cache()
    by_factory = chain_plan(problem=factory)  # a closure: not cached, built per tree
    assert len(calls) == 3
    assert by_factory == chain_plan()
    cached = chain_plan(problem=CHAIN)  # picklable: built once, then restored
    assert cached == by_factory
    clear_problem_cache()


# ----- the merged result -----------------------------------------------------------------------
def test_merged_result_is_the_best_tree_and_the_max_curve() -> None:
    res = chain_plan(record_info="value", n_trees=4)
    curves = np.array([t.plan.best_return_curve for t in res.trees])
    assert np.array_equal(res.best_return_curve, curves.max(axis=0))
    best = int(np.argmax([t.plan.best_return for t in res.trees]))
    assert res.best_tree == best and res.best_return == res.trees[best].plan.best_return
    assert res.best_return == res.best_return_curve[-1]
    assert res.total_simulations == 240 and res.n_simulations == 60
    assert res.n_steps == sum(t.plan.n_steps for t in res.trees)
    x, y = res.curve_by_total_simulations()
    assert x[0] == 4 and x[-1] == 240 and y is res.best_return_curve
    leaders = np.argmax(curves, axis=0)
    assert res.info_curve is not None
    assert res.info_curve[-1] == res.trees[leaders[-1]].plan.info_curve[-1]  # type: ignore[index]
    assert len({t.plan.best_return for t in res.trees}) > 1  # the trees differ
    late = res.best_return_at([0.0, 1e9])
    assert late[0] == -math.inf and late[1] == res.best_return
    row = res.summary()
    assert row["n_trees"] == 4 and row["merge"] == "max_q" and len(row["tree_best_returns"]) == 4
    assert row["decision"]["tree"] == res.decision.tree  # type: ignore[union-attr]
    pickle.loads(pickle.dumps(res))


def test_keep_trees_and_time_limit() -> None:
    res = chain_plan(keep_trees=True)
    assert all(t.plan.mcts is not None for t in res.trees)
    assert res.trees[0].plan.mcts is not res.trees[1].plan.mcts
    quick = plan_root_parallel(
        NullProblem(2), "voot", 10**6, n_trees=2, executor="serial", time_limit=0.05, depth_limit=3
    )
    assert 0 < quick.n_simulations < 10**6
    assert all(t.elapsed[-1] >= 0.05 for t in quick.trees)


# ----- merge rules on hand-made statistics ----------------------------------------------------
def stats(actions: Any, q: Any, n: Any, feasible: Any = None, box: float = 1.0) -> RootStats:
    a = np.atleast_2d(np.array(actions, dtype=float))
    d = a.shape[1]
    f = np.ones(len(q), dtype=bool) if feasible is None else feasible
    return RootStats(a, np.array(q, float), np.array(n), np.array(f), np.zeros(d), np.full(d, box))


def test_max_q_skips_infeasible_edges_and_breaks_ties_by_tree() -> None:
    roots = [
        stats([[0.1, 0.1], [0.2, 0.2]], [1.0, 9.0], [3, 1], [True, False]),
        stats([[0.5, 0.5], [0.6, 0.6]], [2.0, 0.5], [1, 8]),
        stats([[0.7, 0.7]], [2.0], [1]),
    ]
    d = merge_roots(roots, "max_q")
    assert d is not None
    assert (d.tree, d.edge, d.q, d.score, d.members) == (1, 0, 2.0, 2.0, ((1, 0),))
    assert np.array_equal(d.action, [0.5, 0.5]) and d.n_candidates == 4
    m = merge_roots(roots, MergeRule.MOST_VISITED)
    assert m is not None and (m.tree, m.edge, m.score) == (1, 1, 8.0)


def test_most_visited_breaks_ties_by_q_then_tree() -> None:
    roots = [stats([[0.1], [0.2]], [1.0, 3.0], [5, 5]), stats([[0.3]], [3.0], [5])]
    d = merge_roots(roots, "most_visited")
    assert d is not None and (d.tree, d.edge) == (0, 1)


def test_all_infeasible_roots_fall_back_to_every_edge() -> None:
    roots = [stats([[0.1], [0.9]], [-2.5, -2.1], [1, 1], [False, False])]
    d = merge_roots(roots, "max_q")
    assert d is not None and d.edge == 1 and d.n_candidates == 2


def test_vote_prefers_a_region_several_trees_explored() -> None:
    lone = stats([[0.9, 0.9], [0.5, 0.1]], [5.0, 1.0], [10, 1])  # best single action
    near = [[0.10, 0.10], [0.12, 0.11], [0.15, 0.12]]
    roots = [
        lone,
        stats(near, [3.0, 3.5, 2.0], [4, 4, 2]),
        stats([[0.11, 0.13]], [3.2], [6]),
    ]
    assert merge_roots(roots, "max_q").tree == 0  # type: ignore[union-attr]
    assert merge_roots(roots, "most_visited").tree == 0  # type: ignore[union-attr]
    d = merge_roots(roots, "vote", vote_radius=0.1)
    assert d is not None
    # Every action near (0.1, 0.1) sees the other three: V = 4 + 4 + 2 + 6 = 16 > 10;
    # ties among them go to the higher own Q (3.5).
    assert (d.tree, d.edge, d.score) == (1, 1, 16.0)
    assert d.members == ((1, 0), (1, 1), (1, 2), (2, 0))
    assert d.members_best_q == 3.5
    assert d.members_mean_q == pytest.approx((4 * 3.0 + 4 * 3.5 + 2 * 2.0 + 6 * 3.2) / 16)
    # A radius too small for any neighbour: every action votes alone (most visited wins).
    alone = merge_roots(roots, "vote", vote_radius=0.0)
    assert alone is not None and (alone.tree, alone.edge, alone.score) == (0, 0, 10.0)


def test_vote_distance_is_measured_in_box_widths() -> None:
    # Box [0, 100] x [0, 100] vs [0, 1] x [0, 1]: the same actions in widths.
    wide = [stats([[10.0, 10.0], [14.0, 10.0]], [1.0, 2.0], [3, 1], box=100.0)]
    dist = normalized_distances(wide[0].actions, wide[0].actions, wide[0].lower, wide[0].upper)
    assert dist[0, 1] == pytest.approx(math.sqrt(0.04**2 / 2))
    close = merge_roots(wide, "vote", vote_radius=0.03)
    assert close is not None and close.score == 4.0
    far = merge_roots(wide, "vote", vote_radius=0.02)
    assert far is not None and far.score == 3.0 and far.edge == 0


def test_merge_of_empty_roots_and_of_different_boxes() -> None:
    empty = RootStats(*map(np.array, ([[]], [], [], [], [0, 0], [1, 1])))
    assert merge_roots([empty, empty], "vote") is None
    assert merge_roots([], "max_q") is None
    a = stats([[0.1]], [1.0], [1])
    b = stats([[0.1]], [1.0], [1], box=2.0)
    with pytest.raises(ValueError, match="same root state"):
        merge_roots([a, b], "max_q")
    with pytest.raises(ValueError, match=r"\(m, 2\)"):
        RootStats(*map(np.array, (np.zeros((1, 3)), [1.0], [1], [True], [0, 0], [1, 1])))
    with pytest.raises(ValueError, match="one per action"):
        RootStats(*map(np.array, (np.zeros((2, 2)), [1.0], [1, 1], [True, True], [0, 0], [1, 1])))


# ----- bad input -----------------------------------------------------------------------------
@pytest.mark.parametrize("k", [0, -1, 1.5, True, "2"])
def test_bad_number_of_trees(k: Any) -> None:
    with pytest.raises(ValueError, match="n_trees must be an integer >= 1"):
        RootParallelConfig(n_trees=k)
    with pytest.raises(ValueError, match="n_trees must be an integer >= 1"):
        plan_root_parallel(NullProblem(2), "voot", 5, n_trees=k, executor="serial")


def test_unknown_merge_rule_lists_the_valid_ones() -> None:
    with pytest.raises(ValueError, match="valid merge rules are: max_q, most_visited, vote"):
        RootParallelConfig(merge="average")
    with pytest.raises(ValueError, match="unknown merge rule 'best'"):
        plan_root_parallel(NullProblem(2), "voot", 5, merge="best", executor="serial")
    with pytest.raises(ValueError, match="valid merge rules"):
        merge_roots([], "mean")
    assert RootParallelConfig(merge="Most-Visited").merge is MergeRule.MOST_VISITED


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"vote_radius": 1.5}, "vote_radius must be a number in"),
        ({"vote_radius": float("nan")}, "vote_radius"),
        ({"executor": "threads"}, "valid executors are: process, serial"),
        ({"executor": object()}, "map"),
        ({"executor": "serial", "max_workers": 2}, "max_workers applies"),
        ({"executor": "process", "keep_trees": True}, "in-process executor"),
        ({"time_limit": 0}, "time_limit"),
        ({"record_info": 3}, "record_info"),
        ({"n_simulations": 0}, "n_simulations"),
        ({"reevaluations": -1}, "reevaluations"),
    ],
)
def test_bad_options(kwargs: dict[str, Any], message: str) -> None:
    args: dict[str, Any] = {"n_simulations": 5, "executor": "serial", "depth_limit": 2}
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        plan_root_parallel(NullProblem(2), "voot", **args)


def test_bad_problems() -> None:
    with pytest.raises(ValueError, match="zero-argument factory"):
        plan_root_parallel(42, "voot", 5, executor="serial")  # type: ignore[arg-type]

    class Local(NullProblem):  # defined in a function: cannot be pickled
        pass

    with pytest.raises(ValueError, match="pass a zero-argument factory"):
        plan_root_parallel(Local(2), "voot", 5, executor="process", depth_limit=2)
    with pytest.raises(ValueError, match="max_workers must be"):
        LocalProcessExecutor(max_workers=0)
    with pytest.raises(ValueError, match="valid start methods"):
        LocalProcessExecutor(start_method="teleport")


def test_an_error_in_a_worker_reaches_the_caller_and_stops_the_pool() -> None:
    broken = functools.partial(make_chain, "no_such_chain", 3)
    with pytest.raises(ValueError, match="unknown chain 'no_such_chain'"):
        plan_root_parallel(broken, "voot", 5, n_trees=2, executor="process")
    pool = LocalProcessExecutor(max_workers=1)
    with pytest.raises(ValueError, match="unknown chain"), pool:
        plan_root_parallel(broken, "voot", 5, n_trees=2, executor=pool)
    assert pool._pool is None  # closed (its workers terminated) by the with block
