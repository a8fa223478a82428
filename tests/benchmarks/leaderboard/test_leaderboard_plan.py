"""Tests of voot.bench.leaderboard.plan: where each entry's setting comes from (training
layouts only), the runs listed, the cost estimate, and a resumable run of a tiny suite."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from leaderboard_fixtures import tiny_store, tiny_suite_file

from voot.bench.leaderboard import plan as L
from voot.bench.leaderboard.suite import Entry, load_suite
from voot.bench.store.result_store import ResultStore

ROOT = Path(__file__).resolve().parents[3]


def test_v1_reuses_the_protocol_where_it_selected_on_training_layouts() -> None:
    suite = load_suite("v1")
    choices = L.choose_settings(suite, suite.entries, [])
    voot = choices[("voot/GeneratedKitchen-v0", "voot")]
    assert voot.source == "protocol" and "training layouts 1000-1019" in voot.note
    from voot.bench.protocol.settings import protocol_selection

    assert voot.params == protocol_selection("generated_kitchen", "voot", "medium").params
    # no committed selection (or a variant): tuned here, unknown until its runs finish
    for name in ("hoot", "cem", "pw_uct[pw_authors]"):
        assert choices[("voot/GeneratedStorage-v0", name)].source == "tuned"
        assert choices[("voot/GeneratedStorage-v0", name)].params is None
    assert choices[("voot/GeneratedKitchen-v0", "random_shooting")].source == "single"


def test_tuning_runs_only_on_training_layouts_and_evaluation_on_held_out_ones() -> None:
    suite = load_suite("v1")
    tuning, evaluation, _ = L.all_specs(suite, suite.entries, [])
    assert {s.layout for s in tuning} == set(suite.tuning_layouts)
    assert {s.layout for s in evaluation} == set(suite.heldout_layouts)
    assert {s.env_kwargs_dict["difficulty"] for s in tuning} == {"medium"}
    assert {s.env_kwargs_dict["difficulty"] for s in evaluation} == set(suite.levels)
    per_entry = len(suite.families) * len(suite.levels) * len(suite.heldout_layouts)
    assert len(evaluation) == per_entry * len(suite.entries)
    authors = [s for s in tuning if s.variant == "pw_authors"]
    assert authors and all(s.params_dict["widening"] == "authors" for s in authors)
    assert {s.params_dict["pw_k"] for s in authors} == {0.8, 1.0}


def test_the_estimate_uses_the_store_then_the_committed_stores_then_a_probe() -> None:
    suite = load_suite("v1")
    entries = [suite.entry("voot"), suite.entry("cem")]
    tuning, evaluation, _ = L.all_specs(suite, entries, [])
    specs = [*tuning, *evaluation]
    probed: list[Any] = []

    def fake_probe(spec: Any) -> dict[str, Any]:
        probed.append(spec)
        return {"status": "ok", "search_time": 0.5 * spec.simulations}

    costs = L.estimate_suite(
        specs, [], {s.run_id for s in specs}, reference=L.reference_rows(), run=fake_probe
    )
    by = {(c.problem, c.planner): c for c in costs}
    assert by[("voot/GeneratedKitchen-v0", "voot")].source.startswith("committed stores")
    cem = by[("voot/GeneratedKitchen-v0", "cem")]
    assert cem.source == "probe: 20 simulations" and cem.seconds_per_simulation == 0.5
    assert cem.pending == cem.runs == len([s for s in specs if s.planner == "cem"]) // 2
    assert len(probed) == 2  # one per family
    text = L.format_costs(costs, 1)
    assert "CPU-hours" in text and "GeneratedStorage" in text


def test_a_plugin_planner_is_an_entry_like_any_other() -> None:
    suite = load_suite("v1")
    entry = Entry("voot.planners:builtin_planner")
    assert L.protocol_params(suite, suite.families[0], entry) is None


def test_a_tiny_suite_runs_resumes_and_redoes_nothing(tmp_path: Path) -> None:
    suite = load_suite(str(tiny_suite_file()))
    path = tiny_store(tmp_path)
    store = ResultStore(path, create=False)
    rows = store.load(kind="plan")
    tuning, evaluation, choices = L.all_specs(suite, suite.entries, rows)
    assert len(tuning) == 2 and len(evaluation) == 4
    assert {r["run_id"] for r in rows} == {s.run_id for s in [*tuning, *evaluation]}
    chosen = choices[("voot/GeneratedKitchen-v0", "doot[small]")]
    assert chosen.source == "tuned" and chosen.params is not None
    assert chosen.params["reevaluations"] == 2
    ran: list[int] = []

    def run_specs(specs: Any) -> int:
        from voot.bench.sweep.engine import run_sweep

        summary = run_sweep(specs, store, progress=False)
        ran.append(summary.ran)
        return summary.failed

    assert L.run_suite(suite, suite.entries, store, run_specs) == 0
    assert sum(ran) == 0  # everything finished: nothing redone
    assert L.pending_of([*tuning, *evaluation], store) == []


def test_an_outside_planner_enters_by_module_attr(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The example package's planner, as ``module:attr``: tuned on the training layout
    (its own grid), evaluated on the held-out ones, scored and carded like voot's own."""
    from voot.bench.leaderboard.card import write_cards
    from voot.bench.leaderboard.scores import coverage, run_scores
    from voot.bench.store.compact import CompactConfig
    from voot.bench.sweep.engine import run_sweep

    monkeypatch.syspath_prepend(str(ROOT / "examples" / "greedy_planner"))
    suite = load_suite(str(tiny_suite_file()))
    entry = suite.entry("greedy_planner:greedy")
    store = ResultStore(tmp_path / "s", compact=CompactConfig(points=3))
    failed = L.run_suite(
        suite, [entry], store, lambda specs: run_sweep(specs, store, progress=False).failed
    )
    assert failed == 0
    rows = store.load(kind="plan")
    assert len(rows) == 3 + 2  # width 2, 4, 8 on the training layout; 2 held-out layouts
    choice = L.choose_settings(suite, [entry], rows)[("voot/GeneratedKitchen-v0", entry.name)]
    assert choice.source == "tuned" and choice.params is not None
    assert coverage(suite, [entry], rows).complete == (("voot/GeneratedKitchen-v0", "easy"),)
    scores, _ = run_scores(suite, [entry], rows, [("voot/GeneratedKitchen-v0", "easy")])
    assert len(scores) == 2
    (card,) = write_cards(store.path, suite)
    assert card.name == "greedy_planner_greedy.json"
