"""Tests of voot.bench.cli.main: the dispatcher (every subcommand registered, in the order of
the help), errors as one line and exit status 2, the seed options, the console script."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from voot.bench.cli.main import SUBCOMMANDS, build_parser, main
from voot.bench.cli.passthrough import PASSTHROUGH

#: The subcommands in the order ``voot-bench --help`` lists them.
COMMANDS = [
    "demo",
    "figure5",
    "demo-voo",
    "bbfo",
    "plan",
    "ablation",
    "compact",
    "shipped",
    "store-speed",
    "select",
    "plot",
    "claims",
    "speed",
    "difficulty",
    "ladder",
    "mesh-speed",
    "memory",
    *PASSTHROUGH,
    "speedup",
]


def test_every_subcommand_is_registered_once_in_the_order_of_the_help(
    capsys: pytest.CaptureFixture[str],
) -> None:
    parser = build_parser()
    (sub,) = [a for a in parser._actions if a.dest == "command"]
    assert list(sub.choices) == COMMANDS  # type: ignore[union-attr]
    assert len(SUBCOMMANDS) == 11
    with pytest.raises(SystemExit) as done:
        main(["--help"])
    listed = re.findall(r"^    (\S+)", capsys.readouterr().out, flags=re.MULTILINE)
    assert done.value.code == 0 and listed == COMMANDS
    for name, p in sub.choices.items():  # type: ignore[union-attr]
        assert callable(p.get_default("func")), name


def test_an_interrupt_is_exit_status_130(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from voot.bench.cli import measure as cli_measure

    def interrupted(args: object) -> int:
        raise KeyboardInterrupt

    monkeypatch.setattr(cli_measure, "cmd_speed", interrupted)
    assert main(["speed"]) == 130
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
        (["speed", "--cases", "voo"], "--cases: 'voo' is not METHOD:N"),
    ],
)
def test_clear_errors(argv: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main([*argv, "--dry-run"] if argv[0] == "bbfo" else argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("voot-bench: error: ") and message in err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["bbfo", "--budget-scale", "inf", "--dry-run"], "budget_scale must be > 0 and finite"),
        (
            ["plan", "--problems", "shekel_chain", "--env-kwargs", "dim=5", "--dry-run"],
            "--env-kwargs \\['dim'\\] apply to gymnasium environments",
        ),
    ],
)
def test_cli_errors_that_were_tracebacks_or_silence(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    assert re.search(message, capsys.readouterr().err)


@pytest.mark.parametrize("command", ["demo-voo", "speed", "demo", "figure5", "difficulty"])
@pytest.mark.parametrize("seed", ["-1", "1.5", "x"])
def test_every_seed_option_is_checked_by_the_parser(
    command: str, seed: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main([command, "--seed", seed])
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
    for command in ("demo", "demo-voo", "bbfo", "plan", "plot", "speed", "select"):
        assert command in done.stdout
