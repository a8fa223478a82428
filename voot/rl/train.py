"""Train an RL baseline for an exact budget of env steps and report the best trajectory.

:func:`train` builds the stable-baselines3 algorithm of a config (:mod:`voot.rl.config`)
on a :class:`~voot.rl.task.PlanningTask`, trains it and stops after *exactly* ``budget``
env steps (SB3's ``learn`` would finish its rollout: PPO collects ``n_steps`` at a time,
so a callback stops it at the budget's step). What it returns is the paper's measure of
an RL run: the best trajectory found *during training* (the task's best finished
episode), as the compact curve of its improvements, plus the clock at chosen step
counts (``checkpoints``).

Reproducibility on CPU: torch is set to one thread (``torch.set_num_threads(1)``: its
parallel reductions may sum in another order with more), the algorithm gets
``seed`` (SB3 seeds Python's ``random``, numpy's global generator, torch and the action
space with it), and the device is the config's (``"cpu"`` by default). The same config,
env and seed then give bit-identical curves in any process (``tests/rl/test_rl_train.py``
checks it across two processes); the timings differ.

stable-baselines3 and torch are imported when :func:`train` runs, not with this module:
they are the ``rl`` extra (``pip install -e ".[rl]"``); without them :func:`require_sb3`
raises an ImportError that names the extra.
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass, field
from typing import Any

from voot import validation as V
from voot.rl.config import DDPGConfig, PPOConfig, RLConfig
from voot.rl.task import PlanningTask

#: How to install what :func:`train` needs.
INSTALL_HINT = 'pip install -e ".[rl]"  (or: pip install "voot[rl]")'
#: Threads torch may use in a run (more may change the last bits of the results).
TORCH_THREADS = 1


class MissingExtraError(ImportError):
    """stable-baselines3 or torch is not installed (the message names the ``rl`` extra)."""


def require_sb3() -> Any:
    """The ``stable_baselines3`` module, or a :class:`MissingExtraError` naming the extra."""
    try:
        import stable_baselines3
        import torch  # noqa: F401
    except ImportError as exc:
        raise MissingExtraError(
            f"the RL baselines (ppo, ddpg) need stable-baselines3 and torch, which are not"
            f" installed ({exc}); install the rl extra: {INSTALL_HINT}"
        ) from None
    return stable_baselines3


@dataclass(frozen=True)
class TrainResult:
    """The outcome of one training run.

    Attributes:
        algorithm: ``"ppo"`` or ``"ddpg"``.
        n_steps: env steps taken (the budget).
        n_episodes: episodes finished.
        best_return: best discounted return (goal bonus excluded) of a finished episode.
        best_objects_left: ``objects_left`` at the end of that episode (None if unknown).
        best_by_step: ``(step, best)`` at every improvement (the compact curve).
        objects_by_step: the ``objects_left`` of each improvement.
        checkpoints: the step counts asked for.
        elapsed: wall seconds since training started, at each checkpoint.
        cpu_elapsed: this process's CPU seconds since training started, at each one.
        wall_time: wall seconds of the whole training (model set-up included).
    """

    algorithm: str
    n_steps: int
    n_episodes: int
    best_return: float
    best_objects_left: float | None
    best_by_step: tuple[tuple[int, float], ...]
    objects_by_step: tuple[float | None, ...]
    checkpoints: tuple[int, ...] = ()
    elapsed: tuple[float, ...] = ()
    cpu_elapsed: tuple[float, ...] = ()
    wall_time: float = 0.0
    task: PlanningTask | None = field(default=None, compare=False, repr=False)

    def best_at(self, step: int) -> tuple[float, float | None]:
        """``(best, objects_left)`` within the first ``step`` env steps."""
        if self.task is None:
            raise ValueError("this result has no task to read the curve from")
        return self.task.best_at(step)


def _algorithm(sb3: Any, config: RLConfig, env: PlanningTask, seed: int) -> Any:
    kwargs = config.sb3_kwargs()
    if isinstance(config, PPOConfig):
        return sb3.PPO("MlpPolicy", env, seed=seed, verbose=0, **kwargs)
    if isinstance(config, DDPGConfig):
        import numpy as np
        from stable_baselines3.common.noise import NormalActionNoise

        shape = env.action_space.shape
        assert shape is not None
        n = int(shape[-1])
        noise = (
            NormalActionNoise(np.zeros(n), config.action_noise_sigma * np.ones(n))
            if config.action_noise_sigma > 0
            else None
        )
        return sb3.DDPG("MlpPolicy", env, seed=seed, verbose=0, action_noise=noise, **kwargs)
    raise ValueError(f"no SB3 algorithm for {type(config).__name__}; valid: PPOConfig, DDPGConfig")


def train(
    config: RLConfig,
    env: PlanningTask,
    budget: int,
    seed: int,
    checkpoints: list[int] | tuple[int, ...] = (),
) -> TrainResult:
    """Train ``config``'s algorithm on ``env`` for exactly ``budget`` env steps.

    Args:
        config: a :class:`~voot.rl.config.PPOConfig` or :class:`~voot.rl.config.DDPGConfig`.
        env: the task (a fresh one: its step count must be 0).
        budget: env steps to train for (>= 1).
        seed: the algorithm's seed (>= 0).
        checkpoints: non-decreasing step counts in ``0 .. budget`` at which to read the
            clocks (0 reads 0.0).

    Raises:
        MissingExtraError: stable-baselines3 or torch is missing (names the extra).
        ValueError: bad budget, seed or checkpoints, or a used task.
    """
    n = V.integer(budget, "budget", 1)
    s = V.integer(seed, "seed", 0)
    marks = [V.integer(c, "checkpoint", 0, n) for c in checkpoints]
    if any(b < a for a, b in itertools.pairwise(marks)):
        raise ValueError("checkpoints must be non-decreasing step counts")
    if not isinstance(env, PlanningTask):
        raise ValueError(f"env must be a voot.rl.PlanningTask, got {type(env).__name__}")
    if env.n_steps:
        raise ValueError(f"the task has already taken {env.n_steps} steps; train a fresh one")
    sb3 = require_sb3()
    import torch
    from stable_baselines3.common.callbacks import BaseCallback

    torch.set_num_threads(TORCH_THREADS)
    clock, cpu = time.perf_counter, time.process_time
    start = clock()
    model = _algorithm(sb3, config, env, s)
    elapsed: list[float] = []
    cpu_elapsed: list[float] = []
    k = 0
    while k < len(marks) and marks[k] == 0:
        elapsed.append(0.0)
        cpu_elapsed.append(0.0)
        k += 1
    t0, c0 = clock(), cpu()

    class _Budget(BaseCallback):  # type: ignore[misc]
        """Reads the clocks at the checkpoints; stops training at the budget."""

        def _on_step(self) -> bool:
            nonlocal k
            now = env.n_steps
            if k < len(marks) and marks[k] <= now:
                t, c = clock() - t0, cpu() - c0
                while k < len(marks) and marks[k] <= now:
                    elapsed.append(t)
                    cpu_elapsed.append(c)
                    k += 1
            return now < n

    model.learn(total_timesteps=n, callback=_Budget(), progress_bar=False)
    if env.n_steps != n:
        raise RuntimeError(f"training took {env.n_steps} env steps, expected {n}")
    return TrainResult(
        algorithm=config.name,
        n_steps=env.n_steps,
        n_episodes=env.n_episodes,
        best_return=env.best_return,
        best_objects_left=env.best_objects_left,
        best_by_step=tuple((i.step, i.best) for i in env.improvements),
        objects_by_step=tuple(i.objects_left for i in env.improvements),
        checkpoints=tuple(marks),
        elapsed=tuple(elapsed),
        cpu_elapsed=tuple(cpu_elapsed),
        wall_time=clock() - start,
        task=env,
    )
