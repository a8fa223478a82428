"""Tests of voot.bench.report.ablation_table: claims per switch, flips, and the paired ranking."""

from __future__ import annotations

import pytest
from plan_fixtures import plan_row, step_curve

from voot.bench.report.ablation_table import ablation_table
from voot.bench.store.format import Row

SIMS = 2000
KITCHEN = "voot/KitchenClearing-v1"


def row(planner: str, seed: int, left: float, variant: str = "", params: dict | None = None) -> Row:
    """A kitchen run with ``left`` of 7 obstacles left from simulation 100 on."""
    return plan_row(
        step_curve(0.0, 7.0 - left, 100, SIMS),
        planner=planner,
        seed=seed,
        problem=KITCHEN,
        params=params or {"a": 1},
        left=step_curve(7.0, left, 100, SIMS),
        variant=variant,
    )


def rows() -> list[Row]:
    out = []
    for seed in [*range(1000, 1003), *range(6)]:
        jitter = 0.1 * (seed % 3)
        out.append(row("voot", seed, 4.0 + jitter))
        out.append(row("pw_uct", seed, 0.0 + jitter))
        # commit_off: VOOT clears almost everything, PW-UCT unchanged
        out.append(row("voot", seed, 0.2 * (seed % 2), "commit_off"))
        out.append(row("pw_uct", seed, jitter, "commit_off"))
        # pw_authors: PW-UCT gets stuck
        out.append(row("pw_uct", seed, 5.0 + jitter, "pw_authors"))
    return out


def test_flips_and_ranking_are_measured_per_switch() -> None:
    text = ablation_table(rows(), range(1000, 1003))
    lines = text.splitlines()
    voot_off = next(x for x in lines if x.startswith("| commit_off | kitchen_v1 | voot |"))
    assert "reproduced" in voot_off and "**reversed -> reproduced**" in voot_off
    pw_authors = next(x for x in lines if x.startswith("| pw_authors | kitchen_v1 | pw_uct |"))
    assert "**reversed -> reproduced**" in pw_authors
    rank_v1 = next(x for x in lines if x.startswith("| v1 | kitchen_v1 | voot vs pw_uct"))
    assert "PW-UCT ahead" in rank_v1
    # pw_authors leaves VOOT at the default: default VOOT against the authors' PW-UCT
    rank_pw = next(x for x in lines if x.startswith("| pw_authors | kitchen_v1 | voot vs"))
    assert "voot vs pw_uct[pw_authors]" in rank_pw and "VOOT ahead" in rank_pw
    rank_off = next(
        x for x in lines if x.startswith("| commit_off | kitchen_v1 | voot[commit_off] vs")
    )
    assert "voot[commit_off] vs pw_uct[commit_off]" in rank_off
    # tuning seeds are not evaluation seeds: 6 seeds judged
    assert "(6)" in voot_off
    # switches without runs are left out
    assert not any(x.startswith("| kappa_off |") for x in lines)


def test_no_tuned_runs_is_an_error() -> None:
    with pytest.raises(ValueError, match="no tuned plan runs"):
        ablation_table([r for r in rows() if r["config"]["seed"] < 1000], range(1000, 1003))


def test_problems_filter_keeps_only_those_problems() -> None:
    text = ablation_table(rows(), range(1000, 1003), problems=["kitchen_v1"])
    assert "| v1 | kitchen_v1 | voot |" in text
    with pytest.raises(ValueError, match="no tuned plan runs"):
        ablation_table(rows(), range(1000, 1003), problems=["conveyor_v1"])


def test_env_kwargs_draws_the_table_of_that_domain_judged_as_its_problem() -> None:
    domain = {"base_model": "footprint", "rooms": "authors"}
    in_domain = []
    for r in rows():
        r = dict(r, config=dict(r["config"], env_kwargs=dict(domain)))
        if r["config"]["planner"] == "voot":  # VOOT clears everything in this domain
            r["objects_left"] = [0.0] * SIMS
        in_domain.append(r)
    text = ablation_table([*rows(), *in_domain], range(1000, 1003), env_kwargs=domain)
    voot = next(x for x in text.splitlines() if x.startswith("| v1 | kitchen_v1 | voot |"))
    assert "reproduced" in voot and "(6)" in voot
    assert "in the domain base_model=footprint, rooms=authors" in text
    plain = ablation_table([*rows(), *in_domain], range(1000, 1003))
    assert "in the domain" not in plain and plain != text
    with pytest.raises(ValueError, match="no tuned plan runs"):
        ablation_table(rows(), range(1000, 1003), env_kwargs=domain)
