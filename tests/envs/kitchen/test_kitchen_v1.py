"""voot/KitchenClearing-v1: the authors' two-stage feasibility on the kitchen.

(voot.envs.kitchen.env has two test modules: test_kitchen.py for the domain, this one for the
v1 preset's options.)
"""

from __future__ import annotations

import textwrap

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from process_fixtures import run_pickled

import voot  # noqa: F401  (registers the ids)
from voot.envs.core.names import Reason
from voot.envs.core.problem import EnvProblem
from voot.envs.core.scene import object_footprint
from voot.envs.core.units import denormalize, normalize
from voot.envs.kitchen.env import KITCHEN_PRESETS, KitchenClearingEnv, kitchen_config
from voot.envs.kitchen.scripted import kitchen_actions
from voot.envs.motion.rects import rect_overlaps
from voot.tree import MCTS, planner_config


@pytest.fixture(scope="module")
def env() -> KitchenClearingEnv:
    e = gym.make("voot/KitchenClearing-v1").unwrapped
    assert isinstance(e, KitchenClearingEnv)
    return e


def _place(env: KitchenClearingEnv, x: float, y: float, theta: float) -> np.ndarray:
    a = np.zeros(6)
    a[:3] = normalize([x, y, theta], env.config.place_ranges)
    return a


def _forbidden_place(env: KitchenClearingEnv) -> np.ndarray:
    """A placement in the large rooms that passes the kinematic pre-check."""
    rng = np.random.default_rng(0)
    obj = env.objects[env.task.held]
    for _ in range(5000):
        x, y, th = rng.uniform(2.8, 4.0), rng.uniform(-3.5, 3.5), rng.uniform(0, 6.28)
        if not rect_overlaps(object_footprint(obj, x, y, th), env.config.forbidden):
            continue
        a = _place(env, x, y, th)
        if env.precheck(a)[0]:
            return a
    raise AssertionError("no pre-check-feasible placement in the forbidden rooms")


def test_v1_preset_is_the_authors_protocol(env: KitchenClearingEnv) -> None:
    cfg = env.config
    assert cfg == kitchen_config("v1")
    assert cfg.precheck == "kinematic" and cfg.nonclearing_penalty_infeasible
    assert not cfg.pick_requires_free_carry and cfg.pick_base_path
    # v0 keeps the first release's behaviour
    v0 = gym.make("voot/KitchenClearing-v0").unwrapped.config
    assert v0 == kitchen_config("v0") and dict(KITCHEN_PRESETS["v0"]) == {}
    assert v0.precheck == "full_step" and v0.pick_requires_free_carry
    # options override the preset, unknown ones are named
    e = gym.make("voot/KitchenClearing-v1", pick_requires_free_carry=True).unwrapped
    assert e.config.pick_requires_free_carry and e.config.precheck == "kinematic"
    with pytest.raises(ValueError, match="valid options are"):
        KitchenClearingEnv(preset="v1", no_such_option=1)
    with pytest.raises(ValueError, match="valid presets are: v0, v1"):
        KitchenClearingEnv(preset="v2")
    with pytest.raises(ValueError, match="precheck must be one of full_step, kinematic"):
        kitchen_config("v1", precheck="cheap")


def test_forbidden_room_passes_the_precheck_and_fails_at_execution(
    env: KitchenClearingEnv,
) -> None:
    env.reset(seed=0)
    env.step(kitchen_actions(env)[0])
    problem = EnvProblem(env)
    before = env.get_state()
    a = _forbidden_place(env)[:3]
    assert problem.is_feasible(a)
    assert env.get_state() == before  # the pre-check changed nothing
    res = problem.step(a)
    assert not res.feasible and res.reward == -2.0
    assert str(res.info["reason"]).startswith("forbidden room")
    # and in the tree: the child is infeasible, the simulation ends there with -2
    env.set_state(before)
    problem = EnvProblem(env)
    mcts = MCTS(problem, planner_config("uniform_t", root_commitment=None), seed=0)
    root = mcts.root
    mcts.goto(root)
    i = mcts._execute(root, a)
    assert root.children[i].infeasible and root.rewards[i] == -2.0


def test_precheck_covers_kinematics_only(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    pick = kitchen_actions(env)[0]
    ok, info = env.precheck(pick)
    assert ok and info["operator"] == "pick" and info["reason"] == ""
    # a pick whose robot leaves the house fails the pre-check, with the step's reason
    far = normalize([np.pi / 2, 0.75, 0.5, 0.9, np.pi, 0.0], env.config.pick_ranges)
    ok_far, info_far = env.precheck(far)
    _, _, _, _, step_info = env.step(far)
    env.reset(seed=0)
    assert ok_far == step_info["feasible"]
    if not ok_far:
        assert info_far["reason"] == step_info["reason"]
    # the whole step's verdict implies the pre-check's (execution checks more)
    rng = np.random.default_rng(1)
    state = env.get_state()
    for _ in range(200):
        a = rng.uniform(-1, 1, 6)
        env.set_state(state)
        passed, _ = env.precheck(a)
        _, _, _, _, info = env.step(a)
        assert passed or not info["feasible"]


def test_nonclearing_place_at_the_cap_is_infeasible() -> None:
    v0 = KitchenClearingEnv()
    v1 = KitchenClearingEnv(preset="v1", pick_base_path=False)
    found = False
    rng = np.random.default_rng(3)
    for e in (v0, v1):
        e.reset(seed=0)
        e.step(kitchen_actions(e)[0])
    state0, state1 = v0.get_state(), v1.get_state()
    for _ in range(3000):
        x, y, th = rng.uniform(-2, 2.8), rng.uniform(-4, 4), rng.uniform(0, 6.28)
        a = _place(v0, x, y, th)
        v0.set_state(state0)
        _, r0, _, _, i0 = v0.step(a)
        if not (i0["feasible"] and r0 == -2.0):
            continue
        v1.set_state(state1)
        _, r1, _, _, i1 = v1.step(a)
        assert not i1["feasible"] and r1 == -2.0
        assert i1["reason"].startswith("non-clearing place at the penalty cap")
        # an infeasible action changes nothing but the step counter
        after = v1.get_state()
        np.testing.assert_array_equal(after.physics, state1.physics)
        assert after.task.on_path == state1.task.on_path and after.task.held == state1.task.held
        found = True
        break
    assert found, "no non-clearing place with a path of >= 2 m was drawn"


def test_scripted_solution_solves_v1(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    for a in kitchen_actions(env):
        _, _, term, _, info = env.step(a)
        assert info["feasible"], info["reason"]
    assert term and env.objects_left == 0


def test_metric_is_per_operator(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    problem = EnvProblem(env)
    pick_metric = problem.action_metric()
    assert problem.action_metric() is pick_metric  # one object per operator
    problem.step(kitchen_actions(env)[0])
    place_metric = problem.action_metric()
    assert place_metric is not pick_metric
    # places compare x, y only (in metres)
    a = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.5, 0.0, 0.0]])
    d = place_metric(a, np.array([0.0, 0.0, 0.0]))
    half_width = 0.5 * (env.config.house[1] - env.config.house[0])
    np.testing.assert_allclose(d, [0.0, 0.0, 0.5 * half_width])


def test_gymnasium_checks_and_determinism_across_processes() -> None:
    e = gym.make("voot/KitchenClearing-v1")
    check_env(e.unwrapped, skip_render_check=True)
    problem = EnvProblem(gym.make("voot/KitchenClearing-v1").unwrapped, seed=0)
    opts = {"commit_min_reward": 0.0, "commit_reset_on_goal": True, "use_problem_metric": True}
    local = MCTS(problem, planner_config("voot", **opts), seed=5).search(150)
    script = textwrap.dedent(
        """
        import pickle, sys
        import gymnasium as gym
        import voot
        from voot.envs.core.problem import EnvProblem
        from voot.tree import MCTS, planner_config
        opts = pickle.load(sys.stdin.buffer)
        problem = EnvProblem(gym.make("voot/KitchenClearing-v1").unwrapped, seed=0)
        res = MCTS(problem, planner_config("voot", **opts), seed=5).search(150)
        sys.stdout.buffer.write(pickle.dumps((res.best_return_curve, res.n_steps)))
        """
    )
    curve, n_steps = run_pickled(script, opts)
    assert curve.tobytes() == local.best_return_curve.tobytes()
    assert n_steps == local.n_steps


def test_pick_base_path_is_checked_at_execution(env: KitchenClearingEnv) -> None:
    env.reset(seed=0)
    _, _, _, _, info = env.step(kitchen_actions(env)[0])
    assert info["base_path"] is not None and info["base_path_length"] > 0
    v0 = KitchenClearingEnv()
    v0.reset(seed=0)
    _, _, _, _, info0 = v0.step(kitchen_actions(v0)[0])
    assert info0["base_path"] is None
    params = denormalize(kitchen_actions(env)[0], env.config.pick_ranges)
    assert params.shape == (6,)


def test_the_footprint_option_executes_places_the_disc_refuses() -> None:
    """``base_model="footprint"`` (on v1): the scripted solution is unchanged, and of the
    places that pass the pre-check after the first pick, some that fail for want of a
    disc path execute with the exact footprint, the same way twice; none that the disc
    executes fails."""
    disc = KitchenClearingEnv(preset="v1")
    exact = KitchenClearingEnv(preset="v1", base_model="footprint")
    assert disc.config.planner.footprint is None and exact.config.planner.footprint is not None
    for env in (disc, exact):
        env.reset(seed=0)
        env.transition(env.solution_actions()[0])
    d0, e0 = disc.get_state(), exact.get_state()
    rng = np.random.default_rng(3)
    rescued = 0
    for _ in range(400):
        a = rng.uniform(-1, 1, disc.action_dim)
        if not disc.precheck(a)[0]:
            continue
        d = disc.transition(a)[3]
        e = exact.transition(a)[3]
        disc.set_state(d0)
        exact.set_state(e0)
        assert not (d["feasible"] and not e["feasible"]), (d["reason"], e["reason"])
        if d["reason_code"] == Reason.NO_BASE_PATH and e["feasible"]:
            rescued += 1
            again = exact.transition(a)[3]
            exact.set_state(e0)
            assert again["base_path"] == e["base_path"]
        if rescued >= 2:
            break
    assert rescued >= 2
