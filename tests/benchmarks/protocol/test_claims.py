"""Tests of voot.bench.protocol.claims: the paper's claims, our intervals and every verdict."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from plan_fixtures import plan_row, step_curve

from voot.bench.protocol.claims import (
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
from voot.bench.report.plan_runs import plan_data
from voot.bench.store.format import Row

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
    return plan_row(
        step_curve(-2.0, final, 500, SIMS),
        planner=planner,
        seed=seed,
        problem=problem,
        params=params,
        left=step_curve(20.0, left, 500, SIMS),
        initial=20.0,
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


def test_the_paper_claims_restate_the_paper() -> None:
    """Each record's checkpoint, threshold and side, as the paper words them (the
    thresholds' rules are in the comment above PAPER_CLAIMS)."""
    got = [(c.problem, c.metric, c.checkpoint, c.threshold, c.side) for c in PAPER_CLAIMS]
    assert got == [
        ("kitchen_v1", "objects_left", 750, 1.0, "below"),  # almost every obstacle
        ("kitchen_v1", "objects_left", 1700, 1.0, "above"),  # the others need > 1,700
        ("conveyor_v1", "return", 1000, 3.0, "above"),  # a little above 3
        ("conveyor_v1", "return", 1000, 1.0, "below"),  # below 1
        ("conveyor_v1", "return", 3000, 3.5, "above"),  # about 4
        ("conveyor_v1", "return", 3000, 2.0, "below"),  # below 2
        ("conveyor_v1", "objects_handled", 1000, 14.5, "above"),  # 15 objects
        ("conveyor_v1", "objects_handled", 3000, 13.5, "below"),  # 12-13 objects
        ("kitchen_v1", "objects_handled", 2000, 2.5, "below"),  # RL: 1-2 obstacles
        ("conveyor_v1", "objects_handled", 3000, 8.5, "below"),  # RL: at most 8 boxes
    ]
    voot_lines = [c for c in PAPER_CLAIMS if c.planners == ("voot",)]
    assert len(voot_lines) == 4 and all("voot" not in c.planners for c in PAPER_CLAIMS[1::2][:4])


def test_an_interval_touching_the_threshold_settles_nothing() -> None:
    # the threshold on an end of the interval: neither side holds strictly
    assert verdict("below", 1.0, 0.5, 1.0) == NOT_REPRODUCED
    assert verdict("below", 1.0, 1.0, 2.0) == NOT_REPRODUCED
    assert verdict("above", 3.0, 3.0, 4.0) == NOT_REPRODUCED
    assert verdict("above", 3.0, 2.0, 3.0) == NOT_REPRODUCED
    # one missing end is no interval
    assert verdict("below", 1.0, math.nan, 0.5) == NO_DATA
    assert verdict("below", 1.0, 0.2, math.nan) == NO_DATA


def test_the_checkpoint_reads_that_simulation_of_every_metric() -> None:
    """The curves change at simulation 500 (index 499): checkpoint 499 reads the value
    before, 500 the value after, and the runs' last simulation is still data."""
    rows = [row(2.0, planner="voot", seed=s, left=4.0) for s in range(3)]
    data = plan_data(rows)
    cases = {"return": (-2.0, 2.0), "objects_left": (20.0, 4.0), "objects_handled": (0.0, 16.0)}
    for metric, (before, after) in cases.items():
        for k, expected in ((499, before), (500, after), (SIMS, after)):
            (r,) = evaluate(data, [claim(("voot",), metric=metric, checkpoint=k)])
            assert r.value == pytest.approx(expected), (metric, k)
            assert r.low == pytest.approx(expected) == r.high and r.verdict != NO_DATA


def test_two_seeds_are_enough_for_a_t_interval() -> None:
    rows = [row(v, planner="voot", seed=s) for s, v in enumerate([0.1, 0.3])]
    (r,) = evaluate(plan_data(rows), [claim(("voot",), threshold=100.0)])
    assert r.n == 2 and r.interval == "t" and r.verdict == REPRODUCED
    # sample standard deviation 0.1 * sqrt(2), so the half-width is t(0.975, 1) * 0.1
    assert r.low == pytest.approx(0.2 - 12.7062047 * 0.1, rel=1e-6)


def test_the_median_needs_six_seeds_and_object_counts() -> None:
    c = claim(("voot",), metric="simulations_to_clear", threshold=750.0)
    three = [row(1.0, planner="voot", seed=s, left=0.0) for s in range(3)]
    (r,) = evaluate(plan_data(three), [c])
    assert r.verdict == NO_DATA and r.n == 3 and r.note == "3 seeds: no interval"
    assert math.isnan(r.value)  # no data: not even the median is reported
    no_objects = [
        {k: v for k, v in x.items() if k not in ("objects_left", "objects_initial")} for x in three
    ]
    (none,) = evaluate(plan_data(no_objects), [c])
    assert none.verdict == NO_DATA and none.note == "no object counts" and none.n == 0


def test_no_runs_is_zero_seeds_and_the_table_spells_infinities() -> None:
    (r,) = evaluate([], [claim(("voot",))])
    assert r.n == 0 and r.note == "no runs" and math.isnan(r.value)
    never = [row(1.0, planner="voot", seed=s, left=2.0) for s in range(8)]  # never cleared
    c = claim(("voot",), metric="simulations_to_clear", threshold=750.0)
    (m,) = evaluate(plan_data(never), [c])
    assert m.value == math.inf and m.verdict == REVERSED
    table = claims_table([m, replace(m, value=-math.inf, low=-math.inf, high=-math.inf)])
    first, second = table.splitlines()[2:4]  # the lines under the header, in order
    assert first.endswith("| never [never, never] (8) | reversed |")
    assert second.endswith("| -inf [-inf, -inf] (8) | reversed |")


def test_a_value_without_an_interval_is_shown_with_its_note() -> None:
    """evaluate gives no value without an interval, but a caller's own line may have one."""
    (one,) = evaluate(plan_data([row(0.5, planner="voot", seed=0)]), [claim(("voot",))])
    assert one.verdict == NO_DATA and math.isnan(one.value) and one.n == 1
    assert "| — (1 seeds: no interval) | no data |" in claims_table([one])
    valued = replace(one, value=0.5)
    assert "| 0.5 (1 seeds: no interval) | no data |" in claims_table([valued])
