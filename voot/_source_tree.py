"""Import names in a source checkout: ``voot.envs`` from ``envs/``, ``voot.bench`` from
``benchmarks/`` ... as the installed package has them.

An installed voot (wheel or editable) holds ``voot.envs``, ``voot.models`` and ``voot.bench``
where ``[tool.setuptools] package-dir`` of pyproject.toml put them. Python started at the
root of a checkout finds the folder ``voot/`` first, before the installed package, and the
other folders are not inside it; :func:`install` then adds a finder that maps those names
to their folders by the same table, so the README's examples run from the root exactly
as from anywhere else.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import importlib.util
import sys
import tomllib
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType


class SourceTreeFinder(importlib.abc.MetaPathFinder):
    """Finds the packages of ``package-dir`` that live outside ``voot/`` in a checkout."""

    def __init__(self, folders: dict[str, Path]) -> None:
        self.folders = folders

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        folder = self.folders.get(fullname)
        if folder is None:
            return None
        return importlib.util.spec_from_file_location(
            fullname, folder / "__init__.py", submodule_search_locations=[str(folder)]
        )


def install(package_file: str) -> None:
    """Add the finder when ``voot`` was imported from a checkout that needs it."""
    package = Path(package_file).absolute().parent
    root = package.parent
    pyproject = root / "pyproject.toml"
    if not pyproject.is_file() or any(isinstance(f, SourceTreeFinder) for f in sys.meta_path):
        return
    try:
        table = tomllib.loads(pyproject.read_text())["tool"]["setuptools"]["package-dir"]
    except (KeyError, tomllib.TOMLDecodeError, OSError):
        return
    folders = {
        name: root / folder
        for name, folder in table.items()
        if name.startswith("voot.") and not (package / name.split(".", 1)[1]).exists()
    }
    if folders:
        # first, so that a second checkout (a git worktree) beside an editable install of
        # another one imports its own folders
        sys.meta_path.insert(0, SourceTreeFinder(folders))
