"""Tests of voot.bench.cli.memory: ``voot-bench memory`` prints a table per planner and
checks its counts."""

from __future__ import annotations

import pytest

from voot.bench.cli.main import main


def test_memory_prints_a_table_per_planner(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["memory", "--problem", "shekel_chain", "--planners", "voot,pw_uct"]
    assert main([*argv, "--simulations", "20", "--checkpoints", "2"]) == 0
    out = capsys.readouterr().out
    assert "voot on shekel_chain, seed 0:" in out and "pw_uct on shekel_chain, seed 0:" in out
    assert out.count("| 20 |") == 2 and out.count("| 10 |") == 2
    assert out.count("(1 = linear in the tree)") == 2


@pytest.mark.parametrize("flag", ["--simulations", "--checkpoints"])
def test_memory_refuses_zero_counts(flag: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["memory", flag, "0"]) == 2
    assert "must be >= 1" in capsys.readouterr().err
