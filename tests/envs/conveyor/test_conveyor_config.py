"""voot.envs.conveyor.config: the storage rooms' settings, validated, and their versions."""

from __future__ import annotations

import pytest

from voot.envs.conveyor.config import (
    CONVEYOR_PRESETS,
    ROOMS,
    ConveyorConfig,
    conveyor_config,
)
from voot.envs.core.names import Precheck
from voot.envs.motion.base_model import BASE_MODELS
from voot.envs.motion.footprint import FootprintConfig
from voot.envs.motion.planner import BasePlannerConfig


def test_the_versions_differ_only_in_the_precheck() -> None:
    assert set(CONVEYOR_PRESETS) == {"v0", "v1", "v3"}
    v0, v1 = conveyor_config("v0"), conveyor_config("v1")
    assert v1.precheck == Precheck.KINEMATIC
    assert conveyor_config("v1", precheck=v0.precheck) == v0


def test_v3_is_v1_on_the_authors_domain() -> None:
    v3 = conveyor_config("v3")
    assert (v3.rooms, v3.base_model, v3.big_box_ban) == ("authors", "footprint", True)
    assert v3.planner.footprint is not None and v3.planner.footprint.heuristic == "geodesic"
    same = conveyor_config(
        "v1", rooms="authors", base_model="footprint", footprint_heuristic="geodesic",
        big_box_ban=True,
    )  # fmt: skip
    assert v3 == same


def test_the_authors_options_are_off_by_default_and_named() -> None:
    config = ConveyorConfig()
    assert (config.rooms, config.base_model, config.big_box_ban) == ("voot", "disc", False)
    assert config.planner.footprint is None
    assert ConveyorConfig(base_model="footprint").planner.footprint is not None
    with pytest.raises(ValueError, match=", ".join(ROOMS)):
        ConveyorConfig(rooms="paper")
    with pytest.raises(ValueError, match=", ".join(BASE_MODELS)):
        ConveyorConfig(base_model="square")
    with pytest.raises(ValueError, match="unknown"):
        conveyor_config("v9")


def test_footprint_heuristic_sets_the_footprint_options_heuristic() -> None:
    assert ConveyorConfig(base_model="footprint").planner.footprint == FootprintConfig()
    geodesic = ConveyorConfig(base_model="footprint", footprint_heuristic="geodesic")
    assert geodesic.planner.footprint == FootprintConfig(heuristic="geodesic")
    with pytest.raises(ValueError, match="footprint_heuristic must be one of euclidean, geodesic"):
        ConveyorConfig(base_model="footprint", footprint_heuristic="straight")
    with pytest.raises(ValueError, match='needs base_model="footprint"'):
        ConveyorConfig(footprint_heuristic="geodesic")  # the disc: nothing to set
    own = BasePlannerConfig(footprint=FootprintConfig(xy_step=0.05))
    with pytest.raises(ValueError, match=r"FootprintConfig\.heuristic there"):
        ConveyorConfig(base_model="footprint", footprint_heuristic="geodesic", planner=own)
