"""The compiled A* loop of the exact-footprint search (numba), resumable by its caller.

:func:`voot.envs.motion.footprint.astar.astar_compiled` drives it; the reference is the
pure-Python loop of :func:`voot.envs.motion.footprint.astar.astar_python`, whose order
of expansions (and so whose path) this loop reproduces bit for bit:

* the open list is a binary heap of ``(f, pose)`` ordered as Python orders the tuples
  (``f``, then the lattice index). Each pose is pushed again only with a smaller ``f``,
  so no two entries are equal and every correct heap pops the same sequence;
* ``f`` is computed by the same float operations in the same order (no fast-math, no
  fused multiply-add), with ``math.hypot`` of the integer offsets read from a table
  that CPython's own ``math.hypot`` filled (libm's may differ in the last bit).

The loop's tables are dense (one entry per lattice pose, allocated once per search
object and read only where the search has been): each pose's g and the move that
reached it, and per position the hub's disc answers. A pending pose of a lazy scene
(:data:`~.scene.PENDING`) is tested in the loop itself, pose by pose
(:func:`pose_free`, the same bit as the lattice's window test).

What the loop cannot do itself (ask the disc hub to connect, prove connectivity
(:func:`same_component`, also compiled here), grow the heap; test a pending pose when
it runs without a lazy scene's arrays) it asks its caller for: it puts the pose it was
about to expand back on the heap, returns a status and the pose concerned in
``state[2]``, and is called again with the same state once the caller has answered.
Putting the pose back leaves the heap's set of entries unchanged, so the next call pops
the same pose; every answer is a function of the scene alone, so the expansions are
those of the uninterrupted loop.

This module and :mod:`.pose_kernels` import numba; nothing else in voot does, and they
are imported only when an exact-footprint search with ``engine="compiled"`` first runs.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from voot.envs.motion.footprint.components import same_component as _same_component
from voot.envs.motion.footprint.geodesic import geodesic_steps
from voot.envs.motion.footprint.pose_kernels import (
    _PENDING,
    TILE_SHIFT,
    _jit,
    _jit_inline,
    ensure_tile,
    part_hits,
    part_limits,
    pose_free,
    resolve_poses,
    tile_lists,
    tile_of,
)

__all__ = [
    "CONNECT",
    "DISC",
    "EXHAUSTED",
    "FOUND",
    "GROW",
    "LABEL",
    "RESOLVE",
    "TILE_SHIFT",
    "clear_closed",
    "ensure_tile",
    "geodesic",
    "geodesic_reference",
    "new_maps",
    "part_hits",
    "part_limits",
    "path_to",
    "pose_free",
    "resolve_poses",
    "same_component",
    "search",
    "segments_free",
    "tile_lists",
]

#: Statuses of :func:`search` (the pose concerned is ``state[2]``).
FOUND, EXHAUSTED, RESOLVE, DISC, CONNECT, LABEL, GROW = range(7)


@_jit_inline
def _less(fa: float, va: int, fb: float, vb: int) -> bool:
    """Python's ``(fa, va) < (fb, vb)``."""
    if fa == fb:
        return va < vb
    return fa < fb


@_jit_inline
def _push(keys: Any, vals: Any, n: int, f: float, v: int) -> int:
    """Push ``(f, v)`` on the heap of ``n`` entries (capacity checked by the caller)."""
    pos = n
    while pos > 0:
        parent = (pos - 1) >> 1
        if _less(f, v, keys[parent], vals[parent]):
            keys[pos] = keys[parent]
            vals[pos] = vals[parent]
            pos = parent
        else:
            break
    keys[pos] = f
    vals[pos] = v
    return n + 1


@_jit_inline
def _pop(keys: Any, vals: Any, n: int) -> int:
    """Remove the smallest entry (read it at index 0 first); the new size."""
    n -= 1
    if n == 0:
        return 0
    f = keys[n]
    v = vals[n]
    pos = 0
    while True:
        child = 2 * pos + 1
        if child >= n:
            break
        if child + 1 < n and _less(keys[child + 1], vals[child + 1], keys[child], vals[child]):
            child += 1
        if _less(keys[child], vals[child], f, v):
            keys[pos] = keys[child]
            vals[pos] = vals[child]
            pos = child
        else:
            break
    keys[pos] = f
    vals[pos] = v
    return n


def new_maps(plane: int) -> tuple[Any, Any]:
    """Per position (``plane`` of them): ``disc`` (-1 not asked, else whether the hub's disc
    is free there) and ``failed`` (1 where the hub refused to connect)."""
    return np.full(plane, -1, dtype=np.int8), np.zeros(plane, dtype=np.uint8)


@_jit
def clear_closed(closed: Any, touched: Any, count: int) -> None:
    """Reset the bytes of every pose the search reached (the first ``count`` of ``touched``)."""
    for a in range(count):
        closed[touched[a]] = 0


@_jit
def path_to(move: Any, dims: Any, v: int) -> Any:
    """The poses from the search's start to ``v`` (both included), by the moves that reached them.

    ``move[u]``: the index in :func:`search`'s order of the move into ``u`` (0-7 in the
    plane, 8 and 9 the turns by -1 and +1 heading), 255 at the start.
    """
    nk, nx, ny = dims[0], dims[1], dims[2]
    plane = nx * ny
    n = 1
    u = v
    while move[u] != 255:
        u = _parent(u, move[u], nk, ny, plane)
        n += 1
    out = np.empty(n, dtype=np.int64)
    u = v
    for a in range(n - 1, -1, -1):
        out[a] = u
        if a > 0:
            u = _parent(u, move[u], nk, ny, plane)
    return out


@_jit_inline
def _parent(u: int, m: int, nk: int, ny: int, plane: int) -> int:
    """The pose from which move ``m`` (see :func:`path_to`) reached ``u``."""
    if m < 8:
        c = m if m < 4 else m + 1  # the 3 x 3 offsets without the centre
        return u - ((c // 3 - 1) * ny + (c % 3 - 1))
    dk = -1 if m == 8 else 1
    k = u // plane
    return ((k - dk) % nk) * plane + u % plane


@_jit_inline
def _disc_free(x: float, y: float, par: Any, boxes: Any) -> int:
    """The hub's ``is_free(x, y)`` (``DiscProbe.blocked_test``'s operations, in order).

    ``par``: compute here (0/1), start free (0/1), hit radius, xmin, xmax, ymin, ymax.
    """
    if par[1] == 0.0:
        return 0
    r = par[2]
    if not (par[3] + r <= x <= par[4] - r and par[5] + r <= y <= par[6] - r):
        return 0
    r2 = r * r
    for k in range(boxes.shape[1]):
        rx = x - boxes[0, k]
        ry = y - boxes[1, k]
        far = boxes[6, k] + r + 1e-6
        if rx * rx + ry * ry > far * far:
            continue
        c = boxes[2, k]
        s = boxes[3, k]
        lx = rx * c + ry * s
        ly = -rx * s + ry * c
        dx = max(abs(lx) - boxes[4, k], 0.0)
        dy = max(abs(ly) - boxes[5, k], 0.0)
        if dx * dx + dy * dy < r2:
            return 0
    return 1


@_jit
def search(
    free: Any,
    closed: Any,
    keys: Any,
    vals: Any,
    gval: Any,
    move: Any,
    touched: Any,
    disc: Any,
    failed: Any,
    state: Any,
    dims: Any,
    costs: Any,
    h_head: Any,
    hyp: Any,
    geo: Any,
    xs: Any,
    ys: Any,
    disc_par: Any,
    disc_boxes: Any,
    sboxes: Any,
    swins: Any,
    strig: Any,
    slims: Any,
    stiles: Any,
    sdirty: Any,
) -> int:
    """Run A* until it ends or needs its caller; the status (see the module doc).

    ``state``: expansions, connectivity proved (0/1), the pose concerned, heap size,
    poses reached. ``closed``: per pose 0 not reached, 1 closed, 2 open; ``gval``, ``move``
    (one per lattice pose, read where ``closed`` is not 0): its g and the move that reached
    it (:func:`path_to`); ``touched``: the poses reached, in order (the caller grows it
    on :data:`GROW` and resets their ``closed`` after).
    ``dims``: nk, nx, ny, start, goal, has a hub (0/1), label_after, geodesic (0/1).
    ``geo``: the geodesic position term per position when ``dims[7]`` is 1
    (:func:`~.geodesic.geodesic_steps`; an infinite entry is not entered).
    ``costs``: the straight move, the diagonal move, the turn, the heuristic's step
    (``heuristic_weight * xy_step``). ``xs``, ``ys``: the lattice's coordinates;
    ``disc_par``, ``disc_boxes``: the hub's disc test (:func:`_disc_free`), or ask the
    caller (status :data:`DISC`) when ``disc_par[0]`` is 0. When ``dims[8]`` is 1, a
    :data:`_PENDING` pose is tested here (:func:`pose_free` with ``sboxes``, ``swins``,
    ``strig``, ``slims``, ``stiles``, after :func:`ensure_tile` with ``sdirty``), else by the caller (status
    :data:`RESOLVE`).
    """
    nk, nx, ny = dims[0], dims[1], dims[2]
    gi, has_hub, label_after, use_geo = dims[4], dims[5], dims[6], dims[7]
    here = dims[8] == 1
    plane = nx * ny
    gx = (gi % plane) // ny
    gy = gi % ny
    straight, diag, w, h_step = costs[0], costs[1], costs[2], costs[3]
    n = state[3]
    cap = keys.shape[0]
    while n > 0:
        fv = keys[0]
        v = vals[0]
        n = _pop(keys, vals, n)
        if closed[v] == 1:
            continue
        k = v // plane
        rem = v % plane
        i = rem // ny
        j = rem % ny
        if v != gi and has_hub and failed[rem] == 0:
            d = disc[rem]
            if d < 0 and disc_par[0] != 0.0:
                d = _disc_free(xs[i], ys[j], disc_par, disc_boxes)
                disc[rem] = d
            if d < 0:
                n = _push(keys, vals, n, fv, v)
                state[2] = v
                state[3] = n
                return DISC
            if d == 1:
                near = False
                for d_i in range(-1, 2):
                    for d_j in range(-1, 2):
                        other = rem + d_i * ny + d_j
                        if (d_i != 0 or d_j != 0) and 0 <= other < plane and failed[other]:
                            near = True
                if near:
                    failed[rem] = 1
                else:
                    n = _push(keys, vals, n, fv, v)
                    state[2] = v
                    state[3] = n
                    return CONNECT
        if v == gi:
            state[2] = v
            state[3] = n
            return FOUND
        inner = 0 < i < nx - 1 and 0 < j < ny - 1
        # the caller's answers first: room on the heap, the tiles of pending neighbours,
        # the connectivity proof (the pose goes back on the heap meanwhile)
        need = -1
        if n + 11 > cap or state[4] + 11 > touched.shape[0]:
            need = GROW
        if need < 0:
            for d_i in range(-1, 2):
                for d_j in range(-1, 2):
                    if (d_i == 0 and d_j == 0) or need >= 0:
                        continue
                    if not inner and not (0 <= i + d_i < nx and 0 <= j + d_j < ny):
                        continue
                    u = v + d_i * ny + d_j
                    if here:  # (the turns stay in v's tile, read already)
                        if sdirty[tile_of(stiles[0], i + d_i, j + d_j)]:
                            ensure_tile(free, sdirty, stiles[0], i + d_i, j + d_j, nk, nx, ny)
                    if free[u] == _PENDING and closed[u] != 1:
                        if here:
                            free[u] = pose_free(
                                u, nx, ny, xs, ys, sboxes, swins, strig, slims, stiles
                            )
                        else:
                            need = RESOLVE
                            state[2] = u
            for dk in (-1, 1):
                u = ((k + dk) % nk) * plane + rem
                if need < 0 and free[u] == _PENDING and closed[u] != 1:
                    if here:
                        free[u] = pose_free(u, nx, ny, xs, ys, sboxes, swins, strig, slims, stiles)
                    else:
                        need = RESOLVE
                        state[2] = u
        if need < 0 and state[1] == 0 and state[0] + 1 == label_after:
            need = LABEL
            state[2] = v
        if need >= 0:
            n = _push(keys, vals, n, fv, v)
            state[3] = n
            return need
        closed[v] = 1
        state[0] += 1
        # the relaxation below is written out twice (moves in the plane, turns) on purpose:
        # a shared helper measured 5-7% slower per query (footprint-speed, this machine)
        gv = gval[v]
        hk = h_head[k]
        m = -1
        for d_i in range(-1, 2):
            for d_j in range(-1, 2):
                if d_i == 0 and d_j == 0:
                    continue
                m += 1
                if not inner and not (0 <= i + d_i < nx and 0 <= j + d_j < ny):
                    continue
                u = v + d_i * ny + d_j
                if free[u] == 0 or closed[u] == 1:
                    continue
                cost = diag if d_i != 0 and d_j != 0 else straight
                gu = gv + cost
                hp = 0.0
                if use_geo:
                    hp = geo[rem + d_i * ny + d_j]
                    if hp == np.inf:
                        continue
                if closed[u] == 0 or gu < gval[u]:
                    if closed[u] == 0:
                        closed[u] = 2
                        touched[state[4]] = u
                        state[4] += 1
                    gval[u] = gu
                    move[u] = m
                    if use_geo:
                        hu = h_step * hp + hk
                    else:
                        hu = h_step * hyp[abs(i + d_i - gx), abs(j + d_j - gy)] + hk
                    n = _push(keys, vals, n, gu + hu, u)
        for dk in (-1, 1):
            kk = (k + dk) % nk
            u = kk * plane + rem
            if free[u] == 0 or closed[u] == 1:
                continue
            gu = gv + w
            if closed[u] == 0 or gu < gval[u]:
                if closed[u] == 0:
                    closed[u] = 2
                    touched[state[4]] = u
                    state[4] += 1
                gval[u] = gu
                move[u] = 8 if dk == -1 else 9
                if use_geo:
                    hu = h_step * geo[rem] + h_head[kk]
                else:
                    hu = h_step * hyp[abs(i - gx), abs(j - gy)] + h_head[kk]
                n = _push(keys, vals, n, gu + hu, u)
    state[3] = n
    return EXHAUSTED


@_jit
def segments_free(
    free: Any,
    a: Any,
    ends: Any,
    counts: Any,
    dthetas: Any,
    grid: Any,
    dims: Any,
    first: int,
    xs: Any,
    ys: Any,
    sboxes: Any,
    swins: Any,
    strig: Any,
    slims: Any,
    stiles: Any,
    sdirty: Any,
) -> Any:
    """From segment ``first`` on: the first segment from ``a`` to ``ends`` that is not free.

    ``FootprintSearch._segments_free``'s samples with numpy's operations: segment ``s``
    has ``counts[s]`` samples at ``t = m * (1 / (counts[s] - 1))`` (``np.linspace``'s
    arithmetic, the last one exactly 1), snapped by ``np.rint``. ``grid``: xmin, ymin,
    xy_step, heading_step; ``dims``: nk, nx, ny. Returns ``(s, pending)``: the segment
    and -1 when segment ``s`` has a sample off the free lattice (``s`` = the number of
    segments when all are free), or a :data:`PENDING` pose of segment ``s`` to test
    first (call again from ``s`` after). When ``dims[3]`` is 1 a pending pose is tested
    here instead (:func:`pose_free`, as in :func:`search`) and never returned.
    """
    nk, nx, ny = dims[0], dims[1], dims[2]
    xmin, ymin, step, hstep = grid[0], grid[1], grid[2], grid[3]
    for s in range(first, ends.shape[0]):
        n = counts[s]
        inc = 1.0 / (n - 1)
        dx = ends[s, 0] - a[0]
        dy = ends[s, 1] - a[1]
        pending = -1
        for m in range(n):
            t = 1.0 if m == n - 1 else m * inc + 0.0
            x = a[0] + t * dx
            y = a[1] + t * dy
            th = a[2] + t * dthetas[s]
            i = np.int64(np.rint((x - xmin) / step))
            j = np.int64(np.rint((y - ymin) / step))
            if i < 0 or j < 0 or i >= nx or j >= ny:
                return s, -1
            k = np.int64(np.rint(th / hstep)) % nk
            u = (k * nx + i) * ny + j
            if dims[3] == 1:
                if sdirty[tile_of(stiles[0], i, j)]:
                    ensure_tile(free, sdirty, stiles[0], i, j, nk, nx, ny)
            if free[u] == 0:
                return s, -1
            if free[u] == _PENDING and dims[3] == 1:
                free[u] = pose_free(u, nx, ny, xs, ys, sboxes, swins, strig, slims, stiles)
                if free[u] == 0:
                    return s, -1
            elif free[u] == _PENDING and pending < 0:
                pending = u
        if pending >= 0:
            return s, pending
    return ends.shape[0], -1


#: :func:`voot.envs.motion.footprint.geodesic.geodesic_steps`, compiled as it is (the reference of
#: :func:`geodesic`).
geodesic_reference = _jit(geodesic_steps)

#: :func:`voot.envs.motion.footprint.components.same_component`, compiled: the
#: connectivity proof of ``engine="compiled"`` (the same answer as labelling, about 4x
#: faster on the authors' conveyor's lattice).
same_component = _jit(_same_component)


@_jit
def geodesic(passable: Any, gx: int, gy: int) -> Any:
    """:func:`~voot.envs.motion.footprint.geodesic.geodesic_steps`' table, bit for bit, faster.

    The same Dijkstra with the open list in two flat arrays ordered by distance alone
    (ties in any order) instead of a heap of tuples: 1.6x faster on the conveyor's
    lattice. The table does not depend on the order in which equal distances leave the
    heap: a position's distance is the least of ``d(v) + step`` over its neighbours ``v``
    of smaller distance, each final when it leaves (steps are >= 1), and a neighbour of
    equal or larger distance never lowers it.
    """
    nx, ny = passable.shape
    dist = np.full(nx * ny, np.inf)
    if not passable[gx, gy]:
        return dist.reshape(nx, ny)
    diag = np.sqrt(2.0)
    start = gx * ny + gy
    dist[start] = 0.0
    # a push lowers a distance: at most one per (position, neighbour), so never full
    # (untouched pages of np.empty cost nothing; growing the arrays in the loop costs 2x)
    cap = 8 * nx * ny + 1
    keys = np.empty(cap, dtype=np.float64)
    vals = np.empty(cap, dtype=np.int64)
    keys[0], vals[0] = 0.0, start
    n = 1
    while n > 0:
        d = keys[0]
        v = vals[0]
        n -= 1
        if n > 0:  # the last entry sifts down from the root
            f, w, pos = keys[n], vals[n], 0
            while True:
                c = 2 * pos + 1
                if c >= n:
                    break
                if c + 1 < n and keys[c + 1] < keys[c]:
                    c += 1
                if keys[c] < f:
                    keys[pos], vals[pos] = keys[c], vals[c]
                    pos = c
                else:
                    break
            keys[pos], vals[pos] = f, w
        if d > dist[v]:
            continue
        i = v // ny
        j = v % ny
        for d_i in range(-1, 2):
            ii = i + d_i
            if ii < 0 or ii >= nx:
                continue
            for d_j in range(-1, 2):
                jj = j + d_j
                if (d_i == 0 and d_j == 0) or jj < 0 or jj >= ny or not passable[ii, jj]:
                    continue
                nd = d + (diag if d_i != 0 and d_j != 0 else 1.0)
                u = ii * ny + jj
                if nd < dist[u]:
                    dist[u] = nd
                    pos = n  # sift up
                    n += 1
                    while pos > 0:
                        parent = (pos - 1) >> 1
                        if nd < keys[parent]:
                            keys[pos], vals[pos] = keys[parent], vals[parent]
                            pos = parent
                        else:
                            break
                    keys[pos], vals[pos] = nd, u
    return dist.reshape(nx, ny)
