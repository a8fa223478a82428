"""The compiled A* loop of the exact-footprint search (numba), resumable by its caller.

:func:`voot.envs.motion.footprint_astar.astar_compiled` drives it; the reference is the
pure-Python loop of :func:`voot.envs.motion.footprint_astar.astar_python`, whose order
of expansions (and so whose path) this loop reproduces bit for bit:

* the open list is a binary heap of ``(f, pose)`` ordered as Python orders the tuples
  (``f``, then the lattice index). Each pose is pushed again only with a smaller ``f``,
  so no two entries are equal and every correct heap pops the same sequence;
* ``f`` is computed by the same float operations in the same order (no fast-math, no
  fused multiply-add), with ``math.hypot`` of the integer offsets read from a table
  that CPython's own ``math.hypot`` filled (libm's may differ in the last bit).

What the loop cannot do itself (test a :data:`~.footprint_scene.PENDING` tile, ask the
disc hub, label the connected components, grow the heap) it asks its caller for: it
puts the pose it was about to expand back on the heap, returns a status and the pose
concerned in ``state[2]``, and is called again with the same state once the caller has
answered. Putting the pose back leaves the heap's set of entries unchanged, so the
next call pops the same pose; every answer is a function of the scene alone, so the
expansions are those of the uninterrupted loop.

This module imports numba; nothing else in voot does, and it is imported only when an
exact-footprint search with ``engine="compiled"`` first runs.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
from numba import types
from numba.typed import Dict

from voot.envs.motion.geodesic import geodesic_steps

__all__ = [
    "CONNECT",
    "DISC",
    "EXHAUSTED",
    "FOUND",
    "GROW",
    "LABEL",
    "RESOLVE",
    "clear_closed",
    "geodesic",
    "new_maps",
    "part_hits",
    "path_to",
    "rehash",
    "search",
    "segments_free",
    "table_put",
]

#: Statuses of :func:`search` (the pose concerned is ``state[2]``).
FOUND, EXHAUSTED, RESOLVE, DISC, CONNECT, LABEL, GROW = range(7)

_PENDING = 2


def _jit(func: Any) -> Any:
    """``numba.njit`` with the on-disk cache where numba has a writable place for it.

    numba refuses ``cache=True`` (RuntimeError) when neither the source's ``__pycache__``
    nor its user-wide cache directory (``NUMBA_CACHE_DIR``) is writable; then the loop is
    compiled in each process instead.
    """
    try:
        return numba.njit(cache=True, nogil=True)(func)
    except RuntimeError:  # a read-only install without NUMBA_CACHE_DIR (tested)
        return numba.njit(nogil=True)(func)


@_jit
def _less(fa: float, va: int, fb: float, vb: int) -> bool:
    """Python's ``(fa, va) < (fb, vb)``."""
    if fa == fb:
        return va < vb
    return fa < fb


@_jit
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


@_jit
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


@_jit
def new_maps() -> Any:
    """Empty ``disc`` (position -> disc free) and ``failed`` (hub positions refused) maps."""
    disc = Dict.empty(types.int64, types.int64)
    failed = Dict.empty(types.int64, types.int64)
    return disc, failed


@_jit
def _slot(tkeys: Any, key: int) -> int:
    """The slot of ``key`` in the open-addressing table ``tkeys`` (-1 empty), or its empty slot."""
    mask = tkeys.shape[0] - 1
    h = (key * 2654435761) & mask
    while True:
        k = tkeys[h]
        if k == key or k == -1:
            return h
        h = (h + 1) & mask


@_jit
def table_put(tkeys: Any, tg: Any, tpar: Any, key: int, g: float, par: int) -> int:
    """Set ``key``'s g and parent; 1 if ``key`` is new (the caller counts the entries)."""
    h = _slot(tkeys, key)
    new = 0
    if tkeys[h] == -1:
        tkeys[h] = key
        new = 1
    tg[h] = g
    tpar[h] = par
    return new


@_jit
def rehash(tkeys: Any, tg: Any, tpar: Any) -> Any:
    """The table with twice the slots and the same entries."""
    n = 2 * tkeys.shape[0]
    keys2 = np.full(n, -1, dtype=np.int64)
    g2 = np.empty(n, dtype=np.float64)
    par2 = np.empty(n, dtype=np.int64)
    for h in range(tkeys.shape[0]):
        if tkeys[h] >= 0:
            table_put(keys2, g2, par2, tkeys[h], tg[h], tpar[h])
    return keys2, g2, par2


@_jit
def clear_closed(closed: Any, tkeys: Any) -> None:
    """Reset the closed bytes of every pose the search reached (the keys of the table)."""
    for u in tkeys:
        if u >= 0:
            closed[u] = 0


@_jit
def path_to(tkeys: Any, tpar: Any, v: int) -> Any:
    """The poses from the search's start to ``v`` (both included)."""
    n = 0
    u = v
    while u >= 0:
        n += 1
        u = tpar[_slot(tkeys, u)]
    out = np.empty(n, dtype=np.int64)
    u = v
    for a in range(n - 1, -1, -1):
        out[a] = u
        u = tpar[_slot(tkeys, u)]
    return out


@_jit
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
    tkeys: Any,
    tg: Any,
    tpar: Any,
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
) -> int:
    """Run A* until it ends or needs its caller; the status (see the module doc).

    ``state``: expansions, connectivity proved (0/1), the pose concerned, heap size,
    table entries. ``tkeys``, ``tg``, ``tpar``: the poses reached, their g and parent (an
    open-addressing table, -1 empty, at most half full: the caller grows it on
    :data:`GROW`).
    ``dims``: nk, nx, ny, start, goal, has a hub (0/1), label_after, geodesic (0/1).
    ``geo``: the geodesic position term per position when ``dims[7]`` is 1
    (:func:`~.geodesic.geodesic_steps`; an infinite entry is not entered).
    ``costs``: the straight move, the diagonal move, the turn, the heuristic's step
    (``heuristic_weight * xy_step``). ``xs``, ``ys``: the lattice's coordinates;
    ``disc_par``, ``disc_boxes``: the hub's disc test (:func:`_disc_free`), or ask the
    caller (status :data:`DISC`) when ``disc_par[0]`` is 0.
    """
    nk, nx, ny = dims[0], dims[1], dims[2]
    gi, has_hub, label_after, use_geo = dims[4], dims[5], dims[6], dims[7]
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
        if closed[v]:
            continue
        k = v // plane
        rem = v % plane
        i = rem // ny
        j = rem % ny
        if v != gi and has_hub and rem not in failed:
            d = disc.get(rem, -1)
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
                        if (d_i != 0 or d_j != 0) and (rem + d_i * ny + d_j) in failed:
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
        if n + 11 > cap or 2 * (state[4] + 10) > tkeys.shape[0]:
            need = GROW
        if need < 0:
            for d_i in range(-1, 2):
                for d_j in range(-1, 2):
                    if (d_i == 0 and d_j == 0) or need >= 0:
                        continue
                    if not inner and not (0 <= i + d_i < nx and 0 <= j + d_j < ny):
                        continue
                    u = v + d_i * ny + d_j
                    if free[u] == _PENDING and not closed[u]:
                        need = RESOLVE
                        state[2] = u
            for dk in (-1, 1):
                u = ((k + dk) % nk) * plane + rem
                if need < 0 and free[u] == _PENDING and not closed[u]:
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
        gv = tg[_slot(tkeys, v)]
        hk = h_head[k]
        for d_i in range(-1, 2):
            for d_j in range(-1, 2):
                if d_i == 0 and d_j == 0:
                    continue
                if not inner and not (0 <= i + d_i < nx and 0 <= j + d_j < ny):
                    continue
                u = v + d_i * ny + d_j
                if free[u] == 0 or closed[u]:
                    continue
                cost = diag if d_i != 0 and d_j != 0 else straight
                gu = gv + cost
                hp = 0.0
                if use_geo:
                    hp = geo[rem + d_i * ny + d_j]
                    if hp == np.inf:
                        continue
                h = _slot(tkeys, u)
                if tkeys[h] == -1 or gu < tg[h]:
                    if tkeys[h] == -1:
                        tkeys[h] = u
                        state[4] += 1
                    tg[h] = gu
                    tpar[h] = v
                    if use_geo:
                        hu = h_step * hp + hk
                    else:
                        hu = h_step * hyp[abs(i + d_i - gx), abs(j + d_j - gy)] + hk
                    n = _push(keys, vals, n, gu + hu, u)
        for dk in (-1, 1):
            kk = (k + dk) % nk
            u = kk * plane + rem
            if free[u] == 0 or closed[u]:
                continue
            gu = gv + w
            h = _slot(tkeys, u)
            if tkeys[h] == -1 or gu < tg[h]:
                if tkeys[h] == -1:
                    tkeys[h] = u
                    state[4] += 1
                tg[h] = gu
                tpar[h] = v
                if use_geo:
                    hu = h_step * geo[rem] + h_head[kk]
                else:
                    hu = h_step * hyp[abs(i - gx), abs(j - gy)] + h_head[kk]
                n = _push(keys, vals, n, gu + hu, u)
    state[3] = n
    return EXHAUSTED


@_jit
def part_hits(
    hit: Any,
    di: int,
    dj: int,
    px: Any,
    py: Any,
    ox: Any,
    oy: Any,
    ca: Any,
    sa: Any,
    box: Any,
    part: Any,
    tol: float,
) -> None:
    """Mark in ``hit[:, di:, dj:]`` the poses where a footprint part overlaps a box.

    :meth:`~voot.envs.motion.footprint.FootprintLattice.blocked_window`'s separating-axis
    test, pose by pose with numpy's operations in numpy's order (its trigonometry, the
    per-heading ``ox, oy, ca, sa``, is numpy's, passed in). ``px``, ``py``: positions
    relative to the box centre; ``box``: cos, sin of its yaw and its half sizes;
    ``part``: the part's half sizes.
    """
    cb, sb, bhx, bhy = box[0], box[1], box[2], box[3]
    phx, phy = part[0], part[1]
    lim = np.empty(4)
    axx = np.empty(4)
    axy = np.empty(4)
    for k in range(hit.shape[0]):
        ck, sk = ca[k], sa[k]
        axx[0], axy[0] = cb, sb
        axx[1], axy[1] = -sb, cb
        axx[2], axy[2] = ck, sk
        axx[3], axy[3] = -sk, ck
        for a in range(4):
            ux, uy = axx[a], axy[a]
            hb = bhx * abs(ux * cb + uy * sb) + bhy * abs(-ux * sb + uy * cb)
            hp = phx * abs(ux * ck + uy * sk) + phy * abs(-ux * sk + uy * ck)
            lim[a] = hb + hp - tol
        for i in range(px.shape[0]):
            qx = px[i] + ox[k]
            for j in range(py.shape[0]):
                if hit[k, di + i, dj + j]:
                    continue
                qy = py[j] + oy[k]
                inside = True
                for a in range(4):
                    if not abs(axx[a] * qx + axy[a] * qy) < lim[a]:
                        inside = False
                        break
                if inside:
                    hit[k, di + i, dj + j] = True


@_jit
def segments_free(
    free: Any, a: Any, ends: Any, counts: Any, dthetas: Any, grid: Any, dims: Any, first: int
) -> Any:
    """From segment ``first`` on: the first segment from ``a`` to ``ends`` that is not free.

    ``FootprintSearch._segments_free``'s samples with numpy's operations: segment ``s``
    has ``counts[s]`` samples at ``t = m * (1 / (counts[s] - 1))`` (``np.linspace``'s
    arithmetic, the last one exactly 1), snapped by ``np.rint``. ``grid``: xmin, ymin,
    xy_step, heading_step; ``dims``: nk, nx, ny. Returns ``(s, pending)``: the segment
    and -1 when segment ``s`` has a sample off the free lattice (``s`` = the number of
    segments when all are free), or a :data:`PENDING` pose of segment ``s`` to test
    first (call again from ``s`` after).
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
            if free[u] == 0:
                return s, -1
            if free[u] == _PENDING and pending < 0:
                pending = u
        if pending >= 0:
            return s, pending
    return ends.shape[0], -1


#: :func:`voot.envs.motion.geodesic.geodesic_steps`, compiled (the same function,
#: so the same table bit for bit).
geodesic = _jit(geodesic_steps)
