"""Tests of voot.tree.gym_adapters: gymnasium environments as planning problems."""

from __future__ import annotations

import subprocess
import sys

import gymnasium as gym
import numpy as np
import pytest

import voot  # noqa: F401  (registers the environment ids)
from voot.tree import FeasibilityCheck, GymProblem, MujocoGymProblem, PlanningProblem, plan
from voot.tree.gym_adapters import box_bounds


def _roundtrip(problem: GymProblem, n_before: int = 5, n_after: int = 8, seed: int = 0) -> None:
    """Snapshot, step a sequence, wander off, restore, step again: bit-identical."""
    rng = np.random.default_rng(seed)
    b = problem.action_bounds()
    for _ in range(n_before):
        problem.step(b.sample(rng))
    snap = problem.snapshot()
    actions = b.sample(rng, n_after)

    def run() -> list[tuple[bytes, float, bool, bool]]:
        out = []
        for a in actions:
            r = problem.step(a)
            out.append(
                (np.asarray(problem.last_observation).tobytes(), r.reward, r.terminal, r.feasible)
            )
        return out

    first = run()
    for _ in range(4):  # move elsewhere
        problem.step(b.sample(rng))
    problem.restore(snap)
    second = run()
    assert first == second


@pytest.mark.parametrize("env_id", ["Reacher-v5", "InvertedPendulum-v5"])
def test_mujoco_snapshot_roundtrip_is_bit_identical(env_id: str) -> None:
    env = gym.make(env_id)
    problem = MujocoGymProblem(env, seed=0)
    assert isinstance(problem, PlanningProblem)
    assert not isinstance(problem, FeasibilityCheck)
    _roundtrip(problem)
    snap = problem.snapshot()
    assert not snap[0].flags.writeable  # snapshots are immutable values
    env.close()


def test_mujoco_snapshot_restores_the_time_limit_counter() -> None:
    env = gym.make("Reacher-v5", max_episode_steps=6)
    problem = MujocoGymProblem(env, seed=1)
    a = np.zeros(2)
    for _ in range(3):
        problem.step(a)
    snap = problem.snapshot()
    results = [problem.step(a).terminal for _ in range(3)]
    assert results == [False, False, True]  # truncated at step 6
    problem.restore(snap)
    assert [problem.step(a).terminal for _ in range(3)] == results
    env.close()


def test_mujoco_restore_without_forward() -> None:
    env = gym.make("InvertedPendulum-v5")
    problem = MujocoGymProblem(env, seed=0, forward=False)
    _roundtrip(problem, seed=3)
    env.close()


def test_plan_on_reacher_replays_exactly_from_the_root() -> None:
    env = gym.make("Reacher-v5", max_episode_steps=50)
    problem = MujocoGymProblem(env, seed=0)
    res = plan(
        problem, "voot", 60, seed=0, depth_limit=3, gamma=1.0, sampler_options={"omega": 0.3}
    )
    assert res.n_steps < res.n_node_visits  # cached edges are not re-simulated
    assert len(res.actions) == 3
    # The plan replays exactly from the root snapshot.
    mcts = res.mcts
    assert mcts is not None
    problem.restore(mcts.root.snapshot)
    replay = [problem.step(a).reward for a in res.actions]
    assert replay == res.rewards.tolist()
    env.close()


def test_voot_tree_does_not_import_mujoco() -> None:
    code = "import sys, voot.tree, voot.tree.gym_adapters; print('mujoco' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_gym_problem_on_an_env_with_get_state() -> None:
    env = gym.make("voot/RastriginChain-v0", dim=3, max_episode_steps=4)
    problem = GymProblem(env, seed=0)
    assert isinstance(problem, FeasibilityCheck) is False  # the chain env has no is_feasible
    _roundtrip(problem, n_before=0, n_after=3)
    # Bonus and feasibility come from the info dict.
    problem.restore((0, (0,)))
    r = problem.step(np.zeros(3))  # the optimum: feasible, bonus 100
    assert r.feasible and r.bonus == 100.0 and r.reward == 0.0
    r = problem.step(np.full(3, 4.5))
    assert not r.feasible and r.terminal and r.reward < -2.0


class _FeasibleEnv(gym.Env[np.ndarray, np.ndarray]):
    """A tiny env with get_state/set_state, is_feasible and a per-state action box."""

    def __init__(self) -> None:
        self.action_space = gym.spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float64)
        self.observation_space = gym.spaces.Box(-np.inf, np.inf, shape=(1,), dtype=np.float64)
        self.t = 0

    def reset(
        self, *, seed: int | None = None, options: dict | None = None
    ) -> tuple[np.ndarray, dict]:
        super().reset(seed=seed)
        self.t = 0
        return np.zeros(1), {}

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict]:
        self.t += 1
        ok = bool(action[0] > 0)
        return (
            np.array([self.t], dtype=np.float64),
            float(action[1]),
            not ok,
            False,
            {"feasible": ok},
        )

    def get_state(self) -> int:
        return self.t

    def set_state(self, state: int) -> None:
        self.t = state

    def is_feasible(self, action: np.ndarray) -> bool:
        return bool(action[0] > 0)

    def action_bounds(self) -> tuple[list[float], list[float]]:
        return ([-1.0, -1.0 + 0.1 * self.t], [1.0, 1.0])


def test_gym_problem_uses_the_envs_feasibility_check_and_state_box() -> None:
    problem = GymProblem(_FeasibleEnv(), seed=0)
    assert isinstance(problem, FeasibilityCheck)
    res = plan(problem, "voot", 40, seed=0, depth_limit=3)
    assert all(res.feasible)
    mcts = res.mcts
    assert mcts is not None
    deeper = [n for n in mcts.nodes if n.depth == 2 and n.bounds is not None]
    assert deeper and deeper[0].bounds.lower[1] == pytest.approx(-0.8)


def test_adapter_errors() -> None:
    with pytest.raises(ValueError, match="get_state"):
        GymProblem(gym.make("Reacher-v5"))
    with pytest.raises(ValueError, match="not a gymnasium MuJoCo env"):
        MujocoGymProblem(gym.make("voot/ShekelChain-v0", dim=3))
    with pytest.raises(ValueError, match="must be 1-D"):
        box_bounds(gym.spaces.Box(-1.0, 1.0, shape=(2, 3)))
    with pytest.raises(ValueError, match="finite"):
        box_bounds(gym.spaces.Box(-np.inf, 1.0, shape=(2,)))
    with pytest.raises(ValueError, match="Box"):
        box_bounds(gym.spaces.Discrete(3))


def _voot_ids() -> list[str]:
    return [i for i in gym.registry if i.startswith("voot/")]


@pytest.mark.parametrize("env_id", _voot_ids())
def test_gym_problem_works_on_every_voot_id_or_names_env_problem(env_id: str) -> None:
    """The chains plan through GymProblem (the env left at the root, the plan replays);
    the robot envs are refused by both gym adapters, naming EnvProblem."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        env = gym.make(env_id)
    if callable(getattr(env.unwrapped, "planning_problem", None)):
        for adapter in (GymProblem, MujocoGymProblem):
            with pytest.raises(ValueError, match="EnvProblem"):
                adapter(env, seed=0)
        env.close()
        return
    problem = GymProblem(env, seed=0)
    before = problem.snapshot()
    res = plan(problem, "voot", n_simulations=30, seed=0)
    assert problem.snapshot() == before
    assert len(res.actions) >= 1
    rewards = []
    for action in res.actions:
        _, reward, _, _, info = env.step(action)
        rewards.append(reward - info["bonus"])
    assert rewards == res.rewards.tolist()


class _RewardEnv(gym.Env[np.ndarray, np.ndarray]):
    """An env with get_state/set_state whose step returns ``reward`` and ``info``."""

    def __init__(self, reward: object, info: dict | None = None) -> None:
        self.observation_space = gym.spaces.Box(-1.0, 1.0, (1,))
        self.action_space = gym.spaces.Box(-1.0, 1.0, (1,))
        self.reward, self.info, self.state = reward, info or {}, 0

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple:
        super().reset(seed=seed)
        return np.zeros(1, dtype=np.float32), {}

    def step(self, action: np.ndarray) -> tuple:
        return np.zeros(1, dtype=np.float32), self.reward, False, False, dict(self.info)

    def get_state(self) -> int:
        return self.state

    def set_state(self, state: int) -> None:
        self.state = state


@pytest.mark.parametrize(
    ("reward", "info", "what"),
    [
        (None, {}, "reward must be a real number .*NoneType"),
        ("1.5", {}, "reward must be a real number .*str"),
        (True, {}, "reward must be a real number .*bool"),
        (0.5, {"bonus": "1"}, r"info\['bonus'\] must be a real number .*str"),
    ],
)
def test_a_gym_reward_that_is_not_a_number_is_refused_naming_the_step(
    reward: object, info: dict, what: str
) -> None:
    problem = GymProblem(_RewardEnv(reward, info), seed=0)
    with pytest.raises(ValueError, match=rf"env\.step\(action=\[0\.5\]\) returned {what}"):
        problem.step(np.array([0.5]))


def test_gym_rewards_of_numpy_types_still_count() -> None:
    for reward in (np.float32(0.25), np.int64(2), 3):
        assert GymProblem(_RewardEnv(reward), seed=0).step(np.array([0.5])).reward == float(reward)
