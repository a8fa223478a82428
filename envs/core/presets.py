"""Named env versions: a config class's presets and the env constructors' config.

An env's config is a frozen dataclass; its named versions (``"v0"``, ``"v1"``) are
mappings of field overrides (:data:`voot.envs.kitchen.config.KITCHEN_PRESETS`,
:data:`voot.envs.conveyor.env.CONVEYOR_PRESETS`). :func:`preset_config` builds one version
with further overrides, :func:`env_config` the config an env constructor ends up with
(an explicit config or the preset's, then the constructor's options); both check the
field names, so a typo is an error naming the valid fields, not a silent default.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from voot import validation as V
from voot.envs.core.state import replace


def preset_config(
    config_class: Any, presets: Mapping[str, Mapping[str, Any]], preset: str, **overrides: Any
) -> Any:
    """``config_class`` at a named preset (a domain version), some fields overridden."""
    if preset not in presets:
        raise ValueError(f"unknown preset {preset!r}; valid presets are: {', '.join(presets)}")
    V.config_options(config_class, overrides)
    return config_class(**{**presets[preset], **overrides})


def env_config(
    config_class: Any,
    presets: Mapping[str, Mapping[str, Any]],
    config: Any,
    preset: str,
    options: Mapping[str, Any],
) -> Any:
    """An env constructor's config: ``config`` (default: the ``preset``'s), ``options`` applied.

    Raises ValueError for a config of the wrong class, an unknown preset or option.
    """
    if config is None:
        config = preset_config(config_class, presets, preset)
    if not isinstance(config, config_class):
        raise ValueError(f"config must be a {config_class.__name__}, got {type(config).__name__}")
    if options:
        V.config_options(config_class, options)
        config = replace(config, **options)
    return config
