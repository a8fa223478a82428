"""Tests of voot.bench.protocol.select: best-mean hyperparameter selection."""

from __future__ import annotations

from typing import Any

import pytest

from voot.bench.protocol.select import (
    function_order,
    largest_budget,
    method_order,
    select_hyperparameters,
    selected_rows,
    selection_table,
)
from voot.bench.store.format import Row, make_row


def fake_row(
    final: float,
    *,
    method: str = "voo",
    params: dict[str, Any] | None = None,
    seed: int = 0,
    function: str = "shekel",
    dim: int = 3,
    budget: int = 4,
    status: str = "ok",
) -> Row:
    config = {
        "function": function,
        "dim": dim,
        "method": method,
        "params": params or {},
        "budget": budget,
        "seed": seed,
        "protocol": 1,
    }
    curve = [final - 3.0, final - 2.0, final - 1.0, final][-budget:] if status == "ok" else []
    return make_row("bbfo", config, status=status, wall_time=0.1, best_so_far=curve)


def test_selects_best_mean_not_best_single_run() -> None:
    rows = [
        # omega=0.1: one lucky seed, mean 4.0
        fake_row(10.0, params={"omega": 0.1}, seed=0),
        fake_row(-2.0, params={"omega": 0.1}, seed=1),
        # omega=0.3: steady, mean 5.0 -> selected
        fake_row(5.0, params={"omega": 0.3}, seed=0),
        fake_row(5.0, params={"omega": 0.3}, seed=1),
        # a failed run of a third setting does not count
        fake_row(0.0, params={"omega": 0.5}, seed=0, status="failed"),
    ]
    (sel,) = select_hyperparameters(rows)
    assert sel.key == ("shekel", 3, 4, "voo")
    assert sel.params == {"omega": 0.3}
    assert sel.best.mean == 5.0 and sel.best.n == 2
    assert [c.label for c in sel.candidates] == ["omega=0.3", "omega=0.1"]
    chosen = selected_rows(rows, [sel])
    assert [r["config"]["params"] for r in chosen] == [{"omega": 0.3}] * 2


def test_ties_go_to_the_first_label_and_cells_are_separate() -> None:
    rows = [
        fake_row(1.0, params={"omega": 0.5}),
        fake_row(1.0, params={"omega": 0.01}),
        fake_row(3.0, params={"omega": 0.5}, dim=10),
        fake_row(2.0, params={"omega": 0.01}, dim=10),
        fake_row(7.0, method="random", dim=10),
    ]
    sels = select_hyperparameters(rows)
    assert [(s.dim, s.method, s.best.label) for s in sels] == [
        (3, "voo", "omega=0.01"),
        (10, "voo", "omega=0.5"),
        (10, "random", "default"),
    ]


def test_largest_budget_per_cell() -> None:
    rows = [
        fake_row(1.0, budget=2),
        fake_row(1.0, budget=4),
        fake_row(1.0, budget=2, dim=10),
    ]
    kept = largest_budget(rows)
    assert [(r["config"]["dim"], r["config"]["budget"]) for r in kept] == [(3, 4), (10, 2)]


def test_orders_and_table() -> None:
    assert function_order(["zeta", "shekel", "griewank"]) == ["griewank", "shekel", "zeta"]
    assert method_order(["random", "my_method", "voo", "cmaes"])[:3] == ["voo", "cmaes", "random"]
    rows = [fake_row(2.0, params={"omega": 0.1}), fake_row(1.0, params={"omega": 0.3})]
    sels = select_hyperparameters(rows)
    table = selection_table(sels)
    assert "| shekel | 3 | 4 | voo | omega=0.1 | 2 | 1 | 2 |" in table
    full = selection_table(sels, all_candidates=True)
    assert "omega=0.1*" in full and "omega=0.3 |" in full


def test_plan_rows_select_per_problem_and_planner() -> None:
    from voot.bench.protocol.select import cell_of

    def plan_row(final: float, planner: str, params: dict[str, Any], seed: int, dim: Any) -> Row:
        config = {
            "problem": "voot/KitchenClearing-v0" if dim is None else "shekel_chain",
            "dim": dim,
            "env_kwargs": {},
            "planner": planner,
            "params": params,
            "simulations": 2,
            "seed": seed,
            "protocol": 1,
        }
        return make_row("plan", config, status="ok", wall_time=0.1, best_so_far=[0.0, final])

    rows = [
        plan_row(1.0, "voot", {"omega": 0.1}, 0, None),
        plan_row(3.0, "voot", {"omega": 0.1}, 1, None),
        plan_row(2.5, "voot", {"omega": 0.3}, 0, None),
        plan_row(2.5, "voot", {"omega": 0.3}, 1, None),
        plan_row(0.5, "pw_uct", {}, 0, 10),
    ]
    assert cell_of(rows[0]) == ("kitchen", 0, 2, "voot")
    assert cell_of(rows[-1]) == ("shekel_chain", 10, 2, "pw_uct")
    sels = select_hyperparameters(rows)
    assert [(s.function, s.method, s.best.label) for s in sels] == [
        ("kitchen", "voot", "omega=0.3"),
        ("shekel_chain", "pw_uct", "default"),
    ]
    table = selection_table(sels, kind="plan")
    assert "| problem | dim | simulations | planner |" in table
    assert "| kitchen |  | 2 | voot | omega=0.3 | 2.5 | 2 | 2 |" in table
    assert method_order(["hoot", "voo", "voot", "pw_uct"]) == ["voo", "voot", "pw_uct", "hoot"]


def test_instances_are_never_mixed() -> None:
    from voot.bench.protocol.select import one_instance

    paper = [fake_row(1.0, seed=s) for s in range(2)]
    moved = [make_row("bbfo", {**r["config"], "instance": 3}, **_rest(r)) for r in paper]
    assert one_instance(paper) == (0, paper)
    assert one_instance(moved)[0] == 3
    assert one_instance(paper + moved, 3) == (3, moved)
    assert one_instance(paper + moved, 0) == (0, paper)
    with pytest.raises(ValueError, match=r"several test-function instances \(0, 3\).*--instance"):
        one_instance(paper + moved)
    with pytest.raises(ValueError, match=r"no runs of instance 1.*instance\(s\) 0"):
        one_instance(paper, 1)
    with pytest.raises(ValueError, match="several test-function instances"):
        select_hyperparameters(paper + moved)
    (sel,) = select_hyperparameters(moved)
    assert sel.best.n == 2


def _rest(row: Row) -> dict[str, Any]:
    return {"status": "ok", "wall_time": 0.1, "best_so_far": list(row["best_so_far"])}


def test_a_plan_rows_variant_names_its_planner() -> None:
    from voot.bench.protocol.select import cell_of, planner_label

    assert planner_label("voot") == "voot" and planner_label("voot", "") == "voot"
    assert planner_label("pw_uct", "pw_authors") == "pw_uct[pw_authors]"
    config = {"problem": "voot/KitchenClearing-v1", "dim": None, "simulations": 5}
    plain = {"kind": "plan", "config": {**config, "planner": "voot"}}
    tagged = {"kind": "plan", "config": {**config, "planner": "voot", "variant": "kappa_off"}}
    assert cell_of(plain)[3] == "voot" and cell_of(tagged)[3] == "voot[kappa_off]"


def test_the_selection_pools_a_familys_layouts() -> None:
    """omega=0.1 wins on layout 1 but loses on average over layouts 1-3: the selection is
    per family (env keywords without the layout seed), pooling every layout."""
    from plan_fixtures import plan_row

    from voot.bench.protocol.select import cell_of

    finals = {0.1: {1: 5.0, 2: 0.0, 3: 0.0}, 0.3: {1: 2.0, 2: 2.0, 3: 2.0}}
    rows = [
        plan_row([0.0, f], planner="voot", seed=s, params={"omega": w}, layout=lay)
        for w, per in finals.items()
        for lay, f in per.items()
        for s in (0, 1)
    ]
    assert {cell_of(r) for r in rows} == {("kitchen", 0, 2, "voot")}
    (sel,) = select_hyperparameters(rows)
    assert sel.best.label == "omega=0.3" and sel.best.n == 6
    assert sel.candidates[1].mean == pytest.approx(5.0 / 3.0)
    # a single layout alone would have picked the other setting
    (one,) = select_hyperparameters(
        [r for r in rows if r["config"]["env_kwargs"]["layout_seed"] == 1]
    )
    assert one.best.label == "omega=0.1"
