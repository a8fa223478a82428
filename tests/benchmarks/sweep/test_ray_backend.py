"""Tests of voot.bench.sweep.ray_backend on a real local Ray instance (small and bounded)."""

from __future__ import annotations

import contextlib
import functools
import logging
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from voot.bench.store.format import Row
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.backends import SerialBackend, make_backend
from voot.bench.sweep.engine import run_sweep
from voot.bench.sweep.plan import PlanSpec, build_plan_specs, run_plan_spec, strip_timings

ray = pytest.importorskip("ray")

pytestmark = pytest.mark.ray


@pytest.fixture(scope="module")
def ray_instance() -> Iterator[None]:
    ray.init(
        num_cpus=2,
        include_dashboard=False,
        log_to_driver=False,
        logging_level=logging.WARNING,
    )
    # the flaky run function below lives in this test module, which workers cannot import
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    try:
        yield
    finally:
        ray.cloudpickle.unregister_pickle_by_value(sys.modules[__name__])
        ray.shutdown()


def specs() -> list[PlanSpec]:
    return build_plan_specs(
        ["shekel_chain"], [3], ["voot", "pw_uct"], [0, 1], simulations=15, grid="default"
    )


def test_ray_and_local_sweeps_give_the_same_rows(ray_instance: None, tmp_path: Path) -> None:
    here, there = ResultStore(tmp_path / "local"), ResultStore(tmp_path / "ray")
    assert run_sweep(specs(), here, SerialBackend(), progress=False).ran == 4
    backend = make_backend("ray", 2)
    summary = run_sweep(specs(), there, backend, progress=False)
    assert summary.ran == 4 and summary.failed == 0 and backend.retries == 0
    assert ray.is_initialized()  # an instance it did not start is left running
    local = {r["run_id"]: strip_timings(r) for r in here.load(kind="plan")}
    remote = {r["run_id"]: strip_timings(r) for r in there.load(kind="plan")}
    assert remote == local  # identical rows but for the timings
    again = run_sweep(specs(), there, backend, progress=False)
    assert again.ran == 0 and again.skipped == 4  # resume works the same way


def flaky_run(marker_dir: str, die_once: str, die_always: str, spec: Any) -> Row:
    """Kill the worker process on the first try of ``die_once`` and on every try of
    ``die_always``; run the rest normally."""
    if spec.run_id == die_always:
        os._exit(3)
    if spec.run_id == die_once:
        marker = Path(marker_dir) / spec.run_id
        if not marker.exists():
            marker.write_text("died once")
            os._exit(3)
    return run_plan_spec(spec)


def test_dead_workers_are_retried_then_recorded_as_failed(
    ray_instance: None, tmp_path: Path
) -> None:
    todo = specs()
    once, always = todo[0].run_id, todo[1].run_id
    store = ResultStore(tmp_path / "r")
    backend = make_backend("ray", 2, max_tries=2)
    run = functools.partial(flaky_run, str(tmp_path), once, always)
    summary = run_sweep(todo, store, backend, progress=False, run=run)
    assert summary.ran == 4 and summary.failed == 1  # the sweep went on
    assert backend.retries == 2  # once for each of the two runs
    recovered = store.get(once)
    assert recovered is not None and recovered["status"] == "ok" and recovered["tries"] == 2
    failed = store.get(always)
    assert failed is not None and failed["status"] == "failed" and failed["tries"] == 2
    assert "died in each of 2 tries" in failed["error"]
    assert failed["config"] == todo[1].config()
    assert {r["run_id"] for r in store.load()} == {s.run_id for s in todo} - {always}
    # a later sweep retries the failed run (here it keeps dying, and stays failed)
    again = run_sweep(todo, store, backend, progress=False, run=run)
    assert again.skipped == 3 and again.ran == 1 and again.failed == 1


def test_bad_ray_arguments() -> None:
    from voot.bench.sweep.ray_backend import RayBackend

    with pytest.raises(ValueError, match="workers must be an integer >= 1"):
        RayBackend(0)
    with pytest.raises(ValueError, match="max_tries must be an integer >= 1"):
        RayBackend(max_tries=0)
    with pytest.raises(ValueError, match="address and max_tries apply to the ray backend"):
        make_backend("process", 2, address="auto")


def raise_on_three(x: int) -> int:
    if x == 3:
        raise ValueError("three")
    return x * x


def test_ray_backend_is_an_executor_for_root_parallel_trees(ray_instance: None) -> None:
    from voot.bench.sweep.ray_backend import RayBackend
    from voot.parallel import Executor
    from voot.tree import make_chain, plan_root_parallel

    backend = RayBackend(2)
    assert isinstance(backend, Executor) and not backend.in_process
    assert list(backend.map(raise_on_three, [4, 1, 2])) == [16, 1, 4]  # the items' order
    with pytest.raises(ValueError, match="three"):
        list(backend.map(raise_on_three, [1, 3]))
    factory = functools.partial(make_chain, "shekel", 3)
    serial = plan_root_parallel(factory, "voot", 20, seed=1, n_trees=3, executor="serial")
    with backend:
        on_ray = plan_root_parallel(factory, "voot", 20, seed=1, n_trees=3, executor=backend)
    assert on_ray == serial


def _ray_descendants(pid: int) -> dict[int, float]:
    import psutil

    try:
        procs = psutil.Process(pid).children(recursive=True)
    except psutil.NoSuchProcess:
        return {}
    out = {}
    for p in procs:
        with contextlib.suppress(psutil.Error):
            out[p.pid] = p.create_time()
    return out


def _alive(pid: int, started: float) -> bool:
    import psutil

    try:
        p = psutil.Process(pid)
        return p.create_time() == started and p.status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_a_killed_driver_leaves_no_ray_processes(tmp_path: Path) -> None:
    """kill -KILL of ``voot-bench plan --backend ray`` while its actors run: the local
    instance it started (GCS, raylet, agents, workers) is gone within seconds."""
    pytest.importorskip("psutil")
    argv = [
        *(sys.executable, "-c", "from voot.bench.cli.main import main; raise SystemExit(main())"),
        *("plan", "--out", str(tmp_path / "store"), "--problems", "shekel_chain"),
        *("--dims", "10", "--planners", "uniform_t", "--grid", "default", "--seeds", "20"),
        *("--simulations", "200000", "--workers", "1", "--backend", "ray", "--no-progress"),
    ]
    driver = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    seen: dict[int, float] = {}
    try:
        deadline = time.monotonic() + 40.0
        names: list[str] = []
        while time.monotonic() < deadline and driver.poll() is None:
            seen.update(_ray_descendants(driver.pid))
            names = []
            for pid in seen:
                with contextlib.suppress(Exception):
                    import psutil

                    names.append(psutil.Process(pid).name())
            if any("_Worker" in n for n in names) and "raylet" in names:
                break
            time.sleep(0.3)
        assert driver.poll() is None, "the sweep ended before it could be killed"
        assert "raylet" in names and any("_Worker" in n for n in names), names
        os.kill(driver.pid, signal.SIGKILL)
        driver.wait(timeout=10)
        deadline = time.monotonic() + 15.0
        while time.monotonic() < deadline and any(_alive(p, t) for p, t in seen.items()):
            time.sleep(0.3)
        survivors = [p for p, t in seen.items() if _alive(p, t)]
        assert not survivors, f"Ray processes {survivors} outlived their killed driver"
    finally:
        if driver.poll() is None:
            driver.kill()
            driver.wait()
        for pid, started in seen.items():  # only the driver's own descendants, by pid
            if _alive(pid, started):
                with contextlib.suppress(ProcessLookupError):
                    os.kill(pid, signal.SIGKILL)


def test_reap_on_driver_death_is_a_boolean() -> None:
    from voot.bench.sweep.ray_backend import RayBackend

    assert RayBackend().reap_on_driver_death is True
    with pytest.raises(ValueError, match="reap_on_driver_death must be True or False"):
        RayBackend(reap_on_driver_death=1)  # type: ignore[arg-type]
