"""The kitchen's fixed path and the obstacles on it (voot.envs.kitchen.path)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.path import ClearingPath
from voot.envs.kitchen.scripted import kitchen_actions
from voot.envs.motion.swept_volume import obstacles_on_path


@pytest.fixture(scope="module")
def env() -> KitchenClearingEnv:
    return KitchenClearingEnv()


def test_on_path_memory_gives_the_swept_volume_answers() -> None:
    env = KitchenClearingEnv()
    env.reset(seed=0)
    clearing = env._clearing
    assert clearing is not None and clearing.path is env.path
    for a in kitchen_actions(env):
        env.transition(a)
        names = set(
            obstacles_on_path(env.path.waypoints, env.config.robot_radius, env.object_boxes())
        )
        expect = tuple(i for i in clearing.order if env.objects[i].name in names)
        assert env._on_path() == expect
        if env.task.operator == "pick" and not env.task.done:
            assert env.task.on_path == expect
    assert clearing.memo  # answers were remembered


def test_handling_order_sorts_the_initial_obstacles_along_the_path(
    env: KitchenClearingEnv,
) -> None:
    env.reset(seed=0)
    clearing = env._clearing
    assert clearing is not None
    boxes = env.object_boxes()
    first = env.task.on_path  # the initial obstacles, in handling order
    assert clearing.order[: len(first)] == first
    assert sorted(clearing.order) == list(range(len(env.objects)))
    positions = [clearing.position(boxes[i]) for i in first]
    assert positions == sorted(positions) and positions[0] > 0.0
    assert clearing.rank == {i: k for k, i in enumerate(clearing.order)}
    # a fresh ClearingPath of the same path and footprints finds the same order
    names = [o.name for o in env.objects]
    again = ClearingPath(env.path, env.config.robot_radius, names, boxes)
    assert again.order == clearing.order and again.on_path(boxes) == first


def test_position_is_the_arc_length_of_the_nearest_path_point(env: KitchenClearingEnv) -> None:
    clearing = env._clearing
    assert clearing is not None
    w = env.path.waypoints[:, :2]
    length = float(np.sum(np.hypot(*np.diff(w, axis=0).T)))
    box = env.object_box(0)
    at = [dataclasses.replace(box, cx=float(x), cy=float(y)) for x, y in (w[0], w[-1])]
    assert clearing.position(at[0]) == pytest.approx(0.0, abs=1e-12)
    assert clearing.position(at[1]) == pytest.approx(length)
