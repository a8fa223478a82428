"""End-to-end tests of ``voot-bench bbfo`` on a tiny grid (with select and plot on its
store)."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main
from voot.bench.store.result_store import ResultStore

TINY = (
    "--functions rastrigin,shekel --dims 3 --methods voo random --seeds 2 --budget 12"
    " --workers 1 --no-progress"
).split()


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


def test_out_under_a_file_is_a_clear_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "file").write_text("x")
    out = str(tmp_path / "file" / "store")
    args = ["bbfo", "--out", out, "--functions", "shekel", "--dims", "3", "--methods", "voo"]
    assert main([*args, "--seeds", "1", "--budget", "5", "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "is a file, not a folder" in err  # refused before any run
    assert not (tmp_path / "file" / "store").exists()
