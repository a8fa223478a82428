"""Learning across layouts: SB3 PPO trained on a family's training layouts, tested on held-out ones.

A generated family (``voot/GeneratedKitchen-v0`` by default, at ``easy``) has one
observation space for every layout, so one ``MlpPolicy`` spans it. This script:

1. trains SB3's PPO on ``gym.make_vec(id, n_envs, vectorization_mode="sync",
   split="training")``: each reset draws one of the protocol's 20 training layouts
   (1000-1019) from the reset's seed stream;
2. evaluates on the 20 held-out layouts (0-19, ``split="heldout"``, episode ``i`` on
   held-out layout ``i mod 20``, reset seed ``i``) the trained policy, with its mean
   actions (``ppo``) and with actions sampled from it (``ppo (sampled)``, what it does
   in training), and a random policy (the action space sampled); then the trained
   policy's mean actions on the training layouts the same way, for the gap between
   them. Episode ``i`` seeds torch and the action space with ``i``;
3. writes the result (per-episode and mean return, objects left, success) as JSON.

Returns are undiscounted sums of the env's rewards (the goal bonus included); success is
an episode that ends with no object left. The layouts each phase saw are in the JSON
(``training_layouts_seen``, ``layouts`` of each evaluation), so the split is checkable.

Deterministic for a seed on CPU: torch on one thread, PPO seeded, the vector env reset
with the seed once (its autoresets continue that stream), the evaluations seeded per
episode. Run from the repository root::

    python docs/scripts/ppo_across_layouts.py --steps 200000 --n-envs 4 \\
        --eval-episodes 40 --out docs/data/ppo-across-layouts.json
"""

from __future__ import annotations

import argparse
import json
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AsyncVectorEnv, AutoresetMode, SyncVectorEnv

import voot  # noqa: F401  (registers the ids)
from voot.envs.core.generation import HELDOUT_LAYOUTS, TRAINING_LAYOUTS
from voot.rl.train import TORCH_THREADS, require_sb3

#: PPO's settings here: SB3's defaults but a shorter rollout (many updates on a small budget).
PPO_KWARGS: dict[str, Any] = {"n_steps": 256, "batch_size": 64, "ent_coef": 0.01}


@dataclass(frozen=True)
class Evaluation:
    """Episodes of one policy on one split: what happened in each, and the means."""

    policy: str
    split: str
    layouts: list[int]
    returns: list[float]
    objects_left: list[int]
    mean_return: float
    mean_objects_left: float
    success_rate: float


def _sb3_vec_env(env: SyncVectorEnv | AsyncVectorEnv, seed: int) -> Any:
    """A gymnasium vector env (same-step autoreset) seen as an SB3 ``VecEnv``.

    SB3 takes its own vector envs only; this adapter keeps gymnasium's ``make_vec`` (the
    documented way to vectorize a family) and hands SB3 what it expects: a per-env info
    list, ``terminal_observation`` and ``TimeLimit.truncated`` at an episode's end. It
    records every layout a step's info names (``layouts_seen``).
    """
    from stable_baselines3.common.vec_env import VecEnv

    class GymVecEnv(VecEnv):  # type: ignore[misc]
        def __init__(self) -> None:
            super().__init__(env.num_envs, env.single_observation_space, env.single_action_space)
            self.layouts_seen: set[int] = set()
            self._actions: np.ndarray | None = None

        def _infos(self, info: dict[str, Any], done: np.ndarray) -> list[dict[str, Any]]:
            out: list[dict[str, Any]] = [{} for _ in range(self.num_envs)]
            final = info.get("final_info", {})
            for i in range(self.num_envs):
                if done[i]:
                    out[i]["terminal_observation"] = info["final_obs"][i]
                    out[i]["TimeLimit.truncated"] = bool(self._truncated[i] and not self._term[i])
                    self.layouts_seen.add(int(final["layout_seed"][i]))
                self.layouts_seen.add(int(info["layout_seed"][i]))
            return out

        def reset(self) -> np.ndarray:
            obs, info = env.reset(seed=seed)
            self.layouts_seen.update(int(k) for k in info["layout_seed"])
            return obs

        def step_async(self, actions: np.ndarray) -> None:
            self._actions = actions

        def step_wait(self) -> Any:
            obs, reward, self._term, self._truncated, info = env.step(self._actions)
            done = self._term | self._truncated
            return obs, reward.astype(np.float32), done, self._infos(info, done)

        def close(self) -> None:
            env.close()

        def get_attr(self, name: str, indices: Any = None) -> list[Any]:
            return list(env.get_attr(name))

        def set_attr(self, name: str, value: Any, indices: Any = None) -> None:
            env.set_attr(name, value)

        def env_method(
            self, method_name: str, *method_args: Any, indices: Any = None, **method_kwargs: Any
        ) -> list[Any]:
            return list(env.call(method_name, *method_args, **method_kwargs))

        def env_is_wrapped(self, wrapper_class: Any, indices: Any = None) -> list[bool]:
            return [False] * self.num_envs

    return GymVecEnv()


def evaluate(
    env_id: str,
    difficulty: str,
    split: str,
    episodes: int,
    policy: str,
    act: Callable[[np.ndarray, gym.Env[Any, Any]], np.ndarray],
) -> Evaluation:
    """``episodes`` episodes on ``split``'s layouts in turn (episode ``i``: layout ``i`` mod
    20, reset seed ``i``), acting with ``act(obs, env)``."""
    import torch

    layouts: Sequence[int] = TRAINING_LAYOUTS if split == "training" else HELDOUT_LAYOUTS
    env = gym.make(env_id, split=split, difficulty=difficulty)
    seen, returns, left = [], [], []
    for i in range(episodes):
        obs, info = env.reset(seed=i, options={"layout_seed": layouts[i % len(layouts)]})
        env.action_space.seed(i)  # one stream per episode, as the committed result was drawn
        torch.manual_seed(i)  # a sampling policy's draws
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, info = env.step(act(obs, env))
            total += float(reward)
            done = terminated or truncated
        seen.append(int(info["layout_seed"]))
        returns.append(total)
        left.append(int(info["objects_left"]))
    env.close()
    return Evaluation(
        policy=policy,
        split=split,
        layouts=seen,
        returns=returns,
        objects_left=left,
        mean_return=float(np.mean(returns)),
        mean_objects_left=float(np.mean(left)),
        success_rate=float(np.mean([n == 0 for n in left])),
    )


def run(
    steps: int,
    n_envs: int = 4,
    eval_episodes: int = 20,
    seed: int = 0,
    env_id: str = "voot/GeneratedKitchen-v0",
    difficulty: str = "easy",
    ppo_kwargs: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Train PPO for ``steps`` env steps on the training layouts, then evaluate (module docstring)."""
    sb3 = require_sb3()
    import torch

    torch.set_num_threads(TORCH_THREADS)
    kwargs = {**PPO_KWARGS, **(ppo_kwargs or {})}
    t0, c0 = time.perf_counter(), time.process_time()
    vec = gym.make_vec(
        env_id,
        num_envs=n_envs,
        vectorization_mode="sync",
        vector_kwargs={"autoreset_mode": AutoresetMode.SAME_STEP},
        split="training",
        difficulty=difficulty,
    )
    assert isinstance(vec, SyncVectorEnv)
    venv = _sb3_vec_env(vec, seed)
    model = sb3.PPO("MlpPolicy", venv, seed=seed, verbose=0, device="cpu", **kwargs)
    model.learn(total_timesteps=steps)
    train_cpu = time.process_time() - c0
    venv.close()

    def trained(obs: np.ndarray, env: gym.Env[Any, Any]) -> np.ndarray:
        return model.predict(obs, deterministic=True)[0]

    def sampled(obs: np.ndarray, env: gym.Env[Any, Any]) -> np.ndarray:
        return model.predict(obs, deterministic=False)[0]

    def random(obs: np.ndarray, env: gym.Env[Any, Any]) -> np.ndarray:
        return env.action_space.sample()

    evals = [
        evaluate(env_id, difficulty, "heldout", eval_episodes, "ppo", trained),
        evaluate(env_id, difficulty, "heldout", eval_episodes, "ppo (sampled)", sampled),
        evaluate(env_id, difficulty, "heldout", eval_episodes, "random", random),
        evaluate(env_id, difficulty, "training", eval_episodes, "ppo", trained),
    ]
    return {
        "env_id": env_id,
        "difficulty": difficulty,
        "seed": seed,
        "steps": int(model.num_timesteps),
        "n_envs": n_envs,
        "ppo_kwargs": kwargs,
        "training_layouts_seen": sorted(venv.layouts_seen),
        "evaluations": [asdict(e) for e in evals],
        "train_cpu_seconds": round(train_cpu, 1),
        "cpu_seconds": round(time.process_time() - c0, 1),
        "wall_seconds": round(time.perf_counter() - t0, 1),
    }


def table(result: dict[str, Any]) -> str:
    """The Markdown table of a result's evaluations."""
    rows = ["| policy | layouts | mean return | objects left | success |", "|---|---|---|---|---|"]
    for e in result["evaluations"]:
        rows.append(
            f"| {e['policy']} | {e['split']} ({len(e['returns'])} episodes)"
            f" | {e['mean_return']:.1f} | {e['mean_objects_left']:.2f}"
            f" | {100 * e['success_rate']:.0f}% |"
        )
    return "\n".join(rows)


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100_000, help="PPO's env steps (all envs)")
    parser.add_argument("--n-envs", type=int, default=4, help="envs in the training vector env")
    parser.add_argument("--eval-episodes", type=int, default=40, help="episodes per evaluation")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--env-id", default="voot/GeneratedKitchen-v0")
    parser.add_argument("--difficulty", default="easy")
    parser.add_argument("--out", type=Path, help="write the result JSON here")
    args = parser.parse_args(argv)
    result = run(
        args.steps, args.n_envs, args.eval_episodes, args.seed, args.env_id, args.difficulty
    )
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(result, indent=1) + "\n")
    print(table(result))
    print(
        f"{result['steps']} steps, CPU {result['cpu_seconds']} s (training {result['train_cpu_seconds']} s)"
    )


if __name__ == "__main__":
    main()
