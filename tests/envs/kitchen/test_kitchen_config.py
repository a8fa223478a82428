"""The kitchen's task rules and versions (voot.envs.kitchen.config)."""

from __future__ import annotations

import math

import pytest

from voot.envs.core.presets import PRECHECKS
from voot.envs.kitchen.config import KITCHEN_PRESETS, KitchenConfig, kitchen_config


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"horizon": 0}, "horizon"),
        ({"robot_radius": -1.0}, "robot_radius"),
        ({"grasp_angle": (2.0, 1.0)}, "grasp_angle"),
        ({"house": (0, 1, 2)}, "house"),
        ({"infeasible_reward": 1.0}, "infeasible_reward"),
        ({"pick_requires_free_carry": "yes"}, "pick_requires_free_carry"),
        ({"pick_reward": True}, "pick_reward must be a number, got True"),
        ({"infeasible_reward": True}, "infeasible_reward must be a finite number < 0, got True"),
        ({"infeasible_reward": "x"}, "infeasible_reward must be a finite number < 0"),
        ({"house": (0, 1, True, 2)}, "house"),
    ],
)
def test_config_validation(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        KitchenConfig(**kwargs)  # type: ignore[arg-type]


def test_presets_are_the_documented_versions() -> None:
    assert list(KITCHEN_PRESETS) == ["v0", "v1"]
    assert kitchen_config() == kitchen_config("v0") == KitchenConfig()
    v1 = kitchen_config("v1")
    assert v1.precheck == "kinematic" and v1.precheck in PRECHECKS
    assert v1.nonclearing_penalty_infeasible and v1.pick_base_path
    assert not v1.pick_requires_free_carry
    assert kitchen_config("v1", horizon=7).horizon == 7
    with pytest.raises(TypeError):
        KITCHEN_PRESETS["v1"]["precheck"] = "full_step"  # type: ignore[index]
    with pytest.raises(ValueError, match="valid presets are: v0, v1"):
        kitchen_config("v2")


def test_parameter_ranges_are_in_action_order() -> None:
    cfg = KitchenConfig()
    assert cfg.pick_ranges == (
        cfg.grasp_angle,
        cfg.height_fraction,
        cfg.depth_fraction,
        cfg.base_distance,
        cfg.base_angle,
        cfg.facing_offset,
    )
    assert cfg.pick_ranges[0] == pytest.approx((math.radians(45.0), math.pi))
    assert cfg.place_ranges == ((-2.0, 6.0), (-4.0, 4.0), (0.0, 2.0 * math.pi))


def test_the_base_model_option() -> None:
    """``base_model="footprint"`` sets the planner's footprint option (with the chosen
    heuristic); bad names and the disc's carry rule are refused by name."""
    from voot.envs.motion.base_model import BASE_MODELS

    cfg = kitchen_config("v1", base_model="footprint", footprint_heuristic="geodesic")
    assert cfg.planner.footprint is not None and cfg.planner.footprint.heuristic == "geodesic"
    assert kitchen_config("v1").planner.footprint is None
    with pytest.raises(ValueError, match=", ".join(BASE_MODELS)):
        kitchen_config("v1", base_model="sphere")
    with pytest.raises(ValueError, match="footprint_heuristic must be one of euclidean"):
        kitchen_config("v1", base_model="footprint", footprint_heuristic="manhattan")
    with pytest.raises(ValueError, match='needs base_model="footprint"'):
        kitchen_config("v1", footprint_heuristic="geodesic")
    with pytest.raises(ValueError, match="needs pick_requires_free_carry=False"):
        kitchen_config("v0", base_model="footprint")
