"""Tests of voot.bench.cli.common: the list, range and NAME=VALUE parsers, opening a
result store, the note of runs already stored, and SIGTERM as Ctrl-C."""

from __future__ import annotations

import os
import signal
from pathlib import Path

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
