"""The caches of generated artefacts: the disk folder, files checked against their key, and
bounded in-process memos.

Generated scenes are costly to make (meshes, grasp tables, compiled storage rooms and their
witnesses), so they are kept on disk under :func:`cache_dir` (``$VOOT_CACHE``, else
``~/.cache/voot``) and in the process. This module holds what every such cache shares:

* **A cache serves only what it was asked for.** Each file is written with the key it was
  made for (what it is: a shape spec and tag, a layout's seed, level and generator
  version) and a SHA-256 of its contents (:func:`sha256`); a reader checks both
  before it serves the file. A file of another key (copied or swapped in), an edited one
  or one that cannot be read is rebuilt and replaced, with one :class:`CacheWarning`
  naming it (:func:`warn_rebuilt`); a missing file is built silently.
* **An unusable folder is no error.** If ``$VOOT_CACHE`` is a regular file, a path under
  a file, or a folder that cannot be written, :func:`writable_dir` says so with one
  :class:`CacheWarning` naming ``VOOT_CACHE`` (once per folder and process) and the caches
  keep their artefacts in memory only: an env is still made.
* **Files are written atomically** (:func:`write_atomic`: a temporary file renamed), so
  processes can share the cache.
* **In-process memos are bounded** (:class:`LRUMemo`: the least recently used entry is
  forgotten past its size), so a process that visits many layouts levels off.
* **MuJoCo's own asset cache** (the compiler keeps every mesh file it has processed, by
  name, up to a capacity of 500 MiB by default) would hold each new layout's meshes:
  about 0.33 MB a storage layout, the creep of a process visiting new layouts until it is
  full. A generated scene's compile bypasses it (:func:`generated_compile`), unless
  ``$VOOT_MUJOCO_CACHE_MB`` (:data:`MUJOCO_CACHE_VAR`) sets its capacity (``0``: off);
  measured in docs/environments.md, "Memory over 200 layouts".

Light (standard library only) so that every cache (:mod:`voot.envs.assets.meshes`, the
storage rooms' :mod:`voot.envs.conveyor.generated.instance`) can use it.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import tempfile
import warnings
from collections import OrderedDict
from collections.abc import Iterator
from pathlib import Path
from typing import Any, TypeVar

__all__ = [
    "MUJOCO_CACHE_VAR",
    "CacheWarning",
    "LRUMemo",
    "cache_dir",
    "generated_compile",
    "mujoco_cache_bytes",
    "sha256",
    "warn_rebuilt",
    "writable_dir",
    "write_atomic",
]

K = TypeVar("K")
V = TypeVar("V")

#: The environment variable naming the cache folder.
ENV_VAR = "VOOT_CACHE"

#: The environment variable bounding MuJoCo's asset cache, in MB (module docstring).
MUJOCO_CACHE_VAR = "VOOT_MUJOCO_CACHE_MB"

#: The folders found unusable in this process, and the cache roots warned about (once each).
_UNUSABLE: set[Path] = set()
_WARNED: set[Path] = set()


class CacheWarning(UserWarning):
    """A cached file was rebuilt (foreign, edited, unreadable) or the cache folder is
    unusable (the artefacts then stay in memory)."""


def cache_dir() -> Path:
    """The on-disk cache's folder: ``$VOOT_CACHE`` if set, else ``~/.cache/voot``."""
    env = os.environ.get(ENV_VAR)
    return Path(env) if env else Path.home() / ".cache" / "voot"


def writable_dir(folder: Path) -> bool:
    """Whether ``folder`` (under :func:`cache_dir`) exists or can be made, and takes files.

    False, with one :class:`CacheWarning` naming ``VOOT_CACHE`` per cache root and
    process (the meshes' and the storage rooms' folders under it warn once together), when
    it cannot (a regular file in the way, a read-only folder): the caller then keeps
    what it made in memory. Never raises an ``OSError``.
    """
    if folder in _UNUSABLE:
        return False
    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".probe", suffix=".tmp")
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        _UNUSABLE.add(folder)
        root = cache_dir()
        if root in _WARNED:
            return False
        _WARNED.add(root)
        where = os.environ.get(ENV_VAR)
        named = f"{ENV_VAR}={where}" if where else f"{ENV_VAR} unset, default {cache_dir()}"
        warnings.warn(
            f"voot's cache folder {folder} is unusable ({type(exc).__name__}: {exc.strerror or exc});"
            f" generated artefacts stay in memory in this process ({named}; set {ENV_VAR} to"
            " a writable folder)",
            CacheWarning,
            stacklevel=2,
        )
        return False
    return True


def write_atomic(path: Path, data: bytes) -> bool:
    """Write ``data`` to ``path`` atomically (a temporary file, then a rename).

    Two processes writing the same file each write a complete one and the last rename
    wins; a reader sees the old file, the new one or none, never half of one. Returns
    False, having written nothing, if the folder is unusable (:func:`writable_dir`).
    """
    if not writable_dir(path.parent):
        return False
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    except OSError:
        return False
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError as exc:
        warnings.warn(
            f"voot cache: could not write {path} ({type(exc).__name__}: {exc}); kept in memory",
            CacheWarning,
            stacklevel=3,
        )
        return False
    finally:
        Path(tmp).unlink(missing_ok=True)  # a failed write's; renamed away after success
    return True


def sha256(*parts: bytes) -> str:
    """The hex SHA-256 of ``parts`` (each length-prefixed, so that the split counts)."""
    h = hashlib.sha256()
    for p in parts:
        h.update(len(p).to_bytes(8, "little"))
        h.update(p)
    return h.hexdigest()


def warn_rebuilt(path: Path, why: str) -> None:
    """One line saying that the cached file ``path`` was not served, and why: it is
    rebuilt and replaced."""
    warnings.warn(f"voot cache: {path} {why}; rebuilt", CacheWarning, stacklevel=3)


class LRUMemo(OrderedDict[K, V]):
    """A dict that keeps its last :attr:`size` entries (``get`` and setting an entry make
    it the most recent; the least recent is forgotten past the size)."""

    def __init__(self, size: int) -> None:
        super().__init__()
        if size < 1:
            raise ValueError(f"size must be an integer >= 1, got {size!r}")
        self.size = size

    def get(self, key: K, default: Any = None) -> Any:  # type: ignore[override]
        """The entry of ``key`` (now the most recent), else ``default``."""
        if key in self:
            self.move_to_end(key)
            return self[key]
        return default

    def __setitem__(self, key: K, value: V) -> None:
        super().__setitem__(key, value)
        self.move_to_end(key)
        while len(self) > self.size:
            self.popitem(last=False)


def mujoco_cache_bytes() -> int | None:
    """The capacity of MuJoCo's asset cache asked by ``$VOOT_MUJOCO_CACHE_MB`` (a number
    of megabytes >= 0; ``0`` turns the cache off), in bytes; None if it is unset or empty
    (MuJoCo's default capacity stays).

    Raises:
        ValueError: The variable is not a finite number >= 0 (the message names it).
    """
    text = os.environ.get(MUJOCO_CACHE_VAR, "").strip()
    if not text:
        return None
    try:
        mb = float(text)
    except ValueError:
        mb = -1.0
    if not 0.0 <= mb < float("inf"):
        raise ValueError(
            f"{MUJOCO_CACHE_VAR}={text!r}: the capacity of MuJoCo's asset cache must be a"
            " number of megabytes >= 0 (0 turns it off), or unset for MuJoCo's default"
        )
    return int(mb * 1e6)


@contextlib.contextmanager
def generated_compile() -> Iterator[int]:
    """The setting of MuJoCo's asset cache for one compile of a generated scene
    (:func:`voot.envs.assets.meshes.compile_scene`); yields the capacity in force, in bytes.

    MuJoCo's compiler keeps every mesh it processed, by name, up to its capacity (500 MiB
    by default): a generated layout's new meshes would add about 0.33 MB a storage layout
    to the process for nothing, as each layout is compiled once and then kept as a model
    (the memos, the storage rooms' ``.mjb.z``). So:

    * ``$VOOT_MUJOCO_CACHE_MB`` unset (the default): the compile bypasses the cache (its
      capacity is 0 during the compile, which also drops what it held, and the previous
      capacity is restored after), so a process that visits new layouts levels off;
    * set: the cache gets that capacity before the compile and keeps it (``0``: off).

    Raises:
        ValueError: The variable is set but not a number of megabytes >= 0.
    """
    import mujoco  # here: the rest of this module is standard library only

    cache = mujoco.mj_getCache()
    wanted = mujoco_cache_bytes()
    if wanted is not None:
        if wanted != mujoco.mj_getCacheCapacity(cache):
            mujoco.mj_setCacheCapacity(cache, wanted)
        yield int(wanted)
        return
    previous = int(mujoco.mj_getCacheCapacity(cache))
    mujoco.mj_setCacheCapacity(cache, 0)
    try:
        yield 0
    finally:
        mujoco.mj_setCacheCapacity(cache, previous)
