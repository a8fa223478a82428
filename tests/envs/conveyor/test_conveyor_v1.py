"""voot/ConveyorPacking-v1: the authors' two-stage feasibility on the conveyor."""

from __future__ import annotations

import textwrap

import gymnasium as gym
import numpy as np
from gymnasium.utils.env_checker import check_env
from process_fixtures import run_pickled

import voot  # noqa: F401  (registers the ids)
from voot.envs.conveyor.config import conveyor_config
from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.scripted import conveyor_actions
from voot.envs.core.problem import EnvProblem


def test_v1_precheck_is_region_and_collision_only() -> None:
    env = gym.make("voot/ConveyorPacking-v1").unwrapped
    assert isinstance(env, ConveyorPackingEnv)
    assert env.config == conveyor_config("v1") and env.config.precheck == "kinematic"
    assert gym.make("voot/ConveyorPacking-v0").unwrapped.config.precheck == "full_step"
    env.reset(seed=0)
    state = env.get_state()
    rng = np.random.default_rng(0)
    passed = executed_fail = 0
    for _ in range(300):
        a = rng.uniform(-1, 1, 9)
        env.set_state(state)
        ok, info = env.precheck(a)
        assert env.get_state() == state  # the pre-check changes nothing
        _, _, _, _, step = env.step(a)
        assert ok or not step["feasible"]  # execution checks more than the pre-check
        if not ok and "no base path" not in step["reason"]:
            assert info["reason"] == step["reason"]  # same first failure, same words
        passed += ok
        executed_fail += ok and not step["feasible"]
    # some draws pass the kinematics and fail only for want of a base path
    assert passed > 0 and executed_fail > 0


def test_scripted_solution_and_checks() -> None:
    env = gym.make("voot/ConveyorPacking-v1").unwrapped
    check_env(env, skip_render_check=True)
    env.reset(seed=0)
    problem = EnvProblem(env)
    for a in conveyor_actions(env):
        assert problem.is_feasible(a)
        res = problem.step(a)
        assert res.feasible, res.info["reason"]
    assert res.terminal and env.objects_left == 0
    m = problem.action_metric()
    pts = np.zeros((2, 9))
    pts[1, 2] = pts[1, 5] = pts[1, 8] = 1.0  # headings only
    np.testing.assert_allclose(m(pts, np.zeros(9)), [0.0, 0.0])


def test_determinism_across_processes() -> None:
    env = gym.make("voot/ConveyorPacking-v1").unwrapped
    env.reset(seed=0)
    rng = np.random.default_rng(4)
    probes = [conveyor_actions(env)[0]] + [rng.uniform(-1, 1, 9) for _ in range(15)]
    local = [(env.precheck(a), env.step(a)[1:]) for a in probes]
    script = textwrap.dedent(
        """
        import pickle, sys
        import gymnasium as gym
        import voot
        probes = pickle.load(sys.stdin.buffer)
        env = gym.make("voot/ConveyorPacking-v1").unwrapped
        env.reset(seed=0)
        out = [(env.precheck(a), env.step(a)[1:]) for a in probes]
        sys.stdout.buffer.write(pickle.dumps(out))
        """
    )
    remote = run_pickled(script, probes)
    from gymnasium.utils.env_checker import data_equivalence

    assert data_equivalence(local, remote, exact=True)
