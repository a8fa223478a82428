"""Named env versions (voot.envs.core.presets): a preset's config and an env constructor's."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import pytest

from voot.envs.core.presets import env_config, preset_config


@dataclass(frozen=True)
class Settings:
    """A config class as the envs write them."""

    horizon: int = 10
    mode: str = "a"


PRESETS: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {"v0": MappingProxyType({}), "v1": MappingProxyType({"mode": "b"})}
)


def test_preset_config_applies_the_preset_then_the_overrides() -> None:
    assert preset_config(Settings, PRESETS, "v0") == Settings()
    assert preset_config(Settings, PRESETS, "v1") == Settings(mode="b")
    assert preset_config(Settings, PRESETS, "v1", mode="c", horizon=3) == Settings(3, "c")
    with pytest.raises(ValueError, match="unknown preset 'v2'; valid presets are: v0, v1"):
        preset_config(Settings, PRESETS, "v2")
    with pytest.raises(ValueError, match="valid options are"):
        preset_config(Settings, PRESETS, "v0", nope=1)


def test_env_config_takes_a_config_or_the_presets_then_the_options() -> None:
    assert env_config(Settings, PRESETS, None, "v1", {}) == Settings(mode="b")
    given = Settings(horizon=4)
    assert env_config(Settings, PRESETS, given, "v1", {}) is given  # the preset is not used
    assert env_config(Settings, PRESETS, given, "v0", {"mode": "z"}) == Settings(4, "z")
    with pytest.raises(ValueError, match="config must be a Settings, got dict"):
        env_config(Settings, PRESETS, {"horizon": 4}, "v0", {})
    with pytest.raises(ValueError, match="valid options are"):
        env_config(Settings, PRESETS, None, "v0", {"nope": 1})
    with pytest.raises(ValueError, match="valid presets are"):
        env_config(Settings, PRESETS, None, "v9", {})
