"""Tests of voot.bench.cli.common: the list, range and NAME=VALUE parsers, opening a
result store, the note of runs already stored, and SIGTERM as Ctrl-C."""

from __future__ import annotations

import os
import signal
from pathlib import Path
from typing import Any

import pytest

from voot.bench.cli.common import (
    CLIError,
    existing_store,
    open_store,
    parse_assignments,
    parse_int_list,
    parse_range,
    sigterm_as_interrupt,
    split_list,
    stored_note,
)


def test_parse_range() -> None:
    assert parse_range("3", "s") == [0, 1, 2]
    assert parse_range("5:8", "s") == [5, 6, 7]
    for bad, message in [
        ("0", "s: need at least 1"),
        ("4:4", "inverted or empty range '4:4'"),
        ("-1:3", "starts below 0"),
        ("1:2:3", "is not N or START:STOP"),
        ("x", "is not N or START:STOP"),
    ]:
        with pytest.raises(CLIError, match=message):
            parse_range(bad, "s")


def test_split_and_integer_lists() -> None:
    assert split_list(["a,b", " c ", "d,,"]) == ["a", "b", "c", "d"]
    assert split_list(None) == []
    assert parse_int_list(["3", "10,20", "5:7"], "--dims") == [3, 10, 20, 5, 6]
    with pytest.raises(CLIError, match="--dims: 'x' is not an integer"):
        parse_int_list(["x"], "--dims")


def test_parse_assignments() -> None:
    got = parse_assignments(["omega=0.3", "depth_limit=5,flag=true", "s=text", "n=None"], "--set")
    assert got == {"omega": 0.3, "depth_limit": 5, "flag": True, "s": "text", "n": None}
    for bad in ("omega", "=3"):
        with pytest.raises(CLIError, match="is not NAME=VALUE"):
            parse_assignments([bad], "--set")
    # a name given twice: refused, naming both values (the last would silently win)
    with pytest.raises(CLIError, match=r"layout_seed is given twice \(layout_seed=1\.5 and"):
        parse_assignments(["layout_seed=1.5", "layout_seed=0"], "--env-kwargs")
    with pytest.raises(CLIError, match="given twice"):
        parse_assignments(["omega=0.3,omega=0.3"], "--set")


def test_stores_open_and_the_stored_note(tmp_path: Path) -> None:
    from voot.bench.sweep.bbfo import build_specs, run_spec

    assert existing_store(str(tmp_path / "none")) is None
    (tmp_path / "file").write_text("x")
    with pytest.raises(CLIError, match="cannot create the result store there"):
        open_store(str(tmp_path / "file" / "store"))
    specs = build_specs(["rastrigin"], [3], ["random"], [0, 1], budget=5)
    assert stored_note(str(tmp_path / "none"), specs) == ""
    store = open_store(str(tmp_path / "s"))
    assert stored_note(str(tmp_path / "s"), specs) == ""
    store.write(run_spec(specs[0]))
    assert stored_note(str(tmp_path / "s"), specs) == "; 1 already in the store"
    assert existing_store(str(tmp_path / "s")) is not None


def test_sigterm_is_an_interrupt() -> None:
    before = signal.getsignal(signal.SIGTERM)
    with pytest.raises(KeyboardInterrupt), sigterm_as_interrupt():
        os.kill(os.getpid(), signal.SIGTERM)
    assert signal.getsignal(signal.SIGTERM) == before


def test_sweep_options_are_shared_and_checked() -> None:
    import argparse

    from voot.bench.cli.common import CLIError, add_backend_options, check_sweep_options

    p = argparse.ArgumentParser()
    add_backend_options(p)
    p.add_argument("--probe-simulations", type=int, default=20)
    check_sweep_options(p.parse_args(["--backend", "ray", "--address", "auto"]))
    with pytest.raises(CLIError, match="go with --backend ray"):
        check_sweep_options(p.parse_args(["--address", "auto"]))
    with pytest.raises(CLIError, match="--probe-simulations must be >= 1"):
        check_sweep_options(p.parse_args(["--probe-simulations", "0"]))


# ----- checks before any work (issue 34) ----------------------------------------------
def test_check_output_refuses_paths_that_cannot_be_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from voot.bench.cli.common import CLIError, check_output

    (tmp_path / "file").write_text("x")
    (tmp_path / "dir").mkdir()
    check_output(None, "--png")  # not given: nothing to check
    check_output(str(tmp_path / "new" / "deeper" / "t.md"), "--markdown")  # made later
    check_output(str(tmp_path / "file"), "--markdown")  # an existing file is replaced
    check_output(str(tmp_path / "dir"), "--out", folder=True)
    with pytest.raises(CLIError, match=r"--markdown .*file is a file, not a folder"):
        check_output(str(tmp_path / "file" / "t.md"), "--markdown")
    with pytest.raises(CLIError, match=r"--out .*file is a file, not a folder"):
        check_output(str(tmp_path / "file" / "a" / "b"), "--out", folder=True)
    with pytest.raises(CLIError, match=r"--png .*is a folder; give a file name"):
        check_output(str(tmp_path / "dir"), "--png")
    with pytest.raises(CLIError, match=r"--out .*is a file, not a folder; give a folder"):
        check_output(str(tmp_path / "file"), "--out", folder=True)
    with pytest.raises(CLIError, match="an empty path"):
        check_output("", "--markdown")
    # an unwritable folder (the tests may run as root, which writes anywhere: ask os.access)
    monkeypatch.setattr("os.access", lambda path, mode: False)
    with pytest.raises(CLIError, match=r"--markdown .*the folder .*dir is not writable"):
        check_output(str(tmp_path / "dir" / "t.md"), "--markdown")
    with pytest.raises(CLIError, match=r"--markdown .*file: not writable"):
        check_output(str(tmp_path / "file"), "--markdown")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dir", "file"]  # nothing made


def test_write_markdown_under_a_file_is_a_cli_error(tmp_path: Path) -> None:
    from voot.bench.cli.common import CLIError, write_markdown

    (tmp_path / "file").write_text("x")
    with pytest.raises(CLIError, match=r"--markdown .*cannot write the file"):
        write_markdown(str(tmp_path / "file" / "t.md"), "text")


def test_ranges_too_long_to_list_are_refused() -> None:
    from voot.bench.cli.common import MAX_RANGE_LENGTH, CLIError, parse_range

    assert len(parse_range(str(MAX_RANGE_LENGTH), "--seeds")) == MAX_RANGE_LENGTH
    with pytest.raises(CLIError, match=r"--seeds: .* more than a sweep can run"):
        parse_range(str(MAX_RANGE_LENGTH + 1), "--seeds")
    with pytest.raises(CLIError, match="more than a sweep can run"):
        parse_range("0:9223372036854775808", "--layout-seeds")


@pytest.mark.parametrize(
    "value",
    [-1, 1.5, 1.0, True, "1", "abc", None, 2**63],
)
def test_layout_seed_keywords_are_integers_in_range(value: object) -> None:
    from voot.bench.cli.common import CLIError, check_layout_value

    with pytest.raises(CLIError, match=r"--env-kwargs: layout_seed must be an integer in \[0, "):
        check_layout_value(value, "--env-kwargs")


def test_layout_seed_keywords_in_range_pass() -> None:
    from voot.bench.cli.common import MAX_LAYOUT_SEED, check_layout_value

    for value in (0, 7, MAX_LAYOUT_SEED):
        check_layout_value(value, "--env-kwargs")


def test_check_envs_makes_one_env_per_problem_at_the_ends_of_its_layouts() -> None:
    from voot.bench.cli.common import CLIError, check_envs
    from voot.bench.sweep.plan import build_plan_specs

    def specs(problem: str, **kw: Any) -> list[Any]:
        return build_plan_specs([problem], None, ["voot"], [0, 1], simulations=2, **kw)

    assert check_envs(specs("shekel_chain")) == 0  # a chain makes no env
    assert check_envs(specs("voot/ShekelChain-v0", env_kwargs={"dim": 3})) == 1
    conveyor = specs("generated_storage", layout_seeds=[5, 3, 9])
    assert check_envs(conveyor) == 2  # layouts 3 and 9, not 5
    assert check_envs(specs("generated_storage", layout_seeds=[4])) == 1
    # a chain among envs is passed over, the envs after it are still made
    assert check_envs([*specs("shekel_chain"), *specs("generated_storage", layout_seeds=[4])]) == 1
    with pytest.raises(CLIError, match=r"--env-kwargs: .*difficulty='extreme'.* valid levels"):
        check_envs(specs("generated_storage", env_kwargs={"difficulty": "extreme"}))
    with pytest.raises(CLIError, match=r"--layout-seeds: voot/ConveyorPacking-v1 takes no"):
        check_envs(specs("conveyor_v1", layout_seeds=[1]), layout_option="--layout-seeds")
    with pytest.raises(CLIError, match=r"--env-kwargs: .*cannot be made: .*no_such_option"):
        check_envs(specs("conveyor_v1", env_kwargs={"no_such_option": 1}))
