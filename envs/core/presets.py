"""Named env versions: a config class's presets and the env constructors' config.

An env's config is a frozen dataclass; its named versions (``"v0"``, ``"v1"``) are
mappings of field overrides (:data:`voot.envs.kitchen.config.KITCHEN_PRESETS`,
:data:`voot.envs.conveyor.config.CONVEYOR_PRESETS`). :func:`preset_config` builds one version
with further overrides, :func:`env_config` the config an env constructor ends up with
(an explicit config or the preset's, then the constructor's options); both check the
field names, so a typo is an error naming the valid fields, not a silent default.
:func:`check_step_rules` checks the fields every robot env's config has (the reward of
an infeasible action, the horizon, the pre-check, the IK and planner settings).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from voot import validation as V
from voot.envs.core.names import Precheck, choices
from voot.envs.core.state import replace
from voot.envs.motion.planner import BasePlannerConfig
from voot.envs.robot.arm_ik import IKConfig

#: What a planner's pre-check of an action covers (a config's ``precheck``).
PRECHECKS: tuple[Precheck, ...] = tuple(Precheck)


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


def check_step_rules(config: Any) -> None:
    """Check and normalise the fields every robot env's frozen config has, in place.

    ``infeasible_reward`` (a float below 0), ``horizon`` (an integer >= 1), ``precheck``
    (made a :class:`Precheck`), ``ik`` (an :class:`IKConfig`) and ``planner`` (a
    :class:`BasePlannerConfig`); a config's ``__post_init__`` calls it, and errors name
    the field as ``ConfigClass.field``.

    Raises:
        ValueError: A field out of its range or of the wrong type.
    """
    cls = type(config).__name__
    r = V.number(config.infeasible_reward, f"{cls}.infeasible_reward", high=0.0, open_high=True)
    object.__setattr__(config, "infeasible_reward", r)
    V.integer(config.horizon, f"{cls}.horizon", 1)
    if config.precheck not in PRECHECKS:
        raise ValueError(
            f"{cls}.precheck must be one of {choices(Precheck)}, got {config.precheck!r}"
        )
    object.__setattr__(config, "precheck", Precheck(config.precheck))
    if not isinstance(config.ik, IKConfig):
        raise ValueError(f"{cls}.ik must be an IKConfig, got {type(config.ik).__name__}")
    if not isinstance(config.planner, BasePlannerConfig):
        raise ValueError(
            f"{cls}.planner must be a BasePlannerConfig, got {type(config.planner).__name__}"
        )
