"""The "Bring your own planner" page (docs/planners.md) runs as written: its ``python``
blocks, in order, in one namespace, and the planner it defines runs in the sweep."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "planners.md"


def page_blocks(language: str) -> list[str]:
    """The page's fenced blocks of ``language``, in order."""
    return re.findall(rf"^```{language}\n(.*?)^```", PAGE.read_text(), flags=re.S | re.M)


def test_the_pages_python_blocks_run(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    blocks = page_blocks("python")
    assert len(blocks) >= 4
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, Any] = {"__name__": "planners_page"}
    for block in blocks:
        exec(compile(block, str(PAGE), "exec"), namespace)
    printed = capsys.readouterr().out
    assert "steps measured by voot" in printed and "VOOT: best return" in printed
    assert "planner 'broken' raised ValueError in simulation 2 of 5" in printed


def test_the_pages_planner_runs_in_the_sweep(monkeypatch: pytest.MonkeyPatch) -> None:
    """The page's planner, registered by name, through build_plan_specs and a run."""
    from voot.bench.sweep import planners as SP
    from voot.bench.sweep.plan import build_plan_specs, run_plan_spec
    from voot.planners import as_planner

    namespace: dict[str, Any] = {}
    exec(compile(page_blocks("python")[0], str(PAGE), "exec"), namespace)
    registry = SP._builtin_registry()
    registry.register(as_planner("random_rollouts", namespace["random_rollouts"]))
    monkeypatch.setattr(SP, "REGISTRY", registry)
    specs = build_plan_specs(["shekel_chain"], [3], ["random_rollouts"], [0], simulations=5)
    assert [s.params for s in specs] == [(("horizon", h),) for h in (2, 3, 5)]
    row = run_plan_spec(specs[0])
    assert row["status"] == "ok" and row["simulator_calls"] == row["calls_curve"][-1] > 0


def test_the_pages_entry_point_matches_the_example_package() -> None:
    toml = (ROOT / "examples" / "greedy_planner" / "pyproject.toml").read_text()
    assert '[project.entry-points."voot.planners"]' in toml
    assert '[project.entry-points."voot.planners"]' in page_blocks("toml")[0]


def test_the_example_package_runs_by_module_attribute(monkeypatch: pytest.MonkeyPatch) -> None:
    """examples/greedy_planner, not installed: ``greedy_planner:greedy`` from its folder."""
    from voot.planners import import_planner, run_planner
    from voot.tree.chains import make_chain

    monkeypatch.syspath_prepend(str(ROOT / "examples" / "greedy_planner"))
    greedy = import_planner("greedy_planner:greedy")
    assert greedy.settings_grid("chain") == [{"width": w} for w in (2, 4, 8)]
    out = run_planner(greedy, make_chain("shekel", 3), 6, np.random.SeedSequence(0), {"width": 2})
    assert len(out.best_so_far) == 6 and out.n_steps > 6  # two candidates per action
