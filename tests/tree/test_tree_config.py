"""Tests of voot.tree.config: validated options, paper defaults and named planners."""

from __future__ import annotations

import pickle

import pytest

from voot.tree import (
    PLANNERS,
    MCTSConfig,
    available_planners,
    available_samplers,
    planner_config,
)
from voot.tree.config import Backup, FinalAction, Selection, normalize_planner


def test_defaults_are_the_papers() -> None:
    cfg = MCTSConfig()
    assert cfg.sampler == "voo" and cfg.selection is Selection.REEVALUATE
    assert cfg.reevaluations == 5  # the authors' w on the robot domains
    assert cfg.feasibility_retries == 50
    assert cfg.root_commitment == 10
    assert cfg.backup is Backup.MAX
    assert cfg.final_action is FinalAction.MAX_Q
    assert cfg.depth_limit is None and cfg.gamma == 0.9


def test_unknown_sampler_lists_the_valid_ones() -> None:
    with pytest.raises(ValueError, match="unknown sampler 'voronoi'") as err:
        MCTSConfig(sampler="voronoi")
    for name in ("voo", "doo", "rand_doo", "uniform", "hoo"):
        assert name in str(err.value)
    assert set(available_samplers()) >= {"voo", "doo", "rand_doo", "uniform", "hoo"}


def test_unknown_planner_lists_the_valid_ones() -> None:
    with pytest.raises(ValueError, match="unknown planner 'mcts'") as err:
        planner_config("mcts")
    for name in ("voot", "doot", "rand_doot", "pw_uct", "voronoi_pw", "hoot"):
        assert name in str(err.value)


def test_planner_names_are_normalised() -> None:
    assert normalize_planner("RAND-DOOT") == "rand_doot"
    assert planner_config("PW-UCT").selection is Selection.PROGRESSIVE_WIDENING


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_every_planner_builds(name: str) -> None:
    cfg = planner_config(name)
    assert cfg.sampler == PLANNERS[name]["sampler"]
    assert name in available_planners()


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("selection", "ucb", "unknown selection"),
        ("backup", "min", "unknown backup"),
        ("final_action", "random", "unknown final_action"),
        ("best_return_over", "roots", "unknown best_return_over"),
        ("reevaluations", -1, "reevaluations"),
        ("kappa_r", 1.5, "kappa_r"),
        ("depth_limit", 0, "depth_limit must be an integer >= 1 or None"),
        ("gamma", 1.1, "gamma"),
        ("feasibility_retries", 0, "feasibility_retries"),
        ("root_commitment", 0, "root_commitment"),
        ("pw_k", 0.0, "pw_k must be > 0"),
        ("pw_alpha", 2.0, "pw_alpha"),
        ("ucb_c", -1.0, "ucb_c"),
        ("terminal_child_forces_new", "yes", "True or False"),
        ("sampler_options", [1, 2], "sampler_options must be a mapping"),
    ],
)
def test_bad_fields_are_value_errors(field: str, value: object, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        MCTSConfig(**{field: value})  # type: ignore[arg-type]


def test_sampler_options_are_validated_up_front() -> None:
    with pytest.raises(ValueError, match="omegaa"):
        MCTSConfig(sampler="voo", sampler_options={"omegaa": 0.3})
    with pytest.raises(ValueError, match="omega"):
        MCTSConfig(sampler="voo", sampler_options={"omega": 3.0})
    with pytest.raises(ValueError, match="takes no options"):
        MCTSConfig(sampler="uniform", selection="progressive_widening", sampler_options={"a": 1})
    with pytest.raises(ValueError, match="valid options are"):
        planner_config("hoot", sampler_options={"nu": 1.0})
    cfg = planner_config("voot", sampler_options={"omega": 0.3, "sampler": "uniform"})
    assert cfg.sampler_config().omega == 0.3


def test_hoo_goes_with_hoo_selection() -> None:
    with pytest.raises(ValueError, match="go together"):
        MCTSConfig(sampler="hoo", selection="reevaluate")
    with pytest.raises(ValueError, match="go together"):
        MCTSConfig(sampler="voo", selection="hoo")


def test_unknown_override_lists_the_fields() -> None:
    with pytest.raises(ValueError, match="valid options are"):
        planner_config("voot", n_r=3)


def test_config_is_frozen_picklable_and_flattens() -> None:
    cfg = planner_config("voronoi_pw", sampler_options={"omega": 0.1})
    with pytest.raises(AttributeError):
        cfg.gamma = 0.5  # type: ignore[misc]
    assert pickle.loads(pickle.dumps(cfg)) == cfg
    d = cfg.to_dict()
    assert d["selection"] == "progressive_widening" and d["sampler_options"] == {"omega": 0.1}
    assert cfg.replace(gamma=0.5).gamma == 0.5
    with pytest.raises(ValueError):
        cfg.replace(gamma=5.0)
