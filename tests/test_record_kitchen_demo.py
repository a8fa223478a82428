"""Tests of voot.record.kitchen_demo: the kitchen demo, its GIF and the Figure-5 recordings."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("rerun")
pytest.importorskip("mujoco")
pytest.importorskip("matplotlib")

from voot.envs.scripted import kitchen_actions
from voot.record.kitchen_demo import (
    DemoSummary,
    ProposalLog,
    figure5,
    main,
    make_problem,
    plan_animation,
    planner_options,
    run,
)
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


def test_plan_animation_follows_the_scripted_solution() -> None:
    problem = make_problem(0)
    env = problem.unwrapped
    # pick and place box1, then chair1 (a planner's place actions are 3-D)
    actions = [a if k % 2 == 0 else a[:3] for k, a in enumerate(kitchen_actions(env)[:4])]
    expected = make_problem(0)
    for a in actions:
        expected.step(a)
    frames = plan_animation(problem, actions, size=(96, 72), label="test")
    assert len(frames) > 2 * len(actions)  # drives and arm motions between the states
    assert all(f.shape == (72, 96, 3) and f.dtype == np.uint8 for f in frames)
    assert frames[0].std() > 5 and not np.array_equal(frames[0], frames[-1])
    # the problem is left at the end of the plan, exactly
    assert problem.snapshot() == expected.snapshot()
    with pytest.raises(ValueError, match="size"):
        plan_animation(problem, [], size=(10, 10))


def test_figure5_records_the_place_node_and_its_rejected_proposals(tmp_path: Path) -> None:
    runs = figure5(tmp_path, seed=0, visits=4, max_simulations=300, verbose=False)
    assert set(runs) == {"voot", "pw_uct"}
    for r in runs.values():
        assert r.visits >= 4 and 1 <= r.n_samples <= r.visits
        assert r.rejected_entity == r.entity.replace("/placements", "/rejected")
        rec = read_recording(r.recording)
        last = rec.timelines["search"].max
        assert last == r.n_simulations - 1
        t, positions = rec.column(r.rejected_entity, "Points3D:positions", "search")[-1]
        assert t == last and len(positions) == r.n_rejected
        q = rec.latest(r.entity, "q_hat", "search")
        assert len(q) == r.n_samples
        assert "/scene/forbidden_rooms" in rec.entities
    assert (tmp_path / "kitchen_figure5.png").stat().st_size > 10_000


def test_proposal_log_keeps_rejected_proposals_per_state() -> None:
    problem = ProposalLog(make_problem(0))
    s0 = problem.snapshot()
    pick = kitchen_actions(problem.unwrapped)[0]
    assert problem.is_feasible(pick)
    problem.step(pick)
    s1 = problem.snapshot()
    bad = np.array([0.95, 0.95, 0.5])  # a placement in the forbidden rooms
    assert not problem.is_feasible(bad)
    assert len(problem.checks) == 2
    rejected = problem.rejected(s1)
    assert rejected.shape == (1, 3) and rejected[0, 0] > 2.8
    assert problem.rejected(s0).shape == (0, 3)  # the pick was feasible


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
    with pytest.raises(ValueError, match="visits"):
        figure5(tmp_path, visits=0)
    with pytest.raises(ValueError, match="no place node"):
        figure5(tmp_path, seed=0, planners=("voot",), visits=50, max_simulations=5, image=None)
    assert main(["--out", str(tmp_path / "cli"), "--simulations", "0"]) == 2
