"""Tests of voot.bench.kitchen_figure5: the Figure-5 recordings on the kitchen."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("rerun")
pytest.importorskip("mujoco")
pytest.importorskip("matplotlib")

from voot.bench.kitchen_demo import make_problem
from voot.bench.kitchen_figure5 import ProposalLog, figure5
from voot.envs.scripted import kitchen_actions
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
