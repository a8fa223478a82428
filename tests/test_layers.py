"""The import layers: lower packages load nothing of the layers above them (nor MuJoCo).

Each check imports packages in a fresh interpreter and inspects ``sys.modules``.

One exception, by design: ``import voot`` (which every ``voot.*`` import runs first)
registers the gymnasium ids from the families' problem records, which live beside each
family's env (``voot.envs.kitchen.problems`` ...). So the lower layers load exactly those
records modules, the package inits above them (docstrings only) and the typed names they
use (``voot.envs.core.names``, and the protocol's layout split, ``voot.envs.core.splits``): data, no MuJoCo, no env code. :data:`RECORD_MODULES` is
that allowance; anything else of ``voot.envs`` is still an offence.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest


def loaded_after(*packages: str) -> list[str]:
    """The modules loaded in a fresh interpreter after importing ``packages``."""
    code = (
        "import importlib, json, sys\n"
        f"for name in {list(packages)!r}:\n"
        "    importlib.import_module(name)\n"
        "print(json.dumps(sorted(sys.modules)))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], check=True, capture_output=True, text=True, timeout=120
    )
    modules: list[str] = json.loads(out.stdout.strip().splitlines()[-1])
    return modules


def _record_modules() -> frozenset[str]:
    from voot._registration import FAMILIES

    inits = {m.rsplit(".", k)[0] for m in FAMILIES for k in range(1, m.count("."))}
    return frozenset(
        {*FAMILIES, *inits, "voot.envs.core", "voot.envs.core.names", "voot.envs.core.splits"}
    )


#: What ``import voot`` loads of ``voot.envs``: the families' records modules, their
#: package inits and the typed names (see the module docstring).
RECORD_MODULES = _record_modules()


def offending(modules: list[str], *prefixes: str) -> list[str]:
    """The modules that are one of ``prefixes`` or inside one of them (the records
    modules of :data:`RECORD_MODULES` aside)."""
    return [
        m
        for m in modules
        if m not in RECORD_MODULES and any(m == p or m.startswith(p + ".") for p in prefixes)
    ]


def test_import_voot_loads_only_the_records_of_voot_envs() -> None:
    modules = loaded_after("voot")
    loaded = {m for m in modules if m == "voot.envs" or m.startswith("voot.envs.")}
    assert loaded == RECORD_MODULES
    assert offending(modules, "mujoco", "gymnasium.envs.mujoco", "voot.tree", "voot.bench") == []


def test_optim_functions_tree_load_no_mujoco_envs_or_bench() -> None:
    modules = loaded_after("voot.tree", "voot.optim", "voot.functions")
    assert "voot.tree.root_parallel" in modules
    assert offending(modules, "mujoco", "voot.envs", "voot.bench", "voot.record", "voot.rl") == []


def test_the_library_loads_no_argparse() -> None:
    # argparse converters (voot.bench.cli.types) belong to the command line; the
    # library's checks (voot.validation) raise ValueError and need no argparse
    modules = loaded_after(
        "voot.validation", "voot.optim", "voot.tree", "voot.functions", "voot.parallel"
    )
    assert "voot.validation" in modules and "argparse" not in modules


def test_parallel_loads_nothing_of_the_layers_above() -> None:
    modules = loaded_after("voot.parallel")
    assert offending(modules, "mujoco", "voot.tree", "voot.envs", "voot.bench", "ray") == []


def test_rl_loads_no_torch_sb3_or_bench() -> None:
    modules = loaded_after("voot.rl")
    assert offending(modules, "torch", "stable_baselines3", "voot.bench", "mujoco") == []


def test_record_loads_no_bench() -> None:
    modules = loaded_after("voot.record")
    assert offending(modules, "voot.bench") == []


@pytest.mark.parametrize("package", ["voot.tree", "voot.optim", "voot.functions"])
def test_each_lower_package_alone_loads_no_mujoco(package: str) -> None:
    assert offending(loaded_after(package), "mujoco", "voot.envs", "voot.bench") == []
