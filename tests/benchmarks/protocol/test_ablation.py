"""Tests of voot.bench.protocol.ablation: the switches, their variants' grids and runs."""

from __future__ import annotations

import pytest

from voot.bench.protocol.ablation import (
    ABLATION_PROBLEMS,
    AUTHORS_PW_KS,
    SWITCHES,
    ablation_specs,
    check_switches,
    switch_list,
    variant_grid,
)
from voot.bench.protocol.select import cell_of
from voot.bench.sweep.planners import planner_grid


def test_every_switch_is_a_valid_planner_config_on_its_domains() -> None:
    for switch in SWITCHES.values():
        specs = ablation_specs([switch], [0], include_baseline=False)
        assert {s.problem for s in specs} == set(switch.problems)
        assert {s.planner for s in specs} == set(switch.planners())
        for spec in specs:
            cfg = spec.run_config()  # validates every option
            for name, value in spec.params:
                if name in cfg.to_dict():
                    got = getattr(cfg, name)
                    assert got == value or str(got) == str(value), (switch.name, name)


def test_switch_options_reach_the_config() -> None:
    spec = next(
        s
        for s in ablation_specs([SWITCHES["pw_authors"]], [0], include_baseline=False)
        if s.planner == "pw_uct"
    )
    cfg = spec.run_config()
    assert str(cfg.widening) == "authors" and cfg.pw_k in AUTHORS_PW_KS
    voo = next(
        s
        for s in ablation_specs([SWITCHES["voo_gaussian"]], [0], include_baseline=False)
        if s.planner == "voot"
    )
    assert str(voo.run_config().sampler_config().sampler) == "gaussian"
    off = ablation_specs([SWITCHES["commit_off"]], [0], include_baseline=False)
    assert all(s.run_config().root_commitment is None for s in off)
    ten = ablation_specs([SWITCHES["commit_10"]], [0], include_baseline=False)
    assert {s.problem for s in ten} == {"voot/ConveyorPacking-v1"}
    assert all(s.run_config().root_commitment == 10 for s in ten)


def test_variant_grid_replaces_axes_and_adds_overrides() -> None:
    base = planner_grid("pw_uct", "robot")
    grid = variant_grid(SWITCHES["pw_authors"], "pw_uct")
    assert len(grid) == len(AUTHORS_PW_KS) * len({g["ucb_c"] for g in base})
    assert {g["pw_k"] for g in grid} == set(AUTHORS_PW_KS)
    assert all(g["widening"] == "authors" for g in grid)
    five = variant_grid(SWITCHES["reevaluations_5"], "voot")
    assert {g["reevaluations"] for g in five} == {5}
    assert variant_grid(None, "voot") == planner_grid("voot", "robot")


def test_the_baseline_runs_are_the_protocol_runs() -> None:
    """No variant: the same run ids as voot-bench plan (so the v1 rows are shared)."""
    from voot.bench.sweep.plan import build_plan_specs

    plain = build_plan_specs(["kitchen_v1"], None, ["voot", "pw_uct"], [3])
    ours = ablation_specs([], [3], problems=["kitchen_v1"])
    assert {s.run_id for s in ours} == {s.run_id for s in plain}
    assert all("variant" not in s.config() for s in ours)


def test_a_variant_is_its_own_cell_and_run() -> None:
    specs = ablation_specs([SWITCHES["kappa_off"]], [0], problems=["kitchen_v1"])
    cells = {cell_of({"kind": "plan", "config": s.config()})[3] for s in specs}
    assert cells == {"voot", "pw_uct", "voot[kappa_off]"}
    ids = [s.run_id for s in specs]
    assert len(ids) == len(set(ids))


def test_check_switches_names_the_choices() -> None:
    assert [s.name for s in check_switches(["kappa-off", "v1"])] == ["kappa_off"]
    assert len(check_switches(None)) == len(SWITCHES)
    with pytest.raises(ValueError, match=r"valid switches are: v1 .*pw_authors"):
        check_switches(["pw_inverted"])
    text = switch_list()
    assert all(name in text for name in SWITCHES) and "[conveyor only]" in text
    assert set(ABLATION_PROBLEMS) == {"voot/KitchenClearing-v1", "voot/ConveyorPacking-v1"}


def test_check_applicable_refuses_switches_and_problems_that_do_not_meet() -> None:
    from voot.bench.protocol.ablation import SWITCHES, check_applicable

    conveyor_only, both = SWITCHES["commit_10"], SWITCHES["kappa_off"]
    check_applicable([conveyor_only], ["conveyor_v1"])
    check_applicable([conveyor_only, both], ["kitchen_v1", "conveyor_v1"])
    check_applicable([], ["kitchen_v2"])  # the v1 defaults alone run anywhere
    with pytest.raises(ValueError, match="commit_10 applies to voot/ConveyorPacking-v1 only"):
        check_applicable([conveyor_only], ["kitchen_v1"])  # named by default
    with pytest.raises(ValueError, match="no ablation switch applies to voot/KitchenClearing-v1"):
        check_applicable([conveyor_only], ["kitchen_v1"], named=False)
    with pytest.raises(ValueError, match="no ablation switch applies to voot/KitchenClearing-v2"):
        check_applicable([both], ["kitchen_v1", "kitchen_v2"])


@pytest.mark.parametrize("simulations", [0, -5, True, 2.5])
def test_ablation_specs_refuse_a_budget_that_is_not_a_positive_integer(simulations: object) -> None:
    from voot.bench.protocol.ablation import SWITCHES, ablation_specs

    with pytest.raises(ValueError, match="simulations must be an integer >= 1"):
        ablation_specs([SWITCHES["kappa_off"]], [0], simulations=simulations)  # type: ignore[arg-type]


def test_env_kwargs_make_the_runs_of_that_version_of_the_domain() -> None:
    """A domain switch (here the authors' domain) runs every variant apart: the same
    planners and settings, other run ids, its keywords in the problem label."""
    kwargs = {"base_model": "footprint", "big_box_ban": True, "rooms": "authors"}
    plain = ablation_specs([SWITCHES["pw_authors"]], [0], problems=["conveyor_v1"])
    domain = ablation_specs(
        [SWITCHES["pw_authors"]], [0], problems=["conveyor_v1"], env_kwargs=kwargs
    )
    assert [(s.planner, s.params, s.variant) for s in domain] == [
        (s.planner, s.params, s.variant) for s in plain
    ]
    assert all(s.env_kwargs_dict == kwargs for s in domain)
    assert not {s.run_id for s in domain} & {s.run_id for s in plain}
    assert all("rooms=authors" in s.label for s in domain)
    with pytest.raises(ValueError, match="plain JSON values"):
        ablation_specs([], [0], problems=["conveyor_v1"], env_kwargs={"rooms": object()})
