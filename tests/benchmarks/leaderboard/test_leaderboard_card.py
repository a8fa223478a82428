"""Tests of voot.bench.leaderboard.card: result cards (content, own checksum, store
checksum) and verify (re-runs match a genuine store bit for bit; a tampered or
corrupted store fails, naming the run and field or the file)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from leaderboard_fixtures import tiny_store, tiny_suite_file

from voot.bench.leaderboard import card as K
from voot.bench.leaderboard.suite import load_suite
from voot.bench.store.format import StoreError, row_bytes
from voot.bench.store.result_store import ResultStore
from voot.bench.store.shipped import store_digest


def tamper(store: Path, key: str = "best_return") -> str:
    """Change ``key`` of one finished row, rewritten with a valid row checksum (what a
    submitter who edited results would ship); the run id changed."""
    path = sorted(ResultStore(store, create=False).row_files())[0]
    row = json.loads(path.read_bytes())
    row.pop("checksum", None)
    row[key] = row[key] + 1.0
    path.write_bytes(row_bytes(row))
    return str(row["run_id"])


def test_a_card_per_entry_says_what_a_submission_needs(tmp_path: Path) -> None:
    store = tiny_store(tmp_path)
    suite = load_suite(str(tiny_suite_file()))
    cards = K.check_cards(store, suite)
    assert sorted(c["entry"] for c in cards) == ["doot[small]", "random_shooting"]
    doot = next(c for c in cards if c["entry"] == "doot[small]")
    assert doot["suite"] == "v1" and doot["suite_digest"] == suite.digest
    assert doot["store_checksum"] == store_digest(store)["sha256"]
    assert doot["fixed_options"] == {"reevaluations": 2}
    (fam,) = doot["families"]
    assert fam["settings_source"] == "tuned" and fam["settings"]["epsilon"] in (0.1, 1.0)
    assert fam["evaluation_runs_finished"] == {"easy": 2} and fam["evaluation_runs_listed"] == 2
    assert fam["simulator_calls"] > 0 and fam["cpu_seconds_search"] > 0
    assert doot["planner_version"]


def test_an_edited_card_or_a_changed_store_is_an_error(tmp_path: Path) -> None:
    store = tiny_store(tmp_path)
    path = store / K.CARDS_DIR / "random_shooting.json"
    card = json.loads(path.read_text())
    card["families"][0]["settings"] = {"cheat": 1}
    path.write_text(json.dumps(card))
    with pytest.raises(StoreError, match="changed after it was written"):
        K.check_cards(store)
    K.write_cards(store, load_suite(str(tiny_suite_file())))
    K.check_cards(store)
    tamper(store)
    with pytest.raises(StoreError, match="store checksum"):
        K.check_cards(store)
    other = load_suite("v1")
    K.write_cards(store, load_suite(str(tiny_suite_file())))
    with pytest.raises(StoreError, match="suite digest"):
        K.check_cards(store, other)


def test_verify_passes_on_a_genuine_store(tmp_path: Path) -> None:
    store = tiny_store(tmp_path)
    n, mismatches = K.verify_store(store, 3)
    assert n == 3 and mismatches == []


def test_verify_fails_on_a_tampered_store_naming_the_run_and_field(tmp_path: Path) -> None:
    store = tiny_store(tmp_path)
    run_id = tamper(store)
    n, mismatches = K.verify_store(store, 10)
    assert n == 6
    assert [(m.run_id, m.fields) for m in mismatches] == [(run_id, ("best_return",))]


def test_a_corrupted_row_is_a_clear_error(tmp_path: Path) -> None:
    store = tiny_store(tmp_path)
    path = sorted(ResultStore(store, create=False).row_files())[0]
    data = path.read_bytes()
    path.write_bytes(data.replace(b'"seed":0', b'"seed":1', 1))
    with pytest.raises(StoreError, match=path.name):
        K.verify_store(store, 2)


def test_differing_fields_ignore_timings_only() -> None:
    a = {"best_so_far": [0.0, 1.0], "elapsed": [1.0], "versions": {"voot": "1"}, "x": float("nan")}
    b = {"best_so_far": [0.0, 1.0], "elapsed": [2.0], "versions": {"voot": "2"}, "x": float("nan")}
    assert K.differing_fields(a, b) == []
    b["best_so_far"] = [0.0, 1.0000000000000002]
    assert K.differing_fields(a, b) == ["best_so_far"]
    assert K.differing_fields({"n": 1}, {"n": 1.0}) == ["n"]


def test_the_sample_is_deterministic_and_without_repeats() -> None:
    rows = [{"run_id": f"{i:04d}"} for i in range(50)]
    first = K.sample_rows(rows, 7, seed=3)
    assert first == K.sample_rows(list(reversed(rows)), 7, seed=3)
    assert len({r["run_id"] for r in first}) == 7
    assert K.sample_rows(rows, 99) == rows
