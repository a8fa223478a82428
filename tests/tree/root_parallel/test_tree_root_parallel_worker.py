"""Tests of voot.tree.root_parallel.worker: one tree, and the problem cache it uses."""

from __future__ import annotations

import functools
import os
import pickle

import numpy as np

from voot.parallel import worker_cache
from voot.tree import make_chain, planner_config
from voot.tree.root_parallel import TreeTask, clear_problem_cache, prebuild_problem, run_tree

CHAIN = functools.partial(make_chain, "shekel", 3)


def task(index: int = 0, **kwargs: object) -> TreeTask:
    args: dict[str, object] = {
        "index": index,
        "source": CHAIN,
        "is_factory": True,
        "root_snapshot": None,
        "config": planner_config("voot"),
        "n_simulations": 15,
        "seed": np.random.SeedSequence(0).spawn(index + 1)[index],
    }
    args.update(kwargs)
    return TreeTask(**args)  # type: ignore[arg-type]


def test_run_tree_is_deterministic_and_keeps_the_factory_problem() -> None:
    clear_problem_cache()
    first = run_tree(task())
    assert [key[0] for key in worker_cache().keys()] == ["problem"]  # type: ignore[index]
    again = run_tree(task())  # the kept problem, restored to its root
    assert again == first and again.pid == os.getpid()
    assert first.plan.mcts is None and first.root.n_actions > 0
    assert first.elapsed.shape == (15,)
    assert run_tree(task(1)) != first
    clear_problem_cache()
    assert len(worker_cache()) == 0


def test_a_problem_object_is_used_as_it_is() -> None:
    problem = CHAIN()
    root = problem.snapshot()
    res = run_tree(task(source=problem, is_factory=False, root_snapshot=root, keep_tree=True))
    assert res.plan.mcts is not None and res.plan.mcts.problem is problem
    assert len(res.plan.best_return_curve) == 15


def test_tasks_pickle_and_prebuild_fills_the_cache() -> None:
    clear_problem_cache()
    assert pickle.loads(pickle.dumps(task())).index == 0
    prebuild_problem(CHAIN)
    assert len(worker_cache()) == 1
    clear_problem_cache()
