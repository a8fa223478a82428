"""Tests of voot.bench.leaderboard.table: the report of a store (coverage, aggregate,
per-cell tables, profiles figure), a partial store reported as partial, and the
committed leaderboard redrawing docs/leaderboard.md exactly."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from leaderboard_fixtures import tiny_store, tiny_suite_file

from voot.bench.leaderboard.suite import load_suite
from voot.bench.leaderboard.table import build_report, splice_page
from voot.bench.store.result_store import ResultStore

ROOT = Path(__file__).resolve().parents[3]
STORE = ROOT / "docs" / "data" / "leaderboard-v1"
PAGE = ROOT / "docs" / "leaderboard.md"


def intervals(text: str) -> list[tuple[float, float, float]]:
    found = re.findall(r"(-?\d+\.\d+) \[(-?\d+\.\d+), (-?\d+\.\d+)\]", text)
    return [(float(a), float(b), float(c)) for a, b, c in found]


def test_the_report_of_a_complete_store(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    suite = load_suite(str(tiny_suite_file()))
    store = tiny_store(tmp_path)
    rep = build_report(store, suite, figure=tmp_path / "profiles.png")
    assert rep.complete == (("voot/GeneratedKitchen-v0", "easy"),)
    for leaders in rep.leader.values():  # every entry at the highest IQM (ties all named)
        assert set(leaders.split(", ")) <= {"random_shooting", "doot[small]"}
    assert "complete: every cell" in rep.markdown and "**partial**" not in rep.markdown
    assert "P(ref > entry)" in rep.markdown and "#### GeneratedKitchen easy" in rep.markdown
    assert (tmp_path / "profiles.png").stat().st_size > 10_000
    # every interval holds its estimate; the handled fractions and P(X > Y) stay in [0, 1]
    aggregate = rep.markdown.split("### Aggregated")[1].split("### Per family")[0]
    for est, low, high in intervals(rep.markdown):
        assert low <= est <= high
    for _est, low, high in intervals(aggregate):
        assert 0.0 <= low <= high <= 1.0
    assert f"--suite {tiny_suite_file()}" in rep.markdown


def test_a_partial_store_is_reported_as_partial_without_a_leader(tmp_path: Path) -> None:
    suite = load_suite(str(tiny_suite_file()))
    store = tiny_store(tmp_path)
    s = ResultStore(store, create=False)
    victim = next(
        p
        for p in s.row_files()
        if '"layout_seed":1' in p.read_text()
        and '"doot"' in p.read_text()
        and '"easy"' in p.read_text()
    )
    victim.unlink()
    for p in store.glob(".index*"):
        p.unlink()
    rep = build_report(store, suite)
    assert rep.complete == () and rep.leader == {}
    assert "**partial**: 0 of 1 cells complete" in rep.markdown
    assert "No cell is complete yet" in rep.markdown and "1/2" in rep.markdown
    assert "Still to run: 1 runs" in rep.markdown


def test_splice_page_replaces_only_between_the_markers() -> None:
    page = "intro\n<!-- leaderboard:start -->\nold\n<!-- leaderboard:end -->\noutro\n"
    assert splice_page(page, "new\n") == (
        "intro\n<!-- leaderboard:start -->\nnew\n<!-- leaderboard:end -->\noutro\n"
    )
    with pytest.raises(ValueError, match="markers"):
        splice_page("no markers", "x")


def committed_body() -> str:
    text = PAGE.read_text()
    return text.split("<!-- leaderboard:start -->\n", 1)[1].split("<!-- leaderboard:end -->")[0]


@pytest.mark.skipif(not STORE.is_dir(), reason="no committed leaderboard store")
def test_the_committed_leaderboard_redraws_its_page(tmp_path: Path) -> None:
    """docs/leaderboard.md is what ``voot-bench leaderboard report`` draws from the
    committed store, to the character (on a copy of the store)."""
    pytest.importorskip("matplotlib")
    copy = tmp_path / STORE.name
    shutil.copytree(STORE, copy, ignore=shutil.ignore_patterns(".index*", ".*.lock"))
    rep = build_report(
        copy,
        load_suite("v1"),
        figure=tmp_path / "profiles.png",
        figure_link="figures/leaderboard-profiles.png",
        store_label="docs/data/leaderboard-v1",
    )
    assert rep.markdown == committed_body()
    if rep.complete:
        assert (tmp_path / "profiles.png").stat().st_size > 10_000


def test_tied_entries_are_all_named_not_one_by_its_order() -> None:
    from voot.bench.leaderboard.scores import Budget, RunScore
    from voot.bench.leaderboard.table import aggregate
    from voot.bench.report.stats import Bootstrap

    cell = ("voot/GeneratedKitchen-v0", "easy")
    values = {"a": [1.0, 1.0, 1.0], "b": [1.0, 1.0, 1.0], "c": [0.0, 1.0, 0.5]}
    scores = [
        RunScore(e, cell, layout, 0, dict.fromkeys(Budget, v), dict.fromkeys(Budget, v))
        for e, vs in values.items()
        for layout, v in enumerate(vs)
    ]
    text, leader, iqm = aggregate(scores, ["c", "a", "b"], [cell], Bootstrap(reps=200))
    assert leader[Budget.CALLS] == leader[Budget.CPU] == "a, b"
    assert "| a | 1.000 [1.000, 1.000] | ref |" in text
    assert iqm[Budget.CALLS]["c"].estimate == 0.5
