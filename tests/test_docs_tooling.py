"""Tests of the documentation tooling in tools/docs (MkDocs hook, Griffe extension)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[1]


def load(name: str) -> ModuleType:
    path = ROOT / "tools" / "docs" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"_docs_{name}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def test_stage_packages_lays_out_the_installed_tree(tmp_path: Path) -> None:
    pytest.importorskip("mkdocs")
    hooks = load("mkdocs_hooks")
    mapping = hooks.package_dirs(ROOT)
    assert mapping["voot.envs"] == ROOT / "envs"
    assert mapping["voot.bench"] == ROOT / "benchmarks"
    staged = hooks.stage_packages(ROOT, tmp_path)
    assert staged[0] == "voot" and set(staged) == set(mapping)
    for name in mapping:
        assert (tmp_path.joinpath(*name.split(".")) / "__init__.py").is_file(), name
    assert (tmp_path / "voot" / "functions.py").is_file()
    copied = [p for p in tmp_path.rglob("*") if p.is_file()]
    assert all(p.suffix in (".py", ".pyi", ".typed") for p in copied)
    assert not any("__pycache__" in p.parts for p in copied)
    with pytest.raises(ValueError, match="already exists"):
        hooks.stage_packages(ROOT, tmp_path)


def test_rst_roles_are_rewritten() -> None:
    pytest.importorskip("griffe")
    ext = load("griffe_rst_roles")
    text = (
        "Maximise :math:`f(x) = x^2` with :class:`~voot.optim.Bounds` and :func:`maximize`.\n"
        "\n"
        "The loop is::\n"
        "\n"
        "    x = opt.ask()\n"
        "\n"
        ".. math::\n"
        "\n"
        "    R_n = f^* - f(x_n)\n"
        "\n"
        "End."
    )
    out = ext.rewrite(text)
    assert r"\(f(x) = x^2\)" in out
    assert "`voot.optim.Bounds`" in out and "`maximize`" in out
    assert "The loop is:\n" in out and "::" not in out
    assert "$$\nR_n = f^* - f(x_n)\n$$" in out
    assert out.endswith("End.")


def test_the_built_site_loads_no_remote_script(tmp_path: Path) -> None:
    """Offline readers get rendered maths: MathJax ships with the docs, nothing is fetched."""
    import re
    import subprocess
    import sys

    root = Path(__file__).resolve().parent.parent
    site = tmp_path / "site"
    subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
        cwd=root,
        check=True,
        capture_output=True,
        timeout=300,
    )
    pages = list(site.rglob("*.html"))
    assert pages
    remote = re.compile(r"<script[^>]+src=\"(https?:)?//", re.I)
    offenders = [p.name for p in pages if remote.search(p.read_text(errors="replace"))]
    assert not offenders, offenders
    assert (site / "javascripts" / "mathjax" / "tex-svg.js").stat().st_size > 1_000_000
    assert "tex-svg.js" in (site / "voo" / "index.html").read_text()
