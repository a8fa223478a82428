"""Tests of voot.bench.cli.speedup: ``voot-bench measure speedup`` reports its errors as one line
(the comparison itself: tests/benchmarks/measure/test_speedup.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main


def test_cli_errors(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["measure", "speedup", "--workloads", "nope"]) == 2
    assert "unknown workload" in capsys.readouterr().err
    assert main(["measure", "speedup", "--v1", "--simulations", "x"]) == 2
    assert capsys.readouterr().err.startswith("voot-bench: error: ")


def test_speedup_json_under_a_file_is_refused_before_measuring(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from cli_fixtures import assert_refused

    (tmp_path / "file").write_text("x")
    argv = ["measure", "speedup", "--json", str(tmp_path / "file" / "s.json")]
    assert_refused(argv, tmp_path, capsys, "--json", "is a file, not a folder")
