"""Tests of ``voot-bench select``, ``plot`` and ``claims``: options of the other kind of
run are refused."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli import main

PLAN_TINY = [
    "--problems",
    "shekel_chain",
    "--dims",
    "3",
    "--planners",
    "voot",
    "pw_uct",
    "--seeds",
    "2",
    "--simulations",
    "12",
    "--grid",
    "default",
    "--workers",
    "1",
    "--no-progress",
]


def test_plot_options_of_the_other_kind(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "plan"
    argv = ["plan", "--out", str(out), *PLAN_TINY]
    argv[argv.index("--seeds") + 1] = "1"
    assert main(argv) == 0
    assert main(["plot", str(out), "--regret"]) == 2
    assert "apply to bbfo runs" in capsys.readouterr().err
    assert main(["plot", str(out), "--kind", "bbfo"]) == 2
    assert "no finished bbfo runs" in capsys.readouterr().err
    bbfo = tmp_path / "bbfo"
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", str(bbfo), *small, "--budget", "5", "--workers", "1"]) == 0
    assert main(["plot", str(bbfo), "--png-seconds", "x.png"]) == 2
    assert "apply to plan runs" in capsys.readouterr().err
