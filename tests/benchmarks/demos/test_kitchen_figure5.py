"""Tests of voot.bench.demos.figure5: the Figure-5 recordings on the kitchen."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("rerun")
pytest.importorskip("mujoco")
pytest.importorskip("matplotlib")

from voot.bench.demos.figure5 import ProposalLog, figure5
from voot.bench.demos.kitchen_demo import make_problem
from voot.envs.kitchen.scripted import kitchen_actions
from voot.record.reader import read_recording


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
    with pytest.raises(ValueError, match="visits"):
        figure5(tmp_path, visits=0)
    with pytest.raises(ValueError, match="no place node"):
        figure5(tmp_path, seed=0, planners=("voot",), visits=50, max_simulations=5, image=None)
    with pytest.raises(ValueError, match="figure5 runs on the paper's kitchen"):
        figure5(tmp_path, env_id="voot/KitchenClearing-v2")  # the demo takes v2, figure5 not


def test_v1_counts_add_up_and_come_from_the_env_step_info(tmp_path: Path) -> None:
    import json
    from collections import Counter

    from voot.bench.demos.kitchen_demo import options_for
    from voot.tree.planners import plan

    env_id = "voot/KitchenClearing-v1"
    runs = figure5(
        tmp_path,
        seed=0,
        planners=("rand_doot", "voot"),
        visits=12,
        max_simulations=400,
        verbose=False,
        env_id=env_id,
        image="f5.png",
    )
    saved = json.loads((tmp_path / "f5.json").read_text())
    assert saved["env_id"] == env_id and saved["visits"] == 12
    failed_somewhere = False
    for key, r in runs.items():
        counts = r.counts()
        assert saved["planners"][key] == counts
        assert counts["drawn"] == counts["executed"] + counts["precheck_failed"] == r.n_drawn
        assert counts["executed"] == counts["feasible"] + sum(r.execution_failures.values())
        assert counts["precheck_failed"] == sum(r.precheck_failures.values())
        assert "" not in r.execution_failures and "" not in r.precheck_failures
        # replay every executed placement through env.step: the same reason codes
        res = plan(make_problem(0, env_id), key, r.n_simulations, 0, **options_for(env_id, key))
        assert res.mcts is not None
        node = res.mcts.nodes[r.node_id]
        assert node.visits == r.visits and len(node.actions) == r.n_samples
        problem = make_problem(0, env_id)
        replayed: Counter[str] = Counter()
        for action in node.actions:
            problem.restore(node.snapshot)
            step = problem.step(action)
            if not step.feasible:
                replayed[step.info["reason_code"]] += 1
        assert dict(replayed) == r.execution_failures
        assert set(r.execution_failures) <= {"forbidden room", "no base path"}
        rec = read_recording(r.recording)
        text = rec.latest(r.counts_entity, "TextDocument:text", "search")
        assert r.counts_text().split("\n")[0] in str(text)
        if r.n_samples > r.n_feasible:
            failed_somewhere = True
            _, positions = rec.column(r.failed_entity, "Points3D:positions", "search")[-1]
            assert len(positions) == r.n_samples - r.n_feasible
    assert failed_somewhere  # v1 finds forbidden rooms and base paths only at execution
    assert (tmp_path / "f5.png").stat().st_size > 10_000
