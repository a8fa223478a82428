"""The environments' speed benchmark command (voot.bench.measure.env_speed, ``voot-bench
measure env-speed``) runs; no timing assertions."""

from __future__ import annotations

import re

import pytest

from voot.bench.cli.main import main


def test_run_and_report(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["measure", "env-speed", "--n", "4"]) == 0
    out = capsys.readouterr().out
    assert "kitchen pick (6-D)" in out and "conveyor place x3 (9-D)" in out
    assert "snapshot restore" in out
    assert len(re.findall(r"\| \d+/4", out)) == 3  # feasible counts of 4 actions per operator
    assert re.search(r"first box: \d+\)", out)


def test_bad_arguments(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["measure", "env-speed", "--n", "0"]) == 2
    assert "--n must be >= 1" in capsys.readouterr().err
