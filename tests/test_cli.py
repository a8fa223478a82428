"""End-to-end tests of the voot-bench command line on a tiny grid."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import types
from pathlib import Path

import pytest

from voot.bench.cli import main, parse_range
from voot.bench.store import ResultStore

TINY = [
    "--functions",
    "rastrigin,shekel",
    "--dims",
    "3",
    "--methods",
    "voo",
    "random",
    "--seeds",
    "2",
    "--budget",
    "12",
    "--workers",
    "1",
    "--no-progress",
]


def test_bbfo_select_plot_end_to_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "results"
    assert main(["bbfo", "--out", str(out), *TINY]) == 0
    n_runs = 2 * (6 + 1) * 2  # functions x (voo grid + random) x seeds
    assert (
        f"{n_runs} runs: 0 already in the store, {n_runs} ran (0 failed)" in capsys.readouterr().out
    )
    assert len(ResultStore(out).load()) == n_runs

    assert main(["bbfo", "--out", str(out), *TINY]) == 0  # resume: nothing to do
    assert f"{n_runs} already in the store, 0 ran" in capsys.readouterr().out

    assert main(["select", str(out)]) == 0
    table = capsys.readouterr().out
    assert (
        "| rastrigin | 3 | 12 | voo | omega=" in table and "| shekel | 3 | 12 | random |" in table
    )

    png, md = tmp_path / "fig.png", tmp_path / "docs" / "table.md"
    assert main(["plot", str(out), "--png", str(png), "--markdown", str(md)]) == 0
    printed = capsys.readouterr().out
    assert png.read_bytes()[:4] == b"\x89PNG"
    text = md.read_text()
    assert "| function | dim | budget | voo | random |" in text and "| shekel | 3 | 12 |" in text
    assert "| function | dim | budget | voo | random |" in printed
    assert main(["plot", str(out), "--regret", "--log", "--methods", "voo"]) == 0
    assert "lower is better" in capsys.readouterr().out


def test_dry_run_lists_cells(capsys: pytest.CaptureFixture[str]) -> None:
    assert (
        main(["bbfo", "--dry-run", "--functions", "shekel", "--methods", "voo", "--seeds", "3"])
        == 0
    )
    cap = capsys.readouterr()
    assert "shekel-20D budget 5000: voo 18" in cap.out
    assert "shekel-3D budget 500" in cap.out
    assert "54 runs" in cap.err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["bbfo", "--functions", "nope"], "unknown function 'nope'; valid functions are:"),
        (["bbfo", "--methods", "vooo"], "unknown method 'vooo'; valid methods are:"),
        (["bbfo", "--seeds", "5:2"], "inverted or empty range '5:2'"),
        (["bbfo", "--seeds", "0"], "--seeds: need at least 1"),
        (["bbfo", "--dims", "x"], "--dims: 'x' is not an integer"),
        (["bbfo", "--budget-scale", "-1"], "budget_scale must be > 0"),
        (["bbfo", "--budget-scale", "inf"], "budget_scale must be > 0"),
        (["bbfo", "--methods", "rembo", "--dims", "3"], "the grid is empty"),
        (["plot", "/nonexistent/store"], "no voot result store here"),
        (["plot", "x", "--log"], "--log needs --regret"),
        (["bbfo", "--instance", "-1"], "instance must be an integer >= 0"),
        (["demo-voo", "--function", "nope"], "unknown function 'nope'"),
        (["speed", "--cases", "voo"], "--cases: 'voo' is not METHOD:N"),
    ],
)
def test_clear_errors(argv: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main([*argv, "--dry-run"] if argv[0] == "bbfo" else argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("voot-bench: error: ") and message in err


def test_corrupt_and_foreign_stores_are_reported_and_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "r"
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", str(out), *small, "--budget", "5", "--workers", "1"]) == 0
    capsys.readouterr()
    victim = ResultStore(out).row_files()[0]
    victim.write_text("{oops")
    for argv in (["bbfo", "--out", str(out), *TINY], ["plot", str(out)], ["select", str(out)]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert str(victim) in err and "corrupt" in err
    assert victim.read_text() == "{oops"

    foreign = tmp_path / "foreign"
    foreign.mkdir()
    (foreign / "data.csv").write_text("a,b\n")
    assert main(["bbfo", "--out", str(foreign), *TINY]) == 2
    assert "not a voot result store" in capsys.readouterr().err
    assert [p.name for p in foreign.iterdir()] == ["data.csv"]


def test_demo_prints_best_optimum_and_regret(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo-voo", "--budget", "200", "--dim", "10"]) == 0
    out = capsys.readouterr().out
    assert "voo on shekel-10D: 200 evaluations" in out
    for word in ("best value found", "known optimum", "regret", "best after   100"):
        assert word in out


def test_speed_table(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    calls = []

    def measure_ask_cost(method: str, n: int, dim: int, repeats: int, seed: int) -> float:
        calls.append((method, n, dim, repeats, seed))
        if method == "gp_ucb":
            raise RuntimeError("too slow today")
        return 0.002

    fake = types.ModuleType("voot.bench.speed")
    fake.measure_ask_cost = measure_ask_cost  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "voot.bench.speed", fake)
    assert main(["speed", "--repeats", "2"]) == 1  # one case failed
    out = capsys.readouterr().out
    assert calls[0] == ("voo", 1000, 20, 2, 0) and ("voo", 5000, 20, 2, 0) in calls
    assert {c[0] for c in calls} == {"voo", "cmaes", "gp_ucb"}
    assert "| voo | 1000 | 2.000 |" in out
    assert "| gp_ucb | 100 | error: RuntimeError: too slow today |" in out
    assert main(["speed", "--cases", "voo:10", "--dim", "3"]) == 0
    assert calls[-1] == ("voo", 10, 3, 5, 0)


PLAN_TINY = [
    "--problems",
    "shekel_chain",
    "--dims",
    "3",
    "--planners",
    "voot",
    "pw_uct",
    "--seeds",
    "2",
    "--simulations",
    "12",
    "--grid",
    "default",
    "--workers",
    "1",
    "--no-progress",
]


def test_plan_plot_select_end_to_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "plan"
    assert main(["plan", "--out", str(out), *PLAN_TINY]) == 0
    assert "4 runs: 0 already in the store, 4 ran (0 failed)" in capsys.readouterr().out
    assert main(["plan", "--out", str(out), *PLAN_TINY]) == 0  # resume: nothing to do
    assert "4 already in the store, 0 ran" in capsys.readouterr().out
    rows = ResultStore(out).load(kind="plan")
    assert len(rows) == 4 and all(len(r["best_so_far"]) == 12 for r in rows)

    png, secs, md = tmp_path / "f4.png", tmp_path / "f4s.png", tmp_path / "docs" / "plan.md"
    argv = ["plot", str(out), "--png", str(png), "--png-seconds", str(secs), "--markdown", str(md)]
    assert main([*argv, "--at", "5", "12"]) == 0
    printed = capsys.readouterr().out
    assert png.read_bytes()[:4] == b"\x89PNG" and secs.read_bytes()[:4] == b"\x89PNG"
    assert "| problem | simulations | voot | pw_uct |" in printed
    assert "| shekel_chain 3-D | 5 |" in printed and "| shekel_chain 3-D | 12 |" in printed
    assert md.read_text().startswith("### Best return")
    assert main(["plot", str(out), "--planners", "voot", "--problems", "shekel-chain"]) == 0
    assert "| problem | simulations | voot |\n" in capsys.readouterr().out

    assert main(["select", str(out)]) == 0
    assert "| shekel_chain | 3 | 12 | voot | default |" in capsys.readouterr().out

    # a store with both kinds needs --kind
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", str(out), *small, "--budget", "5", "--workers", "1"]) == 0
    capsys.readouterr()
    assert main(["plot", str(out)]) == 2
    assert "choose one with --kind" in capsys.readouterr().err
    assert main(["plot", str(out), "--kind", "plan"]) == 0
    assert main(["select", str(out), "--kind", "bbfo"]) == 0
    assert "| rastrigin | 3 | 5 | random |" in capsys.readouterr().out


def test_plan_and_plot_sampling_based_planners(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "mpc"
    argv = ["plan", "--out", str(out), *PLAN_TINY]
    i = argv.index("voot")
    argv[i : i + 2] = ["cem", "voot"]  # a sampling-based planner next to a tree planner
    assert main(argv) == 0
    rows = ResultStore(out).load(kind="plan")
    assert {r["config"]["planner"] for r in rows} == {"cem", "voot"}
    png = tmp_path / "mpc.png"
    assert main(["plot", str(out), "--png", str(png)]) == 0
    printed = capsys.readouterr().out
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert "| problem | simulations | voot | cem |" in printed
    assert "| shekel_chain 3-D | cem |" in printed  # the cost table
    assert main(["plot", str(out), "--planners", "CEM"]) == 0
    assert "| problem | simulations | cem |\n" in capsys.readouterr().out


def test_plan_records_a_run(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rrd = tmp_path / "run.rrd"
    argv = ["plan", "--out", str(tmp_path / "r"), *PLAN_TINY, "--record", str(rrd)]
    argv[argv.index("pw_uct")] = "voot"  # one planner ...
    argv[argv.index("--seeds") + 1] = "1"  # ... one seed: one run, recorded to run.rrd itself
    assert main(argv) == 0
    assert rrd.stat().st_size > 0
    assert ResultStore(tmp_path / "r").load()[0]["recorded"] == str(rrd)
    assert main(argv) == 0  # already done: not run (nor recorded) again
    assert "were not recorded again" in capsys.readouterr().err


def test_plan_dry_run(capsys: pytest.CaptureFixture[str]) -> None:
    assert (
        main(["plan", "--dry-run", "--problems", "kitchen", "conveyor", "--grid", "default"]) == 0
    )
    cap = capsys.readouterr()
    assert "kitchen 2000 simulations, 20 seeds: voot 20, rand_doot 20" in cap.out
    assert "conveyor 3000 simulations, 50 seeds" in cap.out
    assert "350 runs" in cap.err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["plan", "--problems", "nope"], "unknown problem 'nope'"),
        (["plan", "--planners", "vooot"], "unknown planner 'vooot'; valid planners are:"),
        (["plan", "--set", "omega"], "--set: 'omega' is not NAME=VALUE"),
        (["plan", "--set", "depth_limit=0"], "depth_limit must be an integer >= 1"),
        (["plan", "--address", "auto"], "--address and --max-tries go with --backend ray"),
        (["plan", "--record", "r.rrd", "--backend", "ray"], "--record writes .rrd files"),
        (["plan", "--simulations", "0"], "simulations must be integers >= 1"),
        (["plan", "--seeds", "3:1"], "inverted or empty range"),
    ],
)
def test_plan_clear_errors(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main([*argv, "--dry-run"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("voot-bench: error: ") and message in err


def test_plot_options_of_the_other_kind(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "plan"
    argv = ["plan", "--out", str(out), *PLAN_TINY]
    argv[argv.index("--seeds") + 1] = "1"
    assert main(argv) == 0
    assert main(["plot", str(out), "--regret"]) == 2
    assert "apply to bbfo runs" in capsys.readouterr().err
    assert main(["plot", str(out), "--kind", "bbfo"]) == 2
    assert "no finished bbfo runs" in capsys.readouterr().err
    bbfo = tmp_path / "bbfo"
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", str(bbfo), *small, "--budget", "5", "--workers", "1"]) == 0
    assert main(["plot", str(bbfo), "--png-seconds", "x.png"]) == 2
    assert "apply to plan runs" in capsys.readouterr().err


def test_bbfo_instance_runs_apart(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "r"
    small = ["--functions", "griewank", "--dims", "3", "--methods", "soo,random", "--seeds", "2"]
    small += ["--budget", "20", "--workers", "1", "--no-progress"]
    assert main(["bbfo", "--out", str(out), *small, "--dry-run", "--instance", "1"]) == 0
    cap = capsys.readouterr()
    assert "griewank-3D instance 1 budget 20: soo 2, random 2" in cap.out
    assert "4 runs, 80 evaluations, seeds 0..1, instance 1" in cap.err
    assert main(["bbfo", "--out", str(out), *small]) == 0
    assert main(["bbfo", "--out", str(out), *small, "--instance", "1"]) == 0
    assert "4 runs: 0 already in the store, 4 ran" in capsys.readouterr().out  # no collision
    rows = ResultStore(out).load()
    assert sorted(r["config"].get("instance", 0) for r in rows) == [0] * 4 + [1] * 4
    assert len({r["run_id"] for r in rows}) == 8
    # select and plot refuse to mix the instances, and take one with --instance.
    assert main(["select", str(out)]) == 2
    assert "several test-function instances (0, 1)" in capsys.readouterr().err
    assert main(["plot", str(out)]) == 2
    assert "choose one with --instance K" in capsys.readouterr().err
    assert main(["select", str(out), "--instance", "0"]) == 0
    assert "| griewank | 3 | 20 | soo | default | 0 | 2 |" in capsys.readouterr().out
    assert main(["plot", str(out), "--instance", "0", "--regret"]) == 0
    assert "| griewank | 3 | 20 | **0 ± 0 (2)** |" in capsys.readouterr().out  # SOO hits f*
    png = tmp_path / "fig.png"
    assert main(["plot", str(out), "--instance", "1", "--regret", "--png", str(png)]) == 0
    cap = capsys.readouterr()
    assert "instance 1" in cap.out and "test-function instance 1" in cap.err
    assert "| griewank | 3 | 20 | **0 ± 0 (2)** |" not in cap.out  # ... but not shifted f*
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert main(["plot", str(out), "--instance", "2"]) == 2
    assert "no runs of instance 2" in capsys.readouterr().err


def test_parse_range() -> None:
    assert parse_range("3", "s") == [0, 1, 2]
    assert parse_range("5:8", "s") == [5, 6, 7]


SCRIPT = shutil.which("voot-bench", path=str(Path(sys.executable).parent))


@pytest.mark.skipif(SCRIPT is None, reason="console script not installed")
def test_console_script_help() -> None:
    assert SCRIPT is not None
    done = subprocess.run([SCRIPT, "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0
    for command in ("demo", "demo-voo", "bbfo", "plan", "plot", "speed", "select"):
        assert command in done.stdout


def test_demo_plans_on_the_kitchen_and_writes_a_recording(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "demo"
    assert main(["demo", "--simulations", "5", "--seed", "0", "--no-video", "--out", str(out)]) == 0
    assert (out / "kitchen_voot.rrd").stat().st_size > 0
    assert "rerun " in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["bbfo", "--budget-scale", "inf", "--dry-run"], "budget_scale must be > 0 and finite"),
        (
            ["plan", "--problems", "shekel_chain", "--env-kwargs", "dim=5", "--dry-run"],
            "--env-kwargs \\['dim'\\] apply to gymnasium environments",
        ),
    ],
)
def test_cli_errors_that_were_tracebacks_or_silence(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    assert re.search(message, capsys.readouterr().err)


def test_out_under_a_file_is_a_clear_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "file").write_text("x")
    out = str(tmp_path / "file" / "store")
    args = ["bbfo", "--out", out, "--functions", "shekel", "--dims", "3", "--methods", "voo"]
    assert main([*args, "--seeds", "1", "--budget", "5", "--no-progress"]) == 2
    assert "cannot create the result store there" in capsys.readouterr().err


def test_plan_set_sampler_reaches_voo_and_plot_at_beyond_budget(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import json

    out = tmp_path / "p"
    base = ["plan", "--out", str(out), "--problems", "shekel_chain", "--dims", "3"]
    base += ["--planners", "voot", "--seeds", "1", "--simulations", "5", "--grid", "default"]
    assert main([*base, "--set", "sampler=gaussian", "--no-progress"]) == 0
    row = json.loads(next((out / "runs").glob("*.json")).read_text())
    assert row["planner_config"]["sampler"] == "voo"
    assert row["planner_config"]["sampler_options"]["sampler"] == "gaussian"
    capsys.readouterr()
    assert main(["plot", str(out), "--at", "50"]) == 2
    assert "beyond the runs' budget" in capsys.readouterr().err


def test_a_resumed_sweep_says_how_many_runs_are_stored(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = str(tmp_path / "p")
    base = ["plan", "--out", out, "--problems", "shekel_chain", "--dims", "3"]
    base += ["--planners", "voot", "--simulations", "5", "--grid", "default", "--no-progress"]
    assert main([*base, "--seeds", "1"]) == 0
    capsys.readouterr()
    assert main([*base, "--seeds", "2", "--dry-run"]) == 0
    assert "2 runs, 10 simulations; 1 already in the store" in capsys.readouterr().err


@pytest.mark.parametrize("command", ["demo-voo", "speed", "demo", "figure5", "difficulty"])
@pytest.mark.parametrize("seed", ["-1", "1.5", "x"])
def test_every_seed_option_is_checked_by_the_parser(
    command: str, seed: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main([command, "--seed", seed])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert f"argument --seed: must be an integer >= 0, got '{seed}'" in err


TUNE_TINY = [
    "--problems",
    "shekel_chain",
    "--dims",
    "3",
    "--planners",
    "voot",
    "--simulations",
    "8",
    "--workers",
    "1",
    "--no-progress",
]


def test_plan_with_tuning_seeds_end_to_end(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "plan"
    tuned = ["plan", "--out", str(out), *TUNE_TINY, "--tuning-seeds", "1000:1002", "--seeds", "0:2"]
    assert main([*tuned, "--dry-run"]) == 0
    printed = capsys.readouterr()
    assert "tuning: 12 runs (every setting) on seeds 1000-1001" in printed.err
    assert (
        "evaluation: 2 runs (the selected setting) on seeds 0-1, after the tuning runs"
        in printed.err
    )
    assert main([*tuned, "--estimate", "--probe-simulations", "3"]) == 0
    printed = capsys.readouterr().out
    assert (
        "| shekel_chain-3D | voot | 14 | 14 | 112 |" in printed
        and "probe: 3 simulations" in printed
    )
    assert "wall-hours on 1 worker" in printed
    # part of the tuning by hand (seed 1000): the tuned command reuses those very rows
    by_hand = ["plan", "--out", str(out), *TUNE_TINY, "--seeds", "1000:1001"]
    assert main(by_hand) == 0
    capsys.readouterr()
    assert main(tuned) == 0
    printed = capsys.readouterr()
    assert "12 runs: 6 already in the store, 6 ran (0 failed)" in printed.out
    assert "2 runs: 0 already in the store, 2 ran (0 failed)" in printed.out
    assert "settings selected on tuning seeds 1000-1001" in printed.err
    rows = ResultStore(out).load(kind="plan")
    assert len(rows) == 14
    from voot.bench.select import select_hyperparameters

    (sel,) = select_hyperparameters([r for r in rows if r["config"]["seed"] >= 1000])
    evaluation = [r for r in rows if r["config"]["seed"] < 1000]
    assert sorted(r["config"]["seed"] for r in evaluation) == [0, 1]
    assert all(r["config"]["params"] == sel.params for r in evaluation)
    assert main(tuned) == 0  # resume: nothing left
    assert "2 runs: 2 already in the store, 0 ran" in capsys.readouterr().out
    assert main([*tuned, "--estimate"]) == 0
    printed = capsys.readouterr().out
    assert "| shekel_chain-3D | voot | 14 | 0 | 0 |" in printed and "store: 14 rows" in printed

    # plot: the evaluation seeds with the tuned setting, one figure per axis
    figs, md = tmp_path / "figs", tmp_path / "plan.md"
    argv = ["plot", str(out), "--tuning-seeds", "1000:1002", "--axes-dir", str(figs)]
    assert main([*argv, "--markdown", str(md)]) == 0
    printed = capsys.readouterr().out
    for name in ("plan-simulations.png", "plan-calls.png", "plan-cpu-seconds.png"):
        assert (figs / name).read_bytes()[:4] == b"\x89PNG"
        assert f"`{name}`:" in printed
    text = md.read_text()
    assert "Settings selected on tuning seeds 1000-1001, disjoint from the evaluation seeds" in text
    assert f"| shekel_chain 3-D | voot | {sel.best.label} | 2 |" in text
    assert "### Simulator calls: executed steps and pre-checks" in text
    assert main(["plot", str(out)]) == 0  # without the option: the same-seed rule, all seeds
    assert f"| shekel_chain 3-D | voot | {sel.best.label} | 2 |" not in capsys.readouterr().out
    # the claims: a chain store has none of the paper's problems, every line says so
    assert main(["claims", str(out), "--tuning-seeds", "1000:1002"]) == 0
    printed = capsys.readouterr().out
    assert "| no data |" in printed and "reproduced: 0" in printed
    assert "disjoint from the evaluation seeds" in printed


def test_plan_tuning_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = str(tmp_path / "plan")
    base = ["plan", "--out", out, *TUNE_TINY, "--dry-run"]
    assert main([*base, "--tuning-seeds", "0:2", "--seeds", "1:3"]) == 2
    assert "seeds 1 are both tuning and evaluation seeds" in capsys.readouterr().err
    assert main([*base, "--tuning-seeds", "5:2", "--seeds", "0:2"]) == 2
    assert "--tuning-seeds: inverted or empty range" in capsys.readouterr().err
    assert main([*base, "--estimate", "--probe-simulations", "0"]) == 2
    assert "--probe-simulations must be >= 1" in capsys.readouterr().err
    assert main(["plot", out, "--tuning-seeds", "0:2"]) == 2  # no store there
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", out, *small, "--budget", "5", "--workers", "1"]) == 0
    capsys.readouterr()
    assert main(["plot", out, "--axes-dir", str(tmp_path / "f")]) == 2
    assert "apply to plan runs" in capsys.readouterr().err
    assert main(["claims", out]) == 2
    assert "no finished plan runs" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("command", "option"),
    [
        ("plan", "--tuning-seeds"),
        ("plan", "--estimate"),
        ("plot", "plan-cpu-seconds.png"),
        ("claims", "--markdown"),
    ],
)
def test_protocol_options_in_the_help(
    command: str, option: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as done:
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split()).replace("- ", "-")  # undo the wrapping
    assert done.value.code == 0 and option in text


def test_plan_compact_and_compact_commands(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from voot.bench.cli import main
    from voot.bench.compact import CompactConfig
    from voot.bench.store import ResultStore

    base = ["plan", "--problems", "shekel_chain", "--dims", "3", "--planners", "voot"]
    base += ["--seeds", "2", "--simulations", "30", "--grid", "default", "--workers", "1"]
    base += ["--no-progress", "--backend", "serial"]
    assert main([*base, "--out", str(tmp_path / "c"), "--compact", "--compact-points", "9"]) == 0
    store = ResultStore(tmp_path / "c")
    assert store.compact == CompactConfig(points=9)
    assert all("compact" in r for r in store.load(expand=False))
    # resumed without the flag: nothing runs, the store stays compact
    capsys.readouterr()
    assert main([*base, "--out", str(tmp_path / "c")]) == 0
    assert "2 already in the store" in capsys.readouterr().err and len(store) == 2
    assert main([*base, "--out", str(tmp_path / "c"), "--compact"]) == 2  # other settings
    assert "voot-bench compact" in capsys.readouterr().err
    assert main([*base, "--out", str(tmp_path / "f")]) == 0
    assert main(["compact", str(tmp_path / "f"), str(tmp_path / "f2"), "--points", "5"]) == 0
    out = capsys.readouterr().out
    assert "2 rows in" in out and "2 copied now" in out
    assert ResultStore(tmp_path / "f2").compact == CompactConfig(points=5)
    with pytest.raises(SystemExit):  # argparse lists the valid spacings
        main(["compact", str(tmp_path / "f"), str(tmp_path / "f3"), "--spacing", "cubic"])
    assert "choose from 'log', 'linear'" in capsys.readouterr().err
    assert main(["compact", str(tmp_path / "f"), str(tmp_path / "f3"), "--points", "1"]) == 2
    assert "points must be" in capsys.readouterr().err


def test_store_speed_prints_both_layouts(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    from voot.bench import store as store_mod
    from voot.bench.cli import main

    monkeypatch.setattr(store_mod, "RACY_NS", 0)
    assert main(["store-speed", "--rows", "2", "--length", "300", "--repeats", "1"]) == 0
    out = capsys.readouterr().out
    assert "| full |" in out and "| compact |" in out
    assert main(["store-speed", "--rows", "0"]) == 2
