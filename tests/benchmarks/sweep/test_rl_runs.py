"""voot.bench.sweep.rl: PPO and DDPG rows in the plan store, with a matched budget.

The tests marked ``rl`` train (they need the rl extra); the others check the set-up and
the error for a missing extra without torch.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from voot.bench.sweep import rl as R
from voot.bench.sweep.plan import build_plan_specs, strip_timings
from voot.bench.sweep.planners import (
    PLAN_PLANNERS,
    RL_PLANNERS,
    normalize_plan_planner,
    planner_grid,
)


def test_rl_planners_are_plan_planners_with_one_default_setting() -> None:
    assert set(RL_PLANNERS) <= set(PLAN_PLANNERS)
    for grid in ("paper", "default"):
        assert planner_grid("ppo", "robot", grid) == [{}]
        assert planner_grid("DDPG", "chain", grid) == [{}]
    assert normalize_plan_planner("PPO") == "ppo"
    with pytest.raises(ValueError, match=r"valid planners are: .*ddpg.*ppo.*voot"):
        normalize_plan_planner("sac")


def test_matched_steps_round_half_up_and_end_at_the_budget() -> None:
    assert R.matched_steps(10, 4) == [3, 5, 8, 10]  # 2.5 -> 3, 7.5 -> 8 (half up)
    assert R.matched_steps(3, 6) == [1, 1, 2, 2, 3, 3]  # 0.5 -> 1
    assert R.matched_steps(1, 3) == [0, 1, 1]
    steps = R.matched_steps(12_345, 2_000)
    assert steps[-1] == 12_345 and steps == sorted(steps)


def test_rl_run_config_takes_the_reference_planners_discount() -> None:
    from voot.bench.sweep.planners import run_config

    kitchen = run_config("voot/KitchenClearing-v1", None, "ppo", {})
    conveyor = run_config("voot/ConveyorPacking-v1", None, "ddpg", {"tau": 0.01})
    chain = run_config("shekel_chain", 3, "ppo", {"match": "pw_uct"})
    assert (kitchen.gamma, conveyor.gamma, chain.gamma) == (0.9, 0.99, 0.9)
    assert conveyor.tau == 0.01
    with pytest.raises(ValueError, match="gamma is the problem's discount"):
        run_config("shekel_chain", 3, "ppo", {"gamma": 0.5})
    with pytest.raises(ValueError, match=r"unknown option\(s\) \['omega'\].*valid options"):
        run_config("shekel_chain", 3, "ppo", {"omega": 0.3})
    with pytest.raises(ValueError, match="valid planners are"):
        run_config("shekel_chain", 3, "ppo", {"match": "nope"})


def test_horizon_and_recording_are_refused_for_rl(monkeypatch: pytest.MonkeyPatch) -> None:
    import voot.rl

    monkeypatch.setattr(voot.rl, "require_sb3", lambda: None)  # no torch needed here
    with pytest.raises(ValueError, match="max_episode_steps"):
        build_plan_specs(["shekel_chain"], [3], ["ppo"], [0], simulations=5, horizon=4)
    with pytest.raises(ValueError, match="keep none"):
        build_plan_specs(["shekel_chain"], [3], ["ppo"], [0], simulations=5, record="x.rrd")


def test_a_missing_rl_extra_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    from voot.rl import MissingExtraError, require_sb3

    monkeypatch.setitem(sys.modules, "stable_baselines3", None)  # import fails
    with pytest.raises(MissingExtraError, match=r'pip install -e "\.\[rl\]"'):
        require_sb3()
    with pytest.raises(MissingExtraError, match="stable-baselines3 and torch"):
        build_plan_specs(["shekel_chain"], [3], ["voot", "ppo"], [0], simulations=5)
    assert build_plan_specs(["shekel_chain"], [3], ["voot"], [0], simulations=5)  # no RL: fine


def test_the_cli_reports_a_missing_extra(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from voot.bench.cli.main import main

    monkeypatch.setitem(sys.modules, "stable_baselines3", None)
    argv = ["plan", "--out", str(tmp_path / "s"), "--problems", "shekel_chain", "--dims", "3"]
    code = main([*argv, "--planners", "ddpg", "--seeds", "1", "--simulations", "5"])
    assert code != 0
    assert "install the rl extra" in capsys.readouterr().err


# ----- training runs (the rl extra) ------------------------------------------------------
PLAN = ["plan", "--grid", "default", "--workers", "1", "--seeds", "0:1"]


def run_cli(*args: str) -> None:
    """``voot-bench ARGS`` in a separate process (fails the test on a non-zero exit)."""
    code = "import sys; from voot.bench.cli.main import main; sys.exit(main(sys.argv[1:]))"
    subprocess.run(
        [sys.executable, "-c", code, *args], check=True, capture_output=True, timeout=600
    )


def rows(store: Path) -> list[dict[str, Any]]:
    return [json.loads(p.read_text()) for p in sorted((store / "runs").glob("*.json"))]


def by_planner(store: Path) -> dict[tuple[str, str], dict[str, Any]]:
    return {(r["config"]["problem"], r["config"]["planner"]): r for r in rows(store)}


@pytest.fixture(scope="module")
def stores(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """Two stores made by the same tiny sweep in two separate processes."""
    out = []
    for name in ("a", "b"):
        store = tmp_path_factory.mktemp(name) / "store"
        for problem, extra in (("shekel_chain", ["--dims", "3"]), ("kitchen_v1", [])):
            run_cli(
                *PLAN, "--out", str(store), "--problems", problem, *extra,
                "--planners", "voot", "ppo", "ddpg", "--simulations", "20",
            )  # fmt: skip
        out.append(store)
    return out[0], out[1]


@pytest.mark.rl
def test_rl_rows_match_the_voot_rows_budget(stores: tuple[Path, Path]) -> None:
    runs = by_planner(stores[0])
    assert len(runs) == 6 and all(r["status"] == "ok" for r in runs.values())
    for problem in ("shekel_chain", "voot/KitchenClearing-v1"):
        tree = runs[(problem, "voot")]
        calls = tree["n_steps"] + tree["n_feasibility_checks"]
        for planner in ("ppo", "ddpg"):
            r = runs[(problem, planner)]
            assert r["rl_steps"] == calls == r["n_steps"] == r["simulator_calls"]
            assert r["reference"] == {
                "planner": "voot",
                "simulations": 20,
                "n_steps": tree["n_steps"],
                "n_feasibility_checks": tree["n_feasibility_checks"],
            }
            assert r["steps_per_simulation"] == calls / 20
            assert len(r["best_so_far"]) == len(r["calls_curve"]) == len(r["elapsed"]) == 20
            assert len(r["cpu_elapsed"]) == 20 and r["calls_curve"][-1] == calls
            assert r["calls_curve"] == R.matched_steps(calls, 20)
            # best_so_far is the compact curve read at the matched steps
            for step, best in zip(r["calls_curve"], r["best_so_far"], strict=True):
                known = [b for s, b in r["best_by_step"] if s <= step]
                assert best == (known[-1] if known else 0.0)
    kitchen = runs[("voot/KitchenClearing-v1", "ppo")]
    assert kitchen["objects_initial"] == 7 and len(kitchen["objects_left"]) == 20
    assert kitchen["reference"]["n_feasibility_checks"] > 0  # v1 pre-checks were counted


@pytest.mark.rl
def test_rl_rows_are_bit_identical_across_processes(stores: tuple[Path, Path]) -> None:
    a, b = by_planner(stores[0]), by_planner(stores[1])
    assert a.keys() == b.keys()
    for key in a:
        ra, rb = (strip_timings(r[key]) for r in (a, b))
        ra.pop("checksum", None), rb.pop("checksum", None)
        assert ra == rb, key


@pytest.mark.rl
def test_plot_draws_the_rl_rows(stores: tuple[Path, Path], tmp_path: Path) -> None:
    png, md = tmp_path / "f.png", tmp_path / "t.md"
    run_cli("plot", str(stores[0]), "--png", str(png), "--markdown", str(md))
    tables = md.read_text()
    assert png.stat().st_size > 10_000
    for planner in ("ppo", "ddpg"):
        assert f"| kitchen_v1 | {planner} |" in tables


@pytest.mark.rl
def test_a_second_sweep_resumes(stores: tuple[Path, Path]) -> None:
    before = {p.name for p in (stores[0] / "runs").glob("*.json")}
    out = subprocess.run(
        [
            sys.executable, "-c",
            "import sys; from voot.bench.cli.main import main; sys.exit(main(sys.argv[1:]))",
            *PLAN, "--out", str(stores[0]), "--problems", "kitchen_v1",
            "--planners", "ppo", "ddpg", "--simulations", "20",
        ],
        check=True, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert "2 already in the store, 0 ran" in out.stdout + out.stderr
    assert {p.name for p in (stores[0] / "runs").glob("*.json")} == before
