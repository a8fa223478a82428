"""Tests of voot.parallel.cache: the one per-process cache of worker processes."""

from __future__ import annotations

import functools

import pytest

from voot.parallel import CACHE_SIZE, WorkerCache, clear_worker_cache, worker_cache


def test_lru_keeps_the_most_recent_and_closes_the_dropped() -> None:
    closed: list[str] = []
    cache = WorkerCache(size=2)
    built: list[str] = []

    def build(name: str) -> str:
        built.append(name)
        return name.upper()

    assert cache.get("a", functools.partial(build, "a"), closed.append) == "A"
    assert cache.get("b", functools.partial(build, "b"), closed.append) == "B"
    assert cache.get("a", functools.partial(build, "a")) == "A"  # kept: not built again
    assert built == ["a", "b"]
    cache.get("c", functools.partial(build, "c"), closed.append)  # drops b, the oldest
    assert closed == ["B"] and cache.keys() == ["a", "c"] and len(cache) == 2
    assert "b" not in cache and "a" in cache
    cache.clear()
    assert sorted(closed) == ["A", "B", "C"] and not cache


def test_errors_of_close_are_ignored() -> None:
    def boom(_: object) -> None:
        raise RuntimeError("cannot close")

    cache = WorkerCache(size=1)
    cache.get(1, lambda: 1, boom)
    cache.get(2, lambda: 2, boom)  # drops 1; its close raises, silently
    cache.clear()
    assert len(cache) == 0


def test_bad_size() -> None:
    with pytest.raises(ValueError, match="size must be"):
        WorkerCache(0)


def test_one_cache_per_process_shared_by_environments_and_problems() -> None:
    from voot.bench.protocol import problems as P
    from voot.tree import make_chain
    from voot.tree.root_parallel import worker

    assert worker_cache() is P._ENV_CACHE is worker._PROBLEM_CACHE
    assert CACHE_SIZE == P.ENV_CACHE_SIZE == worker.PROBLEM_CACHE_SIZE
    clear_worker_cache()
    env = P.cached_env("voot/ShekelChain-v0", {"dim": 3})
    factory = functools.partial(make_chain, "shekel", 3)
    worker.prebuild_problem(factory)
    kinds = [key[0] for key in worker_cache().keys()]  # type: ignore[index]
    assert kinds == ["env", "problem"]
    assert P.cached_env("voot/ShekelChain-v0", {"dim": 3}) is env
    P.clear_env_cache()  # one cache: clearing it forgets the problems too
    assert len(worker_cache()) == 0
