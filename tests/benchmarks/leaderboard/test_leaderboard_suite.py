"""Tests of voot.bench.leaderboard.suite: the shipped suite v1, its digest, and clear
errors for bad suite files."""

from __future__ import annotations

import dataclasses
import hashlib
import tomllib
from pathlib import Path
from typing import Any

import pytest

from voot.bench.leaderboard.suite import (
    SuiteError,
    load_suite,
    parse_suite,
    suite_path,
)


def v1_data() -> dict[str, Any]:
    return tomllib.loads(suite_path("v1").read_text())


def test_v1_loads_frozen_with_the_digest_of_its_file() -> None:
    suite = load_suite("v1")
    assert suite.name == "v1" and suite.ref == "v1"
    assert suite.digest == hashlib.sha256(suite_path("v1").read_bytes()).hexdigest()
    assert [f.problem for f in suite.families] == [
        "voot/GeneratedKitchen-v0",
        "voot/GeneratedStorage-v0",
    ]
    assert suite.levels == ("easy", "medium", "hard")
    assert suite.heldout_layouts == tuple(range(20))
    assert not set(suite.heldout_layouts) & set(suite.tuning_layouts)
    with pytest.raises(dataclasses.FrozenInstanceError):
        suite.version = 2  # type: ignore[misc]


def test_v1_lists_every_built_in_planner() -> None:
    from voot.bench.sweep.planners import REGISTRY

    builtin = [n for n in REGISTRY.names() if REGISTRY.get(n).builtin]
    planners = {e.planner for e in load_suite("v1").entries}
    assert set(builtin) <= planners
    assert "pw_uct[pw_authors]" in [e.name for e in load_suite("v1").entries]


def test_a_changed_file_has_another_digest(tmp_path: Path) -> None:
    text = suite_path("v1").read_text()
    path = tmp_path / "mine.toml"
    path.write_text(text + "\n# a comment\n")
    mine = load_suite(str(path))
    assert mine == load_suite("v1")  # same definition ...
    assert mine.digest != load_suite("v1").digest  # ... but not the same file
    assert mine.ref == str(path)


def test_entry_by_name_or_any_planner() -> None:
    suite = load_suite("v1")
    assert suite.entry("pw_uct[pw_authors]").set == (("widening", "authors"),)
    assert suite.entry("mypkg.mod:plan").planner == "mypkg.mod:plan"


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"levels": ["easy", "nightmare"]}, "valid levels are: easy, medium, hard"),
        ({"heldout_layouts": "1000:1005"}, "both training"),
        ({"heldout_layouts": "5:2"}, "heldout_layouts"),
        ({"colour": "red"}, "unknown key"),
        ({"families": []}, "at least one"),
        ({"entries": [{"planner": "pw_uct", "set": {"widening": "authors"}}]}, "variant"),
        ({"entries": [{"planner": "voot"}, {"planner": "voot"}]}, "repeat"),
        ({"version": 0}, "version"),
    ],
)
def test_bad_suites_say_what_is_wrong(change: dict[str, Any], message: str) -> None:
    with pytest.raises(SuiteError, match=message):
        parse_suite({**v1_data(), **change}, "bad.toml")


def test_unknown_suite_names_the_valid_ones(tmp_path: Path) -> None:
    with pytest.raises(SuiteError, match="valid suites are: v1"):
        load_suite("v9")
    bad = tmp_path / "bad.toml"
    bad.write_text("version = [")
    with pytest.raises(SuiteError, match="not a TOML file"):
        load_suite(str(bad))
