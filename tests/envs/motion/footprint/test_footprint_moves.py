"""Tests of voot.envs.motion.footprint.moves: joining lattice poses by a few moves."""

from __future__ import annotations

from voot.envs.motion.footprint.moves import join_locally, step_between


def test_step_between_moves_position_first_then_heading() -> None:
    path = step_between((0, 2, 2), (1, 4, 3), 8, lambda k, i, j: True)
    assert path == [(0, 3, 3), (0, 4, 3), (1, 4, 3)]
    assert step_between((0, 2, 2), (1, 4, 3), 8, lambda k, i, j: (i, j) != (3, 3)) is None
    assert step_between((0, 0, 0), (0, 9, 0), 8, lambda k, i, j: True) is None  # > 4 moves


def test_join_locally_goes_around_a_blocked_pose() -> None:
    blocked = {(0, 3, 3)}
    path = join_locally((0, 2, 2), (0, 4, 4), (8, 10, 10), lambda k, i, j: (k, i, j) not in blocked)
    assert path is not None and path[-1] == (0, 4, 4) and (0, 3, 3) not in path
    walled = lambda k, i, j: i != 3  # noqa: E731
    assert join_locally((0, 2, 2), (0, 4, 4), (8, 10, 10), walled) is None
