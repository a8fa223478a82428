"""The README's Python examples run as written, pasted into an interpreter started at the
repository root after a non-editable install.

At the root, ``import voot`` finds the folder ``voot/`` before the installed package, and
``envs/``, ``benchmarks/``, ``models/`` are not inside it: :mod:`voot._source_tree` maps them.
The test stages the package as a wheel installs it (the ``package-dir`` table of
pyproject.toml), puts it on the path behind the root, takes any editable-install finder
away, and runs the ``python`` blocks of README.md, in order, in one fresh interpreter at
the root.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Run before a README block: drop editable-install finders (a wheel has none), put the
#: staged install behind the root (as site-packages is), then run the block.
PRELUDE = """\
import sys
sys.meta_path[:] = [
    f for f in sys.meta_path
    if "Editable" not in (f.__name__ if isinstance(f, type) else type(f).__name__)
]
sys.path_importer_cache.clear()
sys.path.insert(1, {site!r})
for name in [m for m in sys.modules if m == "voot" or m.startswith("voot.")]:
    del sys.modules[name]
"""


def readme_python_blocks() -> list[str]:
    """The fenced ``python`` blocks of README.md, in order."""
    text = (ROOT / "README.md").read_text()
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def stage_wheel_layout(dest: Path) -> Path:
    """Copy the sources as a wheel lays them out (``envs/`` -> ``voot/envs`` ...)."""
    table = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    for package, folder in sorted(table["package-dir"].items(), key=lambda kv: kv[0].count(".")):
        shutil.copytree(
            ROOT / folder,
            dest.joinpath(*package.split(".")),
            ignore=shutil.ignore_patterns("__pycache__", "*.pyc"),
            dirs_exist_ok=True,
        )
    return dest


def test_the_readme_has_python_examples() -> None:
    blocks = readme_python_blocks()
    assert len(blocks) >= 3
    assert any("voot.envs" in b for b in blocks) and any("voot.bench" in b for b in blocks)


def test_readme_examples_run_at_the_repository_root(tmp_path: Path) -> None:
    # pasted one after the other into one interpreter, as a reader does (later blocks use
    # the names of earlier ones)
    site = stage_wheel_layout(tmp_path / "site")
    code = PRELUDE.format(site=str(site)) + "\n".join(readme_python_blocks())
    code += "\nimport voot, voot.envs\nprint('FROM', voot.__file__, voot.envs.__file__)\n"
    out = subprocess.run(
        [sys.executable, "-"], input=code, cwd=ROOT, capture_output=True, text=True, timeout=600
    )
    assert out.returncode == 0, out.stderr[-3000:]
    where = out.stdout.strip().splitlines()[-1].split()
    # the root's voot/ is the one imported, and its envs come from the root's envs/
    assert where[1] == str(ROOT / "voot" / "__init__.py")
    assert where[2] == str(ROOT / "envs" / "__init__.py")


def test_without_the_source_tree_finder_the_root_would_shadow_the_install(
    tmp_path: Path,
) -> None:
    # the failure the finder prevents: the root's voot/ without its sibling folders (import
    # voot already needs voot.envs: it registers the ids from the families' records there)
    site = stage_wheel_layout(tmp_path / "site")
    code = PRELUDE.format(site=str(site)) + (
        "import importlib.util\n"
        "spec = importlib.util.spec_from_file_location('voot._source_tree',"
        f" {str(ROOT / 'voot' / '_source_tree.py')!r})\n"
        "s = importlib.util.module_from_spec(spec)\n"
        "spec.loader.exec_module(s)\n"
        "s.install = lambda package_file: None\n"
        "sys.modules['voot._source_tree'] = s\n"
        "import voot\n"
    )
    out = subprocess.run(
        [sys.executable, "-"], input=code, cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert out.returncode != 0 and "No module named 'voot.envs'" in out.stderr
