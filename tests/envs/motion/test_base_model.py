"""voot.envs.motion.base_model: the domains' shared base-model rule."""

from __future__ import annotations

import pytest

from voot.envs.motion.base_model import BASE_MODELS, base_model_planner
from voot.envs.motion.footprint import FootprintConfig
from voot.envs.motion.planner import BasePlannerConfig


def test_the_footprint_model_sets_a_default_footprint_with_the_heuristic() -> None:
    plain = BasePlannerConfig()
    assert base_model_planner("Cfg", "disc", "euclidean", plain) is plain
    got = base_model_planner("Cfg", "footprint", "geodesic", plain)
    assert got.footprint == FootprintConfig(heuristic="geodesic")
    own = BasePlannerConfig(footprint=FootprintConfig(xy_step=0.05))
    assert base_model_planner("Cfg", "footprint", "euclidean", own) is own  # the caller's kept


def test_bad_choices_are_named() -> None:
    with pytest.raises(
        ValueError, match=r"Cfg\.base_model must be one of " + ", ".join(BASE_MODELS)
    ):
        base_model_planner("Cfg", "sphere", "euclidean", BasePlannerConfig())
    with pytest.raises(ValueError, match=r"Cfg\.footprint_heuristic must be one of euclidean"):
        base_model_planner("Cfg", "footprint", "manhattan", BasePlannerConfig())
    with pytest.raises(ValueError, match='needs base_model="footprint"'):
        base_model_planner("Cfg", "disc", "geodesic", BasePlannerConfig())
