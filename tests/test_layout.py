"""The repository's rooms: no folder of library code holds more than 15 modules flat, and
every folder of library code is a package whose ``__init__`` states its surface."""

from __future__ import annotations

import ast
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: The most modules one folder of library code may hold flat (its ``__init__`` aside).
MAX_FLAT_MODULES = 15


def library_folders() -> list[Path]:
    """Every folder under the installed folders (pyproject's package-dir) holding Python."""
    table = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    out = []
    for folder in table["package-dir"].values():
        for path in sorted((ROOT / folder).rglob("*.py")):
            if "__pycache__" not in path.parts and path.parent not in out:
                out.append(path.parent)
    return out


def test_the_installed_folders_are_found() -> None:
    names = {p.relative_to(ROOT).as_posix() for p in library_folders()}
    assert {"voot", "voot/tree", "envs", "envs/kitchen", "benchmarks/cli", "models"} <= names


@pytest.mark.parametrize("folder", library_folders(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_no_folder_holds_more_than_15_modules_flat(folder: Path) -> None:
    modules = [p.name for p in folder.glob("*.py") if p.name != "__init__.py"]
    assert len(modules) <= MAX_FLAT_MODULES, sorted(modules)


@pytest.mark.parametrize("folder", library_folders(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_folder_is_a_package_that_states_its_surface(folder: Path) -> None:
    init = folder / "__init__.py"
    if folder.name == "models":  # package data and the script that writes it
        assert init.is_file()
        return
    assert init.is_file(), f"{folder} has modules but no __init__.py"
    doc = ast.get_docstring(ast.parse(init.read_text()))
    assert doc and len(doc.split()) >= 5, f"{init} states no public surface"
