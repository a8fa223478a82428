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


def test_authors_widening_is_the_inverted_linear_test() -> None:
    standard = ProgressiveWidening(planner_config("pw_uct", pw_k=1.0, pw_alpha=0.5))
    authors = ProgressiveWidening(planner_config("pw_uct", pw_k=0.5, widening="authors"))
    # standard: widen while |A| <= k sqrt(N)
    assert standard.widens(3, 9) and not standard.widens(4, 9)
    # the authors': widen while |A| > k N (so with k < 1, |A| = N always widens)
    assert authors.widens(10, 10) and authors.widens(6, 11)
    assert not authors.widens(5, 10) and not authors.widens(2, 10)
    one = ProgressiveWidening(planner_config("pw_uct", pw_k=1.0, widening="authors"))
    assert one.widens(1, 0) and not one.widens(1, 1) and not one.widens(3, 7)


def test_unknown_widening_names_the_choices() -> None:
    with pytest.raises(ValueError, match="valid choices are: standard, authors"):
        planner_config("pw_uct", widening="inverted")
