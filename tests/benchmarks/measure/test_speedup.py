"""``voot-bench speedup`` (voot.bench.measure.speedup): baseline commit vs current code; no timing asserts."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from voot.bench.measure import speedup
from voot.bench.measure.speedup import SpeedupError, Workload


def _checkout() -> Path:
    try:
        return speedup.repo_root()
    except SpeedupError as exc:
        pytest.skip(f"not in a git checkout: {exc}")


def test_select_workloads() -> None:
    names = [w.name for w in speedup.select_workloads(None)]
    assert names == ["kitchen-voot", "conveyor-pwuct"]
    ws = speedup.select_workloads(["conveyor-pwuct"], ["7"])
    assert [(w.name, w.simulations, w.planner) for w in ws] == [("conveyor-pwuct", 7, "pw_uct")]
    ws = speedup.select_workloads(None, ["kitchen-voot=9"])
    assert [w.simulations for w in ws] == [9, 3000]
    for bad, match in ((["x=3"], "unknown workload"), (["0"], ">= 1"), (["a"], "N or NAME=N")):
        with pytest.raises(SpeedupError, match=match):
            speedup.select_workloads(None, bad)
    with pytest.raises(SpeedupError, match="unknown workload"):
        speedup.select_workloads(["nope"])


def test_outside_a_checkout_says_so(tmp_path: Path) -> None:
    with pytest.raises(SpeedupError, match="git checkout"):
        speedup.repo_root(tmp_path)
    for d in ("voot", "envs", "models", "benchmarks"):
        (tmp_path / d).mkdir()
    if shutil.which("git") is not None:
        with pytest.raises(SpeedupError, match="pip-installed wheel"):
            speedup.repo_root(tmp_path)


def test_unknown_commit() -> None:
    root = _checkout()
    with pytest.raises(SpeedupError, match="not in the repository"):
        speedup.resolve_commit(root, "0" * 40)


def test_import_root_lays_out_the_packages(tmp_path: Path) -> None:
    root = _checkout()
    dest = speedup.import_root(root, tmp_path / "current")
    for name in ("envs", "models", "bench", "tree", "__init__.py"):
        assert (dest / "voot" / name).exists(), name
    code = "import voot.envs.kitchen.env, voot.bench.measure.speedup as s; print(s.__file__)"
    out = subprocess.run(
        [sys.executable, "-c", code],
        cwd=dest,
        env={**os.environ, "PYTHONPATH": str(dest)},
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().startswith(str(dest))


def test_compare_tiny_workloads() -> None:
    _checkout()
    workloads = [
        Workload("kitchen-voot", "voot/KitchenClearing-v0", "voot", 4),
        Workload("conveyor-pwuct", "voot/ConveyorPacking-v0", "pw_uct", 1),
    ]
    full, current, comparisons = speedup.compare(workloads, "HEAD", curve=True)
    assert len(full) == 40 and current
    for c in comparisons:
        assert c.identical and c.baseline.curve == c.current.curve
        assert c.baseline.n_steps == c.current.n_steps > 0
        assert c.ratio > 0 and c.current.split is not None
        assert speedup.curve_digest([float.fromhex(v) for v in c.current.curve or ()]) == (
            c.current.curve_sha256
        )
    kitchen, conveyor = comparisons
    assert kitchen.current.split is not None and kitchen.current.split["prescreen"] > 0
    assert conveyor.current.split is not None and conveyor.current.split["prescreen"] == 0
    text = speedup.format_report(full, current, comparisons)
    assert (
        "bit-identical: yes" in text and "ms wall per simulation" in text and "kitchen-voot" in text
    )
    assert "v0 pre-screens" in speedup.split_line(kitchen.current)
    assert "v0 pre-screens" not in speedup.split_line(conveyor.current)
    data = speedup.report_json(full, current, comparisons)
    assert [w["curve_identical"] for w in data["workloads"]] == [True, True]


def test_compare_repeats_alternate_and_keep_the_fastest() -> None:
    _checkout()
    workloads = [Workload("kitchen-voot", "voot/KitchenClearing-v0", "voot", 3)]
    full, current, (c,) = speedup.compare(workloads, "HEAD", split=False, repeats=2)
    assert len(c.baseline_cpu) == len(c.current_cpu) == c.repeats == 2
    assert c.baseline.cpu == min(c.baseline_cpu) and c.current.cpu == min(c.current_cpu)
    assert c.identical and c.repeats_agree
    text = speedup.format_report(full, current, (c,))
    assert "2 alternating runs each" in text and "every run:" in text
    data = speedup.report_json(full, current, (c,))
    assert data["workloads"][0]["current_cpu_runs"] == list(c.current_cpu)
    with pytest.raises(SpeedupError, match="repeats must be an integer >= 1"):
        speedup.compare(workloads, "HEAD", repeats=0)
