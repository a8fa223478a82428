"""Tests of voot.envs.core.caches: the cache folder, atomic writes, the unusable-folder
fallback and the bounded memos."""

from __future__ import annotations

import os
import tempfile
import warnings
from collections.abc import Iterator
from pathlib import Path

import gymnasium as gym
import pytest

import voot  # noqa: F401  (registers the ids)
from voot.envs.core import caches as C
from voot.envs.core.caches import CacheWarning, LRUMemo


@pytest.fixture(autouse=True)
def _fresh_warnings() -> None:
    C._UNUSABLE.clear()
    C._WARNED.clear()


def _unusable_paths(tmp_path: Path) -> list[Path]:
    a_file = tmp_path / "a-file"
    a_file.write_text("not a folder")
    return [a_file, a_file / "under"]


def test_an_unusable_folder_is_said_once_naming_voot_cache(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    for root in _unusable_paths(tmp_path):
        monkeypatch.setenv("VOOT_CACHE", str(root))
        with pytest.warns(CacheWarning, match=f"VOOT_CACHE={root}") as got:
            assert C.writable_dir(root / "meshes") is False
            assert C.writable_dir(root / "meshes") is False  # known now: not tried again
            assert C.writable_dir(root / "storage") is False  # the same root: no 2nd warning
            assert C.write_atomic(root / "meshes" / "x.npz", b"data") is False
        assert len(got) == 1


def test_an_unwritable_folder_is_unusable(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # as root a chmod'ed folder stays writable, so the refusal is simulated where it is met
    def refuse(*args: object, **kwargs: object) -> None:
        raise PermissionError(13, "Permission denied")

    monkeypatch.setenv("VOOT_CACHE", str(tmp_path))
    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    with pytest.warns(CacheWarning, match="Permission denied.*VOOT_CACHE"):
        assert C.writable_dir(tmp_path / "meshes") is False


def test_a_write_that_fails_leaves_nothing_and_says_so(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def broken(*args: object, **kwargs: object) -> None:
        raise OSError(28, "No space left on device")

    path = tmp_path / "f.bin"
    assert C.writable_dir(tmp_path) is True
    with monkeypatch.context() as mp:
        mp.setattr(os, "replace", broken)
        with pytest.warns(CacheWarning, match=r"could not write .*f\.bin .*No space left"):
            assert C.write_atomic(path, b"data") is False
    assert list(tmp_path.iterdir()) == []  # no file, no temporary
    with monkeypatch.context() as mp:  # the folder takes files, but this one cannot start
        mp.setattr(C, "writable_dir", lambda folder: True)
        mp.setattr(tempfile, "mkstemp", broken)
        assert C.write_atomic(path, b"data") is False
    assert C.write_atomic(path, b"data") is True and path.read_bytes() == b"data"


def test_write_atomic_writes_whole_files(tmp_path: Path) -> None:
    path = tmp_path / "sub" / "f.bin"
    assert C.write_atomic(path, b"one") and path.read_bytes() == b"one"
    assert C.write_atomic(path, b"two") and path.read_bytes() == b"two"
    assert sorted(p.name for p in path.parent.iterdir()) == ["f.bin"]


def test_sha256_counts_the_split() -> None:
    assert C.sha256(b"ab", b"c") != C.sha256(b"a", b"bc")
    assert C.sha256(b"ab") == C.sha256(b"ab") and len(C.sha256()) == 64


def test_lru_memo_keeps_its_last_entries() -> None:
    memo: LRUMemo[int, str] = LRUMemo(2)
    memo[1] = "a"
    memo[2] = "b"
    assert memo.get(1) == "a"  # now the most recent
    memo[3] = "c"
    assert sorted(memo) == [1, 3] and memo.get(2) is None and memo.get(2, "x") == "x"
    with pytest.raises(ValueError, match="size must be an integer >= 1"):
        LRUMemo(0)
    one: LRUMemo[str, int] = LRUMemo(1)
    one["a"], one["b"] = 1, 2
    assert dict(one) == {"b": 2}


@pytest.mark.parametrize("family", ["voot/GeneratedStorage-v0", "voot/GeneratedKitchen-v0"])
def test_make_works_on_an_unusable_cache_with_one_warning(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, family: str
) -> None:
    """Before: a raw NotADirectoryError from gym.make."""
    from voot.envs.assets import meshes
    from voot.envs.conveyor.generated import instance as SI
    from voot.envs.kitchen.generated import instance as KI

    for root in _unusable_paths(tmp_path):
        C._WARNED.clear()
        monkeypatch.setenv("VOOT_CACHE", str(root))
        SI.clear_memo()
        KI.clear_kitchen_cache()
        meshes.clear_memory_cache()
        with warnings.catch_warnings(record=True) as got:
            warnings.simplefilter("always")
            env = gym.make(family, layout_seed=6)
            env.reset(seed=0)
        said = [w for w in got if issubclass(w.category, CacheWarning)]
        assert len(said) == 1 and "VOOT_CACHE" in str(said[0].message)
        assert (tmp_path / "a-file").read_text() == "not a folder"  # untouched
    SI.clear_memo()
    meshes.clear_memory_cache()


def test_the_cache_folder_follows_voot_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("VOOT_CACHE", "/some/where")
    assert C.cache_dir() == Path("/some/where")
    monkeypatch.delenv("VOOT_CACHE")
    assert C.cache_dir() == Path.home() / ".cache" / "voot"
    assert os.environ.get("VOOT_CACHE") is None


@pytest.fixture
def mujoco_capacity() -> Iterator[None]:
    """Restore MuJoCo's asset-cache capacity after the test (a process-wide setting)."""
    import mujoco

    cache = mujoco.mj_getCache()
    before = mujoco.mj_getCacheCapacity(cache)
    yield
    mujoco.mj_setCacheCapacity(cache, before)


@pytest.mark.parametrize(
    ("text", "expected"),
    [("", None), ("  ", None), ("0", 0), ("64", 64_000_000), (" 1.5 ", 1_500_000)],
)
def test_the_mujoco_cache_capacity_is_read_in_megabytes(
    monkeypatch: pytest.MonkeyPatch, text: str, expected: int | None
) -> None:
    monkeypatch.setenv(C.MUJOCO_CACHE_VAR, text)
    assert C.mujoco_cache_bytes() == expected
    monkeypatch.delenv(C.MUJOCO_CACHE_VAR)
    assert C.mujoco_cache_bytes() is None


@pytest.mark.parametrize("text", ["-1", "abc", "nan", "inf", "-0.5", "1e400"])
def test_a_bad_mujoco_cache_capacity_names_the_variable(
    monkeypatch: pytest.MonkeyPatch, text: str, mujoco_capacity: None
) -> None:
    import mujoco

    monkeypatch.setenv(C.MUJOCO_CACHE_VAR, text)
    before = mujoco.mj_getCacheCapacity(mujoco.mj_getCache())
    with (
        pytest.raises(ValueError, match=f"VOOT_MUJOCO_CACHE_MB={text!r}.*megabytes >= 0"),
        C.generated_compile(),
    ):
        pass
    assert mujoco.mj_getCacheCapacity(mujoco.mj_getCache()) == before


def test_a_generated_compile_bypasses_mujocos_cache_unless_a_capacity_is_asked(
    monkeypatch: pytest.MonkeyPatch, mujoco_capacity: None
) -> None:
    import mujoco

    cache = mujoco.mj_getCache()
    mujoco.mj_setCacheCapacity(cache, 123_000_000)
    monkeypatch.delenv(C.MUJOCO_CACHE_VAR, raising=False)
    with C.generated_compile() as capacity:  # unset: off during the compile only
        assert capacity == 0 == mujoco.mj_getCacheCapacity(cache)
    assert mujoco.mj_getCacheCapacity(cache) == 123_000_000  # the user's, restored
    with pytest.raises(RuntimeError), C.generated_compile():
        raise RuntimeError("a failed compile")
    assert mujoco.mj_getCacheCapacity(cache) == 123_000_000  # restored after an error too
    monkeypatch.setenv(C.MUJOCO_CACHE_VAR, "2.5")
    with C.generated_compile() as capacity:
        assert capacity == 2_500_000
    assert mujoco.mj_getCacheCapacity(cache) == 2_500_000  # asked: kept
    monkeypatch.setenv(C.MUJOCO_CACHE_VAR, "0")
    with C.generated_compile() as capacity:
        assert capacity == 0
