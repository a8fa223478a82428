"""Tests of voot.bench.measure.overhead: the planner's own overhead and the cost of recording."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main
from voot.bench.measure.overhead import measure, measure_overhead


def test_measure_counts_visits() -> None:
    row = measure("voot", 3, 50, depth=5)
    assert row["node_visits"] == 250 and row["simulations"] == 50
    assert float(row["us_per_visit"]) > 0


def test_the_overhead_command_prints_a_table(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["measure", "overhead", "--planners", "voot", "hoot", "--dims", "2"]
    assert main([*argv, "--simulations", "20"]) == 0
    out = capsys.readouterr().out
    assert "us/visit" in out and "voot" in out and "hoot" in out


def test_measure_returns_the_figures(tmp_path: Path) -> None:
    row = measure_overhead("null", dim=2, n_simulations=30, repeats=1, directory=tmp_path)
    assert row["problem"] == "null" and row["simulations"] == 30
    assert row["off_s"] > 0 and row["on_s"] > 0 and row["setup_s"] > 0
    assert row["ratio"] == pytest.approx(row["on_s"] / row["off_s"])
    assert row["rrd_bytes"] > 1000
    assert row["n_nodes"] > 30
    assert list(tmp_path.iterdir()) == []  # the recordings are temporary


def test_shekel_chain_setup_and_errors(capsys: pytest.CaptureFixture[str]) -> None:
    row = measure_overhead("shekel", dim=3, n_simulations=5)
    assert row["n_nodes"] == 6
    with pytest.raises(ValueError, match="valid problems are: shekel, null"):
        measure_overhead("nope")
    with pytest.raises(ValueError, match="repeats"):
        measure_overhead("null", repeats=0)
    argv = ["measure", "record-overhead", "--problems", "null", "--dim", "2"]
    assert main([*argv, "--simulations", "10", "--repeats", "1"]) == 0
    out = capsys.readouterr().out
    assert "ratio" in out and out.strip().splitlines()[-1].startswith("null")
