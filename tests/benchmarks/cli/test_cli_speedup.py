"""Tests of voot.bench.cli.speedup: ``voot-bench measure speedup`` reports its errors as one line
(the comparison itself: tests/benchmarks/measure/test_speedup.py)."""

from __future__ import annotations

import pytest

from voot.bench.cli.main import main


def test_cli_errors(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["measure", "speedup", "--workloads", "nope"]) == 2
    assert "unknown workload" in capsys.readouterr().err
    assert main(["measure", "speedup", "--v1", "--simulations", "x"]) == 2
    assert capsys.readouterr().err.startswith("voot-bench: error: ")
