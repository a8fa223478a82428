"""Tests of voot.bench.claims: the paper's claims, our intervals and every verdict."""

from __future__ import annotations

import math

import pytest

from voot.bench.claims import (
    NO_DATA,
    NOT_REPRODUCED,
    PAPER_CLAIMS,
    REPRODUCED,
    REVERSED,
    Claim,
    claims_table,
    evaluate,
    verdict,
)
from voot.bench.plan_runs import plan_data
from voot.bench.store_format import Row, make_row

SIMS = 3000
CONVEYOR = "voot/ConveyorPacking-v1"


def row(
    final: float,
    *,
    planner: str,
    seed: int,
    left: float = 5.0,
    params: dict | None = None,
    problem: str = CONVEYOR,
) -> Row:
    """A run whose best return is ``final`` from simulation 500 on (-2 before), with
    ``left`` of 20 objects left from then on."""
    config = {
        "problem": problem,
        "dim": None,
        "env_kwargs": {},
        "planner": planner,
        "params": params or {},
        "simulations": SIMS,
        "seed": seed,
        "protocol": 1,
    }
    best = [-2.0] * 499 + [final] * (SIMS - 499)
    objects = [20.0] * 499 + [left] * (SIMS - 499)
    return make_row(
        "plan",
        config,
        status="ok",
        wall_time=1.0,
        best_so_far=best,
        objects_left=objects,
        objects_initial=20.0,
    )


def claim(planners: tuple[str, ...], **kw: object) -> Claim:
    base = dict(
        claim="test",
        problem="conveyor_v1",
        metric="return",
        planners=planners,
        checkpoint=1000,
        threshold=1.0,
        side="below",
        paper="below 1",
    )
    return Claim(**{**base, **kw})  # type: ignore[arg-type]


def test_verdict_rules() -> None:
    assert verdict("below", 1.0, 0.2, 0.9) == REPRODUCED
    assert verdict("below", 1.0, 1.1, 3.0) == REVERSED
    assert verdict("below", 1.0, 0.5, 1.5) == NOT_REPRODUCED
    assert verdict("above", 3.0, 3.1, 4.0) == REPRODUCED
    assert verdict("above", 3.0, 1.0, 2.9) == REVERSED
    assert verdict("above", 3.0, 2.0, 3.0) == NOT_REPRODUCED  # touching is not settled
    assert verdict("above", 3.0, math.nan, math.nan) == NO_DATA
    with pytest.raises(ValueError, match="side must be one of above, below"):
        verdict("over", 1.0, 0.0, 1.0)


def test_claims_are_validated() -> None:
    with pytest.raises(ValueError, match="metric must be one of return, objects_left"):
        claim(("voot",), metric="reward")
    with pytest.raises(ValueError, match="checkpoint"):
        claim(("voot",), checkpoint=0)
    with pytest.raises(ValueError, match="no planners"):
        claim(())
    problems = {c.problem for c in PAPER_CLAIMS}
    assert problems == {"kitchen_v1", "conveyor_v1"} and len(PAPER_CLAIMS) == 10


def test_every_verdict_from_synthetic_rows() -> None:
    rows = []
    for seed in range(3):
        rows.append(row(0.2 + 0.1 * seed, planner="doot", seed=seed))  # clearly below 1
        rows.append(row(4.0 + 0.1 * seed, planner="pw_uct", seed=seed))  # clearly above
        rows.append(row([-2.0, 2.0, 1.5][seed], planner="voronoi_pw", seed=seed))  # straddles
    rows.append(row(0.0, planner="hoot", seed=0))  # one seed: no interval
    data = plan_data(rows)
    planners = ("doot", "pw_uct", "voronoi_pw", "hoot", "cem")
    results = evaluate(data, [claim(planners)])
    got = {r.planner: r.verdict for r in results}
    assert got == {
        "doot": REPRODUCED,
        "pw_uct": REVERSED,
        "voronoi_pw": NOT_REPRODUCED,
        "hoot": NO_DATA,
        "cem": NO_DATA,
    }
    doot = results[0]
    assert doot.interval == "t" and doot.n == 3 and doot.value == pytest.approx(0.3)
    assert doot.low < 0.3 < doot.high < 1.0
    notes = {r.planner: r.note for r in results}
    assert notes["hoot"] == "1 seeds: no interval" and notes["cem"] == "no runs"
    # beyond the runs' budget, and before the curves reach their values
    (late,) = evaluate(data, [claim(("doot",), checkpoint=SIMS + 1)])
    assert late.verdict == NO_DATA and late.note == f"runs of {SIMS} simulations"
    (early,) = evaluate(data, [claim(("doot",), checkpoint=100)])
    assert early.value == -2.0 and early.verdict == REPRODUCED
    table = claims_table(results, "a note.")
    assert "reproduced: 1, not reproduced: 1, reversed: 1, no data: 2." in table
    assert "| test | conveyor_v1 | doot | return | 1000 | below 1 | < 1 | 0.3 [" in table
    assert "| ″ | conveyor_v1 | pw_uct |" in table and "— (no runs) | no data |" in table
    assert table.endswith("a note.")


def test_object_metrics_and_the_median() -> None:
    rows = [row(1.0, planner="voot", seed=s, left=n) for s, n in enumerate([5.0, 4.0, 6.0])]
    data = plan_data(rows)
    (handled,) = evaluate(
        data, [claim(("voot",), metric="objects_handled", threshold=14.5, side="above")]
    )
    assert handled.value == pytest.approx(15.0) and handled.verdict == NOT_REPRODUCED
    (left,) = evaluate(data, [claim(("voot",), metric="objects_left", threshold=1.0, side="below")])
    assert left.value == pytest.approx(5.0) and left.verdict == REVERSED
    cleared = [row(1.0, planner="voot", seed=s, left=0.0) for s in range(8)]
    (median,) = evaluate(
        plan_data(cleared),
        [claim(("voot",), metric="simulations_to_clear", threshold=750.0, side="below")],
    )
    assert median.value == 500.0 and median.interval == "order statistics"
    assert median.verdict == REPRODUCED
    no_objects = {k: v for k, v in rows[0].items() if k not in ("objects_left", "objects_initial")}
    (none,) = evaluate(plan_data([no_objects]), [claim(("voot",), metric="objects_left")])
    assert none.verdict == NO_DATA and none.note == "no object counts"


def test_claims_honour_the_tuning_seeds() -> None:
    """c=1 wins on the tuning seeds, c=2 over all seeds: the tuned rule judges c=1 on the
    evaluation seeds only, the same-seed rule c=2 on every seed; the verdicts differ."""
    rows = []
    for seed in (1000, 1001):
        rows += [
            row(1.0, planner="pw_uct", seed=seed, params={"c": 1}),
            row(0.0, planner="pw_uct", seed=seed, params={"c": 2}),
        ]
    for seed in (0, 1, 2):
        rows += [
            row(3.0 + 0.1 * seed, planner="pw_uct", seed=seed, params={"c": 1}),
            row(5.0 + 0.1 * seed, planner="pw_uct", seed=seed, params={"c": 2}),
        ]
    c = claim(("pw_uct",), threshold=4.0)
    (same_seeds,) = evaluate(plan_data(rows), [c])
    assert same_seeds.n == 5 and same_seeds.verdict == NOT_REPRODUCED
    (tuned,) = evaluate(plan_data(rows, tuning_seeds=[1000, 1001]), [c])
    assert tuned.n == 3 and tuned.value == pytest.approx(3.1) and tuned.verdict == REPRODUCED


def test_claims_on_layouts_count_layouts() -> None:
    """Two layouts x three seeds: n is the number of layouts, the interval is over the
    per-layout means (here 1 and 3: mean 2, half-width 12.7)."""

    def on_layout(value: float, seed: int, layout: int) -> Row:
        r = row(value, planner="pw_uct", seed=seed)
        return {**r, "config": {**r["config"], "env_kwargs": {"layout_seed": layout}}}

    rows = [on_layout(v, s, layout) for layout, v in ((0, 1.0), (1, 3.0)) for s in range(3)]
    (result,) = evaluate(plan_data(rows), [claim(("pw_uct",), threshold=4.0)])
    assert result.n == 2 and result.value == pytest.approx(2.0)
    assert result.high - result.value == pytest.approx(12.7062047, rel=1e-6)
    # the six runs taken as independent seeds would give [0.85, 3.15]: "reproduced"
    assert result.verdict == NOT_REPRODUCED
