"""No import cycles among voot's modules, imports inside functions counted.

The graph comes from ``tools/import_cycles.py`` (run it to list the cycles): every
``import`` of a voot module at any depth of a module's code, ``if TYPE_CHECKING:`` blocks
aside, with the import names of ``[tool.setuptools] package-dir``.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _tool() -> ModuleType:
    path = ROOT / "tools" / "import_cycles.py"
    spec = importlib.util.spec_from_file_location("import_cycles", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


TOOL = _tool()
GRAPH = TOOL.import_graph(ROOT)
#: The sub-packages checked one by one (``voot.bench``, ``voot.envs``, ``voot.tree`` ...), so
#: a failure names where the cycle is.
PACKAGES = sorted({".".join(n.split(".")[:2]) for n in GRAPH if n.count(".") >= 2})


@pytest.mark.parametrize("package", PACKAGES)
def test_no_import_cycle_touches(package: str) -> None:
    found = TOOL.cycles(GRAPH, package + ".")
    assert not found, "import cycles:\n" + "\n".join(found)


def test_no_import_cycle_anywhere() -> None:
    found = TOOL.cycles(GRAPH)
    assert not found, "import cycles:\n" + "\n".join(found)


def test_the_graph_reads_every_package_and_nested_imports() -> None:
    assert {"voot.bench", "voot.envs", "voot.models", "voot.tree"} <= set(PACKAGES)
    # an import inside a function counts (voot.bench.sweep.planners imports voot.tree's
    # config lazily); a TYPE_CHECKING-only one does not
    assert "voot.tree.config" in GRAPH["voot.bench.sweep.planners"]
    assert "voot.bench.sweep.plan" not in GRAPH["voot.bench.sweep.search"]


def test_the_helper_finds_cycles_self_imports_and_resolves_relative_imports(
    tmp_path: Path,
) -> None:
    (tmp_path / "pyproject.toml").write_text(
        '[tool.setuptools]\npackage-dir = { "voot" = "voot", "voot.extra" = "extra" }\n'
    )
    pkg = tmp_path / "voot"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("def f():\n    from voot import b\n")
    (pkg / "b.py").write_text("from . import a\n")
    (pkg / "c.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import voot.a\nimport voot.c\n"
    )
    extra = tmp_path / "extra"
    extra.mkdir()
    (extra / "__init__.py").write_text("from voot.a import f\n")
    graph = TOOL.import_graph(tmp_path)
    assert graph["voot.a"] == {"voot.b"} and graph["voot.b"] == {"voot.a"}
    assert graph["voot.c"] == {"voot.c"}  # the TYPE_CHECKING import left out
    assert graph["voot.extra"] == {"voot.a"}  # from a module import a name: the module
    found = TOOL.cycles(graph)
    assert found[0] == "2 modules: voot.a, voot.b\n    e.g. voot.a -> voot.b -> voot.a"
    assert found[1] == "voot.c imports itself"
