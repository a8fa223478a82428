"""Tests of the argparse converters of the command line (voot.bench.cli.types)."""

from __future__ import annotations

import argparse

import pytest

from voot.bench.cli.types import seed_argument


def test_seed_argument() -> None:
    assert seed_argument("12") == 12
    assert seed_argument("0") == 0
    for bad in ("-1", "1.5", "x", ""):
        with pytest.raises(argparse.ArgumentTypeError, match="must be an integer >= 0"):
            seed_argument(bad)


def test_argparse_reports_the_option_and_the_rule(capsys: pytest.CaptureFixture[str]) -> None:
    parser = argparse.ArgumentParser(prog="voot-bench x")
    parser.add_argument("--seed", type=seed_argument, default=0)
    assert parser.parse_args(["--seed", "7"]).seed == 7
    with pytest.raises(SystemExit):
        parser.parse_args(["--seed", "-3"])
    assert "argument --seed: must be an integer >= 0, got '-3'" in capsys.readouterr().err
