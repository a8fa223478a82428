"""Tests of voot.bench.sweep.bbfo: the grid, the run protocol, determinism, resume."""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from store_fixtures import Interrupting, killed_and_resumed

from voot.bench.store.format import Row, StoreError
from voot.bench.store.lock import LOCK_NAME, StoreBusyError, WriterLock
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.backends import ProcessBackend, SerialBackend, make_backend
from voot.bench.sweep.bbfo import (
    PAPER_METHODS,
    RunSpec,
    build_specs,
    describe_config,
    initial_point,
    instance_of,
    method_grid,
    paper_budget,
    run_spec,
    summarize_specs,
)
from voot.bench.sweep.engine import execution_order, pending_specs, run_sweep
from voot.functions import get_function
from voot.optim.voo import VOOConfig

TINY = {"functions": ["rastrigin"], "dims": [3], "methods": ["voo", "random"], "budget": 15}


def tiny_specs(seeds: Sequence[int] = (0, 1), grid: str = "paper") -> list[RunSpec]:
    return build_specs(
        TINY["functions"], TINY["dims"], TINY["methods"], seeds, grid=grid, budget=TINY["budget"]
    )


def test_paper_budgets() -> None:
    assert paper_budget("griewank", 20) == 500
    assert paper_budget("rastrigin", 3) == 500
    assert paper_budget("shekel", 3) == 500
    assert paper_budget("shekel", 20) == 5000
    assert paper_budget("shekel", 10) == 1000
    assert paper_budget("rastrigin", 20) == 1000


def test_grid_sizes_skips_and_budgets() -> None:
    n_voo = len(VOOConfig.paper_grid()["omega"])
    specs = build_specs(["rastrigin"], [3, 10], ["voo", "random"], range(3))
    assert len(specs) == 2 * (n_voo + 1) * 3
    assert {s.budget for s in specs if s.dim == 3} == {500}
    assert {s.budget for s in specs if s.dim == 10} == {1000}
    assert {s.params_dict["omega"] for s in specs if s.method == "voo"} == set(
        VOOConfig.paper_grid()["omega"]
    )
    default = build_specs(["rastrigin"], [3], ["voo"], range(2), grid="default")
    assert [s.params for s in default] == [(), ()]
    scaled = build_specs(["shekel"], [20], ["random"], [0], budget_scale=0.01)
    assert scaled[0].budget == 50
    # the paper does not run REMBO in 3-D
    rembo = build_specs(["shekel"], [3, 10], ["rembo"], [0], grid="default")
    assert [s.dim for s in rembo] == [10]
    assert len({s.run_id for s in specs}) == len(specs)


def test_default_sweep_is_the_papers() -> None:
    specs = build_specs(seeds=[0], grid="default")
    assert {s.function for s in specs} == {"griewank", "rastrigin", "shekel"}
    assert {s.dim for s in specs} == {3, 10, 20}
    assert {s.method for s in specs} == set(PAPER_METHODS)
    assert len(specs) == 9 * len(PAPER_METHODS) - 3  # no REMBO in the three 3-D cells


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"functions": ["nope"]}, "unknown function 'nope'; valid functions are: .*rastrigin"),
        ({"methods": ["vooo"]}, "unknown method 'vooo'; valid methods are: .*voo"),
        ({"dims": [0]}, "dims must be integers >= 1"),
        ({"seeds": [-1]}, "seeds must be integers >= 0"),
        ({"seeds": []}, "no seeds"),
        ({"grid": "huge"}, "unknown grid 'huge'; valid grids are: paper, default"),
        ({"budget_scale": 0.0}, "budget_scale must be > 0"),
        ({"budget_scale": True}, "budget_scale must be > 0"),
        ({"budget": 0}, "budget must be integers >= 1"),
        ({"functions": ["shekel"], "dims": [5]}, "shekel"),
    ],
)
def test_bad_sweep_arguments(kwargs: dict[str, Any], match: str) -> None:
    good = dict(functions=["rastrigin"], dims=[3], methods=["voo"], seeds=[0])
    with pytest.raises(ValueError, match=match):
        build_specs(**{**good, **kwargs})


def test_method_grid_default_and_paper() -> None:
    assert method_grid("voo", "default") == [{}]
    assert method_grid("VOO") == [{"omega": w} for w in VOOConfig.paper_grid()["omega"]]
    assert method_grid("random") == [{}]


def test_all_methods_share_the_initial_point() -> None:
    f = get_function("rastrigin", 3)
    x0 = initial_point("rastrigin", 3, 4, f.bounds.lower, f.bounds.upper)
    assert f.bounds.contains(x0)
    assert not np.array_equal(x0, initial_point("rastrigin", 3, 5, f.bounds.lower, f.bounds.upper))
    firsts = set()
    for spec in build_specs(["rastrigin"], [3], ["voo", "random", "cmaes"], [4], budget=1):
        r = run_spec(spec)
        assert r["status"] == "ok", r.get("error")
        firsts.add(r["best_so_far"][0])
    assert firsts == {f(x0)}


def test_run_row_contents() -> None:
    spec = tiny_specs(seeds=[0])[0]
    r = run_spec(spec)
    assert r["status"] == "ok" and r["error"] is None
    assert r["kind"] == "bbfo" and r["run_id"] == spec.run_id
    assert r["config"] == spec.config() and r["config"]["params"] == spec.params_dict
    best = np.array(r["best_so_far"])
    assert best.size == spec.budget and np.all(np.diff(best) >= 0)
    f = get_function(spec.function, spec.dim)
    assert f(np.array(r["best_x"])) == best[-1]
    assert r["method_config"]["omega"] == spec.params_dict["omega"]


def test_failed_run_gives_a_failed_row() -> None:
    spec = RunSpec("rastrigin", 3, "voo", (("omega", 2.0),), 10, 0)
    r = run_spec(spec)
    assert r["status"] == "failed"
    assert r["error"].startswith("ValueError: omega")
    assert "Traceback" in r["traceback"]


def test_same_spec_same_curve_across_processes() -> None:
    specs = tiny_specs()
    here = {s.run_id: run_spec(s)["best_so_far"] for s in specs}
    rows = list(ProcessBackend(workers=2).map_unordered(run_spec, specs))
    assert len(rows) == len(specs)
    there = {r["run_id"]: r["best_so_far"] for r in rows}
    assert there == here  # bit-identical floats


def test_execution_order_is_seed_major_and_deterministic() -> None:
    specs = tiny_specs(seeds=[2, 0, 1])
    order = execution_order(specs)
    assert sorted(map(id, order)) == sorted(map(id, specs))
    assert [s.seed for s in order] == sorted(s.seed for s in specs)
    assert order == execution_order(specs)


def test_interrupted_sweep_resumes_without_redoing_or_losing(tmp_path: Path) -> None:
    specs = tiny_specs()
    store = ResultStore(tmp_path / "r")
    ran: list[str] = []

    def counting(spec: RunSpec) -> Row:
        ran.append(spec.run_id)
        return run_spec(spec)

    with pytest.raises(KeyboardInterrupt):
        run_sweep(specs, store, Interrupting(after=5), progress=False, run=counting)
    assert len(ran) == 5
    first = {p.name: p.read_bytes() for p in store.row_files()}
    assert len(first) == 5
    summary = run_sweep(specs, store, SerialBackend(), progress=False, run=counting)
    assert summary.skipped == 5 and summary.ran == len(specs) - 5 and summary.failed == 0
    assert sorted(ran) == sorted(s.run_id for s in specs)  # each run exactly once
    assert {r["run_id"] for r in store.load()} == {s.run_id for s in specs}
    for name, data in first.items():  # finished rows untouched
        assert (store.runs_path / name).read_bytes() == data
    again = run_sweep(specs, store, SerialBackend(), progress=False, run=counting)
    assert again.ran == 0 and again.skipped == len(specs)


class _FullDisk:
    """A file of ``os.fdopen`` whose write puts half the bytes down, then fails ENOSPC."""

    def __init__(self, fh: Any) -> None:
        self.fh = fh

    def write(self, data: bytes) -> int:
        self.fh.write(data[: len(data) // 2])
        self.fh.flush()
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    def __getattr__(self, name: str) -> Any:
        return getattr(self.fh, name)

    def __enter__(self) -> _FullDisk:
        return self

    def __exit__(self, *exc: object) -> None:
        self.fh.close()


@pytest.mark.parametrize("where", ["write", "fsync"])
def test_a_full_disk_stops_the_sweep_and_a_resume_redoes_only_the_unfinished(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, where: str
) -> None:
    """ENOSPC while writing the 4th row (half its bytes down, or all of them before the
    fsync): a StoreError naming the store, the run and the cause (it was a bare OSError
    traceback), no trace of that row, every earlier row intact, and a resume that runs
    that run and the rest exactly once."""
    specs = tiny_specs()
    store = ResultStore(tmp_path / "r")
    rows_written = []
    real_fdopen, real_fsync = os.fdopen, os.fsync

    def is_row(fd: int) -> bool:
        return f"{os.sep}runs{os.sep}" in os.readlink(f"/proc/self/fd/{fd}")

    def full(fd: int) -> bool:
        if not is_row(fd):
            return False
        rows_written.append(fd)
        return len(rows_written) == 4

    def fdopen(fd: int, *args: Any, **kwargs: Any) -> Any:
        fh = real_fdopen(fd, *args, **kwargs)
        return _FullDisk(fh) if where == "write" and full(fd) else fh

    def fsync(fd: int) -> None:
        if where == "fsync" and full(fd):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real_fsync(fd)

    monkeypatch.setattr(os, "fdopen", fdopen)
    monkeypatch.setattr(os, "fsync", fsync)
    ran: list[str] = []

    def counting(spec: RunSpec) -> Row:
        ran.append(spec.run_id)
        return run_spec(spec)

    order = execution_order(specs)
    with pytest.raises(
        StoreError, match=r"could not write the row of run .* \(No space left"
    ) as err:
        run_sweep(specs, store, SerialBackend(), progress=False, run=counting)
    assert order[3].run_id in str(err.value) and str(store.path) in str(err.value)
    assert "run the same command again to resume" in str(err.value)
    monkeypatch.undo()
    assert sorted(p.name for p in store.runs_path.iterdir()) == sorted(
        f"{s.run_id}.json" for s in order[:3]
    )  # no temporary file, no half row
    assert ResultStore(store.path).verify() == 3
    first = {p.name: p.read_bytes() for p in store.row_files()}
    ran.clear()
    summary = run_sweep(specs, store, SerialBackend(), progress=False, run=counting)
    assert summary.skipped == 3 and sorted(ran) == sorted(s.run_id for s in order[3:])
    assert {r["run_id"] for r in store.load()} == {s.run_id for s in specs}
    for name, data in first.items():
        assert (store.runs_path / name).read_bytes() == data


def test_failed_runs_are_retried_unless_skipped(tmp_path: Path) -> None:
    store = ResultStore(tmp_path)
    specs = tiny_specs(seeds=[0])
    bad = specs[0]

    def flaky(spec: RunSpec) -> Row:
        row = run_spec(spec)
        if spec == bad:
            row.update(status="failed", error="RuntimeError: flaky")
        return row

    s1 = run_sweep(specs, store, progress=False, run=flaky)
    assert s1.failed == 1 and "flaky" in str(s1)
    assert [s.run_id for s in pending_specs(specs, store)] == [bad.run_id]
    assert pending_specs(specs, store, retry_failed=False) == []
    s2 = run_sweep(specs, store, progress=False)
    assert s2.ran == 1 and s2.failed == 0
    assert store.get(bad.run_id)["status"] == "ok"


def test_a_sweep_holds_the_writer_lock_and_takes_over_a_stale_one(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    specs = build_specs(["shekel"], [3], ["voo"], range(2), budget=5, grid="default")
    store = ResultStore(tmp_path / "r")
    seen = []

    def run(spec: Any) -> Row:  # the lock is held while the runs go
        seen.append(json.loads((store.path / LOCK_NAME).read_text())["pid"])
        return run_spec(spec)

    with WriterLock(store.path), pytest.raises(StoreBusyError, match="another voot-bench"):
        run_sweep(specs, store, progress=False, run=run)
    assert len(store) == 0 and seen == []
    dead = {"pid": 999_999_999, "host": "gone", "started": "then", "command": "voot-bench x"}
    (store.path / LOCK_NAME).write_text(json.dumps(dead))  # left by a killed sweep
    assert run_sweep(specs, store, progress=False, run=run).ran == 2
    assert seen == [os.getpid()] * 2 and not (store.path / LOCK_NAME).exists()
    err = capsys.readouterr().err
    assert "took over the writer lock" in err and "pid 999999999 on host gone" in err


def test_killed_sweep_process_resumes(tmp_path: Path) -> None:
    """SIGKILL a real `voot-bench bbfo` midway, rerun it, and check the store."""
    out = tmp_path / "r"
    argv = [
        "bbfo", "--out", str(out), "--functions", "shekel", "--dims", "10",
        "--methods", "voo", "--seeds", "4", "--budget", "250",
        "--workers", "1", "--no-progress",
    ]  # fmt: skip
    store, before = killed_and_resumed(argv, out, rows=3)
    specs = build_specs(["shekel"], [10], ["voo"], range(4), budget=250)
    assert before <= {f"{s.run_id}.json" for s in specs}
    assert {r["run_id"] for r in store.load()} == {s.run_id for s in specs}


def test_make_backend() -> None:
    assert isinstance(make_backend("process", 1), SerialBackend)
    assert isinstance(make_backend("process", 2), ProcessBackend)
    assert isinstance(make_backend("serial"), SerialBackend)
    with pytest.raises(ValueError, match="valid backends are: process, serial"):
        make_backend("ray-ish")
    with pytest.raises(ValueError, match="workers"):
        ProcessBackend(workers=0)


# ----- test-function instances -------------------------------------------------------------
def test_instance_is_in_the_config_and_run_id_only_when_nonzero() -> None:
    paper = build_specs(["griewank"], [3], ["soo"], [0], budget=5)
    (shifted,) = build_specs(["griewank"], [3], ["soo"], [0], budget=5, instance=2)
    (spec,) = paper
    assert spec.instance == 0 and "instance" not in spec.config()  # paper run ids unchanged
    assert spec == RunSpec("griewank", 3, "soo", (), 5, 0)
    assert shifted.instance == 2 and shifted.config()["instance"] == 2
    assert shifted.run_id != spec.run_id
    assert {k: v for k, v in shifted.config().items() if k != "instance"} == spec.config()
    assert "instance 2 seed 0" in describe_config(shifted.config())
    assert "instance" not in describe_config(spec.config())
    assert "griewank-3D instance 2 budget 5: soo 1" in summarize_specs([shifted])
    assert instance_of(spec.config()) == 0 and instance_of(shifted.config()) == 2
    for bad in (-1, 1.5, True):
        with pytest.raises(ValueError, match="instance must be an integer >= 0"):
            build_specs(["griewank"], [3], ["soo"], [0], instance=bad)  # type: ignore[arg-type]


def test_shifted_instance_keeps_the_initial_point_and_defeats_the_centre() -> None:
    f0, f1 = get_function("griewank", 3), get_function("griewank", 3, instance=1)
    x0 = initial_point("griewank", 3, 0, f0.bounds.lower, f0.bounds.upper)
    rows = {k: run_spec(RunSpec("griewank", 3, "soo", (), 30, 0, k)) for k in (0, 1)}
    assert all(r["status"] == "ok" for r in rows.values())
    assert rows[0]["best_so_far"][0] == f0(x0) and rows[1]["best_so_far"][0] == f1(x0)
    # SOO samples the centre of the box: the exact optimum of the paper's Griewank only.
    assert rows[0]["best_so_far"][-1] == 0.0
    assert rows[1]["best_so_far"][-1] < -1e-3
    assert f1(np.array(rows[1]["best_x"])) == rows[1]["best_so_far"][-1]


def test_runs_execute_with_one_blas_thread() -> None:
    from threadpoolctl import threadpool_info

    from voot.bench.sweep.engine import one_blas_thread

    @one_blas_thread
    def threads(_: object) -> list[int]:
        return [int(lib["num_threads"]) for lib in threadpool_info()]

    inside = threads(None)
    assert inside and all(n == 1 for n in inside)


def test_fixed_parameters_join_every_setting_and_are_checked() -> None:
    specs = build_specs(["griewank"], [3], ["voo"], [0], fixed={"sampler": "gaussian"})
    assert len(specs) == len(method_grid("voo"))
    assert all(dict(s.params)["sampler"] == "gaussian" for s in specs)
    plain = build_specs(["griewank"], [3], ["voo"], [0])
    assert {s.run_id for s in specs}.isdisjoint(s.run_id for s in plain)
    # a fixed value overrides the grid axis of the same name: one setting left
    one = build_specs(["griewank"], [3], ["voo"], [0], fixed={"omega": 0.1})
    assert [dict(s.params) for s in one] == [{"omega": 0.1}]
    with pytest.raises(ValueError, match=r"cmaes.*valid options"):
        build_specs(["griewank"], [3], ["voo", "cmaes"], [0], fixed={"sampler": "gaussian"})
    with pytest.raises(ValueError, match="valid samplers are"):
        build_specs(["griewank"], [3], ["voo"], [0], fixed={"sampler": "gauss"})


# ----- the registry of spec kinds -------------------------------------------------------------
def test_run_any_dispatches_on_the_registered_kinds() -> None:
    from voot.bench.sweep import engine as sweep

    assert sweep.RUNNERS["bbfo"] is run_spec
    spec = RunSpec("rastrigin", 3, "random", (), 5, 0)
    assert sweep.run_any(spec)["best_so_far"] == run_spec(spec)["best_so_far"]
    with pytest.raises(TypeError, match="cannot run a int"):
        sweep.run_any(3)


def test_sweep_does_not_import_the_plan_sweep() -> None:
    code = "import sys, voot.bench.sweep.bbfo; print('voot.bench.sweep.plan' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_duplicate_specs_run_once(tmp_path: Path) -> None:
    """The same run listed twice (e.g. overlapping grids) is run and stored once."""
    from voot.bench.store.result_store import ResultStore
    from voot.bench.sweep.bbfo import build_specs
    from voot.bench.sweep.engine import run_sweep

    specs = build_specs(["shekel"], [3], ["voo"], range(2), budget=10, grid="default")
    doubled = [*specs, *specs[::-1]]
    calls: list[str] = []

    def run(spec: Any) -> Any:
        calls.append(spec.run_id)
        from voot.bench.sweep.bbfo import run_spec

        return run_spec(spec)

    store = ResultStore(tmp_path / "s")
    summary = run_sweep(doubled, store, progress=False, run=run)
    assert summary.total == len(specs) == summary.ran and summary.skipped == 0
    assert sorted(calls) == sorted(s.run_id for s in specs)
    assert len(store.load()) == len(specs)
    again = run_sweep(doubled, store, progress=False, run=run)
    assert again.skipped == len(specs) and again.ran == 0 and len(calls) == len(specs)


def test_the_progress_bar_is_on_by_default_and_counts_failures(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    specs = tiny_specs(seeds=[0])

    def failing(spec: RunSpec) -> Row:
        row = run_spec(spec)
        row.update(status="failed", error="RuntimeError: no")
        return row

    run_sweep(specs, ResultStore(tmp_path / "a"), run=failing)
    bar = capsys.readouterr().err
    done = f"{len(specs)}/{len(specs)}"
    assert done in bar and f"failed={len(specs)}" in bar
    run_sweep(specs, ResultStore(tmp_path / "b"))
    bar = capsys.readouterr().err
    assert done in bar and "failed" not in bar
    run_sweep(tiny_specs(seeds=[1]), ResultStore(tmp_path / "c"), progress=False)
    assert capsys.readouterr().err == ""


class Recording:
    """A serial backend whose generator records being closed (what cancels the runs
    that have not started, in the process backends)."""

    name = "recording"

    def __init__(self) -> None:
        self.closed = False
        self.started = 0

    def map_unordered(self, fn: Callable[[Any], Row], items: Sequence[Any]) -> Iterator[Row]:
        try:
            for item in items:
                self.started += 1
                yield fn(item)
        finally:
            self.closed = True


def test_a_sweep_stopped_by_an_error_closes_the_backend_at_once(tmp_path: Path) -> None:
    class Full(ResultStore):
        def write(self, row: Row) -> Path:
            raise OSError("no space left on device")

    backend = Recording()
    specs = tiny_specs()
    try:
        run_sweep(specs, Full(tmp_path / "s"), backend, progress=False)
    except StoreError as exc:  # the write's OSError, named (voot.bench.sweep.bbfo.write_row)
        error = exc  # its traceback keeps run_sweep's frame, and the generator, alive
    assert "no space" in str(error.__cause__)
    assert backend.closed and backend.started == 1  # closed by run_sweep, not by gc
