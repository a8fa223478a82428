"""The per-process cache of expensive objects that worker processes keep between items.

A worker of a sweep or of a root-parallel search runs many items (runs, trees) on the
same world. Building that world can cost far more than one item (a MuJoCo model, a
scene), so each process keeps what it built in one small least-recently-used cache,
:func:`worker_cache`, and later items reuse it. Reuse is invisible in the results: the
users reset what they take out (an environment is reset with the run's seed, a planning
problem restored to its initial snapshot), so a kept object behaves as a fresh one.

One cache per process, whatever uses it (``voot.bench.protocol.problems.cached_env`` for
environments, ``voot.tree.root_parallel`` for problems built from factories): the
number of heavy objects a worker holds is bounded once (:data:`CACHE_SIZE`), not per
user. Users keep their keys apart by making them tuples that start with their own tag
(``("env", ...)``, ``("problem", ...)``).
"""

from __future__ import annotations

import contextlib
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any, TypeVar

from voot import validation

V = TypeVar("V")

#: Objects each process keeps (the least recently used one is dropped, and closed).
CACHE_SIZE = 4


class WorkerCache:
    """A least-recently-used map from keys to built objects.

    Args:
        size: how many objects to keep (>= 1).

    An entry may come with a ``close`` function (e.g. ``env.close``), called when the
    entry is dropped, by the LRU rule or by :meth:`clear`; errors of ``close`` are
    ignored (closing is best effort).
    """

    def __init__(self, size: int = CACHE_SIZE) -> None:
        validation.integer(size, "size", 1)
        self.size = size
        self._entries: OrderedDict[Hashable, tuple[Any, Callable[[Any], object] | None]] = (
            OrderedDict()
        )

    def get(
        self,
        key: Hashable,
        build: Callable[[], V],
        close: Callable[[V], object] | None = None,
    ) -> V:
        """The object kept under ``key``, or ``build()`` kept under it (oldest dropped)."""
        entry = self._entries.get(key)
        if entry is not None:
            self._entries.move_to_end(key)
            value: V = entry[0]
            return value
        value = build()
        self._entries[key] = (value, close)
        while len(self._entries) > self.size:
            _, (old, closer) = self._entries.popitem(last=False)
            _close(old, closer)
        return value

    def clear(self) -> None:
        """Drop (and close) every kept object."""
        while self._entries:
            _, (old, closer) = self._entries.popitem()
            _close(old, closer)

    def __contains__(self, key: object) -> bool:
        return key in self._entries

    def __len__(self) -> int:
        return len(self._entries)

    def keys(self) -> list[Hashable]:
        """The keys, least recently used first."""
        return list(self._entries)


def _close(value: Any, closer: Callable[[Any], object] | None) -> None:
    if closer is not None:
        with contextlib.suppress(Exception):
            closer(value)


_CACHE = WorkerCache()


def worker_cache() -> WorkerCache:
    """This process's cache (one per process, shared by every user)."""
    return _CACHE


def clear_worker_cache() -> None:
    """Drop (and close) everything this process keeps."""
    _CACHE.clear()
