"""Tests of ``voot-bench demo-voo`` and ``demo``."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli import main


def test_demo_prints_best_optimum_and_regret(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo-voo", "--budget", "200", "--dim", "10"]) == 0
    out = capsys.readouterr().out
    assert "voo on shekel-10D: 200 evaluations" in out
    for word in ("best value found", "known optimum", "regret", "best after   100"):
        assert word in out


def test_demo_plans_on_the_kitchen_and_writes_a_recording(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "demo"
    assert main(["demo", "--simulations", "5", "--seed", "0", "--no-video", "--out", str(out)]) == 0
    assert (out / "kitchen_voot.rrd").stat().st_size > 0
    assert "rerun " in capsys.readouterr().out
