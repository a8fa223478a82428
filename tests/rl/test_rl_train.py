"""voot.rl.train: an exact budget of env steps and the best-trajectory curve.

Every test here trains (torch and stable-baselines3: the rl extra), so all are marked
``rl``; the missing-extra error is tested without torch in tests/benchmarks/sweep/test_rl_runs.py.
"""

from __future__ import annotations

import json
import subprocess
import sys
from typing import Any

import gymnasium as gym
import pytest

import voot  # noqa: F401 - registers the ids
from voot.rl import PlanningTask, rl_config, train

pytestmark = pytest.mark.rl


def chain_task(gamma: float = 0.9) -> PlanningTask:
    env = gym.make("voot/ShekelChain-v0", dim=3, disable_env_checker=True)
    return PlanningTask(env, seed=0, gamma=gamma)


SCRIPT = """
import json, sys
import gymnasium as gym
import voot
from voot.rl import PlanningTask, rl_config, train
algorithm, options = sys.argv[1], json.loads(sys.argv[2])
env = gym.make("voot/ShekelChain-v0", dim=3, disable_env_checker=True)
task = PlanningTask(env, seed=0, gamma=0.9)
res = train(rl_config(algorithm, **options), task, 75, seed=0, checkpoints=[0, 1, 40, 75])
print(json.dumps({
    "n_steps": res.n_steps, "task_steps": task.n_steps, "algorithm": res.algorithm,
    "n_episodes": res.n_episodes, "task_episodes": task.n_episodes,
    "checkpoints": res.checkpoints, "elapsed": res.elapsed, "cpu_elapsed": res.cpu_elapsed,
    "best_by_step": res.best_by_step, "best_return": res.best_return,
    "task_best": task.best_return, "best_at_75": res.best_at(75),
}))
"""


def train_in_subprocess(algorithm: str, options: dict[str, Any]) -> dict[str, Any]:
    """Train in a fresh process: one where no test has created a GL context (MuJoCo's EGL
    and triton's LLVM, which torch loads with its first optimiser, may clash; docs/rl.md)."""
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT, algorithm, json.dumps(options)],
        check=True,
        capture_output=True,
        text=True,
        timeout=300,
    ).stdout
    result: dict[str, Any] = json.loads(out.strip().splitlines()[-1])
    return result


@pytest.mark.parametrize(
    ("algorithm", "options"),
    [("ppo", {"n_steps": 32, "batch_size": 16}), ("ddpg", {"learning_starts": 10})],
)
def test_trains_for_exactly_the_budget(algorithm: str, options: dict[str, Any]) -> None:
    res = train_in_subprocess(algorithm, options)
    assert res["n_steps"] == res["task_steps"] == 75  # PPO would finish its rollout (96)
    assert res["algorithm"] == algorithm and res["n_episodes"] == res["task_episodes"] >= 1
    assert res["checkpoints"] == [0, 1, 40, 75]
    assert len(res["elapsed"]) == len(res["cpu_elapsed"]) == 4
    assert res["elapsed"][0] == 0.0 and res["elapsed"] == sorted(res["elapsed"])
    steps = [s for s, _ in res["best_by_step"]]
    assert steps == sorted(steps) and steps[-1] <= 75
    bests = [b for _, b in res["best_by_step"]]
    assert bests == sorted(bests) and bests[-1] == res["best_return"] == res["task_best"]
    assert res["best_at_75"] == [res["best_return"], None]


def test_bad_arguments() -> None:
    task = chain_task()
    config = rl_config("ppo")
    with pytest.raises(ValueError, match="budget"):
        train(config, task, 0, seed=0)
    with pytest.raises(ValueError, match="checkpoint"):
        train(config, task, 10, seed=0, checkpoints=[11])
    with pytest.raises(ValueError, match="non-decreasing"):
        train(config, task, 10, seed=0, checkpoints=[5, 3])
    with pytest.raises(ValueError, match="PlanningTask"):
        train(config, task.env, 10, seed=0)  # type: ignore[arg-type]
    task.reset()
    task.step(task.action_space.low.copy())
    with pytest.raises(ValueError, match="fresh"):
        train(config, task, 10, seed=0)


# Bit-identical results in two processes: tests/benchmarks/sweep/test_rl_runs.py compares whole rows of
# PPO and DDPG (chain and kitchen) from two separate sweeps.


RENDER_THEN_TRAIN = """
import mujoco, torch
from voot.envs.core.rendering import new_renderer
try:
    new_renderer(mujoco.MjModel.from_xml_string("<mujoco/>"), 8, 8).close()
except Exception:
    pass
torch.optim.Adam([torch.zeros(2, requires_grad=True)])  # imports torch._dynamo, triton
print("trained after rendering")
"""


def test_a_process_that_renders_then_trains_does_not_crash() -> None:
    # With PyPI's CUDA torch, triton loaded after Mesa's EGL driver segfaults (exit -11).
    env = {**__import__("os").environ, "MUJOCO_GL": "egl"}
    out = subprocess.run(
        [sys.executable, "-c", RENDER_THEN_TRAIN], env=env, capture_output=True, text=True
    )
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    assert "trained after rendering" in out.stdout
