"""Tests of ``voot-bench measure mesh-speed`` (voot.bench.cli.env_cost; ``env-speed``:
tests/benchmarks/measure/test_env_speed.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main


def test_mesh_speed_prints_its_tables(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("VOOT_CACHE", str(tmp_path / "cache"))
    argv = ["measure", "mesh-speed", "--kinds", "box", "plate", "--repeats", "1", "--calls", "200"]
    assert main([*argv, "--no-scene"]) == 0
    out = capsys.readouterr().out
    assert "| box | 0.1 x 0.15 x 0.2 | 12 | 1 |" in out
    assert "| plate |" in out and "scene of" not in out
    assert out.count("| box |") == 2  # the shape table and the lookup table
    assert not (tmp_path / "cache").exists()  # measured in a temporary cache


def test_mesh_speed_rejects_bad_arguments(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["measure", "mesh-speed", "--kinds", "teapot"]) == 2
    assert "unknown kind 'teapot'; valid kinds: box, crate" in capsys.readouterr().err
    assert main(["measure", "mesh-speed", "--repeats", "0"]) == 2
    assert "--repeats and --calls must be >= 1" in capsys.readouterr().err
