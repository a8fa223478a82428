"""Tests of voot.envs.conveyor.generated.witness: the constructive proof that a layout packs."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from voot.envs.conveyor.generated.instance import SceneConveyorEnv, layout_config
from voot.envs.conveyor.generated.layout import generate_storage_layout
from voot.envs.conveyor.generated.scene import compile_storage_scene
from voot.envs.conveyor.generated.witness import Witness, find_witness, room_slots


def _env(seed: int, difficulty: str, attempt: int = 0) -> tuple[SceneConveyorEnv, object]:
    layout = generate_storage_layout(seed, difficulty, attempt)
    return SceneConveyorEnv(compile_storage_scene(layout), layout_config(layout)), layout


def test_room_slots_fill_rows_from_the_back_wall() -> None:
    # a room 4 m (x) by 3 m (y) entered from the east: boxes face west (pi)
    slots = room_slots((-5.0, -1.0, 0.0, 3.0), math.pi, depth=0.6, pitch=1.1, margin=0.8)
    rows = sorted({s[0] for s in slots})
    cols = sorted({s[1] for s in slots})
    assert rows == pytest.approx([0.0, 0.6, 1.2, 1.8, 2.4, 3.0])  # floor(4 / 0.6) rows
    # across: y in [0.8, 2.2] (lateral axis of heading pi is -y), centred, 1.1 apart
    assert len(cols) == 2 and cols[1] - cols[0] == pytest.approx(1.1)
    assert 0.5 * (cols[0] + cols[1]) == pytest.approx(-1.5)
    # rows back to front, each row side to side
    assert [s[0] for s in slots] == sorted(s[0] for s in slots)
    assert room_slots((0.0, 1.0, 0.0, 1.0), 0.0, 0.6, 1.1, margin=0.8) == []


@pytest.mark.parametrize(("seed", "difficulty"), [(0, "easy"), (1, "medium"), (2, "hard")])
def test_the_witness_packs_every_box_through_the_step(seed: int, difficulty: str) -> None:
    env, layout = _env(seed, difficulty)
    w = find_witness(env, layout)
    assert w.solved and w.reason == ""
    assert len(w.placements) == len(w.rooms) == env.n
    assert len(w.actions) == math.ceil(env.n / 3)
    assert w.checks >= env.n
    assert env.task.done and env.objects_left == 0
    # replayed from a reset, the plan packs again with the same rewards
    env.reset(seed=0)
    total = 0.0
    for a in w.actions:
        _, reward, terminated, _, info = env.step(np.array(a))
        assert info["feasible"], info["reason"]
        total += reward
    assert terminated and total == w.total_return
    # each box lies in the room it was assigned to
    for (x, y, _), room in zip(w.placements, w.rooms, strict=True):
        assert layout.room_at(x, y) == room


def test_a_search_that_may_try_nothing_fails_and_says_which_box() -> None:
    env, layout = _env(0, "easy")
    w = find_witness(env, layout, tries_per_room=0)
    assert not w.solved and w.actions == () and w.reason == "obj_00 fits in no room"


def test_witness_json_round_trip_is_exact() -> None:
    env, layout = _env(3, "medium")
    w = find_witness(env, layout)
    back = Witness.from_json(json.loads(json.dumps(w.to_json())))
    assert back == w
