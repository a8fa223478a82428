"""Tests of voot.bench.cli.measure: ``voot-bench speed`` and its cases, ``ladder`` (``difficulty``:
tests/benchmarks/protocol/test_difficulty.py)."""

from __future__ import annotations

import sys
import types
from pathlib import Path

import pytest

from voot.bench.cli.common import CLIError
from voot.bench.cli.main import main
from voot.bench.cli.measure import SPEED_CASES, parse_cases


def test_speed_table(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    calls = []

    def measure_ask_cost(method: str, n: int, dim: int, repeats: int, seed: int) -> float:
        calls.append((method, n, dim, repeats, seed))
        if method == "gp_ucb":
            raise RuntimeError("too slow today")
        return 0.002

    fake = types.ModuleType("voot.bench.measure.speed")
    fake.measure_ask_cost = measure_ask_cost  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "voot.bench.measure.speed", fake)
    assert main(["speed", "--repeats", "2"]) == 1  # one case failed
    out = capsys.readouterr().out
    assert calls[0] == ("voo", 1000, 20, 2, 0) and ("voo", 5000, 20, 2, 0) in calls
    assert {c[0] for c in calls} == {"voo", "cmaes", "gp_ucb"}
    assert "| voo | 1000 | 2.000 |" in out
    assert "| gp_ucb | 100 | error: RuntimeError: too slow today |" in out
    assert main(["speed", "--cases", "voo:10", "--dim", "3"]) == 0
    assert calls[-1] == ("voo", 10, 3, 5, 0)


def test_parse_cases() -> None:
    assert parse_cases(None) == list(SPEED_CASES)
    assert parse_cases(["VOO:10,cmaes:5", "gp-ucb:2"]) == [
        ("voo", 10),
        ("cmaes", 5),
        ("gp_ucb", 2),
    ]
    with pytest.raises(CLIError, match="N must be >= 1 in 'voo:0'"):
        parse_cases(["voo:0"])
    with pytest.raises(ValueError, match="unknown method"):
        parse_cases(["nope:3"])


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
