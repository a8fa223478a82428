"""Joining two poses of the (heading, x, y) lattice by a few lattice moves.

What :class:`~voot.envs.motion.footprint.search.FootprintSearch` uses to refine a coarse
lattice's path (``coarse_first``) on the fine lattice: straight moves where the poses
between are free (:func:`step_between`), else the fewest moves around within one pose
(:func:`join_locally`). ``free(k, i, j)`` answers for a pose; both are deterministic.
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["Pose", "join_locally", "step_between"]

Pose = tuple[int, int, int]


def step_between(
    a: Pose, b: Pose, nk: int, free: Callable[[int, int, int], bool]
) -> list[Pose] | None:
    """Lattice moves from ``a`` to ``b`` (position first, then heading), ``b`` included.

    None if a pose on the way is blocked, or ``b`` is more than 4 moves away.
    """
    k, i, j = a
    kb, ib, jb = b
    out: list[Pose] = []
    while (k, i, j) != b:
        if (i, j) != (ib, jb):
            i += (ib > i) - (ib < i)
            j += (jb > j) - (jb < j)
        else:
            k = (k + (1 if (kb - k) % nk <= nk // 2 else -1)) % nk
        if len(out) == 4 or not free(k, i, j):
            return None
        out.append((k, i, j))
    return out


def join_locally(
    a: Pose, b: Pose, shape: tuple[int, int, int], free: Callable[[int, int, int], bool]
) -> list[Pose] | None:
    """The fewest lattice moves from ``a`` to ``b`` within one pose of their bounding box.

    Breadth-first over the free poses whose position is at most one step outside the
    box spanned by ``a`` and ``b`` and whose heading is at most one step outside the
    shorter arc between theirs (neighbours in a fixed order: deterministic); ``b``
    included, None if there is no such way.
    """
    nk, nx, ny = shape
    ka, ia, ja = a
    kb, ib, jb = b
    i0, i1 = max(0, min(ia, ib) - 1), min(nx - 1, max(ia, ib) + 1)
    j0, j1 = max(0, min(ja, jb) - 1), min(ny - 1, max(ja, jb) + 1)
    arc = (kb - ka) % nk
    lo, span = (ka, arc) if arc <= nk // 2 else (kb, nk - arc)
    headings = {(lo + d) % nk for d in range(-1, span + 2)}
    parent: dict[Pose, Pose | None] = {a: None}
    frontier = [a]
    while frontier and b not in parent:
        nxt = []
        for k, i, j in frontier:
            for dk, di, dj in _LOCAL_MOVES:
                u = ((k + dk) % nk, i + di, j + dj)
                if (
                    u in parent
                    or u[0] not in headings
                    or not (i0 <= u[1] <= i1 and j0 <= u[2] <= j1)
                    or not free(*u)
                ):
                    continue
                parent[u] = (k, i, j)
                nxt.append(u)
        frontier = nxt
    if b not in parent:
        return None
    out: list[Pose] = []
    v: Pose | None = b
    while v is not None and v != a:
        out.append(v)
        v = parent[v]
    return out[::-1]


#: The lattice moves (d_heading, d_i, d_j): 8 in position, then the two headings.
_LOCAL_MOVES = (
    *((0, d_i, d_j) for d_i in (-1, 0, 1) for d_j in (-1, 0, 1) if d_i or d_j),
    (-1, 0, 0),
    (1, 0, 0),
)
