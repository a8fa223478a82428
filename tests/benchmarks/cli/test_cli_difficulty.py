"""Tests of voot.bench.cli.difficulty: ``voot-bench ladder`` (``difficulty``:
tests/benchmarks/protocol/test_difficulty.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main


def test_ladder_prints_and_writes_the_tables(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "ladder.md"
    argv = ["ladder", "--env", "kitchen_v2", "--levels", "easy", "--layouts", "0:1"]
    assert main([*argv, "--samples", "5", "--rollouts", "1", "--markdown", str(out)]) == 0
    text = out.read_text()
    assert "Difficulty ladder of voot/KitchenClearing-v2: layouts 0;" in text
    assert text.strip() in capsys.readouterr().out
    assert main([*argv, "--samples", "0"]) == 2
    assert "--samples must be >= 1" in capsys.readouterr().err
    assert main([*argv, "--layouts", "x"]) == 2
