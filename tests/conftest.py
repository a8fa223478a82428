"""Test-session settings shared by every test module."""

import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

# Headless rendering: MuJoCo reads MUJOCO_GL when it is first imported, so set it before
# any test module imports mujoco (CI sets it too; a user's own value wins).
os.environ.setdefault("MUJOCO_GL", "egl")

# The generated scenes' on-disk cache (meshes, grasp tables, storage instances): a fresh
# folder per test session, so the tests never write into the user's ~/.cache/voot and
# always exercise the cold path once. Child processes the tests start inherit it.
_OWN_CACHE = "VOOT_CACHE" not in os.environ
if _OWN_CACHE:
    os.environ["VOOT_CACHE"] = tempfile.mkdtemp(prefix="voot-test-cache-")


def pytest_unconfigure(config: object) -> None:
    """Remove the session's own cache folder."""
    if _OWN_CACHE:
        shutil.rmtree(os.environ["VOOT_CACHE"], ignore_errors=True)


@pytest.fixture
def mesh_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A fresh mesh cache folder and empty in-process mesh caches, for one test."""
    from voot.envs.assets import meshes

    monkeypatch.setenv("VOOT_CACHE", str(tmp_path / "cache"))
    meshes.clear_memory_cache()
    yield tmp_path / "cache"
    meshes.clear_memory_cache()
