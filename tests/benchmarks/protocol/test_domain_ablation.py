"""Tests of voot.bench.protocol.domain_ablation: the statistics, the table, the shipped store."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from voot.bench.protocol import domain_ablation as D

ROOT = Path(__file__).resolve().parents[3]
STORE = ROOT / "docs" / "data" / "domain-ablation-v1.json"


def test_switches_and_unknown_switch() -> None:
    assert list(D.SWITCHES) == ["v1", "footprint", "big_box_ban", "authors_rooms", "authors_domain"]
    with pytest.raises(ValueError, match="choose from v1, footprint"):
        D.make_env("nope")
    authors = D.make_env("authors_domain").config
    assert authors.big_box_ban is True and authors.rooms == "authors"
    assert D.make_env("footprint").config.planner.footprint is not None
    assert D.make_env("v1").config.planner.footprint is None


def test_measure_counts_and_the_common_draws() -> None:
    a = D.measure("v1", draws=60, executions=3, rollouts=1)
    b = D.measure("big_box_ban", draws=60, executions=3, rollouts=1)
    assert [n["depth"] for n in a["nodes"]] == list(D.NODES)
    # the pre-check does not depend on the switch: the same passes
    assert [n["passed"] for n in a["nodes"]] == [n["passed"] for n in b["nodes"]]
    for n in a["nodes"]:
        assert n["reached"]
        assert 0 <= n["feasible"] <= n["executed"] <= min(3, n["passed"]) <= 60
    assert a["scripted_solves"] and b["scripted_solves"]
    assert a["scripted_return"] == pytest.approx(b["scripted_return"])
    text = D.table({"rows": [a, b]})
    assert text.count("\n") == 3 and "`big_box_ban`" in text


def test_a_switch_can_have_its_own_execution_bound() -> None:
    store = D.run(("v1", "big_box_ban"), 40, 3, 1, 0, executions_for={"big_box_ban": 1})
    assert store["settings"]["executions_for"] == {"big_box_ban": 1}
    v1, ban = store["rows"]
    assert (v1["executions"], ban["executions"]) == (3, 1)
    assert all(n["executed"] <= 1 for n in ban["nodes"])
    assert any(n["executed"] > 1 for n in v1["nodes"])
    with pytest.raises(ValueError, match="unknown switch 'walls'; choose from v1"):
        D.run(("v1",), 10, 1, 1, 0, executions_for={"walls": 1})
    with pytest.raises(ValueError, match="must be an int >= 1, got 0"):
        D.run(("v1",), 10, 1, 1, 0, executions_for={"v1": 0})


def test_the_authors_rooms_use_their_own_scripted_solution() -> None:
    from voot.envs.conveyor.scripted import AUTHORS_SOLUTION, solution_poses

    assert solution_poses(D.make_env("authors_domain")) is AUTHORS_SOLUTION
    assert solution_poses(D.make_env("authors_rooms")) is AUTHORS_SOLUTION
    assert solution_poses(D.make_env("footprint")) is not AUTHORS_SOLUTION


def test_shipped_store_redraws_the_docs_table() -> None:
    store = json.loads(STORE.read_text())
    assert [r["switch"] for r in store["rows"]] == list(D.SWITCHES)
    assert D.table(store) in (ROOT / "docs" / "results-planning.md").read_text()


def test_the_kitchen_switch() -> None:
    """The kitchen's footprint switch: same pre-check passes (the pre-check tests no base
    path), every rate within its counts, the scripted solution still solving."""
    assert list(D.KITCHEN_SWITCHES) == ["v1", "footprint"]
    assert D.make_env("footprint", "kitchen").config.planner.footprint is not None
    with pytest.raises(ValueError, match="unknown domain 'garage'; choose from conveyor, kitchen"):
        D.make_env("v1", "garage")
    with pytest.raises(ValueError, match="unknown switch 'big_box_ban'; choose from v1, footprint"):
        D.make_env("big_box_ban", "kitchen")
    store = D.run(("v1", "footprint"), 60, 3, 1, 0, domain="kitchen")
    assert store["problem"] == "voot/KitchenClearing-v1"
    v1, fp = store["rows"]
    assert [n["passed"] for n in v1["nodes"]] == [n["passed"] for n in fp["nodes"]]
    for row in (v1, fp):
        assert row["scripted_solves"]
        for n in row["nodes"]:
            assert n["reached"] and 0 <= n["feasible"] <= n["executed"] <= 3
    assert "obstacles cleared" in D.table(store)


def test_shipped_kitchen_store_redraws_the_docs_table() -> None:
    store = json.loads((ROOT / "docs" / "data" / "domain-ablation-kitchen-v1.json").read_text())
    assert [r["switch"] for r in store["rows"]] == list(D.KITCHEN_SWITCHES)
    assert D.table(store) in (ROOT / "docs" / "results-planning.md").read_text()
