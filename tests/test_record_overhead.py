"""Tests of voot.record.overhead: the cost of recording (figures in docs/recordings.md)."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("rerun")

from voot.record.overhead import main, measure_overhead


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
    assert main(["--problems", "null", "--dim", "2", "--simulations", "10", "--repeats", "1"]) == 0
    out = capsys.readouterr().out
    assert "ratio" in out and out.strip().splitlines()[-1].startswith("null")
