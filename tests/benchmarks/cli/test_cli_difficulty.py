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


def test_ladder_refuses_before_measuring(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Bad options are refused before a minute is spent: no traceback, nothing written."""
    from cli_fixtures import assert_refused

    (tmp_path / "file").write_text("x")
    tiny = ["ladder", "--layouts", "1", "--samples", "1", "--rollouts", "1", "--levels", "easy"]
    md = ["--markdown", str(tmp_path / "file" / "t.md")]
    assert_refused([*tiny, *md], tmp_path, capsys, "--markdown", "is a file, not a folder")
    for env in ("kitchen_v1", "voot/ConveyorPacking-v1", "CartPole-v1"):
        assert_refused(
            [*tiny, "--env", env], tmp_path, capsys, f"--env {env}", "is not a generated family"
        )
    assert_refused(
        [*tiny[:-1], "extreme"], tmp_path, capsys, "--levels", "valid levels are: easy, medium"
    )
    big = "9223372036854775808:9223372036854775809"
    assert_refused([*tiny[:2], big], tmp_path, capsys, "--layouts", "layout seeds must be")


def test_difficulty_refuses_a_markdown_path_under_a_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from cli_fixtures import assert_refused

    (tmp_path / "file").write_text("x")
    argv = ["difficulty", "--samples", "1", "--rollouts", "1"]
    assert_refused(
        [*argv, "--markdown", str(tmp_path / "file" / "d.md")], tmp_path, capsys, "--markdown"
    )
