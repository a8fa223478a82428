"""Tests of the sampling-based MPC planners (voot.tree.shooting)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from problem_fixtures import NON_FINITE_STEPS, NonFiniteStep, Quadratic

from voot.optim.base import Bounds
from voot.tree import plan
from voot.tree.null_problem import NullProblem
from voot.tree.planners import normalize_any_planner
from voot.tree.problem import StepResult
from voot.tree.shooting import (
    SHOOTING_PLANNERS,
    CEMConfig,
    MPPIConfig,
    PredictiveSamplingConfig,
    ShootingPlanner,
    available_shooting_planners,
    is_shooting_planner,
    plan_shooting,
    shooting_config,
)

PLANNERS = available_shooting_planners()


class Alternating:
    """The box changes with the depth: 3-D in [0, 1] at even depths, 1-D in [5, 6] at odd.

    Records every action with the depth it was taken at; an action outside its depth's
    box raises. Actions with a[0] below ``infeasible_below`` (even depths) are
    infeasible with reward -2; depth ``terminal_at`` is terminal.
    """

    def __init__(self, infeasible_below: float = -1.0, terminal_at: int | None = None) -> None:
        self.t = 0
        self.infeasible_below = infeasible_below
        self.terminal_at = terminal_at
        self.seen: list[tuple[int, np.ndarray]] = []
        self.restores = 0

    def snapshot(self) -> int:
        return self.t

    def restore(self, snapshot: int) -> None:
        self.t = snapshot
        self.restores += 1

    def action_bounds(self) -> Bounds:
        if self.t % 2 == 0:
            return Bounds.cube(0.0, 1.0, 3)
        return Bounds.cube(5.0, 6.0, 1)

    def step(self, action: np.ndarray) -> StepResult:
        box = self.action_bounds()
        assert action.shape == (box.dim,) and box.contains(action), (self.t, action)
        self.seen.append((self.t, action.copy()))
        if self.t % 2 == 0 and action[0] < self.infeasible_below:
            return StepResult(-2.0, feasible=False)
        self.t += 1
        terminal = self.terminal_at is not None and self.t >= self.terminal_at
        return StepResult(float(action[0]) - 5.0 * (self.t % 2 == 0), terminal=terminal)


@pytest.mark.parametrize("planner", ["cem", "mppi"])
def test_cem_and_mppi_beat_uniform_shooting_on_a_smooth_problem(planner: str) -> None:
    horizon, gamma, budget = 5, 0.9, 600
    optimum = sum(gamma**t for t in range(horizon))
    gaps = {}
    for name in (planner, "random_shooting"):
        finals = [
            plan(Quadratic(), name, n_simulations=budget, seed=s, horizon=horizon).best_return
            for s in range(5)
        ]
        assert all(f <= optimum + 1e-12 for f in finals)
        gaps[name] = optimum - float(np.mean(finals))
    # uniform shooting stays far from the optimum; CEM and MPPI close most of the gap
    assert gaps["random_shooting"] > 0.3
    assert gaps[planner] < 0.25 * gaps["random_shooting"], gaps


def test_predictive_sampling_improves_on_its_nominal() -> None:
    res = plan(Quadratic(), "predictive_sampling", n_simulations=300, seed=0, horizon=5)
    # the first simulation is the nominal (the box centre); the best grows from it
    nominal = sum(0.9**t * (1.0 - float(np.sum(Quadratic().optimum ** 2)) / 4) for t in range(5))
    assert res.best_return_curve[0] == pytest.approx(nominal)
    assert res.best_return > nominal + 0.3


@pytest.mark.parametrize("planner", PLANNERS)
def test_result_counts_and_curve(planner: str) -> None:
    res = plan_shooting(NullProblem(dim=2), planner, n_simulations=37, seed=1, horizon=4)
    assert res.n_simulations == 37
    assert res.best_return_curve.shape == (37,)
    assert np.all(np.diff(res.best_return_curve) >= 0)  # best so far: monotone
    assert res.n_steps == 37 * 4 == res.n_node_visits  # every rollout runs H steps
    assert res.n_feasibility_checks == 0 and res.n_nodes == 0 and res.mcts is None
    assert len(res.actions) == 4 and res.best_action is not None
    assert np.array_equal(res.best_action, res.actions[0])
    ret = sum(0.9**t * r for t, r in enumerate(res.rewards))
    assert res.best_return == pytest.approx(ret) == res.best_return_curve[-1]


@pytest.mark.parametrize("planner", PLANNERS)
def test_deterministic_given_the_seed(planner: str) -> None:
    runs = [
        plan(Quadratic(3), planner, n_simulations=45, seed=seed, horizon=3) for seed in (7, 7, 8)
    ]
    assert np.array_equal(runs[0].best_return_curve, runs[1].best_return_curve)
    assert all(np.array_equal(a, b) for a, b in zip(runs[0].actions, runs[1].actions, strict=True))
    assert not np.array_equal(runs[0].best_return_curve, runs[2].best_return_curve)


@pytest.mark.parametrize("planner", PLANNERS)
def test_infeasible_action_scores_minus_two_and_ends_the_rollout(planner: str) -> None:
    problem = Alternating(infeasible_below=2.0)  # every even-depth action is infeasible
    res = plan(problem, planner, n_simulations=10, seed=0, horizon=6)
    assert res.n_steps == 10  # each rollout stops at its first (infeasible) action
    assert res.best_return == -2.0 and res.feasible == (False,)
    assert all(t == 0 for t, _ in problem.seen)
    # one restore of the root per simulation, and one as the search returns
    assert problem.restores == 11


@pytest.mark.parametrize("planner", PLANNERS)
def test_action_box_is_read_at_every_state(planner: str) -> None:
    problem = Alternating(terminal_at=3)
    res = plan(problem, planner, n_simulations=25, seed=3, horizon=5)
    # Alternating.step asserts each action lies in its own depth's box and has its dim
    assert res.n_steps == 25 * 3  # the terminal state at depth 3 ends every rollout
    assert [a.shape for a in res.actions] == [(3,), (1,), (3,)]
    assert {t for t, _ in problem.seen} == {0, 1, 2}


def test_a_wider_box_later_widens_the_sequences() -> None:
    class Widening(Alternating):
        def action_bounds(self) -> Bounds:  # 1-D first, then 4-D
            return Bounds.cube(0.0, 1.0, 1 if self.t == 0 else 4)

        def step(self, action: np.ndarray) -> StepResult:
            self.seen.append((self.t, action.copy()))
            self.t += 1
            return StepResult(float(action.sum()))

    for planner in PLANNERS:
        problem = Widening()
        planner_ = ShootingPlanner(problem, shooting_config(planner, horizon=3), seed=0)
        res = planner_.search(30)
        assert planner_.mean.shape == (3, 4)
        assert [a.shape for a in res.actions[:2]] == [(1,), (4,)]


def test_bonus_counts_in_the_objective_not_in_the_return() -> None:
    class Bonus(Quadratic):
        def step(self, action: np.ndarray) -> StepResult:
            r = super().step(action)
            return StepResult(r.reward, bonus=1.0, terminal=True)

    res = plan(Bonus(), "cem", n_simulations=10, seed=0, horizon=3)
    assert res.best_return < 1.0 and np.all(res.bonuses == 1.0)
    assert len(res.actions) == 1  # terminal after one step


@pytest.mark.parametrize("planner", PLANNERS)
@pytest.mark.parametrize("bad", NON_FINITE_STEPS, ids=str)
def test_non_finite_reward_or_bonus_stops_every_planner(planner: str, bad: NonFiniteStep) -> None:
    """The tree search's error, naming the step; the cut rollout leaves no trace."""
    shooter = ShootingPlanner(bad.problem(after=7), shooting_config(planner, horizon=3), seed=0)
    with bad.raises():
        shooter.search(20)
    assert shooter.n_simulations == 2  # 2 rollouts of 3 steps; the 8th step was bad
    assert len(shooter.best_return_curve) == 2
    assert all(math.isfinite(v) for v in shooter.best_return_curve)
    assert math.isfinite(shooter.best_return)
    with pytest.raises(ValueError, match="must be finite"):
        shooter.search(1)
    with pytest.raises(ValueError, match="must be finite"):
        plan(bad.problem(), planner, n_simulations=5, seed=0, horizon=2)


def test_callback_stops_and_record_info() -> None:
    class Info(Quadratic):
        def step(self, action: np.ndarray) -> StepResult:
            r = super().step(action)
            return StepResult(r.reward, info={"objects_left": 3})

    seen: list[int] = []

    def stop(planner: ShootingPlanner, i: int) -> bool:
        seen.append(i)
        return i == 4

    res = plan(Info(), "mppi", n_simulations=50, seed=0, callback=stop, record_info="objects_left")
    assert seen == [0, 1, 2, 3, 4] and res.n_simulations == 5
    assert res.info_curve == (3, 3, 3, 3, 3)


def test_search_continues() -> None:
    planner = ShootingPlanner(Quadratic(), CEMConfig(horizon=2, population=10, elites=2), seed=0)
    planner.search(15)
    res = planner.search(15)
    assert res.n_simulations == 30 and res.best_return_curve.shape == (30,)


def test_registry_and_names() -> None:
    assert PLANNERS == ["cem", "mppi", "predictive_sampling", "random_shooting"]
    assert set(SHOOTING_PLANNERS) == set(PLANNERS)
    assert is_shooting_planner("Predictive-Sampling") and not is_shooting_planner("voot")
    assert normalize_any_planner("CEM") == "cem"
    assert normalize_any_planner("RAND-DOOT") == "rand_doot"
    with pytest.raises(ValueError, match="unknown planner 'nope'; valid planners are: cem, doot"):
        normalize_any_planner("nope")
    cfg = shooting_config("mppi", temperature=0.5)
    assert isinstance(cfg, MPPIConfig) and cfg.to_dict()["planner"] == "mppi"
    assert cfg.to_dict()["temperature"] == 0.5


def test_defaults() -> None:
    cem = CEMConfig()
    assert (cem.population, cem.elites, cem.init_std, cem.smoothing) == (50, 5, 0.5, 0.1)
    assert cem.min_std == pytest.approx(math.sqrt(0.001))
    mppi = MPPIConfig()
    assert (mppi.population, mppi.noise, mppi.temperature) == (10, 0.1, 0.01)
    ps = PredictiveSamplingConfig()
    assert (ps.population, ps.noise, ps.horizon, ps.gamma) == (10, 0.1, 20, 0.9)


@pytest.mark.parametrize(
    ("name", "options", "message"),
    [
        ("cem", {"population": 1}, "population must be an integer >= 2"),
        ("cem", {"elites": 0}, "elites must be an integer >= 1"),
        ("cem", {"population": 8, "elites": 9}, r"elites must be <= population \(8\)"),
        ("cem", {"smoothing": 1.0}, "smoothing must be"),
        ("cem", {"init_std": 0.0}, "init_std must be"),
        ("cem", {"min_std": -1.0}, "min_std must be"),
        ("cem", {"init_std": 0.1, "min_std": 0.2}, r"min_std must be <= init_std \(0\.1\)"),
        ("cem", {"horizon": math.nan}, "horizon must be an integer >= 1"),
        ("cem", {"population": "50"}, "population must be an integer >= 2"),
        ("cem", {"init_std": math.inf}, "init_std must be"),
        ("cem", {"smoothing": -0.1}, "smoothing must be"),
        ("mppi", {"population": 0}, "population must be an integer >= 1"),
        ("mppi", {"temperature": -1.0}, "temperature must be"),
        ("predictive_sampling", {"noise": True}, "noise must be"),
        ("mppi", {"temperature": 0}, "temperature must be"),
        ("mppi", {"noise": float("nan")}, "noise must be"),
        ("predictive_sampling", {"population": 1}, "population must be an integer >= 2"),
        ("random_shooting", {"horizon": 0}, "horizon must be an integer >= 1"),
        ("random_shooting", {"gamma": 1.5}, "gamma must be"),
        ("random_shooting", {"noise": 0.1}, r"unknown option\(s\) \['noise'\]"),
        ("random_shooting", {"feasibility_retries": -1}, "feasibility_retries must be"),
        ("random_shooting", {"feasibility_retries": 2.5}, "feasibility_retries must be"),
        ("cem", {"feasibility_retries": 50}, r"unknown option\(s\) \['feasibility_retries'\]"),
        ("cmaes", {}, "unknown sampling-based planner 'cmaes'"),
    ],
)
def test_config_errors_name_the_option(name: str, options: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        shooting_config(name, **options)


def test_bad_problem_and_config() -> None:
    with pytest.raises(TypeError, match="has no snapshot"):
        ShootingPlanner(object(), "cem")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="config must be"):
        ShootingPlanner(Quadratic(), 3)  # type: ignore[arg-type]

    class BadStep(Quadratic):
        def step(self, action: np.ndarray) -> StepResult:
            return 1.0  # type: ignore[return-value]

    with pytest.raises(TypeError, match="must return a StepResult"):
        plan(BadStep(), "cem", n_simulations=1)
    with pytest.raises(ValueError, match="n_simulations must be an integer >= 1"):
        plan(Quadratic(), "mppi", n_simulations=0)


def test_planner_seed_and_options_are_checked_by_name() -> None:
    """A bad seed was numpy's message naming no argument (or, True, taken as seed 1); an
    unknown option next to a config object was a TypeError from dataclasses.replace."""
    for seed in (-1, True, 1.5, "3"):
        with pytest.raises(ValueError, match="seed must be None, an integer >= 0"):
            ShootingPlanner(Quadratic(), "cem", seed)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"unknown option\(s\) \['bogus'\] for CEMConfig"):
        plan_shooting(Quadratic(), CEMConfig(), n_simulations=4, bogus=1)
    assert ShootingPlanner(Quadratic(), "cem", np.int64(3)).rng.random() == (
        np.random.default_rng(3).random()
    )


class PreChecked(Alternating):
    """:class:`Alternating` with a pre-check that passes even-depth actions with
    ``a[1] >= passes_above`` (odd depths always pass); counts the checks."""

    def __init__(self, passes_above: float, **kwargs: float) -> None:
        super().__init__(**kwargs)
        self.passes_above = passes_above
        self.checked: list[tuple[int, np.ndarray]] = []

    def is_feasible(self, action: np.ndarray) -> bool:
        self.checked.append((self.t, action.copy()))
        return self.t % 2 == 1 or bool(action[1] >= self.passes_above)


def test_random_shooting_without_retries_never_pre_checks() -> None:
    problem = PreChecked(passes_above=0.5)
    default = plan(problem, "random_shooting", n_simulations=20, seed=4, horizon=4)
    assert problem.checked == [] and default.n_feasibility_checks == 0
    # a problem without a pre-check: the retries change nothing, same draws
    same = plan(
        Alternating(),
        "random_shooting",
        n_simulations=20,
        seed=4,
        horizon=4,
        feasibility_retries=50,
    )
    assert np.array_equal(same.best_return_curve, default.best_return_curve)
    assert same.n_feasibility_checks == 0


def test_random_shooting_redraws_each_step_until_the_pre_check_passes() -> None:
    problem = PreChecked(passes_above=0.9)  # 10% of the even-depth draws pass
    res = plan(
        problem, "random_shooting", n_simulations=30, seed=2, horizon=4, feasibility_retries=50
    )
    executed = [a for t, a in problem.seen if t % 2 == 0]
    # every executed even-depth action passed (0.9^50 ~ 0.5%: no step ran out of tries)
    assert executed and all(a[1] >= 0.9 for a in executed)
    assert res.n_feasibility_checks == len(problem.checked) > res.n_steps
    assert len(problem.checked) > 2 * len(executed)  # redraws happened at even depths
    # each check but the last of a step failed; the executed action is the last checked
    assert np.array_equal(problem.checked[-1][1], problem.seen[-1][1])


def test_random_shooting_executes_the_last_draw_when_every_try_fails() -> None:
    problem = PreChecked(passes_above=2.0, infeasible_below=2.0)  # nothing passes
    res = plan(
        problem, "random_shooting", n_simulations=5, seed=0, horizon=3, feasibility_retries=7
    )
    assert res.n_feasibility_checks == 5 * 7  # 7 tries per rollout's first step
    assert res.n_steps == 5 and res.best_return == -2.0
    last_tries = [a for _, a in problem.checked[6::7]]
    assert all(np.array_equal(a, b) for a, (_, b) in zip(last_tries, problem.seen, strict=True))


def test_random_shooting_with_retries_is_deterministic_given_the_seed() -> None:
    runs = [
        plan(
            PreChecked(passes_above=0.7),
            "random_shooting",
            n_simulations=25,
            seed=s,
            horizon=4,
            feasibility_retries=10,
        )
        for s in (3, 3, 5)
    ]
    assert np.array_equal(runs[0].best_return_curve, runs[1].best_return_curve)
    assert runs[0].n_feasibility_checks == runs[1].n_feasibility_checks
    assert not np.array_equal(runs[0].best_return_curve, runs[2].best_return_curve)
