"""Tests of ``voot-bench measure mesh-speed`` (voot.bench.cli.env_cost; ``env-speed``:
tests/benchmarks/measure/test_env_speed.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from cli_fixtures import assert_refused

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


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["measure", "domain-ablation", "--draws", "0"], "--draws must be >= 1"),
        (["measure", "domain-ablation", "--switches", "walls"], "valid switches: v1"),
        (["measure", "domain-ablation", "--executions-for", "walls=3"], "unknown switch 'walls'"),
        (["measure", "domain-ablation", "--executions-for", "v1=0"], "give SWITCH=N with N >= 1"),
        (["measure", "domain-ablation", "--executions-for", "v1"], "give SWITCH=N with N >= 1"),
        (["measure", "domain-ablation", "--out", "{file}/x.json"], "is a file, not a folder"),
        (["measure", "domain-ablation", "--table", "{file}"], "not a readable domain-ablation"),
        (["measure", "footprint-speed", "--rollouts", "0"], "--rollouts must be >= 1"),
        (["measure", "footprint-speed", "--repeats", "0"], "--repeats must be >= 1"),
        (["leaderboard", "run", "--out", "{file}/store", "--estimate-only"], "is a file"),
    ],
)
def test_new_measurements_refuse_bad_options_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str], needle: str
) -> None:
    file = tmp_path / "a-file"
    file.write_text("not a store\n")
    assert_refused([a.format(file=file) for a in argv], tmp_path, capsys, needle)
