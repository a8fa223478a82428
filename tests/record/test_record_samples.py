"""Tests of voot.record.samples: a node's sampled actions, their poses and drawings."""

from __future__ import annotations

import numpy as np
import pytest

from voot.optim.base import Bounds
from voot.record.samples import NodeSamples, SampleLog, pose_of
from voot.tree import MCTS, MCTSConfig, StepResult
from voot.tree.null_problem import NullProblem


class Poses:
    """Actions (x, y, theta) carrying a base pose, a placement or neither (by theta)."""

    def __init__(self) -> None:
        self.k = 0

    def snapshot(self) -> int:
        return self.k

    def restore(self, s: int) -> None:
        self.k = s

    def action_bounds(self) -> Bounds:
        return Bounds.cube(-1.0, 1.0, 3)

    def step(self, a: np.ndarray) -> StepResult:
        self.k += 1
        key = ("base_pose", "placement", "other")[min(int((a[2] + 1.0) * 1.5), 2)]
        return StepResult(
            float(a[0]), feasible=bool(a[1] > -0.8), terminal=True, info={key: tuple(a)}
        )


def test_pose_of_accepts_three_finite_numbers_only() -> None:
    assert pose_of({"p": (1, 2, 3)}, "p").tolist() == [1.0, 2.0, 3.0]  # type: ignore[union-attr]
    assert pose_of({"p": np.array([[1.0, 2.0, 3.0]])}, "p") is not None
    for bad in (None, (1, 2), (1, 2, np.nan), "abc", {"x": 1}):
        assert pose_of({"p": bad}, "p") is None
    assert pose_of({}, "p") is None


def test_node_samples_cache_grows_with_the_node() -> None:
    mcts = MCTS(Poses(), MCTSConfig(root_commitment=None), seed=0)
    mcts.search(7)
    cache = NodeSamples(mcts.root)
    cache.update()
    assert cache.n == mcts.root.n_actions == 7
    assert np.array_equal(cache.actions, np.array(mcts.root.actions))
    has_base = ~np.isnan(cache.base_poses[:, 0])
    has_place = ~np.isnan(cache.placements[:, 0])
    keys = [next(iter(c.info)) for c in mcts.root.children]
    assert has_base.tolist() == [k == "base_pose" for k in keys]
    assert has_place.tolist() == [k == "placement" for k in keys]
    assert np.allclose(cache.base_poses[has_base], cache.actions[has_base])
    mcts.search(5)
    cache.update()
    assert cache.n == 12 and cache.actions.shape == (12, 3)
    q, feasible = cache.values()
    assert np.array_equal(q, mcts.root.q) and feasible.tolist() == mcts.root.feasible


def test_sample_log_kinds() -> None:
    mcts = MCTS(Poses(), MCTSConfig(root_commitment=None), seed=0)
    log = SampleLog()
    empty = NodeSamples(mcts.root)
    assert log.add(0, empty, "root") == "none"
    mcts.search(6)
    assert log.add(5, empty, "root") == "scene"
    assert log.entities == {"scene/samples/root/base_poses", "scene/samples/root/placements"}
    series = log._series["scene/samples/root/base_poses"]
    assert series.times == [5] and series.lengths == [
        int((~np.isnan(empty.base_poses[:, 0])).sum())
    ]
    # Heading arrows on the floor.
    o, v = series.arrays["origins"][0], series.arrays["vectors"][0]
    base = empty.base_poses[~np.isnan(empty.base_poses[:, 0])]
    assert np.allclose(o[:, :2], base[:, :2]) and np.allclose(o[:, 2], 0.02)
    assert np.allclose(np.arctan2(v[:, 1], v[:, 0]), base[:, 2]) and np.allclose(v[:, 2], 0)


@pytest.mark.parametrize(("dim", "expect_q_axis"), [(1, True), (3, False)])
def test_plot_fallback(dim: int, expect_q_axis: bool) -> None:
    mcts = MCTS(NullProblem(dim), MCTSConfig(depth_limit=2), seed=0)
    mcts.search(10)
    log = SampleLog(labels=True)
    cache = NodeSamples(mcts.root)
    assert log.add(9, cache, "root") == "plot"
    series = log._series["samples/root"]
    xy = series.arrays["positions"][0]
    acts = np.array(mcts.root.actions)
    assert np.allclose(xy[:, 0], acts[:, 0])
    assert np.allclose(xy[:, 1], mcts.root.q if expect_q_axis else acts[:, 1])
    assert series.arrays["labels"][0][0].startswith("Q=")
