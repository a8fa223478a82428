"""Tests of voot.bench.measure.root_parallel (tiny budgets; the real run is a command)."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from voot.bench.measure.root_parallel import (
    configurations,
    format_table,
    make_setup,
    measure,
    plot,
    sims_done_by,
    table_rows,
)


def test_configurations_never_have_more_workers_than_trees() -> None:
    assert configurations([4, 1, 2], [2, 1]) == [(1, 1), (2, 1), (4, 1), (2, 2), (4, 2)]


def test_setups_and_their_errors() -> None:
    s = make_setup("shekel", 40, dim=3)
    assert s.name == "shekel3" and s.budget == 40 and s.record_info is None
    assert s.factory().action_bounds().dim == 3
    assert make_setup("kitchen").record_info == "objects_left"
    with pytest.raises(ValueError, match="valid problems are: shekel, kitchen"):
        make_setup("conveyor")
    with pytest.raises(ValueError, match="divisible"):
        measure(make_setup("shekel", 10, dim=3), trees=(1, 4), workers=(1,), seeds=(0,))
    with pytest.raises(ValueError, match="include 1"):
        measure(make_setup("shekel", 8, dim=3), trees=(2,), workers=(1,), seeds=(0,))


def test_a_tiny_measurement_gives_a_table_and_a_figure(tmp_path: Path) -> None:
    m = measure(make_setup("shekel", 8, dim=3), trees=(1, 2), workers=(1,), seeds=(0, 1))
    assert sorted(m.fixed) == [(1, 1), (2, 1)]
    assert all(len(v) == 2 for v in m.fixed.values())
    assert sorted(m.long) == [1] and m.long[1][0] is m.fixed[(1, 1)][0]
    # The merged result of 2 trees of 4 simulations is the deterministic one.
    assert [r.total_simulations for r in m.fixed[(2, 1)]] == [8, 8]
    rows = table_rows(m)
    assert [(r["K"], r["W"], r["sims_per_tree"]) for r in rows] == [(1, 1, 8), (2, 1, 4)]
    assert rows[0]["speedup"] == 1.0 and rows[0]["best_at_equal_time"] == rows[0]["best_at_budget"]
    assert math.isnan(rows[1]["best_at_equal_time"])
    text = format_table(rows)
    assert text.count("\n") == 3 and "| shekel3 | 2 | 1 | 4 |" in text
    single = m.fixed[(1, 1)][0]
    assert sims_done_by(single, 1e9) == 8 and sims_done_by(single, -1.0) == 0
    assert np.isfinite(single.cpu_time) and single.cpu_time >= 0
    pytest.importorskip("matplotlib")
    out = plot([m], tmp_path / "fig.png", note="test")
    assert out.stat().st_size > 10_000


def test_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from voot.bench.cli.main import main

    args = ["measure", "root-parallel", "--dim", "3", "--budget", "4", "--trees", "1", "2"]
    args += ["--workers", "1"]
    assert main([*args, "--seeds", "1", "--figure", "", "--json", str(tmp_path / "t.json")]) == 0
    out = capsys.readouterr().out
    assert "| shekel3 | 2 | 1 | 2 |" in out and "load averages" in out
    assert (tmp_path / "t.json").read_text().startswith("{")
    assert main([*args, "--seeds", "0"]) == 2
    assert "--seeds takes one count >= 1" in capsys.readouterr().err


def test_importing_the_benchmark_loads_neither_matplotlib_nor_mujoco() -> None:
    # import voot loads the families' problem records (voot.envs.*.problems), no env code
    code = (
        "import sys, voot.bench.measure.root_parallel;"
        " print(sorted(m for m in ('matplotlib', 'mujoco', 'voot.envs.core.env') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
