"""The package list, derived from the folders (the rest of the metadata is in pyproject.toml).

One rule maps a file to its import name: the first folder of its path is replaced by the
package that ``[tool.setuptools] package-dir`` in pyproject.toml gives it (``voot/`` ->
``voot``, ``envs/`` -> ``voot.envs``, ``models/`` -> ``voot.models``, ``benchmarks/`` ->
``voot.bench``), the rest of the path is the dotted remainder. Every folder with an
``__init__.py`` under those folders is a package, so a new sub-package needs no edit here.
"""

import tomllib
from pathlib import Path

from setuptools import find_packages, setup

HERE = Path(__file__).resolve().parent
PACKAGE_DIR: dict[str, str] = tomllib.loads((HERE / "pyproject.toml").read_text())["tool"][
    "setuptools"
]["package-dir"]

setup(
    packages=[
        name
        for package, folder in PACKAGE_DIR.items()
        for name in [package, *(f"{package}.{sub}" for sub in find_packages(HERE / folder))]
    ]
)
