"""Snapshots, task records and step timings (voot.envs.core.state)."""

from __future__ import annotations

import dataclasses
import math
import pickle

import numpy as np
import pytest

from voot.envs.core.state import (
    EnvState,
    SceneIdentity,
    StepTiming,
    is_count,
    is_finite_tuple,
    pose_tuple,
    replace,
)
from voot.envs.kitchen.config import KitchenConfig
from voot.envs.kitchen.task import KitchenTask


def test_replace_matches_dataclasses_replace() -> None:
    t = KitchenTask(3, "pick", -1, (0.0, 0.0, 0.0), (), (1, 2), False, False)
    for changes in ({"steps": 4}, {"operator": "place", "held": 2}, {}):
        a, b = replace(t, **changes), dataclasses.replace(t, **changes)
        assert a == b and hash(a) == hash(b) and vars(a) == vars(b) and type(a) is KitchenTask
    assert replace(StepTiming(1.0), total=2.0) == StepTiming(1.0, 0.0, 0.0, 2.0)
    with pytest.raises(TypeError):
        replace(t, nope=1)
    # a dataclass with __post_init__ still validates
    with pytest.raises(ValueError, match="horizon"):
        replace(KitchenConfig(), horizon=0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        replace(t, steps=1).steps = 2  # type: ignore[misc]


def test_pose_tuple_gives_python_floats() -> None:
    assert pose_tuple(np.array([1.0, 2.0, 3.0])) == (1.0, 2.0, 3.0)
    assert pose_tuple([1, 2, 3]) == (1.0, 2.0, 3.0)
    assert all(type(v) is float for v in pose_tuple(np.array([1.0, 2.0, 3.0])))
    assert all(type(v) is float for v in pose_tuple(np.array([1, 2, 3], dtype=np.int64)))
    with pytest.raises(ValueError):
        pose_tuple([1.0, 2.0])


def test_record_predicates() -> None:
    assert is_count(0, 0, 3) and is_count(3, 0, 3)
    assert not is_count(4, 0, 3) and not is_count(-1, 0, 3)
    assert not is_count(True, 0, 3) and not is_count(np.int64(1), 0, 3) and not is_count(1.0, 0, 3)
    assert is_finite_tuple((0.0, 1, -2.5), 3)
    assert not is_finite_tuple((0.0, 1.0), 3) and not is_finite_tuple([0.0, 1.0, 2.0], 3)
    assert not is_finite_tuple((0.0, math.nan, 1.0), 3)
    assert not is_finite_tuple((0.0, math.inf, 1.0), 3)
    assert not is_finite_tuple((0.0, True, 1.0), 3) and not is_finite_tuple((0.0, "1", 1.0), 3)


def test_env_state_compares_by_value_and_shares_with_task() -> None:
    physics = np.arange(5.0)
    physics.setflags(write=False)
    task = KitchenTask(0, "pick", -1, (0.0, 0.0, 0.0), (), (1,), False, False)
    rng = {"bit_generator": "PCG64", "state": {"state": 1, "inc": 3}}
    s = EnvState(physics, 7, task, rng)
    assert s == EnvState(physics.copy(), 7, task, dict(rng))
    assert s != EnvState(physics, 8, task, rng) and s != "state"
    with pytest.raises(TypeError):
        hash(s)
    other = replace(task, steps=1)
    t = s.with_task(other)
    assert t.task is other and t.physics is s.physics and t.rng_state is s.rng_state
    assert t.signature == 7 and t != s and type(t) is EnvState
    assert pickle.loads(pickle.dumps(t)) == t


def test_a_state_carries_its_scene_identity() -> None:
    physics = np.arange(5.0)
    physics.setflags(write=False)
    task = KitchenTask(0, "pick", -1, (0.0, 0.0, 0.0), (), (1,), False, False)
    rng = {"bit_generator": "PCG64", "state": {"state": 1, "inc": 3}}
    here = SceneIdentity("conveyor", "generator-1", 3, "easy", "ab" * 16)
    there = dataclasses.replace(here, layout_seed=4)
    s = EnvState(physics, 7, task, rng, here)
    assert s != EnvState(physics, 7, task, rng, there) and s != EnvState(physics, 7, task, rng)
    assert s == EnvState(physics, 7, task, rng, dataclasses.replace(here))
    moved = s.with_task(replace(task, steps=1))
    assert moved.scene is here  # an infeasible step's snapshot keeps the scene
    assert pickle.loads(pickle.dumps(s)) == s
    assert str(here) == "conveyor generator-1 (layout_seed=3, difficulty=easy, scene abababababab)"
    fixed = SceneIdentity("kitchen", "", None, None, "cd" * 16)
    assert str(fixed) == "kitchen (fixed scene, scene cdcdcdcdcdcd)"
    # a snapshot pickled before states carried a scene loads with none (and is refused)
    old = EnvState(physics, 7, task, rng)
    del old.__dict__["scene"]
    assert pickle.loads(pickle.dumps(old)).scene is None
