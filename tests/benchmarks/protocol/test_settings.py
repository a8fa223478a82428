"""Tests of voot.bench.protocol.settings: the committed protocol's selections in the API."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from voot.bench.protocol.settings import (
    PROTOCOL_STORES,
    TABLE_PATH,
    protocol_selection,
    protocol_selections,
    protocol_settings,
    table_from_stores,
)
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.engine import jsonable, params_key
from voot.bench.sweep.planners import run_config
from voot.tree.config import planner_config
from voot.tree.shooting import is_shooting_planner, shooting_config

DATA = Path(__file__).resolve().parents[3] / "docs" / "data"


def test_the_table_is_what_the_stores_select() -> None:
    """The committed table is derived from the committed stores (regenerate it with
    ``python -m voot.bench.protocol.settings --write`` when a store changes)."""
    derived = json.loads(json.dumps(table_from_stores(DATA)))
    assert json.loads(TABLE_PATH.read_text(encoding="utf-8")) == derived
    assert {s["store"] for s in derived["selections"]} == {s.name for s in PROTOCOL_STORES}


def test_options_give_the_config_the_store_ran() -> None:
    """plan(..., planner, **options) runs the config of the protocol's runs, as recorded
    in the store's rows of the selected setting."""
    ran: dict[tuple[str, str, str, str], dict] = {}
    for store in PROTOCOL_STORES:
        for r in ResultStore(DATA / store.name, create=False).load():
            cfg = r["config"]
            level = (cfg.get("env_kwargs") or {}).get("difficulty")
            key = (cfg["problem"], str(level), cfg["planner"], params_key(cfg.get("params") or {}))
            ran.setdefault(key, r["planner_config"])
    for s in protocol_selections():
        options = protocol_settings(s.problem, s.planner, s.difficulty)
        make = shooting_config if is_shooting_planner(s.planner) else planner_config
        config = make(s.planner, **options)
        assert config == run_config(s.problem, None, s.planner, s.params, s.env_kwargs())
        recorded = ran[(s.problem, str(s.difficulty), s.planner, params_key(s.params))]
        mine = jsonable(config.to_dict())  # (fields added since the runs: their defaults)
        assert {k: mine[k] for k in recorded} == recorded


def test_the_selected_setting_is_on_top_of_the_papers_constants() -> None:
    options = protocol_settings("kitchen_v1", "voot")
    assert options["sampler_options"] == {"sampler": "uniform", "omega": 0.3}
    assert options["gamma"] == 0.9 and options["root_commitment"] == 10
    assert options["reevaluations"] == 5  # a selected value is named even if a default
    assert protocol_settings("voot/KitchenClearing-v2", "PW-UCT", "medium")["ucb_c"] == 0.1
    # a sampling-based planner gets the discount and its own setting, no tree option
    assert protocol_settings("kitchen_v1", "cem") == {"gamma": 0.9, "init_std": 0.5}


def test_levels_without_a_selection_get_the_level_selected_on() -> None:
    medium = protocol_selection("kitchen_v2", "voot", "medium")
    assert medium.difficulty == "medium" and medium.store == "heldout-kitchen-v2"
    assert "training layouts 1000-1019" in medium.tuned_on
    for level in ("easy", "hard", None):
        assert protocol_selection("kitchen_v2", "voot", level) == medium
    v1 = protocol_selection("conveyor_v1", "voot")
    assert v1.difficulty is None and v1.runs == 5 and "tuning seeds 1000-1004" in v1.tuned_on


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("kitchen", "voot"), "selected no settings on 'kitchen'; it did on conveyor_v1"),
        (("kitchen_v1", "uniform_t"), "no setting of 'uniform_t' on kitchen_v1; it selected: voot"),
        (("kitchen_v1", "voot", "easy"), "has no difficulty levels"),
        (("kitchen_v1", "ppo"), "no setting of 'ppo'"),
        (("kitchen_v1", "nope"), "unknown planner 'nope'"),
    ],
)
def test_errors_say_what_was_selected(args: tuple[str, ...], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        protocol_settings(*args)
