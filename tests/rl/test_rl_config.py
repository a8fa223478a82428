"""voot.rl.config: the algorithms' options at stable-baselines3's defaults."""

from __future__ import annotations

import inspect
from dataclasses import fields

import pytest

from voot.rl.config import (
    DDPGConfig,
    PPOConfig,
    available_algorithms,
    normalize_algorithm,
    rl_config,
)


def test_names_and_lookup() -> None:
    assert available_algorithms() == ["ddpg", "ppo"]
    assert normalize_algorithm(" PPO ") == "ppo"
    assert isinstance(rl_config("ddpg"), DDPGConfig)
    with pytest.raises(ValueError, match="valid algorithms are: ddpg, ppo"):
        normalize_algorithm("sac")


def test_unknown_option_names_the_valid_ones() -> None:
    with pytest.raises(ValueError, match=r"unknown option\(s\) \['n_step'\].*'n_steps'"):
        rl_config("ppo", n_step=10)


@pytest.mark.parametrize(
    ("cls", "name", "value"),
    [
        (PPOConfig, "gamma", 1.5),
        (PPOConfig, "n_steps", 1),
        (PPOConfig, "batch_size", 0),
        (PPOConfig, "clip_range", 0.0),
        (PPOConfig, "normalize_advantage", 1),
        (PPOConfig, "device", "tpu"),
        (DDPGConfig, "tau", 0.0),
        (DDPGConfig, "action_noise_sigma", -0.1),
        (DDPGConfig, "learning_starts", -1),
        (DDPGConfig, "max_episode_steps", 0),
    ],
)
def test_bad_values_are_refused_by_name(cls: type, name: str, value: object) -> None:
    with pytest.raises(ValueError, match=name):
        cls(**{name: value})


def test_the_chosen_values() -> None:
    ddpg = DDPGConfig()
    assert ddpg.action_noise_sigma == 0.1 and ddpg.device == "cpu"
    assert ddpg.max_episode_steps is None
    assert PPOConfig(gamma=0.9).gamma == 0.9
    assert "action_noise_sigma" not in ddpg.sb3_kwargs()
    assert "max_episode_steps" not in PPOConfig().sb3_kwargs()
    assert PPOConfig().to_dict()["name"] == "ppo"


@pytest.mark.rl
@pytest.mark.parametrize("cls", [PPOConfig, DDPGConfig])
def test_defaults_are_the_installed_sb3_defaults(cls: type) -> None:
    import stable_baselines3 as sb3

    algo = getattr(sb3, cls.name.upper())  # type: ignore[attr-defined]
    params = inspect.signature(algo.__init__).parameters
    config = cls()
    ours = {f.name for f in fields(cls)} - {"action_noise_sigma", "max_episode_steps"}
    for name in sorted(ours - {"device"}):
        assert params[name].default == getattr(config, name), name
    assert params["device"].default == "auto"  # ours is "cpu" on purpose
    if cls is DDPGConfig:
        assert params["action_noise"].default is None  # SB3 has no noise; ours is 0.1


def test_inverted_sizes_are_refused() -> None:
    """A PPO minibatch larger than its rollout, or a DDPG batch larger than its replay
    buffer: SB3 cuts or repeats without a word."""
    with pytest.raises(ValueError, match=r"batch_size must be <= n_steps \(32\)"):
        PPOConfig(n_steps=32)  # batch_size 64
    assert PPOConfig(n_steps=32, batch_size=32).batch_size == 32
    with pytest.raises(ValueError, match=r"batch_size must be <= buffer_size \(100\)"):
        rl_config("ddpg", buffer_size=100)  # batch_size 256
    assert DDPGConfig(buffer_size=256).buffer_size == 256
