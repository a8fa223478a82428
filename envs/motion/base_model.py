"""The base-motion model a domain plans with: the disc, or the exact footprint where it fails.

Both robot domains' configs (``ConveyorConfig``, ``KitchenConfig``) take ``base_model``
(``"disc"`` or ``"footprint"``) and ``footprint_heuristic``; :func:`base_model_planner`
turns them into the :class:`~voot.envs.motion.planner.BasePlannerConfig` the domain's
base planner uses, so the rule and its errors are one.
"""

from __future__ import annotations

from dataclasses import replace

from voot.envs.motion.footprint import HEURISTICS, FootprintConfig
from voot.envs.motion.planner import BasePlannerConfig

__all__ = ["BASE_MODELS", "base_model_planner"]

#: The choices of a domain's ``base_model``: the enclosing disc, or the exact footprint
#: where the disc finds no path (:func:`base_model_planner`).
BASE_MODELS = ("disc", "footprint")


def base_model_planner(
    owner: str, base_model: str, heuristic: str, planner: BasePlannerConfig
) -> BasePlannerConfig:
    """The planner settings a domain's ``base_model`` and ``footprint_heuristic`` give.

    ``"footprint"`` sets ``planner.footprint`` to a default :class:`FootprintConfig` with
    ``heuristic`` when the caller set none; ``"disc"`` leaves ``planner`` as it is. The
    domains' configs (``ConveyorConfig``, ``KitchenConfig``: ``owner``) share this rule.

    Raises:
        ValueError: an unknown base model or heuristic, or a heuristic other than
            ``"euclidean"`` that would not be used (no ``"footprint"``, or a
            ``planner.footprint`` of the caller's); the message names the valid choices.
    """
    if base_model not in BASE_MODELS:
        raise ValueError(
            f"{owner}.base_model must be one of {', '.join(BASE_MODELS)}, got {base_model!r}"
        )
    if heuristic not in HEURISTICS:
        raise ValueError(
            f"{owner}.footprint_heuristic must be one of {', '.join(HEURISTICS)}, got {heuristic!r}"
        )
    sets_footprint = (
        base_model == "footprint"
        and isinstance(planner, BasePlannerConfig)
        and planner.footprint is None
    )
    if heuristic != "euclidean" and not sets_footprint:
        raise ValueError(
            f"{owner}.footprint_heuristic sets the heuristic of the footprint"
            ' option that base_model="footprint" sets; it needs base_model="footprint"'
            " and no planner.footprint of the caller's (set FootprintConfig.heuristic"
            " there instead)"
        )
    if not sets_footprint:
        return planner
    return replace(planner, footprint=FootprintConfig(heuristic=heuristic))
