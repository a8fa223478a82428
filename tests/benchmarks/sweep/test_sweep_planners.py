"""Tests of voot.bench.sweep.planners' registry: outside planners by entry point (faked
through importlib.metadata) and by module:attribute (the tests' planner_fixtures) go
through the planning sweep like voot's own, and a broken one fails with its name, losing
no finished run."""

from __future__ import annotations

from importlib import metadata
from pathlib import Path

import numpy as np
import pytest

from voot.bench.store.result_store import ResultStore
from voot.bench.sweep import planners as SP
from voot.bench.sweep.backends import SerialBackend
from voot.bench.sweep.engine import run_sweep
from voot.bench.sweep.plan import build_plan_specs
from voot.planners import ENTRY_POINT_GROUP

GOOD = "planner_fixtures:rollouts"


@pytest.fixture
def installed(monkeypatch: pytest.MonkeyPatch) -> None:
    """Two installed plug-ins, as entry points of voot.planners: one good, one broken."""
    eps = [
        metadata.EntryPoint("fake_greedy", GOOD, ENTRY_POINT_GROUP),
        metadata.EntryPoint("broken", "no_such_module_xyz:planner", ENTRY_POINT_GROUP),
    ]
    monkeypatch.setattr(
        metadata, "entry_points", lambda group: [e for e in eps if e.group == group]
    )
    monkeypatch.setattr(SP, "REGISTRY", SP._builtin_registry())


def _specs(planners: list[str], grid: str = "default", **kw: object) -> list:
    return build_plan_specs(["shekel_chain"], [3], planners, [0, 1], simulations=8, grid=grid, **kw)


def test_voots_planners_are_registered_with_their_grids() -> None:
    for name in SP.PLAN_PLANNERS:
        if name not in SP.RL_PLANNERS:
            assert SP.planner_entry(name).builtin
    assert SP.keeps_tree("voot") and not SP.keeps_tree("cem") and not SP.keeps_tree("ppo")
    assert SP.is_builtin("ppo") and not SP.is_builtin(GOOD)


def test_an_entry_point_planner_is_found_by_its_name(installed: None) -> None:
    assert SP.normalize_plan_planner(" fake_greedy ") == "fake_greedy"
    assert SP.planner_grid("fake_greedy", "chain") == [{"horizon": 2}, {"horizon": 3}]
    assert SP.planner_grid("fake_greedy", "chain", "default") == [{}]
    with pytest.raises(ValueError, match=r"planner 'broken' \(entry point no_such_module_xyz"):
        SP.normalize_plan_planner("broken")
    with pytest.raises(ValueError, match="valid planners are: broken, cem, ddpg, doot, fake_gre"):
        SP.normalize_plan_planner("nope")


def test_an_outside_planner_runs_in_the_sweep_like_voots_own(tmp_path: Path) -> None:
    specs = _specs([GOOD, "voot"], grid="paper", fixed=None)
    outside = [s for s in specs if s.planner == GOOD]
    assert sorted({s.params for s in outside}) == [(("horizon", 2),), (("horizon", 3),)]
    store = ResultStore(tmp_path / "r")
    summary = run_sweep(specs, store, SerialBackend(), progress=False)
    assert summary.failed == 0
    rows = [r for r in store.load(kind="plan") if r["config"]["planner"] == GOOD]
    assert len(rows) == 4 and all(r["status"] == "ok" for r in rows)
    for r in rows:
        # cost measured by voot around the problem: never nan, one point per simulation
        assert r["simulator_calls"] == r["n_steps"] == r["calls_curve"][-1] > 0
        assert len(r["cpu_elapsed"]) == len(r["calls_curve"]) == 8
        assert np.isfinite(r["cpu_elapsed"][-1]) and r["n_nodes"] == 0
        assert r["planner_config"] == {
            "planner": GOOD,
            "version": "",
            "gamma": 0.9,
            **dict(r["config"]["params"]),
        }
        assert r["best_return"] == r["best_so_far"][-1]
    again = run_sweep(specs, store, SerialBackend(), progress=False)
    assert again.skipped == len(specs)  # resumable: every run once


@pytest.mark.parametrize(
    ("bad", "message"),
    [
        ("planner_fixtures:raises_midway", "raised RuntimeError in simulation 3 of 8"),
        ("planner_fixtures:yields_nan", "yielded the best return nan after simulation 2"),
        ("planner_fixtures:no_replay", "returned a plan that does not replay"),
    ],
)
def test_a_plugin_failing_mid_run_loses_no_finished_run(
    tmp_path: Path, bad: str, message: str
) -> None:
    store = ResultStore(tmp_path / "r")
    summary = run_sweep(_specs(["voot", bad]), store, SerialBackend(), progress=False)
    assert summary.failed == 2
    rows = store.load(kind="plan", status=None)
    assert {r["status"] for r in rows if r["config"]["planner"] == "voot"} == {"ok"}
    failed = [r for r in rows if r["config"]["planner"] == bad]
    assert len(failed) == 2 and all(r["status"] == "failed" for r in failed)
    assert all(f"planner '{bad}'" in r["error"] and message in r["error"] for r in failed)


@pytest.mark.parametrize(
    ("planners", "kw", "message"),
    [
        (["no_such_module_xyz:p"], {}, "importing no_such_module_xyz failed"),
        (["planner_fixtures:wrong_signature"], {}, "has the wrong signature"),
        (["planner_fixtures:not_a_planner"], {}, "is a int, not a planner"),
        ([GOOD], {"fixed": {"width": 3}}, f"planner '{GOOD}' does not take these settings"),
        ([GOOD], {"horizon": 2, "record": "x.rrd"}, "keep none (record voot's tree planners"),
    ],
)
def test_a_bad_plugin_fails_before_any_run_naming_itself(
    planners: list[str], kw: dict, message: str
) -> None:
    with pytest.raises(ValueError, match="planner") as info:
        _specs(planners, **kw)
    assert message in str(info.value)


def test_horizon_is_an_outside_planners_setting() -> None:
    assert SP.horizon_param(GOOD, 4) == {"horizon": 4}
    assert {s.params for s in _specs([GOOD], horizon=2)} == {(("horizon", 2),)}
