"""Tests of voot.envs.motion.footprint.components: the free lattice's connectivity proof."""

from __future__ import annotations

from collections import deque

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from voot.envs.motion.footprint.astar import numba_available
from voot.envs.motion.footprint.components import connected_labelled, same_component


def _reachable(free: np.ndarray, a: int, b: int) -> bool:
    """Breadth-first search over the A*'s moves: the definition both functions answer."""
    nk, nx, ny = free.shape
    flat = free.reshape(-1)
    if not (flat[a] and flat[b]):
        return False
    seen = {a}
    queue = deque([a])
    while queue:
        v = queue.popleft()
        if v == b:
            return True
        k, i, j = v // (nx * ny), (v // ny) % nx, v % ny
        steps = [((k + dk) % nk, i, j) for dk in (-1, 1)]
        steps += [(k, i + di, j + dj) for di in (-1, 0, 1) for dj in (-1, 0, 1) if di or dj]
        for kk, ii, jj in steps:
            if 0 <= ii < nx and 0 <= jj < ny:
                u = (kk * nx + ii) * ny + jj
                if flat[u] and u not in seen:
                    seen.add(u)
                    queue.append(u)
    return False


@st.composite
def lattices(draw: st.DrawFn) -> tuple[np.ndarray, int, int]:
    shape = (draw(st.integers(1, 5)), draw(st.integers(1, 6)), draw(st.integers(1, 9)))
    density = draw(st.sampled_from([0.3, 0.5, 0.7, 0.9]))
    seed = draw(st.integers(0, 2**32 - 1))
    free = np.random.default_rng(seed).random(shape) < density
    n = free.size
    return free, draw(st.integers(0, n - 1)), draw(st.integers(0, n - 1))


@settings(max_examples=300, deadline=None)
@given(lattices())
def test_runs_and_labels_answer_as_breadth_first_search(case: tuple[np.ndarray, int, int]) -> None:
    free, a, b = case
    expected = _reachable(free, a, b)
    assert connected_labelled(free, a, b) == expected
    assert same_component(free.reshape(-1), *free.shape, a, b) == expected


def test_the_heading_wraps_round_and_a_blocked_end_is_not_connected() -> None:
    free = np.zeros((6, 3, 4), dtype=bool)
    free[0, 0, :] = free[5, 0, :] = True  # the first and last headings only
    a, b = 0, (5 * 3 + 0) * 4 + 3  # (0, 0, 0) and (5, 0, 3): joined through the wrap
    assert _reachable(free, a, b)
    assert connected_labelled(free, a, b) and same_component(free.reshape(-1), 6, 3, 4, a, b)
    free[5, 0, 1] = False  # split the last heading's row: (5, 0, 3) keeps its side via 0
    assert same_component(free.reshape(-1), 6, 3, 4, a, b)
    free[0, 0, 1] = False  # and the first's at the same column: now apart
    assert not _reachable(free, a, b)
    assert not connected_labelled(free, a, b)
    assert not same_component(free.reshape(-1), 6, 3, 4, a, b)
    free[0, 0, 0] = False  # a blocked end
    assert not connected_labelled(free, a, a)
    assert not same_component(free.reshape(-1), 6, 3, 4, a, a)


def test_diagonal_neighbours_join_but_a_turn_needs_the_same_position() -> None:
    free = np.zeros((3, 2, 2), dtype=bool)
    free[0, 0, 0] = free[0, 1, 1] = True  # diagonal at one heading: joined
    assert same_component(free.reshape(-1), 3, 2, 2, 0, 3)
    free[0, 1, 1] = False
    free[1, 1, 1] = True  # diagonal across headings: not a move of the lattice
    b = (1 * 2 + 1) * 2 + 1
    assert not _reachable(free, 0, b)
    assert not same_component(free.reshape(-1), 3, 2, 2, 0, b)
    assert not connected_labelled(free, 0, b)


@pytest.mark.skipif(not numba_available(), reason="numba is not installed")
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_compiled_runs_answer_as_labelling_on_a_large_lattice(seed: int) -> None:
    from voot.envs.motion.footprint.kernels import same_component as compiled

    rng = np.random.default_rng(seed)
    free = rng.random((12, 40, 50)) < 0.25  # near percolation: pairs joined and apart
    flat = np.flatnonzero(free.reshape(-1))
    answers = []
    for a, b in rng.choice(flat, size=(40, 2)):
        answer = connected_labelled(free, int(a), int(b))
        assert compiled(free.reshape(-1), *free.shape, int(a), int(b)) == answer
        answers.append(answer)
    assert 0 < sum(answers) < len(answers)
