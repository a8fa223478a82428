"""Tests of ``voot-bench leaderboard`` (run, report, card, verify) on the tests' tiny
suite: the estimate printed before running, nothing redone on a rerun, verify's exit
status on a genuine and a tampered store, clear errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from leaderboard_fixtures import tiny_store, tiny_suite_file

from voot.bench.cli.main import main
from voot.bench.store.format import row_bytes
from voot.bench.store.result_store import ResultStore


def test_run_prints_the_cost_first_and_resumes_without_redoing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    store = tiny_store(tmp_path)
    suite = str(tiny_suite_file())
    assert (
        main(["leaderboard", "run", "--suite", suite, "--out", str(store), "--estimate-only"]) == 0
    )
    out = capsys.readouterr()
    assert "CPU cost of the runs still to do" in out.out and "total: 0 runs to run" in out.out
    assert "6 already in" in out.err
    args = ["leaderboard", "run", "--suite", suite, "--out", str(store), "--workers", "1"]
    assert main([*args, "--backend", "serial", "--no-progress"]) == 0
    out = capsys.readouterr()
    assert out.out.index("CPU cost") < out.out.index("0 ran")
    assert "6 already in the store, 0 ran" in out.out or "already in the store, 0 ran" in out.out


def test_estimate_only_runs_nothing(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "new"
    code = main(
        [
            "leaderboard",
            "run",
            "--suite",
            str(tiny_suite_file()),
            "--out",
            str(out),
            "--planners",
            "random_shooting",
            "--estimate-only",
            "--probe-simulations",
            "2",
        ]
    )
    assert code == 0
    text = capsys.readouterr().out
    assert "random_shooting" in text and "probe: 2 simulations" in text
    assert "doot" not in text.split("total:")[0]
    assert not out.exists()


def test_report_card_and_verify(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    store = tiny_store(tmp_path)
    suite = str(tiny_suite_file())
    page = tmp_path / "page.md"
    page.write_text("# Leaderboard\n<!-- leaderboard:start -->\n<!-- leaderboard:end -->\n")
    assert main(["leaderboard", "report", str(store), "--suite", suite, "--page", str(page)]) == 0
    assert "### Aggregated over the complete cells" in page.read_text()
    assert main(["leaderboard", "card", str(store), "--suite", suite]) == 0
    assert main(["leaderboard", "verify", str(store), "--suite", suite, "--sample", "2"]) == 0
    assert "2 match bit for bit, 0 differ" in capsys.readouterr().out
    # a tampered row with a valid checksum, re-carded: the re-run catches it
    path = sorted(ResultStore(store, create=False).row_files())[0]
    row = json.loads(path.read_bytes())
    row.pop("checksum")
    row["n_steps"] += 1
    path.write_bytes(row_bytes(row))
    assert main(["leaderboard", "verify", str(store), "--suite", suite]) == 2  # stale cards
    assert "store checksum" in capsys.readouterr().err
    assert main(["leaderboard", "card", str(store), "--suite", suite]) == 0
    assert main(["leaderboard", "verify", str(store), "--suite", suite, "--sample", "6"]) == 1
    err = capsys.readouterr().err
    assert f"MISMATCH {row['run_id']}" in err and "n_steps" in err


def test_clear_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["leaderboard", "report", str(tmp_path / "none")]) == 2
    assert "no voot result store" in capsys.readouterr().err
    assert main(["leaderboard", "run", "--suite", "v7", "--out", str(tmp_path / "x")]) == 2
    assert "valid suites are: v1" in capsys.readouterr().err
    code = main(
        [
            "leaderboard",
            "run",
            "--planners",
            "nosuch",
            "--out",
            str(tmp_path / "x"),
            "--estimate-only",
        ]
    )
    assert code == 2 and "unknown planner 'nosuch'" in capsys.readouterr().err


@pytest.mark.ray
def test_a_run_on_ray_gives_the_rows_of_a_serial_run(tmp_path: Path) -> None:
    """``--backend ray`` (a local instance the command starts) writes the same runs as the
    serial backend, bit for bit once timings are set aside."""
    ray = pytest.importorskip("ray")
    from voot.bench.sweep.plan import strip_timings

    rows = {}
    for backend in ("serial", "ray"):
        out = tmp_path / backend
        args = ["leaderboard", "run", "--suite", str(tiny_suite_file()), "--out", str(out)]
        assert main([*args, "--backend", backend, "--workers", "2", "--no-progress"]) == 0
        loaded = ResultStore(out, create=False).load(kind="plan")
        rows[backend] = {r["run_id"]: strip_timings(r) for r in loaded}
    assert len(rows["ray"]) == 6
    assert rows["ray"] == rows["serial"]
    assert not ray.is_initialized()  # the instance the command started is stopped
