"""Tests of voot.bench.cli.main: the dispatcher (every command and measurement registered with
a parser and its --help, in the order of the help; the measurements' old spellings; the
version), errors as one line and exit status 2, the seed options, the console script."""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import voot
from voot.bench.cli.main import COMMANDS, MEASUREMENTS, build_parser, main, measurement_names

#: The researcher's commands in the order ``voot-bench --help`` lists them.
RESEARCH = (
    "demo record-demo figure5 demo-voo env-figures bbfo plan ablation select plot claims"
    " difficulty ladder compact shipped export measure"
).split()
#: The measurements in the order ``voot-bench measure --help`` lists them.
MEASURE = (
    "speed voo-speed overhead record-overhead memory root-parallel store-speed env-speed"
    " mesh-speed speedup footprint-speed domain-ablation"
).split()


def listed_commands(argv: list[str], capsys: pytest.CaptureFixture[str]) -> list[str]:
    """The commands the help of ``voot-bench ARGV --help`` lists."""
    with pytest.raises(SystemExit) as done:
        main([*argv, "--help"])
    assert done.value.code == 0
    return re.findall(r"^    (\S+)", capsys.readouterr().out, flags=re.MULTILINE)


def test_the_commands_in_the_order_of_the_help(capsys: pytest.CaptureFixture[str]) -> None:
    assert len(COMMANDS) == 7 and len(MEASUREMENTS) == 5
    assert listed_commands([], capsys) == RESEARCH
    assert listed_commands(["measure"], capsys) == MEASURE
    assert measurement_names(build_parser()) == MEASURE


@pytest.mark.parametrize(
    "argv", [[name] for name in RESEARCH if name != "measure"] + [["measure", m] for m in MEASURE]
)
def test_every_command_has_a_parser_with_help_and_a_handler(
    argv: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    parser = build_parser()
    for word in argv:
        (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
        parser = sub.choices[word]
    assert callable(parser.get_default("func"))
    with pytest.raises(SystemExit) as done:
        main([*argv, "--help"])
    out = capsys.readouterr().out
    assert done.value.code == 0 and out.startswith(f"usage: voot-bench {' '.join(argv)} ")
    assert not re.search(r"\bissues? \d", out)  # no internal issue numbers in the help


@pytest.mark.parametrize("name", MEASURE)
def test_a_measurement_without_measure_is_the_same_command(
    name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit):
        main([name, "--help"])
    old = capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["measure", name, "--help"])
    assert old == capsys.readouterr().out and name not in listed_commands([], capsys)


ROOT = Path(__file__).resolve().parents[3]


def test_every_command_the_docs_name_is_registered() -> None:
    """Every ``voot-bench NAME`` in the code of the README and docs/ (a code span or a line
    of a code block) is a command, and every ``voot-bench measure NAME`` a measurement (the
    docs spell measurements with ``measure``)."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    named = [
        (page.name, m.group(1), m.group(2))
        for page in pages
        for m in re.finditer(
            r"(?:^|`)(?:nice )?voot-bench ([a-z][\w-]*)(?: ([a-z][\w-]*))?",
            page.read_text(),
            flags=re.MULTILINE,
        )
    ]
    assert len(named) > 50
    for page, first, second in named:
        assert first in RESEARCH, (page, first)
        if first == "measure":
            assert second is None or second in MEASURE, (page, second)


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0 and capsys.readouterr().out == f"voot-bench {voot.__version__}\n"


def test_an_interrupt_is_exit_status_130(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from voot.bench.cli import measure as cli_measure

    def interrupted(args: object) -> int:
        raise KeyboardInterrupt

    monkeypatch.setattr(cli_measure, "cmd_speed", interrupted)
    assert main(["measure", "speed"]) == 130
    assert "interrupted; finished runs are saved" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["bbfo", "--functions", "nope"], "unknown function 'nope'; valid functions are:"),
        (["bbfo", "--methods", "vooo"], "unknown method 'vooo'; valid methods are:"),
        (["bbfo", "--seeds", "5:2"], "inverted or empty range '5:2'"),
        (["bbfo", "--seeds", "0"], "--seeds: need at least 1"),
        (["bbfo", "--dims", "x"], "--dims: 'x' is not an integer"),
        (["bbfo", "--budget-scale", "-1"], "budget_scale must be > 0"),
        (["bbfo", "--budget-scale", "inf"], "budget_scale must be > 0"),
        (["bbfo", "--methods", "rembo", "--dims", "3"], "the grid is empty"),
        (["plot", "/nonexistent/store"], "no voot result store here"),
        (["plot", "x", "--log"], "--log needs --regret"),
        (["bbfo", "--instance", "-1"], "instance must be an integer >= 0"),
        (["demo-voo", "--function", "nope"], "unknown function 'nope'"),
        (["measure", "speed", "--cases", "voo"], "--cases: 'voo' is not METHOD:N"),
        # once a traceback, and silence
        (["bbfo", "--budget-scale", "inf"], "budget_scale must be > 0 and finite"),
        (
            ["plan", "--problems", "shekel_chain", "--env-kwargs", "dim=5"],
            "--env-kwargs ['dim'] apply to gymnasium environments",
        ),
        (["plan", "--problems", "nope"], "unknown problem 'nope'"),
        (["plan", "--planners", "vooot"], "unknown planner 'vooot'; valid planners are:"),
        (["plan", "--set", "omega"], "--set: 'omega' is not NAME=VALUE"),
        (["plan", "--set", "depth_limit=0"], "depth_limit must be an integer >= 1"),
        (["plan", "--address", "auto"], "--address and --max-tries go with --backend ray"),
        (["plan", "--record", "r.rrd", "--backend", "ray"], "--record writes .rrd files"),
        (["plan", "--simulations", "0"], "simulations must be integers >= 1"),
        (["plan", "--seeds", "3:1"], "inverted or empty range"),
    ],
)
def test_clear_errors(argv: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    """A user error is one line and exit status 2 (a sweep's with --dry-run: it runs nothing)."""
    assert main([*argv, "--dry-run"] if argv[0] in ("bbfo", "plan") else argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("voot-bench: error: ") and message in err


@pytest.mark.parametrize(
    ("argv", "out", "err"),
    [
        (
            ["bbfo", "--functions", "shekel", "--methods", "voo", "--seeds", "3"],
            ["shekel-20D budget 5000: voo 18", "shekel-3D budget 500"],
            "54 runs",
        ),
        (
            ["plan", "--problems", "kitchen", "conveyor", "--grid", "default"],
            [
                "kitchen 2000 simulations, 20 seeds: voot 20, rand_doot 20",
                "conveyor 3000 simulations, 50 seeds",
            ],
            "350 runs",
        ),
    ],
)
def test_a_dry_run_lists_the_runs(
    argv: list[str], out: list[str], err: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main([*argv, "--dry-run"]) == 0
    cap = capsys.readouterr()
    assert all(line in cap.out for line in out) and err in cap.err


SEEDED = ["demo-voo", "demo", "record-demo", "figure5", "difficulty", "ladder"]


@pytest.mark.parametrize(
    "command",
    [[c] for c in SEEDED]
    + [["measure", m] for m in ("speed", "voo-speed", "overhead", "record-overhead", "memory")]
    + [["measure", "env-speed"]],
)
@pytest.mark.parametrize("seed", ["-1", "1.5", "x"])
def test_every_seed_option_is_checked_by_the_parser(
    command: list[str], seed: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main([*command, "--seed", seed])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert f"argument --seed: must be an integer >= 0, got '{seed}'" in err


@pytest.mark.parametrize(
    ("command", "option"),
    [
        ("plan", "--tuning-seeds"),
        ("plan", "--estimate"),
        ("plot", "plan-cpu-seconds.png"),
        ("claims", "--markdown"),
    ],
)
def test_protocol_options_in_the_help(
    command: str, option: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as done:
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split()).replace("- ", "-")  # undo the wrapping
    assert done.value.code == 0 and option in text


SCRIPT = shutil.which("voot-bench", path=str(Path(sys.executable).parent))


@pytest.mark.skipif(SCRIPT is None, reason="console script not installed")
def test_console_script_help() -> None:
    assert SCRIPT is not None
    done = subprocess.run([SCRIPT, "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0
    for command in ("demo", "demo-voo", "bbfo", "plan", "plot", "measure", "select"):
        assert command in done.stdout
