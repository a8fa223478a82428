"""The configurations of the RL baselines: PPO and DDPG as stable-baselines3 runs them.

Every field is a named, validated option at stable-baselines3's default (SB3 2.x,
``stable_baselines3.PPO`` and ``stable_baselines3.DDPG``, checked against the installed
signatures by ``tests/rl/test_rl_config.py``), except:

* ``gamma``: the problem's discount (the tree's: kitchen 0.9, conveyor 0.99, chains
  0.9), set by the benchmark runner; 0.99, SB3's default, when used directly;
* DDPG's exploration noise, which SB3 leaves off by default (``action_noise=None``): a
  Gaussian of standard deviation ``action_noise_sigma = 0.1`` per action dimension, in
  the policy's scaled action units ``[-1, 1]``, the noise of SB3's own DDPG example
  (docs, "DDPG", ``NormalActionNoise(sigma=0.1 * np.ones(n_actions))``);
* ``device``: ``"cpu"`` instead of SB3's ``"auto"``, so that a machine with a GPU does
  not silently give other (non-reproducible) numbers;
* ``max_episode_steps``: None (an episode ends where the env ends it, as a tree
  rollout), an option of the task (:class:`voot.rl.task.PlanningTask`), not of SB3.

The networks are SB3's defaults (``policy_kwargs`` unset: PPO's ``MlpPolicy`` two
hidden layers of 64 with tanh; DDPG's two of 400 and 300 with ReLU). The paper gives no
RL hyperparameters beyond "PPO and DDPG", so these are the library defaults a user
gets.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass, fields
from functools import partial
from types import MappingProxyType
from typing import Any, ClassVar

from voot import validation as V

#: Devices a run may use (CPU: bit-reproducible; see docs/rl.md).
DEVICES = ("cpu", "cuda", "auto")


@dataclass(frozen=True)
class RLConfig:
    """What every RL algorithm shares (see the module docstring).

    Attributes:
        gamma: discount of the learned return and of the reported one.
        learning_rate: the optimiser's step size (Adam).
        batch_size: minibatch size of an update.
        device: torch device; ``"cpu"`` for reproducible runs.
        max_episode_steps: truncate episodes after this many steps (None: the env's end).
    """

    gamma: float = 0.99
    learning_rate: float = 3e-4
    batch_size: int = 64
    device: str = "cpu"
    max_episode_steps: int | None = None

    name: ClassVar[str] = ""
    #: Field -> check, run in this order by ``__post_init__`` (a subclass extends it).
    _checks: ClassVar[Mapping[str, V.Check]] = {
        "gamma": V.probability,
        "learning_rate": V.positive,
        "batch_size": partial(V.integer, low=1),
        "device": partial(V.one_of, valid=DEVICES),
        "max_episode_steps": partial(V.optional_integer, low=1),
    }

    def __post_init__(self) -> None:
        V.check_fields(self, self._checks)

    def to_dict(self) -> dict[str, Any]:
        """Every field by name, and the algorithm's ``name``."""
        return {"name": self.name, **asdict(self)}

    def sb3_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of the SB3 algorithm's constructor (noise excepted)."""
        skip = {"max_episode_steps", "action_noise_sigma"}
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name not in skip}


@dataclass(frozen=True)
class PPOConfig(RLConfig):
    """Proximal policy optimisation (Schulman et al., 2017), SB3's defaults.

    Attributes:
        learning_rate: 3e-4.
        n_steps: env steps per rollout before an update: 2048.
        batch_size: 64.
        n_epochs: passes over a rollout per update: 10.
        gae_lambda: GAE's :math:`\\lambda`: 0.95.
        clip_range: the policy ratio's clip: 0.2.
        normalize_advantage: True.
        ent_coef: entropy bonus weight: 0.0.
        vf_coef: value loss weight: 0.5.
        max_grad_norm: gradient clipping: 0.5.
    """

    learning_rate: float = 3e-4
    n_steps: int = 2048
    batch_size: int = 64
    n_epochs: int = 10
    gae_lambda: float = 0.95
    clip_range: float = 0.2
    normalize_advantage: bool = True
    ent_coef: float = 0.0
    vf_coef: float = 0.5
    max_grad_norm: float = 0.5

    name: ClassVar[str] = "ppo"
    _checks: ClassVar[Mapping[str, V.Check]] = {
        **RLConfig._checks,
        "n_steps": partial(V.integer, low=2),
        "n_epochs": partial(V.integer, low=1),
        "gae_lambda": V.probability,
        "clip_range": V.positive,
        "normalize_advantage": V.flag,
        "ent_coef": partial(V.positive, allow_zero=True),
        "vf_coef": V.positive,
        "max_grad_norm": V.positive,
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        # SB3 would cut every minibatch down to the one rollout without a word
        why = "a minibatch is drawn from one rollout of n_steps env steps"
        V.at_most(self.batch_size, "batch_size", self.n_steps, "n_steps", why)


@dataclass(frozen=True)
class DDPGConfig(RLConfig):
    """Deep deterministic policy gradient (Lillicrap et al., 2016), SB3's defaults.

    Attributes:
        learning_rate: 1e-3.
        buffer_size: replay buffer capacity: 1,000,000.
        learning_starts: env steps before the first update: 100.
        batch_size: 256.
        tau: target networks' soft update: 0.005.
        train_freq: env steps between updates: 1.
        gradient_steps: gradient steps per update: 1.
        action_noise_sigma: standard deviation of the Gaussian exploration noise, per
            action dimension in scaled units: 0.1 (SB3's DDPG example; SB3 itself
            defaults to no noise).
    """

    learning_rate: float = 1e-3
    buffer_size: int = 1_000_000
    learning_starts: int = 100
    batch_size: int = 256
    tau: float = 0.005
    train_freq: int = 1
    gradient_steps: int = 1
    action_noise_sigma: float = 0.1

    name: ClassVar[str] = "ddpg"
    _checks: ClassVar[Mapping[str, V.Check]] = {
        **RLConfig._checks,
        "buffer_size": partial(V.integer, low=1),
        "learning_starts": partial(V.integer, low=0),
        "tau": partial(V.number, low=0.0, high=1.0, open_low=True),
        "train_freq": partial(V.integer, low=1),
        "gradient_steps": partial(V.integer, low=1),
        "action_noise_sigma": partial(V.positive, allow_zero=True),
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        # SB3 would draw every batch with repeats from a buffer smaller than it
        why = "a batch is drawn from the replay buffer"
        V.at_most(self.batch_size, "batch_size", self.buffer_size, "buffer_size", why)


#: The RL algorithms by name.
RL_ALGORITHMS: Mapping[str, type[RLConfig]] = MappingProxyType(
    {c.name: c for c in (PPOConfig, DDPGConfig)}
)


def available_algorithms() -> list[str]:
    """Names accepted by :func:`rl_config`."""
    return sorted(RL_ALGORITHMS)


def normalize_algorithm(name: object) -> str:
    """The canonical algorithm name (``"PPO"`` -> ``"ppo"``), or a ValueError listing them."""
    return V.registered_name(name, RL_ALGORITHMS, "RL algorithm", "algorithms")


def rl_config(name: str, **overrides: Any) -> RLConfig:
    """The config of algorithm ``name`` with ``overrides`` (unknown ones name the valid)."""
    cls = RL_ALGORITHMS[normalize_algorithm(name)]
    V.config_options(cls, overrides)
    return cls(**overrides)
