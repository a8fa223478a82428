"""End-to-end tests of the voot-bench command line on a tiny grid."""

from __future__ import annotations

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
        (["bbfo", "--methods", "rembo", "--dims", "3"], "the grid is empty"),
        (["plot", "/nonexistent/store"], "no voot result store here"),
        (["plot", "x", "--log"], "--log needs --regret"),
        (["demo", "--function", "nope"], "unknown function 'nope'"),
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
    assert main(["demo", "--budget", "200", "--dim", "10"]) == 0
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


def test_parse_range() -> None:
    assert parse_range("3", "s") == [0, 1, 2]
    assert parse_range("5:8", "s") == [5, 6, 7]


SCRIPT = shutil.which("voot-bench", path=str(Path(sys.executable).parent))


@pytest.mark.skipif(SCRIPT is None, reason="console script not installed")
def test_console_script_help() -> None:
    assert SCRIPT is not None
    done = subprocess.run([SCRIPT, "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0
    for command in ("demo", "bbfo", "plot", "speed", "select"):
        assert command in done.stdout
