"""Tests of voot.record.config: validated recorder options."""

from __future__ import annotations

import pytest

from voot.record.config import RecorderConfig


def test_defaults_watch_the_root_and_the_first_place_node() -> None:
    cfg = RecorderConfig()
    assert cfg.watch == ("root", "place")
    assert cfg.operator_key == "next_operator"
    assert cfg.tree_every is None
    assert cfg.samples_every >= 1 and cfg.flush_every >= 1


def test_normalisation() -> None:
    assert RecorderConfig(watch="root").watch == ("root",)  # type: ignore[arg-type]
    assert RecorderConfig(watch=[0, "pick"]).watch == (0, "pick")  # type: ignore[arg-type]
    assert RecorderConfig(geom_groups=[0, 3]).geom_groups == (0, 3)  # type: ignore[arg-type]
    assert RecorderConfig(floor_height=0).floor_height == 0.0
    cfg = RecorderConfig().replace(samples_every=3)
    assert cfg.samples_every == 3


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"application_id": ""}, "application_id"),
        ({"watch": ("root", -1)}, "watch entries"),
        ({"watch": ("root", "")}, "watch entries"),
        ({"watch": ("root", 1.5)}, "watch entries"),
        ({"watch": ("root", "root")}, "duplicate"),
        ({"watch": 3.0}, "watch must be a tuple"),
        ({"operator_key": ""}, "operator_key"),
        ({"samples_every": 0}, "samples_every must be an integer >= 1"),
        ({"tree_every": 0}, "tree_every must be an integer >= 1 or None"),
        ({"tree_max_nodes": True}, "tree_max_nodes"),
        ({"flush_every": 2.0}, "flush_every"),
        ({"record_plan": 1}, "record_plan must be True or False"),
        ({"geom_groups": (0, 6)}, "geom_groups"),
        ({"geom_groups": 1}, "geom_groups"),
        ({"floor_height": -0.1}, "floor_height"),
        ({"arrow_length": 0}, "arrow_length must be a finite number > 0"),
        ({"point_radius": float("nan")}, "point_radius"),
        ({"infeasible_color": (0, 0)}, "infeasible_color"),
        ({"view_camera": ""}, "view_camera must be None, 'auto' or a camera name"),
        ({"view_camera": 3}, "view_camera must be None, 'auto' or a camera name"),
    ],
)
def test_bad_options_name_the_problem(options: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        RecorderConfig(**options)  # type: ignore[arg-type]


def test_replace_rejects_unknown_options() -> None:
    with pytest.raises(ValueError, match=r"unknown RecorderConfig option\(s\) \['every'\]"):
        RecorderConfig().replace(every=3)
