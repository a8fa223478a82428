"""The paper's reinforcement-learning baselines: PPO and DDPG (stable-baselines3).

The paper trains PPO and DDPG with the same amount of simulated experience the tree
search used and reports the best trajectory found during training. This package gives
the three pieces, over any voot gymnasium env that can be snapshotted:

* :class:`~voot.rl.task.PlanningTask`: one problem instance as an RL task (one initial
  state, an infeasible step ends the episode, steps counted, the best trajectory kept
  by the tree's definition);
* :class:`~voot.rl.config.PPOConfig`, :class:`~voot.rl.config.DDPGConfig`: the
  algorithms' options at stable-baselines3's defaults;
* :func:`~voot.rl.train.train`: an exact budget of env steps, reproducible on CPU.

Importing this package loads neither torch nor stable-baselines3 (they are the ``rl``
extra, loaded when :func:`train` runs). The benchmark runs with a budget matched to a
tree search are in :mod:`voot.bench.sweep.rl`.
"""

from voot.rl.config import (
    RL_ALGORITHMS,
    DDPGConfig,
    PPOConfig,
    RLConfig,
    available_algorithms,
    normalize_algorithm,
    rl_config,
)
from voot.rl.task import EMPTY_PLAN_RETURN, Improvement, PlanningTask, reward_parts
from voot.rl.train import INSTALL_HINT, MissingExtraError, TrainResult, require_sb3, train

__all__ = [
    "EMPTY_PLAN_RETURN",
    "INSTALL_HINT",
    "RL_ALGORITHMS",
    "DDPGConfig",
    "Improvement",
    "MissingExtraError",
    "PPOConfig",
    "PlanningTask",
    "RLConfig",
    "TrainResult",
    "available_algorithms",
    "normalize_algorithm",
    "require_sb3",
    "reward_parts",
    "rl_config",
    "train",
]
