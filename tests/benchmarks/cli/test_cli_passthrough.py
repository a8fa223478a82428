"""Tests of voot.bench.cli.passthrough: the commands whose module parses its own options
get the rest of the command line unparsed, and every entry names a real function."""

from __future__ import annotations

import importlib
import sys
import types

import pytest

from voot.bench.cli import passthrough as cli_passthrough
from voot.bench.cli.main import main
from voot.bench.cli.passthrough import PASSTHROUGH


def test_every_entry_names_a_function_and_a_help_line() -> None:
    assert list(PASSTHROUGH) == [
        "overhead",
        "record-overhead",
        "record-demo",
        "env-speed",
        "env-figures",
        "root-parallel",
        "voo-speed",
    ]
    for name, (target, text) in PASSTHROUGH.items():
        module, function = target.split(":")
        assert callable(getattr(importlib.import_module(module), function)), name
        assert text


def test_the_rest_of_the_line_goes_to_the_module_unparsed(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    calls: list[list[str]] = []

    def fake_main(argv: list[str]) -> int | None:
        calls.append(argv)
        return 3 if "--fail" in argv else None

    fake = types.ModuleType("voot_fake_passthrough")
    fake.run = fake_main  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "voot_fake_passthrough", fake)
    monkeypatch.setitem(cli_passthrough.PASSTHROUGH, "fake", ("voot_fake_passthrough:run", "x"))
    assert main(["fake", "--help", "-x", "1"]) == 0  # --help is the module's, not argparse's
    assert main(["fake", "--fail"]) == 3
    assert calls == [["--help", "-x", "1"], ["--fail"]]
