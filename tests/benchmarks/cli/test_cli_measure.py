"""Tests of voot.bench.cli.measure: ``voot-bench measure speed`` and its cases, ``memory``
(``voo-speed``, ``overhead``, ``record-overhead`` and ``root-parallel``: with their
measurements in tests/benchmarks/measure; ``store-speed``: test_cli_store.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.common import CLIError
from voot.bench.cli.main import main
from voot.bench.cli.measure import SPEED_CASES, parse_cases
from voot.bench.measure import speed


def test_speed_table(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    calls = []

    def measure_ask_cost(method: str, n: int, dim: int, repeats: int, seed: int) -> float:
        calls.append((method, n, dim, repeats, seed))
        if method == "gp_ucb":
            raise RuntimeError("too slow today")
        return 0.002

    monkeypatch.setattr(speed, "measure_ask_cost", measure_ask_cost)
    assert main(["measure", "speed", "--repeats", "2"]) == 1  # one case failed
    out = capsys.readouterr().out
    assert calls[0] == ("voo", 1000, 20, 2, 0) and ("voo", 5000, 20, 2, 0) in calls
    assert {c[0] for c in calls} == {"voo", "cmaes", "gp_ucb"}
    assert "| voo | 1000 | 2.000 |" in out
    assert "| gp_ucb | 100 | error: RuntimeError: too slow today |" in out
    assert main(["measure", "speed", "--cases", "voo:10", "--dim", "3"]) == 0
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


def test_memory_prints_a_table_per_planner(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["measure", "memory", "--problem", "shekel_chain", "--planners", "voot,pw_uct"]
    assert main([*argv, "--simulations", "20", "--checkpoints", "2"]) == 0
    out = capsys.readouterr().out
    assert "voot on shekel_chain, seed 0:" in out and "pw_uct on shekel_chain, seed 0:" in out
    assert out.count("| 20 |") == 2 and out.count("| 10 |") == 2
    assert out.count("(1 = linear in the tree)") == 2


@pytest.mark.parametrize("flag", ["--simulations", "--checkpoints"])
def test_memory_refuses_zero_counts(flag: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["measure", "memory", flag, "0"]) == 2
    assert "must be >= 1" in capsys.readouterr().err


@pytest.mark.parametrize("option", ["--json", "--figure"])
def test_root_parallel_outputs_under_a_file_are_refused_before_measuring(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str
) -> None:
    from cli_fixtures import assert_refused

    (tmp_path / "file").write_text("x")
    argv = ["measure", "root-parallel", option, str(tmp_path / "file" / "out")]
    assert_refused(argv, tmp_path, capsys, option, "is a file, not a folder")
