"""Tests of voot.tree.mcts: the search of paper Algorithms 1-2 and its options."""

from __future__ import annotations

import gc
import math
import subprocess
import sys
import time

import numpy as np
import pytest
from problem_fixtures import NON_FINITE_STEPS, NonFiniteStep, Quadratic

from voot.optim.base import Bounds
from voot.tree import MCTS, MCTSConfig, Node, StepResult, plan, planner_config
from voot.tree.null_problem import NullProblem


def one_step(dim: int = 2) -> Quadratic:
    """Reward 1 - |a - c|^2 on [-1, 1]^d: known optimum 1 at c."""
    return Quadratic(dim, np.linspace(0.2, 0.6, dim), scale=1.0)


class Counter:
    """A deterministic multi-step problem that counts its calls.

    State: the depth t. Reward: a[0] (in [0, 1]). Actions with a[0] < infeasible_below
    are infeasible. Reaching depth ``goal_depth`` is terminal with a bonus.
    """

    def __init__(
        self,
        dim: int = 2,
        infeasible_below: float = -1.0,
        goal_depth: int | None = None,
        bonus: float = 0.0,
        feasibility_check: bool = False,
    ) -> None:
        self.bounds = Bounds.cube(0.0, 1.0, dim)
        self.t = 0
        self.n_steps = 0
        self.n_restores = 0
        self.infeasible_below = infeasible_below
        self.goal_depth = goal_depth
        self.bonus = bonus
        self.n_checks = 0
        if feasibility_check:
            self.is_feasible = self._is_feasible

    def snapshot(self) -> int:
        return self.t

    def restore(self, snapshot: int) -> None:
        self.n_restores += 1
        self.t = snapshot

    def action_bounds(self) -> Bounds:
        return self.bounds

    def _is_feasible(self, action: np.ndarray) -> bool:
        self.n_checks += 1
        return bool(action[0] >= self.infeasible_below)

    def step(self, action: np.ndarray) -> StepResult:
        self.n_steps += 1
        if action[0] < self.infeasible_below:
            return StepResult(-2.0, feasible=False, info={"t": self.t})
        self.t += 1
        goal = self.goal_depth is not None and self.t >= self.goal_depth
        return StepResult(
            float(action[0]), terminal=goal, bonus=self.bonus if goal else 0.0, info={"t": self.t}
        )


# ----- one-step problems: every planner finds the optimum --------------------------------
# (planner, simulations, stated regret); one-step: depth_limit=1, regret = 1 - best return.
ONE_STEP = [
    ("voot", 200, 1e-3),
    ("doot", 200, 1e-3),
    ("rand_doot", 200, 0.1),
    ("uniform_t", 200, 0.05),
    ("pw_uct", 1000, 0.05),
    ("voronoi_pw", 300, 0.05),
    ("hoot", 300, 0.01),
]


@pytest.mark.parametrize(("planner", "n_sims", "regret"), ONE_STEP)
def test_each_planner_finds_one_step_optimum(planner: str, n_sims: int, regret: float) -> None:
    for seed in (0, 1):
        res = plan(one_step(), planner, n_sims, seed=seed, depth_limit=1)
        assert 1.0 - res.best_return <= regret, (planner, seed, res.best_return)
        assert res.best_return_curve.shape == (n_sims,)
        # The plan is the best action, and its reward is the best return.
        assert len(res.actions) == 1
        assert res.rewards[0] == pytest.approx(res.best_return)


def test_voot_beats_uniform_on_one_step_in_6d() -> None:
    voot = np.mean(
        [plan(one_step(6), "voot", 150, seed=s, depth_limit=1).best_return for s in range(3)]
    )
    unif = np.mean(
        [plan(one_step(6), "uniform_t", 150, seed=s, depth_limit=1).best_return for s in range(3)]
    )
    assert voot > unif


# ----- Algorithm 2's rules --------------------------------------------------------------
def test_newest_action_is_reevaluated_w_times_then_a_new_one_is_sampled() -> None:
    mcts = MCTS(
        Counter(),
        planner_config("voot", reevaluations=3, kappa_r=1.0, depth_limit=2, root_commitment=None),
        seed=0,
    )
    mcts.search(8)
    assert mcts.root.n == [4, 4]  # 1 evaluation + 3 re-evaluations each
    # At depth H - 1 every visit samples a new action (no re-evaluation at the leaves).
    for child in mcts.root.children:
        assert child.n == [1] * child.visits


def test_reevaluation_budget_decays_with_kappa_r() -> None:
    cfg = planner_config(
        "uniform_t", reevaluations=4, kappa_r=0.5, depth_limit=3, root_commitment=None
    )
    mcts = MCTS(Counter(), cfg, seed=0)
    mcts.search(50)
    child = mcts.root.children[0]
    # depth 1: budget 4 * 0.5 = 2 re-evaluations -> 3 evaluations per action (all but the newest).
    assert child.n[:-1] == [3] * (len(child.n) - 1)
    assert mcts.root.n[0] == 5


def test_deterministic_edges_are_stepped_once() -> None:
    problem = Counter()
    res = plan(problem, "voot", 200, seed=0, depth_limit=4, root_commitment=None)
    assert problem.n_steps == res.n_steps == res.n_nodes - 1
    assert res.n_node_visits == 200 * 4
    assert res.n_steps < res.n_node_visits  # re-evaluations cost no step


def test_infeasible_action_ends_the_rollout_and_gets_no_children() -> None:
    problem = Counter(infeasible_below=0.5)
    mcts = MCTS(problem, planner_config("uniform_t", depth_limit=3), seed=0)
    mcts.search(100)
    dead = [n for n in mcts.nodes if n.infeasible]
    assert dead and all(not n.children and n.snapshot is None for n in dead)
    for node in mcts.nodes:
        for i, child in enumerate(node.children):
            assert node.feasible[i] == (not child.infeasible)
            if not node.feasible[i]:
                assert node.q[i] == -2.0


def test_feasibility_retries_and_last_infeasible_is_executed() -> None:
    problem = Counter(infeasible_below=2.0, feasibility_check=True)  # nothing is feasible
    mcts = MCTS(problem, planner_config("uniform_t", feasibility_retries=7), seed=0)
    res = mcts.search(3)
    assert res.n_steps == 3  # one new (infeasible) action per simulation
    assert res.n_feasibility_checks == problem.n_checks == 21
    assert mcts.root.feasible == [False, False, False]
    assert res.best_return == -2.0


def test_feasibility_check_filters_new_actions() -> None:
    problem = Counter(infeasible_below=0.5, feasibility_check=True)
    res = plan(problem, "voot", 100, seed=0, depth_limit=3)
    mcts = res.mcts
    assert mcts is not None
    assert all(all(n.feasible) for n in mcts.nodes)
    assert res.n_feasibility_checks > res.n_steps


def test_max_backup_is_bellman_max_consistent() -> None:
    gamma = 0.7
    res = plan(Counter(goal_depth=3, bonus=5.0), "voot", 300, seed=3, gamma=gamma, depth_limit=4)
    assert res.mcts is not None
    for node in res.mcts.nodes:
        for i, child in enumerate(node.children):
            tail = max(child.q) if child.q else 0.0
            assert node.q[i] == pytest.approx(node.rewards[i] + node.bonuses[i] + gamma * tail)


@pytest.mark.parametrize("rule", ["mean", "jump_max_else_mean"])
def test_mean_and_jump_backups(rule: str) -> None:
    gamma = 0.5
    cfg = planner_config(
        "uniform_t",
        backup=rule,
        reevaluations=4,
        kappa_r=1.0,
        depth_limit=2,
        gamma=gamma,
        root_commitment=None,
    )
    mcts = MCTS(Counter(), cfg, seed=1)
    mcts.search(5)
    root, child = mcts.root, mcts.root.children[0]
    returns = [root.rewards[0] + gamma * r for r in child.rewards]  # the 5 simulations
    expected = returns[0]
    for k, g in enumerate(returns[1:], start=2):
        expected = (
            g if (rule == "jump_max_else_mean" and g > expected) else expected + (g - expected) / k
        )
    assert root.q[0] == pytest.approx(expected)


def test_goal_bonus_counts_in_q_but_not_in_reported_return() -> None:
    res = plan(Counter(goal_depth=1, bonus=10.0), "voot", 20, seed=0)
    assert res.mcts is not None
    root = res.mcts.root
    assert all(child.terminal for child in root.children)
    assert root.q[0] == pytest.approx(root.rewards[0] + 10.0)
    assert res.best_return < 1.0  # rewards are in [0, 1]
    assert res.bonuses.tolist() == [10.0]


def test_root_commitment_moves_the_root_and_backs_up_to_the_original_root() -> None:
    cfg = planner_config("voot", root_commitment=3, reevaluations=1, depth_limit=4)
    mcts = MCTS(Counter(), cfg, seed=0)
    mcts.search(60)
    assert mcts.current_root is not mcts.root
    assert mcts.root.visits == 60
    # The first commitment went to the root's best feasible child.
    first = mcts.current_root
    while first.parent is not mcts.root:
        assert first.parent is not None
        first = first.parent
    assert first.edge == mcts.root.best_edge()


def test_root_commitment_off_keeps_the_root() -> None:
    mcts = MCTS(Counter(), planner_config("voot", root_commitment=None, depth_limit=3), seed=0)
    mcts.search(60)
    assert mcts.current_root is mcts.root


def test_progressive_widening_count() -> None:
    cfg = planner_config("pw_uct", pw_k=2.0, pw_alpha=0.5, depth_limit=2, root_commitment=None)
    mcts = MCTS(Counter(), cfg, seed=0)
    mcts.search(100)
    expected = 0
    for visits in range(100):
        if expected <= 2.0 * visits**0.5:
            expected += 1
    assert len(mcts.root.actions) == expected


def test_final_action_rules() -> None:
    for rule in ("max_q", "most_visited"):
        res = plan(Counter(), "pw_uct", 200, seed=0, depth_limit=3, final_action=rule)
        assert res.mcts is not None and res.best_action is not None
        root = res.mcts.root
        i = root.best_edge() if rule == "max_q" else root.most_visited_edge()
        assert np.array_equal(res.best_action, root.actions[i])
        if rule == "most_visited":
            assert root.n[i] == max(root.n)


def test_best_return_curve_and_plan_agree() -> None:
    gamma = 0.9
    res = plan(Counter(), "voot", 150, seed=2, depth_limit=3, gamma=gamma, best_return_over="nodes")
    curve = res.best_return_curve
    assert np.all(np.diff(curve) >= 0)  # over nodes: monotone
    disc = gamma ** np.arange(len(res.rewards))
    assert float(disc @ res.rewards) == pytest.approx(res.best_return) == pytest.approx(curve[-1])
    leaves = plan(Counter(), "voot", 150, seed=2, depth_limit=3, gamma=gamma)
    assert leaves.best_return <= res.best_return


def test_best_return_over_complete_paths() -> None:
    class Cost(Counter):
        def step(self, action: np.ndarray) -> StepResult:
            r = super().step(action)
            return StepResult(r.reward - 1.0, r.feasible, r.terminal, r.bonus, r.info)

    res = plan(
        Cost(), "voot", 60, seed=0, depth_limit=3, best_return_over="complete", root_commitment=None
    )
    assert len(res.actions) == 3  # not the empty plan, whose return 0 beats any cost
    assert np.all(np.diff(res.best_return_curve) >= 0)
    first = MCTS(Cost(), planner_config("voot", depth_limit=3, best_return_over="complete"))
    assert first.best_return == -math.inf
    nodes = plan(Cost(), "voot", 60, seed=0, depth_limit=3, best_return_over="nodes")
    assert len(nodes.actions) == 0 and nodes.best_return == 0.0  # over nodes: the empty plan


def test_callback_record_info_and_early_stop() -> None:
    calls: list[int] = []

    def cb(mcts: MCTS, i: int) -> bool:
        calls.append(i)
        return i == 4

    res = plan(Counter(), "voot", 100, seed=0, callback=cb, record_info="t", depth_limit=3)
    assert calls == [0, 1, 2, 3, 4]
    assert res.n_simulations == 5 and res.best_return_curve.size == 5
    assert res.info_curve is not None and len(res.info_curve) == 5
    assert res.info_curve[-1] == res.best_leaf_info["t"]


def test_search_continues_the_same_tree() -> None:
    mcts = MCTS(Counter(goal_depth=5), "voot", seed=0)
    mcts.search(10)
    res = mcts.search(15)
    assert res.n_simulations == 25 and res.best_return_curve.size == 25


def test_reroot_keeps_the_subtree() -> None:
    mcts = MCTS(Counter(), planner_config("voot", depth_limit=4, root_commitment=None), seed=0)
    mcts.search(100)
    edge = mcts.recommended_edge()
    child = mcts.root.children[edge]
    size = sum(1 for _ in child.subtree())
    new_root = mcts.reroot(edge)
    assert new_root is child and mcts.root is child and new_root.parent is None
    assert len(mcts.nodes) == size and [n.id for n in mcts.nodes] == list(range(size))
    assert all(n.depth == (0 if n.parent is None else n.parent.depth + 1) for n in mcts.nodes)
    res = mcts.search(10)
    assert res.n_simulations == 10


def test_reroot_names_an_edge_out_of_range() -> None:
    mcts = MCTS(Counter(), planner_config("voot", depth_limit=4, root_commitment=None), seed=0)
    mcts.search(20)
    n = len(mcts.root.children)
    for edge in (n, -1):
        with pytest.raises(IndexError, match=f"edge {edge} out of range for a root with {n}"):
            mcts.reroot(edge)


def _best_by_brute_force(mcts: MCTS, depth_limit: int) -> float:
    """The best return over the tree's paths as ``best_return_over`` defines them."""
    mode = mcts.config.best_return_over.value
    nodes = mcts.nodes
    if mode == "leaves":
        pool = [n for n in nodes if not n.children]
    elif mode == "nodes":
        pool = nodes
    else:
        pool = [n for n in nodes if n.terminal or n.infeasible or n.depth >= depth_limit]
    return max((n.path_return for n in pool), default=-math.inf)


@pytest.mark.parametrize(
    ("mode", "infeasible_below"),
    [("leaves", -1.0), ("nodes", -1.0), ("complete", -1.0), ("complete", 0.3)],
)
def test_reroot_recomputes_the_best_path_over_the_kept_subtree(
    mode: str, infeasible_below: float
) -> None:
    """After a re-root the best return and plan are those of the kept subtree, measured
    from the new root, in every ``best_return_over`` mode, and stay so as it grows."""
    cfg = planner_config("voot", depth_limit=4, root_commitment=None, best_return_over=mode)
    mcts = MCTS(Counter(infeasible_below=infeasible_below), cfg, seed=0)
    mcts.search(100)
    # keep a subtree with an infeasible action below it if there is one
    edge = next(
        (
            e
            for e, c in enumerate(mcts.root.children)
            if c.expandable and any(n.infeasible for n in c.subtree())
        ),
        mcts.recommended_edge(),
    )
    new_root = mcts.reroot(edge)
    expected = _best_by_brute_force(mcts, 4)
    assert mcts.best_return == expected
    res = mcts.result()
    if mode == "complete" and infeasible_below > 0.0:
        # the kept subtree's infeasible actions end complete paths
        assert math.isfinite(expected) and res.feasible[-1] is False
    elif mode == "complete":
        # the kept paths end one action short of the horizon, now counted from the new
        # root: none is complete yet, so there is no best plan
        assert expected == -math.inf and res.actions == () and mcts.best_node() is new_root
    else:
        assert expected > 0.0 and len(res.actions) >= 1
        disc = 0.9 ** np.arange(len(res.rewards))
        assert float(disc @ res.rewards) == pytest.approx(res.best_return)
    for _ in range(3):
        mcts.search(10)
        assert mcts.best_return == _best_by_brute_force(mcts, 4) > -math.inf


def test_nodes_are_inspectable() -> None:
    res = plan(Counter(), "voot", 30, seed=0, depth_limit=3)
    assert res.mcts is not None
    root = res.mcts.root
    assert isinstance(root, Node) and root.n_actions == len(root.q)
    assert root.action_array().shape == (root.n_actions, 2)
    assert root.q_values().shape == (root.n_actions,)
    assert "Node(" in repr(root)
    assert res.summary()["n_nodes"] == res.n_nodes


# ----- determinism -----------------------------------------------------------------------
FINGERPRINT = """
from voot.tree import plan
from voot.tree.null_problem import NullProblem

def fingerprint(planner):
    res = plan(NullProblem(4), planner, 300, seed=123, depth_limit=4, root_commitment=5)
    return (res.best_return_curve.tobytes() + b"".join(a.tobytes() for a in res.actions)).hex()
"""


def _fingerprint(planner: str) -> str:
    scope: dict[str, object] = {}
    exec(FINGERPRINT, scope)
    return scope["fingerprint"](planner)  # type: ignore[operator,no-any-return]


@pytest.mark.parametrize("planner", ["voot", "rand_doot", "pw_uct", "hoot"])
def test_same_seed_same_result_in_process(planner: str) -> None:
    assert _fingerprint(planner) == _fingerprint(planner)


def test_same_seed_bit_identical_across_processes() -> None:
    planners = ["voot", "doot", "rand_doot", "voronoi_pw", "hoot"]
    code = FINGERPRINT + f"for p in {planners!r}: print(fingerprint(p))\n"
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    assert out == [_fingerprint(p) for p in planners]


def test_different_seeds_differ() -> None:
    a = plan(NullProblem(4), "voot", 50, seed=1, depth_limit=3)
    b = plan(NullProblem(4), "voot", 50, seed=2, depth_limit=3)
    assert not np.array_equal(a.actions[0], b.actions[0])


# ----- bad input -------------------------------------------------------------------------
@pytest.mark.parametrize("n", [-1, 0, 2.5, True, "10"])
def test_bad_number_of_simulations(n: object) -> None:
    with pytest.raises(ValueError, match="n_simulations must be an integer >= 1"):
        plan(NullProblem(2), "voot", n)  # type: ignore[arg-type]
    mcts = MCTS(NullProblem(2))
    with pytest.raises(ValueError, match="n_simulations"):
        mcts.search(n)  # type: ignore[arg-type]


class BadBox(NullProblem):
    def __init__(self, box: object) -> None:
        super().__init__(3)
        self.box = box

    def action_bounds(self) -> Bounds:
        return self.box  # type: ignore[return-value]


@pytest.mark.parametrize(
    "box",
    [np.zeros((3, 3)), np.zeros((4,)), [[0.0, 1.0, 2.0], [1.0, 0.5, 3.0]]],
)
def test_action_box_of_wrong_shape_is_a_clear_error(box: object) -> None:
    with pytest.raises(ValueError, match=r"action_bounds\(\) returned an invalid action box"):
        MCTS(BadBox(box))


def test_action_box_as_pairs_is_accepted() -> None:
    res = plan(BadBox([[-1.0, 1.0]] * 3), "voot", 5, depth_limit=2)
    assert res.actions[0].shape == (3,)


def test_not_a_problem_is_a_type_error() -> None:
    with pytest.raises(TypeError, match="is not a PlanningProblem"):
        MCTS(object())  # type: ignore[arg-type]


def test_step_must_return_a_step_result() -> None:
    class Bad(NullProblem):
        def step(self, action: np.ndarray) -> StepResult:
            return 1.0  # type: ignore[return-value]

    with pytest.raises(TypeError, match="must return a StepResult"):
        plan(Bad(2), "voot", 1)


def test_endless_rollout_without_depth_limit_is_an_error(monkeypatch: pytest.MonkeyPatch) -> None:
    import voot.tree.mcts as mcts_module

    monkeypatch.setattr(mcts_module, "MAX_UNLIMITED_DEPTH", 50)
    with pytest.raises(RuntimeError, match="set depth_limit"):
        plan(Counter(), "voot", 1)


def test_config_object_and_overrides() -> None:
    cfg = MCTSConfig(sampler="voo", depth_limit=2)
    res = plan(NullProblem(2), cfg, 10, gamma=0.5)
    assert (
        res.mcts is not None and res.mcts.config.gamma == 0.5 and res.mcts.config.depth_limit == 2
    )
    assert math.isfinite(res.best_return)


# ----- two-stage feasibility and the authors' tree-side rules (the v1 presets) ------------
class SignedReward(Counter):
    """Counter with rewards a[0] in [-1, 1]: half the feasible actions earn < 0."""

    def __init__(self, goal_depth: int | None = None) -> None:
        super().__init__(dim=1, goal_depth=goal_depth)
        self.bounds = Bounds.cube(-1.0, 1.0, 1)


def test_commitment_counts_only_root_actions_with_reward_at_least_the_minimum() -> None:
    for low in (None, 0.0):
        problem = SignedReward()
        mcts = MCTS(
            problem,
            planner_config("uniform_t", root_commitment=3, commit_min_reward=low, depth_limit=4),
            seed=1,
        )
        moved: list[tuple[int, int]] = []

        def watch(m: MCTS, i: int, moved: list[tuple[int, int]] = moved) -> None:
            if m.current_root is not m.root and not moved:
                root = m.root
                counted = [
                    r for r, f in zip(root.rewards, root.feasible, strict=True) if f and r >= 0
                ]
                moved.append((root.n_feasible, len(counted)))

        mcts.search(300, callback=watch)
        assert moved, "the root never moved"
        n_feasible, n_nonnegative = moved[0]
        if low is None:
            assert n_feasible == 3
        else:  # negative-reward root actions did not count
            assert n_nonnegative == 3 and n_feasible >= 3
    # some negative rewards were drawn before the third non-negative one
    assert any(r < 0 for r in mcts.root.rewards)


def test_commitment_returns_to_the_original_root_after_a_goal() -> None:
    problem = Counter(dim=1, infeasible_below=0.5, goal_depth=6)
    cfg = planner_config("uniform_t", root_commitment=2, commit_reset_on_goal=True)
    mcts = MCTS(problem, cfg, seed=1)
    seen: list[tuple[bool, bool, int | None]] = []
    mcts.search(
        400,
        callback=lambda m, i: seen.append(
            (m._goal_found, m.current_root is m.root, m.commit_threshold)
        ),
    )
    first_goal = next(i for i, s in enumerate(seen) if s[0])
    assert any(not s[1] for s in seen[:first_goal])  # it had committed before the goal
    back = [i for i, s in enumerate(seen) if i > first_goal and s[1]]
    assert back, "the root never returned to the original root"
    assert seen[back[0]][2] == 2 * seen[back[0] - 1][2]  # and the threshold doubled
    # without the rule, the committed root does not come back
    plain = MCTS(
        Counter(dim=1, infeasible_below=0.5, goal_depth=6),
        cfg.replace(commit_reset_on_goal=False),
        seed=1,
    )
    states: list[bool] = []
    plain.search(400, callback=lambda m, i: states.append(m.current_root is m.root))
    first_move = states.index(False)
    assert not any(states[first_move:])


@pytest.mark.parametrize(
    "planner", ["voot", "doot", "rand_doot", "uniform_t", "pw_uct", "voronoi_pw", "hoot"]
)
def test_every_planner_gets_the_same_retries(planner: str) -> None:
    """A pre-check that always fails: 50 draws per new action, then the last is executed."""
    problem = Counter(dim=2, infeasible_below=2.0, feasibility_check=True)
    res = plan(problem, planner, 20, seed=0)
    assert res.n_steps == 20  # one new (infeasible) action per simulation
    if planner == "doot":  # DOO's proposal is a cell centre: it repeats, so it stops early
        assert 0 < res.n_feasibility_checks < 50 * res.n_steps
    else:
        assert res.n_feasibility_checks == 50 * res.n_steps


def test_failed_draws_are_voronoi_sites_with_minus_two() -> None:
    # all pre-checks fail: the executed last draw is told with -2
    problem = Counter(dim=2, infeasible_below=2.0, feasibility_check=True)
    mcts = MCTS(problem, "voot", seed=0)
    mcts.search(3)
    opt = mcts.root.sampler.optimizer
    assert opt.n_told == 3 and np.all(opt.values[:3] == -2.0)
    np.testing.assert_array_equal(opt.xs, np.array(mcts.root.actions))

    # the pre-check passes, execution fails: also told with -2
    class PassesThenFails(Counter):
        def _is_feasible(self, action: np.ndarray) -> bool:
            self.n_checks += 1
            return True

    problem = PassesThenFails(dim=2, infeasible_below=0.5, feasibility_check=True)
    mcts = MCTS(problem, "voot", seed=0)
    mcts.search(20)
    root = mcts.root
    opt = root.sampler.optimizer
    bad = [i for i, f in enumerate(root.feasible) if not f]
    assert bad and all(opt.values[i] == -2.0 for i in bad)


def test_problem_metric_reaches_the_voo_nodes() -> None:
    calls = []

    def first_coordinate(points: np.ndarray, y: np.ndarray) -> np.ndarray:
        calls.append(1)
        return np.abs(points[:, 0] - y[0])

    class WithMetric(Counter):
        def action_metric(self) -> object:
            return first_coordinate

    problem = WithMetric(dim=2, goal_depth=3)
    mcts = MCTS(problem, planner_config("voot", use_problem_metric=True), seed=0)
    mcts.search(60)
    assert mcts.root.sampler.optimizer.config.metric is first_coordinate
    assert calls
    off = MCTS(WithMetric(dim=2, goal_depth=3), "voot", seed=0)
    off.search(10)
    assert off.root.sampler.optimizer.config.metric is None
    # samplers without a metric option ignore it
    doot = MCTS(
        WithMetric(dim=2, goal_depth=3), planner_config("doot", use_problem_metric=True), seed=0
    )
    doot.search(10)


def test_commitment_moves_to_the_best_q_feasible_child_at_that_moment() -> None:
    """The committed child is the argmax of Q-hat over the root's feasible, expandable
    children *when the threshold is met* (first on ties), not whatever is best later."""
    problem = SignedReward()
    mcts = MCTS(problem, planner_config("uniform_t", root_commitment=4, depth_limit=5), seed=3)
    history: list[tuple[list[float], list[bool]]] = []
    moved_to: list[tuple[int, object]] = []

    def watch(m: MCTS, i: int) -> None:
        root = m.root
        if m.current_root is not root and not moved_to:
            moved_to.append((i, m.current_root))
        history.append(
            (
                list(root.q),
                [f and c.expandable for f, c in zip(root.feasible, root.children, strict=True)],
            )
        )

    mcts.search(200, callback=watch)
    assert moved_to, "the root never committed"
    i, child = moved_to[0]
    q, ok = history[i - 1]  # the root as it was when simulation i started
    best = max((k for k in range(len(q)) if ok[k]), key=lambda k: (q[k], -k))
    assert child is mcts.root.children[best]
    assert sum(ok) == 4  # exactly at the threshold


class RootOrder(Counter):
    """Counter whose k-th root action earns ``root_rewards[k]`` (later ones 0) and whose
    root actions numbered in ``terminal_at`` end the episode (a goal); deeper actions earn
    0. The tree never repeats a step, so the order of the root's actions is its edges'."""

    def __init__(self, root_rewards: tuple[float, ...], terminal_at: tuple[int, ...] = ()) -> None:
        super().__init__(dim=1)
        self.root_rewards, self.terminal_at, self.k = root_rewards, terminal_at, 0

    def step(self, action: np.ndarray) -> StepResult:
        self.n_steps += 1
        if self.t > 0:
            self.t += 1
            return StepResult(0.0, info={"t": self.t})
        k, self.k = self.k, self.k + 1
        self.t = 1
        reward = self.root_rewards[k] if k < len(self.root_rewards) else 0.0
        return StepResult(reward, terminal=k in self.terminal_at, info={"t": self.t})


def test_commitment_goes_to_the_first_child_when_it_is_the_best() -> None:
    """Edge 0 is a child like the others: committed to when its Q-hat is the highest."""
    problem = RootOrder((1.0, 0.6, 0.8))
    mcts = MCTS(problem, planner_config("uniform_t", root_commitment=3, depth_limit=3), seed=0)
    moved: list[tuple[int, int]] = []

    def watch(m: MCTS, i: int) -> None:
        if m.current_root is not m.root and not moved:
            moved.append((i, m.current_root.edge))

    mcts.search(30, callback=watch)
    assert moved, "the root never committed"
    assert moved[0][1] == 0
    assert mcts.root.q[:3] == pytest.approx([1.0, 0.6, 0.8])  # deeper actions earn 0


def test_a_root_with_a_terminal_child_stays_and_doubles_its_threshold() -> None:
    """The original rule: once the root has a terminal child, a commitment check keeps
    the root and doubles the threshold (2, 4, 8, ...), each time the root's counted
    actions reach it."""
    problem = RootOrder((0.5, 0.9, 0.5), terminal_at=(1,))  # the second root action: a goal
    cfg = planner_config("uniform_t", root_commitment=2, depth_limit=3)
    mcts = MCTS(problem, cfg, seed=0)
    assert mcts.commit_threshold == 2
    seen: list[tuple[int, int | None]] = []
    mcts.search(
        40,
        callback=lambda m, i: seen.append((m.root.n_commit_actions, m.commit_threshold)),
    )
    assert mcts.current_root is mcts.root  # never committed
    assert mcts.root.n_terminal_children == 1 and mcts.root.n_commit_actions > 8
    thresholds = [t for _, t in seen]
    changes = [k for k in range(1, len(seen)) if thresholds[k] != thresholds[k - 1]]
    assert sorted(set(thresholds)) == [2 * 2**j for j in range(len(set(thresholds)))]
    assert len(changes) >= 3
    for k in changes:  # doubled at the check after the counted actions reached it
        assert thresholds[k] == 2 * thresholds[k - 1]
        assert seen[k - 1][0] >= thresholds[k - 1] > seen[k - 2][0]
    # without the terminal child the same root commits at its second counted action
    plain = MCTS(RootOrder((0.5, 0.9, 0.5)), cfg, seed=0)
    plain.search(40)
    assert plain.current_root is not plain.root and plain.commit_threshold == 2


class CrashesOnce(Counter):
    """Step calls go: an infeasible root action, a feasible one, then a crash one level
    down (a simulator error, not a reward); from then on every action is feasible."""

    def __init__(self) -> None:
        super().__init__(dim=1)
        self.calls = 0

    def step(self, action: np.ndarray) -> StepResult:
        self.calls += 1
        if self.calls == 1:
            return StepResult(-2.0, feasible=False, info={"t": self.t})
        if self.calls == 3:
            raise RuntimeError("simulator crashed")
        self.t += 1
        return StepResult(0.5, info={"t": self.t})


def test_a_search_interrupted_by_a_step_error_continues_on_a_feasible_child() -> None:
    """The simulation the error cut short left a feasible root action not yet backed up
    (Q-hat -inf): continuing, the commitment moves to it, not to the infeasible one."""
    mcts = MCTS(CrashesOnce(), planner_config("uniform_t", root_commitment=1, depth_limit=3))
    with pytest.raises(RuntimeError, match="crashed"):
        mcts.search(5)
    root = mcts.root
    assert root.feasible == [False, True] and root.q[1] == -math.inf
    first: list[Node] = []
    res = mcts.search(5, callback=lambda m, i: first.append(m.current_root) if not first else None)
    assert first[0] is root.children[1]
    assert res.best_return > 0.0 and mcts.n_steps > 3


@pytest.mark.parametrize(
    "planner", ["voot", "pw_uct", "uniform_t", "hoot", "doot", "rand_doot", "voronoi_pw"]
)
@pytest.mark.parametrize("bad", NON_FINITE_STEPS, ids=str)
def test_non_finite_reward_or_bonus_stops_every_planner(planner: str, bad: NonFiniteStep) -> None:
    mcts = MCTS(bad.problem(after=3), planner_config(planner, depth_limit=3), seed=0)
    with bad.raises():
        mcts.search(20)
    n_nodes = len(mcts.nodes)
    # The tree is unchanged by the failed step, and the next search restores the state.
    with pytest.raises(ValueError, match="must be finite"):
        mcts.search(1)
    assert len(mcts.nodes) == n_nodes
    assert all(math.isfinite(v) for v in mcts.best_return_curve)


@pytest.mark.parametrize("seed", [-1, True, 0.5, "7"])
def test_plan_mcts_and_episodes_check_the_seed(seed: object) -> None:
    from voot.tree import run_episode
    from voot.tree.root_parallel import tree_seeds

    match = "seed must be None, an integer >= 0"
    with pytest.raises(ValueError, match=match):
        plan(NullProblem(2), "voot", 2, seed=seed)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=match):
        MCTS(NullProblem(2), seed=seed)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=match):
        run_episode(NullProblem(2), "voot", 2, seed=seed)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=match):
        tree_seeds(seed, 2)  # type: ignore[arg-type]


def test_search_times_itself_and_restores_the_garbage_collector() -> None:
    """``wall_time`` adds up the searches' seconds; gc is paused only during a search."""
    mcts = MCTS(Counter(), planner_config("voot", depth_limit=3), seed=0)
    was = gc.isenabled()
    try:
        for enabled in (True, False):
            (gc.enable if enabled else gc.disable)()
            before = mcts.wall_time
            began = time.perf_counter()
            mcts.search(5)
            elapsed = time.perf_counter() - began
            assert 0.0 < mcts.wall_time - before <= elapsed
            assert gc.isenabled() is enabled
    finally:
        (gc.enable if was else gc.disable)()


def test_result_of_a_root_with_one_action() -> None:
    mcts = MCTS(Counter(), planner_config("voot", depth_limit=3), seed=0)
    res = mcts.search(1)
    assert len(mcts.root.children) == 1 and mcts.recommended_edge() == 0
    assert res.best_action is not None
    np.testing.assert_array_equal(res.best_action, mcts.root.actions[0])
    assert mcts.result().info_curve is None  # only with_info_curve=True records it
    assert mcts.result(True).info_curve == ()  # nothing recorded by this search


def test_final_action_rules_pick_different_edges_when_they_disagree() -> None:
    """max_q recommends the best Q-hat, most_visited the most visited root edge."""
    for rule in ("max_q", "most_visited"):
        mcts = MCTS(one_step(dim=1), planner_config("uniform_t", depth_limit=1, final_action=rule))
        root = mcts.root
        mcts.goto(root)
        for a in (0.0, 0.5):
            mcts._execute(root, np.array([a]))
        root.q[:] = [0.9, 0.1]  # edge 0 is best ...
        root.n[:] = [1, 5]  # ... edge 1 most visited
        assert mcts.recommended_edge() == (0 if rule == "max_q" else 1)
        assert (
            mcts.result().best_action.tobytes() == root.actions[mcts.recommended_edge()].tobytes()
        )


@pytest.mark.parametrize("backup", ["mean", "jump_max_else_mean"])
def test_the_voo_sampler_sees_every_q_hat_change(backup: str) -> None:
    """Mean and jump backups change Q-hat on later visits: the node's VOO must see them."""
    mcts = MCTS(
        Counter(dim=2, goal_depth=3),
        planner_config("voot", backup=backup, root_commitment=None),
        seed=1,
    )
    mcts.search(120)
    for node in mcts.nodes:
        if node.sampler is None or not node.actions:
            continue
        told = node.sampler.optimizer.values
        assert np.array_equal(told, np.array(node.q)), (backup, node.id)


def test_authors_widening_adds_an_action_every_visit_below_k_one() -> None:
    """The original's PW with w < 1: UCB never runs, every simulation adds a root action."""
    cfg = planner_config(
        "pw_uct", pw_k=0.8, widening="authors", depth_limit=2, root_commitment=None
    )
    res = plan(Counter(dim=1), cfg, 40, seed=0)
    assert res.mcts is not None and len(res.mcts.root.actions) == 40
    # w = 1: once the root has a feasible action it is never widened again
    cfg1 = cfg.replace(pw_k=1.0)
    res1 = plan(Counter(dim=1, infeasible_below=0.5), cfg1, 40, seed=0)
    assert res1.mcts is not None
    root = res1.mcts.root
    assert root.n_feasible == 1 and root.feasible[-1]
    # standard widening at the same k keeps re-evaluating: far fewer root actions
    std = plan(Counter(dim=1), cfg.replace(widening="standard"), 40, seed=0)
    assert std.mcts is not None and len(std.mcts.root.actions) < 20


def test_commit_reset_trigger_root_goal_child_ignores_deeper_goals() -> None:
    """The authors' rule returns to the original root only when the current root has a
    goal child; voot's v1 rule as soon as any goal leaf exists."""
    cfg = planner_config("uniform_t", root_commitment=2, commit_reset_on_goal=True)
    runs = {}
    for trigger in ("goal_found", "root_goal_child"):
        mcts = MCTS(
            Counter(dim=1, infeasible_below=0.5, goal_depth=6),
            cfg.replace(commit_reset_trigger=trigger),
            seed=1,
        )
        seen: list[tuple[bool, int]] = []
        mcts.search(
            400,
            callback=lambda m, i, seen=seen: seen.append((m._goal_found, m.current_root.depth)),
        )
        runs[trigger] = seen
    first_goal = next(i for i, s in enumerate(runs["goal_found"]) if s[0])
    # identical until the first goal (same seed, same rule so far)
    assert runs["goal_found"][: first_goal + 1] == runs["root_goal_child"][: first_goal + 1]
    # afterwards the v1 rule is back at the original root at some point, while the
    # authors' rule keeps descending until the root is the goal's parent (depth 5)
    assert any(d == 0 for _, d in runs["goal_found"][first_goal + 1 :])
    deepest = max(d for _, d in runs["root_goal_child"])
    assert deepest == 5


@pytest.mark.parametrize(
    ("reward", "bonus", "what"),
    [
        (None, 0.0, "reward must be a real number .*NoneType"),
        ("1.5", 0.0, "reward must be a real number .*str"),
        (True, 0.0, "reward must be a real number .*bool"),
        (1 + 0j, 0.0, "reward must be a real number .*complex"),
        (0.5, "1", "goal bonus must be a real number .*str"),
    ],
)
@pytest.mark.parametrize("planner", ["voot", "pw_uct"])
def test_a_reward_that_is_not_a_number_is_refused_naming_the_step(
    planner: str, reward: object, bonus: object, what: str
) -> None:
    """Not coerced (a string read as 1.5, True as 1) or a bare TypeError: the step is named."""
    from problem_fixtures import BadReward

    problem = BadReward(reward, bonus, after=3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=rf"BadReward\.step\(action=\[.*\]\) returned {what}"):
        plan(problem, planner, n_simulations=10, seed=0)


def test_numpy_and_integer_rewards_still_count() -> None:
    from problem_fixtures import BadReward

    for reward in (np.float32(0.25), np.int64(1), 2, np.array(0.5)):
        res = plan(BadReward(reward), "voot", n_simulations=4, seed=0, depth_limit=2)  # type: ignore[arg-type]
        assert math.isfinite(res.best_return)
