"""Tests of voot.bench.kitchen_demo: the kitchen demo (``voot-bench demo``)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("rerun")
pytest.importorskip("mujoco")
pytest.importorskip("matplotlib")

from voot.bench.cli import main
from voot.bench.kitchen_demo import DemoSummary, planner_options, run
from voot.record.reader import read_recording


@pytest.mark.parametrize("planner", ["voot", "pw_uct", "voronoi_pw", "rand_doot"])
def test_planner_options_are_the_benchmarks(planner: str) -> None:
    from voot.bench.problems import domain_options

    assert planner_options(planner) == domain_options("voot/KitchenClearing-v0", None, planner)


def test_tiny_run_writes_a_recording_that_reads_back(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    summary = run(tmp_path / "out", n_simulations=12, seed=0, video_size=(96, 72), fps=5)
    assert isinstance(summary, DemoSummary)
    assert summary.n_simulations == 12 and summary.obstacles == 7
    assert 0 <= summary.cleared <= 7 and summary.plan_length >= 1
    rec = read_recording(summary.recording)
    assert rec.entity("search/best_return").rows == {"search": 12}
    assert rec.entity("scene/plan/base_pose").rows["plan"] >= 1
    assert "/scene/samples/root/base_poses" in rec.entities  # the env's info keys, drawn
    assert rec.n_blueprints == 1 and summary.recording_entities == len(rec.entities)
    assert summary.video is not None and summary.video.stat().st_size > 1000
    assert summary.video_frames > summary.plan_length
    saved = json.loads((tmp_path / "out" / "kitchen_voot.json").read_text())
    assert saved["cleared"] == summary.cleared and saved["recording"] == str(summary.recording)
    out = capsys.readouterr().out
    assert f"cleared {summary.cleared} of 7 obstacles" in out and "rerun " in out


def test_bad_input(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="n_simulations"):
        run(tmp_path, n_simulations=0)
    with pytest.raises(ValueError, match="seed"):
        run(tmp_path, n_simulations=1, seed=-1)
    with pytest.raises(ValueError, match="unknown planner"):
        run(tmp_path, n_simulations=1, planner="nope")
    (tmp_path / "file").write_text("x")
    with pytest.raises(ValueError, match="folder"):
        run(tmp_path / "file", n_simulations=1)
    assert main(["demo", "--out", str(tmp_path / "cli"), "--simulations", "0"]) == 2
