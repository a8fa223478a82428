"""Tests of voot.tree.selection: the rules' own logic (the search's use is in test_tree_mcts)."""

from __future__ import annotations

import math

import pytest

from voot.tree import planner_config
from voot.tree.node import Node
from voot.tree.selection import HOOSelection, ProgressiveWidening, Reevaluate, make_selection


def test_make_selection_matches_the_config() -> None:
    assert isinstance(make_selection(planner_config("voot")), Reevaluate)
    assert isinstance(make_selection(planner_config("pw_uct")), ProgressiveWidening)
    assert isinstance(make_selection(planner_config("hoot")), HOOSelection)
    assert Reevaluate.tells_sampler and ProgressiveWidening.tells_sampler
    assert not HOOSelection.tells_sampler


def test_reevaluation_budget_decays_per_depth() -> None:
    rule = Reevaluate(planner_config("voot", reevaluations=5, kappa_r=0.5))
    assert [rule.budget(h) for h in (2, 0, 1)] == [1.25, 5.0, 2.5]


def test_ucb_skips_infeasible_edges_and_breaks_ties_first() -> None:
    rule = ProgressiveWidening(planner_config("pw_uct", ucb_c=0.0))
    node = Node(0, None, -1, 0, 1.0, 0.0, None)
    node.q, node.n, node.feasible = [5.0, 1.0, 1.0], [1, 1, 1], [False, True, True]
    node.n_feasible, node.visits = 2, 3
    assert rule.ucb(node) == 1
    explore = ProgressiveWidening(planner_config("pw_uct", ucb_c=10.0))
    node.n = [1, 9, 1]
    assert explore.ucb(node) == 2  # the less visited feasible edge
    assert math.isfinite(node.q[1])


def test_unknown_selection_is_rejected() -> None:
    with pytest.raises(ValueError, match="valid choices are"):
        planner_config("voot", selection="greedy")
