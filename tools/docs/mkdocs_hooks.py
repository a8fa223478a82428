"""MkDocs hooks: let mkdocstrings see ``voot`` as it installs, sub-packages included.

voot's sources are split over top-level folders that pyproject.toml maps into one
package (``[tool.setuptools] package-dir``: ``envs/`` -> ``voot.envs``, ``benchmarks/`` ->
``voot.bench``, ...). Griffe, which reads the sources for mkdocstrings, finds packages by
walking folders, so it would see ``voot`` without ``voot.envs`` and ``voot.bench``; its
support for setuptools' editable installs only adds the mapped folders' parents to the
search path and does not apply the renaming either.

So before mkdocstrings starts, this hook copies the Python sources into a temporary tree
laid out as the installed package (``voot/``, ``voot/envs/``, ``voot/bench/`` ...), reading
the mapping from pyproject.toml so it never goes stale, and points the mkdocstrings
Python handler's ``paths`` at that tree. It needs no install and no network, and it is
rebuilt on every build (``mkdocs serve`` also watches the source folders).
"""

from __future__ import annotations

import atexit
import shutil
import tempfile
import tomllib
from pathlib import Path
from typing import Any

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.plugins import event_priority

#: Only these files are copied (sources and typing markers; no MJCF, meshes or caches).
_SUFFIXES = (".py", ".pyi", ".typed")


def package_dirs(root: Path) -> dict[str, Path]:
    """Package name -> source folder, from pyproject.toml's setuptools ``package-dir``."""
    with (root / "pyproject.toml").open("rb") as fh:
        pyproject = tomllib.load(fh)
    mapping = pyproject.get("tool", {}).get("setuptools", {}).get("package-dir", {})
    if not mapping:
        raise ValueError("pyproject.toml has no [tool.setuptools] package-dir mapping")
    return {name: root / folder for name, folder in mapping.items() if name}


def stage_packages(root: Path, dest: Path) -> list[str]:
    """Copy each mapped package's sources to ``dest/<name with / for .>``; return the names."""

    def ignore(folder: str, names: list[str]) -> list[str]:
        base = Path(folder)
        return [
            n
            for n in names
            if n == "__pycache__" or ((base / n).is_file() and not n.endswith(_SUFFIXES))
        ]

    staged = []
    # Parents first, so that voot/ exists before voot/envs/ is added to it.
    for name, src in sorted(package_dirs(root).items(), key=lambda kv: kv[0].count(".")):
        if not src.is_dir():
            raise ValueError(f"package {name!r} maps to {src}, which is not a folder")
        target = dest.joinpath(*name.split("."))
        if target.exists():
            raise ValueError(f"package {name!r}: {target} already exists in the staged tree")
        shutil.copytree(src, target, ignore=ignore)
        staged.append(name)
    return staged


@event_priority(100)  # before mkdocstrings reads its handler options
def on_config(config: MkDocsConfig, **kwargs: Any) -> MkDocsConfig:
    root = Path(config.config_file_path).resolve().parent
    dest = Path(tempfile.mkdtemp(prefix="voot-docs-src-"))
    atexit.register(shutil.rmtree, dest, ignore_errors=True)
    stage_packages(root, dest)
    plugin = config.plugins["mkdocstrings"]
    handlers = plugin.config.handlers
    handlers.setdefault("python", {})["paths"] = [str(dest)]
    return config


def on_serve(server: Any, config: MkDocsConfig, **kwargs: Any) -> Any:
    root = Path(config.config_file_path).resolve().parent
    for src in package_dirs(root).values():
        server.watch(str(src))
    return server
