"""voot.envs.conveyor.scripted: the solutions of voot's and the authors' rooms, and the
slot search that found the latter."""

from __future__ import annotations

import math

import pytest

from voot.envs.conveyor.authors_rooms import AUTHORS_WALLS
from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.scripted import (
    AUTHORS_BIG_SLOTS,
    AUTHORS_SMALL_SLOTS,
    AUTHORS_SOLUTION,
    CONVEYOR_SOLUTION,
    conveyor_actions,
    pose_actions,
    search_solution,
    solution_poses,
)
from voot.envs.core.scene import object_footprint

AUTHORS = {"preset": "v1", "rooms": "authors", "base_model": "footprint", "big_box_ban": True}


def test_each_room_set_has_its_table() -> None:
    voot = ConveyorPackingEnv(preset="v1")
    authors = ConveyorPackingEnv(**AUTHORS)  # type: ignore[arg-type]
    assert solution_poses(voot) is CONVEYOR_SOLUTION
    assert solution_poses(authors) is AUTHORS_SOLUTION
    assert len(AUTHORS_SOLUTION) == len(CONVEYOR_SOLUTION) == 20
    assert [a.tolist() for a in conveyor_actions(voot)] == [
        a.tolist() for a in pose_actions(voot, CONVEYOR_SOLUTION)
    ]


def test_the_authors_table_is_first_slots_inside_the_authors_rooms() -> None:
    env = ConveyorPackingEnv(**AUTHORS)  # type: ignore[arg-type]
    assert set(AUTHORS_SOLUTION[:2]) <= set(AUTHORS_BIG_SLOTS)
    assert set(AUTHORS_SOLUTION[2:]) <= set(AUTHORS_SMALL_SLOTS)
    assert AUTHORS_SOLUTION[0] == AUTHORS_BIG_SLOTS[0]
    assert AUTHORS_SOLUTION[2:5] == AUTHORS_SMALL_SLOTS[:3]
    north = next(w for w in AUTHORS_WALLS if w[0] == "wall_north")[3]
    for i, (x, y, th) in enumerate(AUTHORS_SOLUTION):
        box = object_footprint(env.objects[i], x, y, math.radians(th))
        ymax = max(c[1] for c in box.corners())
        assert ymax < north  # voot's top row (y = 2.55) is not
        if i < 2:  # the big boxes in the authors' first room
            assert -4.0 < x < -0.7 and -0.5 < y < 2.5
        else:  # the small ones in the west room
            assert -7.4 < x < -4.0
    assert max(y for _, y, _ in CONVEYOR_SOLUTION) + 0.2 > north


def test_the_first_action_executes_with_the_footprint_and_not_with_the_disc() -> None:
    exact = ConveyorPackingEnv(**AUTHORS)  # type: ignore[arg-type]
    disc = ConveyorPackingEnv(preset="v1", rooms="authors")
    infos = []
    for env in (exact, exact, disc):
        env.reset(seed=0)
        infos.append(env.transition(conveyor_actions(env)[0]))
    (r1, _, _, i1), (r2, _, _, i2), (_, _, _, i3) = infos
    assert i1["feasible"] and exact.task.placed == 3
    assert r1 == r2 and i1["base_path_lengths"] == i2["base_path_lengths"]  # deterministic
    # the third box goes to the west room's north row: a long path through three openings
    assert i1["base_path_lengths"][2] > 15.0
    assert i3["reason"] == "box 1/3 (obj_00): no base path"


def test_the_search_rederives_the_table_and_says_when_nothing_fits() -> None:
    env = ConveyorPackingEnv(n_objects=3, **AUTHORS)  # type: ignore[arg-type]
    assert search_solution(env) == AUTHORS_SOLUTION[:3]
    assert env.task.done
    with pytest.raises(ValueError, match="no slot of the list fits obj_02"):
        search_solution(env, small_slots=((0.0, 1.0, 90.0),))  # outside


@pytest.mark.slow
def test_the_authors_table_solves_the_authors_domain() -> None:
    """About 2 CPU minutes: 18 exact-footprint paths into the west room."""
    env = ConveyorPackingEnv(**AUTHORS)  # type: ignore[arg-type]
    env.reset(seed=0)
    for a in conveyor_actions(env):
        _, _, _, info = env.transition(a)
        assert info["feasible"], info["reason"]
    assert env.task.done
