"""Tests of voot.bench.backends: sweep backends are voot.parallel executors."""

from __future__ import annotations

import pytest

from voot.bench import backends, sweep
from voot.parallel import Executor, ProcessExecutor, SerialExecutor


def double(x: int) -> int:
    return 2 * x


def test_backends_are_executors() -> None:
    assert backends.SerialBackend is SerialExecutor
    process = backends.make_backend("process", 2)
    assert isinstance(process, backends.ProcessBackend) and isinstance(process, ProcessExecutor)
    assert isinstance(process, Executor) and process.name == "process"
    assert not process.keep_alive and process.workers == 2 and process.max_pending == 8
    assert sorted(process.map_unordered(double, [1, 2, 3])) == [2, 4, 6]
    assert process._pool is None  # a pool per call, shut down when it ends
    assert isinstance(backends.make_backend("serial"), Executor)
    assert backends.BACKENDS == ("process", "serial", "ray")


def test_sweep_re_exports_the_backends() -> None:
    for name in ("Backend", "SerialBackend", "ProcessBackend", "make_backend", "BACKENDS"):
        assert getattr(sweep, name) is getattr(backends, name)


def test_bad_workers_are_named_as_the_sweep_names_them() -> None:
    with pytest.raises(ValueError, match=r"^workers must be an integer >= 1, got 0"):
        backends.ProcessBackend(workers=0)


def test_ray_options_need_the_ray_backend() -> None:
    with pytest.raises(ValueError, match="apply to the ray backend only"):
        backends.make_backend("serial", max_tries=2)
