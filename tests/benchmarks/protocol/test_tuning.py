"""Tests of voot.bench.protocol.tuning: selection on tuning seeds, evaluation on the others."""

from __future__ import annotations

import pytest

from voot.bench.protocol.layouts import check_disjoint
from voot.bench.protocol.tuning import (
    check_tuning_split,
    seeds_text,
    select_on_tuning,
    selected_specs,
    split_rows,
    tuning_note,
    tuning_selections,
    tuning_sentence,
)
from voot.bench.store.format import Row, make_row
from voot.bench.sweep.plan import build_plan_specs


def row(final: float, *, seed: int, omega: float, planner: str = "voot") -> Row:
    config = {
        "problem": "shekel_chain",
        "dim": 3,
        "env_kwargs": {},
        "planner": planner,
        "params": {"omega": omega},
        "simulations": 2,
        "seed": seed,
        "protocol": 1,
    }
    return make_row("plan", config, status="ok", wall_time=1.0, best_so_far=[0.0, final])


def rows() -> list[Row]:
    """omega=0.1 wins on the tuning seeds 1000-1001, omega=0.3 on the evaluation seeds."""
    out = []
    for seed in (1000, 1001):
        out += [row(2.0, seed=seed, omega=0.1), row(1.0, seed=seed, omega=0.3)]
    for seed in (0, 1, 2):
        out += [row(0.0, seed=seed, omega=0.1), row(5.0, seed=seed, omega=0.3)]
    return out


def test_seeds_text_and_notes() -> None:
    assert seeds_text([1002, 1000, 1001, 7]) == "7, 1000-1002"
    assert seeds_text([]) == ""
    note = tuning_note(range(1000, 1005))
    assert note == "settings selected on tuning seeds 1000-1004, disjoint from the evaluation seeds"
    assert tuning_sentence([3]).startswith("Settings selected on tuning seeds 3,")


def test_check_disjoint() -> None:
    check_disjoint([1000], [0, 1])
    with pytest.raises(ValueError, match="seeds 1-2 are both tuning and evaluation seeds"):
        check_disjoint([1, 2, 1000], [0, 1, 2])
    with pytest.raises(ValueError, match="that would be tuning on the test set"):
        check_disjoint([0], [0])
    with pytest.raises(ValueError, match="no tuning seeds"):
        check_disjoint([], [0])


def test_selection_on_tuning_seeds_differs_from_the_same_seed_rule() -> None:
    tuning, evaluation = split_rows(rows(), {1000, 1001})
    assert {r["config"]["seed"] for r in tuning} == {1000, 1001}
    assert {r["config"]["seed"] for r in evaluation} == {0, 1, 2}
    outcome = select_on_tuning(rows(), [1000, 1001])
    (sel,) = outcome.selections
    assert sel.params == {"omega": 0.1} and sel.best.n == 2  # chosen on the tuning seeds
    assert {r["config"]["seed"] for r in outcome.rows} == {0, 1, 2}
    assert all(r["config"]["params"] == {"omega": 0.1} for r in outcome.rows)
    assert outcome.untuned == ()
    # a planner with evaluation rows but no tuning rows is reported, not silently tuned
    extra = [*rows(), row(1.0, seed=0, omega=0.1, planner="voronoi_pw")]
    assert select_on_tuning(extra, [1000, 1001]).untuned == (("shekel_chain", 3, 2, "voronoi_pw"),)


def test_selected_specs_are_the_specs_one_would_run_by_hand() -> None:
    tuning = build_plan_specs(["shekel_chain"], [3], ["voot"], [1000, 1001], simulations=2)
    finals = {0.001: 1.0, 0.1: 3.0, 0.3: 2.0}
    fake = [
        make_row(
            "plan",
            s.config(),
            status="ok",
            wall_time=0.1,
            best_so_far=[0.0, finals[s.params_dict["omega"]] + s.params_dict["reevaluations"]],
        )
        for s in tuning
    ]
    (sel,) = tuning_selections(tuning, fake)
    assert sel.params == {"omega": 0.1, "reevaluations": 100}
    candidates = build_plan_specs(["shekel_chain"], [3], ["voot"], [0, 1], simulations=2)
    chosen = selected_specs(candidates, [sel])
    by_hand = build_plan_specs(
        ["shekel_chain"],
        [3],
        ["voot"],
        [0, 1],
        simulations=2,
        grid="default",
        fixed={"omega": 0.1, "reevaluations": 100},
    )
    assert [s.run_id for s in chosen] == [s.run_id for s in by_hand]
    assert selected_specs(candidates, []) == []
    # rows of other run ids (e.g. evaluation seeds) take no part in the selection
    assert tuning_selections(tuning[:1], fake[1:]) == []


def test_a_planner_without_a_grid_needs_no_tuning_rows() -> None:
    """RL baselines and uniform random shooting have one setting: their evaluation rows
    (at that default setting) are kept; a gridded planner's are not."""

    def default_row(seed: int, planner: str) -> Row:
        r = row(1.0, seed=seed, omega=0.1, planner=planner)
        r["config"] = {**r["config"], "params": {}}
        return r

    extra = [*rows(), default_row(0, "random_shooting"), default_row(1, "random_shooting")]
    extra.append(default_row(0, "pw_uct"))  # a grid, but no tuning rows: left out
    outcome = select_on_tuning(extra, [1000, 1001])
    kept = [r for r in outcome.rows if r["config"]["planner"] == "random_shooting"]
    assert sorted(r["config"]["seed"] for r in kept) == [0, 1]
    assert outcome.untuned == (("shekel_chain", 3, 2, "pw_uct"),)
    fixed = [s for s in outcome.selections if s.method == "random_shooting"]
    assert len(fixed) == 1 and fixed[0].params == {} and fixed[0].best.n == 2


def test_check_tuning_split_needs_tuning_and_evaluation_rows() -> None:
    """Reading a store with tuning seeds: none of them in the store (nothing to select
    on), or all of its seeds tuning seeds (reporting the selection's own seeds)."""
    check_tuning_split(rows(), [1000, 1001])
    check_tuning_split(rows(), [1000, 5])  # one of them is enough
    with pytest.raises(
        ValueError, match=r"no runs of the tuning seeds 7-8 .*its seeds: 0-2, 1000-1001"
    ):
        check_tuning_split(rows(), [7, 8])
    with pytest.raises(ValueError, match=r"every seed of the store \(0-2, 1000-1001\) is a tuning"):
        check_tuning_split(rows(), [0, 1, 2, 1000, 1001])
    with pytest.raises(ValueError, match="tuning on the test set"):
        check_tuning_split([r for r in rows() if r["config"]["seed"] >= 1000], [1000, 1001])
    with pytest.raises(ValueError, match="its seeds: none"):
        check_tuning_split([], [1000])


def layout_row(final: float, *, seed: int, layout: int, omega: float) -> Row:
    r = row(final, seed=seed, omega=omega)
    r["config"] = {**r["config"], "problem": "voot/KitchenClearing-v2", "dim": None,
                   "env_kwargs": {"layout_seed": layout}}  # fmt: skip
    return r


def test_split_rows_by_layout() -> None:
    rows = [
        layout_row(1.0, seed=0, layout=1000, omega=0.1),  # training layout, tuning seed
        layout_row(1.0, seed=5, layout=1000, omega=0.1),  # training layout, other seed
        layout_row(1.0, seed=0, layout=3, omega=0.1),  # held-out layout
        row(1.0, seed=1000, omega=0.1),  # no layout: the seed decides
        row(1.0, seed=7, omega=0.1),
    ]
    tuning, evaluation = split_rows(rows, [0, 1000], [1000])
    assert tuning == [rows[0], rows[3]] and evaluation == [rows[2], rows[4]]
    # every seed of a training layout tunes when no tuning seeds are given
    tuning, evaluation = split_rows(rows, None, [1000])
    assert tuning == [rows[0], rows[1]] and evaluation == [rows[2], rows[3], rows[4]]
    # per problem: a problem without an entry splits by seed
    tuning, evaluation = split_rows(rows, [0], {"voot/KitchenClearing-v2": [1000]})
    assert tuning == [rows[0]] and evaluation == [rows[2], rows[3], rows[4]]
    tuning, _ = split_rows(rows, [0], {"other": [1000]})
    assert tuning == [rows[0], rows[2]]


def test_select_on_training_layouts_report_held_out_layouts() -> None:
    rows = []
    for layout in (1000, 1001):  # training: omega=0.1 wins pooled over both layouts
        rows += [layout_row(3.0 - layout + 1000, seed=0, layout=layout, omega=0.1)]
        rows += [layout_row(1.5, seed=0, layout=layout, omega=0.3)]
    for layout in (0, 1):  # held out: both settings ran, omega=0.3 would win here
        rows += [layout_row(0.0, seed=0, layout=layout, omega=0.1)]
        rows += [layout_row(5.0, seed=0, layout=layout, omega=0.3)]
    out = select_on_tuning(rows, [0], [1000, 1001])
    (sel,) = out.selections
    assert sel.best.label == "omega=0.1" and sel.best.n == 2  # pooled: mean 2.5 > 1.5
    assert [r["config"]["env_kwargs"]["layout_seed"] for r in out.rows] == [0, 1]
    assert all(r["config"]["params"] == {"omega": 0.1} for r in out.rows)
    note = tuning_note([0], [1000, 1001])
    assert note == (
        "settings selected on training layouts 1000-1001 (seeds 0), disjoint from the"
        " held-out layouts reported"
    )
    assert tuning_sentence([], [7]).startswith("Settings selected on training layouts 7,")


def test_check_layout_split_needs_a_tuning_and_a_held_out_layout() -> None:
    from voot.bench.protocol.tuning import check_layout_split

    def row(problem: str, layout: int | None) -> dict:
        kwargs = {} if layout is None else {"layout_seed": layout}
        return {"config": {"problem": problem, "env_kwargs": kwargs, "seed": 0}}

    rows = [row("a", 0), row("a", 1), row("a", 1000), row("b", None)]
    check_layout_split(rows, [1000])
    check_layout_split(rows, {"a": [1000, 1001]})
    with pytest.raises(
        ValueError,
        match=r"no runs on the tuning layouts 5-6 in the store \(its layouts: 0-1, 1000\)",
    ):
        check_layout_split(rows, [5, 6])
    with pytest.raises(
        ValueError, match=r"every layout of the store \(0-1, 1000\) is a tuning layout"
    ):
        check_layout_split(rows, [0, 1, 1000])
    with pytest.raises(ValueError, match="no runs on the tuning layouts 1000 of b in the store"):
        check_layout_split(rows, {"a": [1000], "b": [1000]})
    with pytest.raises(ValueError, match="its layouts: none"):
        check_layout_split([row("b", None)], [0])
