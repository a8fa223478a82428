"""The environments' speed benchmark command (voot.bench.measure.env_speed, voot-bench env-speed) runs; no timing assertions."""

from __future__ import annotations

import re

import pytest

from voot.bench.measure import env_speed as speed


def test_run_and_report(capsys: pytest.CaptureFixture[str]) -> None:
    speed.main(["--n", "4"])
    out = capsys.readouterr().out
    assert "kitchen pick (6-D)" in out and "conveyor place x3 (9-D)" in out
    assert "snapshot restore" in out
    assert len(re.findall(r"\| \d+/4", out)) == 3  # feasible counts of 4 actions per operator
    assert re.search(r"first box: \d+\)", out)


def test_bad_arguments() -> None:
    with pytest.raises(SystemExit):
        speed.main(["--n", "0"])
