"""The exact-footprint lattice's pose tests, compiled (numba).

The separating-axis test of a footprint against obstacle rectangles, as
:meth:`~voot.envs.motion.footprint.FootprintLattice.blocked_window` computes it: over a
window of positions at every heading (:func:`part_hits`), or at one pose
(:func:`pose_free`, with :func:`part_limits`' limits and :func:`tile_lists`' obstacles
per tile), and the lazy scene's pending and dirty bookkeeping (:func:`ensure_tile`,
:func:`resolve_poses`). Every pose is computed by the same operations in the same order,
so each answer is the window's, bit for bit. The A* loop that calls them is
:mod:`.kernels`; this module imports numba and is imported only with it.
"""

from __future__ import annotations

from typing import Any, Literal

import numba
import numpy as np

__all__ = [
    "TILE_SHIFT",
    "ensure_tile",
    "part_hits",
    "part_limits",
    "pose_free",
    "resolve_poses",
    "tile_lists",
    "tile_of",
]

_PENDING = 2


def _jit(func: Any, inline: Literal["never", "always"] = "never") -> Any:
    """``numba.njit`` with the on-disk cache where numba has a writable place for it.

    numba refuses ``cache=True`` (RuntimeError) when neither the source's ``__pycache__``
    nor its user-wide cache directory (``NUMBA_CACHE_DIR``) is writable; then the loop is
    compiled in each process instead. ``inline``: numba's option (:func:`_jit_inline`).
    """
    try:
        return numba.njit(cache=True, nogil=True, inline=inline)(func)
    except RuntimeError:  # a read-only install without NUMBA_CACHE_DIR (tested)
        return numba.njit(nogil=True, inline=inline)(func)


def _jit_inline(func: Any) -> Any:
    """:func:`_jit`, inlined into its compiled callers (numba's ``inline="always"``).

    For the small helpers of the A* loop. A call between compiled functions costs the
    call and, per array argument, an atomic increment and decrement of the array's
    reference count; inlined, numba drops most of those counts, but not an inlined
    function's array arguments where it is called (hence :func:`tile_of`). With
    ``perf``, the counts were 27% of ``footprint-speed``'s CPU samples before; after
    both changes they no longer appear. The same operations run in the same order.
    """
    return _jit(func, inline="always")


@_jit_inline
def pose_free(
    u: int,
    nx: int,
    ny: int,
    xs: Any,
    ys: Any,
    boxes: Any,
    wins: Any,
    trig: Any,
    lims: Any,
    tiles: Any,
) -> int:
    """1 if the footprint at lattice pose ``u`` clears every box, else 0.

    :meth:`~voot.envs.motion.footprint.FootprintLattice.blocked_window`'s answer at one
    pose, by :func:`part_hits`' operations in its order (so the same bit). ``boxes``
    ``(B, 6)``: centre, cos and sin of the yaw, half sizes; ``wins`` ``(B, 1 + P, 4)``:
    the box's window and each part's (``i0, i1, j0, j1``; empty when ``i0 >= i1``);
    ``trig`` ``(P, 4, nk)``: per part and heading ``ox, oy, cos, sin``
    (:meth:`~voot.envs.motion.footprint.FootprintLattice.part_trig`); ``lims``
    ``(B, P, nk, 4)``: the separating-axis limits (:func:`part_limits`);
    ``tiles``: the boxes whose window meets each tile of positions (:func:`tile_lists`),
    the only ones tested (the answer is an "or" over boxes: their order does not matter).
    """
    plane = nx * ny
    k = u // plane
    rem = u % plane
    i = rem // ny
    j = rem % ny
    t = (i >> TILE_SHIFT) * tiles[0] + (j >> TILE_SHIFT)
    for a_b in range(tiles[2 + t], tiles[3 + t]):
        b = tiles[a_b]
        if i < wins[b, 0, 0] or i >= wins[b, 0, 1] or j < wins[b, 0, 2] or j >= wins[b, 0, 3]:
            continue
        cb, sb = boxes[b, 2], boxes[b, 3]
        px = xs[i] - boxes[b, 0]
        py = ys[j] - boxes[b, 1]
        # (scalar reads only: a view such as wins[b, 1 + p] costs numba a reference
        # count's atomic increment and decrement)
        for p in range(wins.shape[1] - 1):
            if (
                i < wins[b, 1 + p, 0]
                or i >= wins[b, 1 + p, 1]
                or j < wins[b, 1 + p, 2]
                or j >= wins[b, 1 + p, 3]
            ):
                continue
            ck, sk = trig[p, 2, k], trig[p, 3, k]
            qx = px + trig[p, 0, k]
            qy = py + trig[p, 1, k]
            if (
                abs(cb * qx + sb * qy) < lims[b, p, k, 0]
                and abs(-sb * qx + cb * qy) < lims[b, p, k, 1]
                and abs(ck * qx + sk * qy) < lims[b, p, k, 2]
                and abs(-sk * qx + ck * qy) < lims[b, p, k, 3]
            ):
                return 0
    return 1


@_jit
def part_limits(row: Any, trig: Any, half: Any, tol: float) -> Any:
    """Per part, heading and axis, :func:`part_hits`' limit ``hb + hp - tol`` for the box
    ``row`` (centre, cos and sin of its yaw, half sizes), by its operations."""
    cb, sb, bhx, bhy = row[2], row[3], row[4], row[5]
    nparts, nk = trig.shape[0], trig.shape[2]
    out = np.empty((nparts, nk, 4))
    for p in range(nparts):
        phx, phy = half[p, 0], half[p, 1]
        for k in range(nk):
            ck, sk = trig[p, 2, k], trig[p, 3, k]
            for a in range(4):
                if a == 0:
                    ux, uy = cb, sb
                elif a == 1:
                    ux, uy = -sb, cb
                elif a == 2:
                    ux, uy = ck, sk
                else:
                    ux, uy = -sk, ck
                hb = bhx * abs(ux * cb + uy * sb) + bhy * abs(-ux * sb + uy * cb)
                hp = phx * abs(ux * ck + uy * sk) + phy * abs(-ux * sk + uy * ck)
                out[p, k, a] = hb + hp - tol
    return out


#: Tiles of :func:`tile_lists`: 2 ** TILE_SHIFT positions a side.
TILE_SHIFT = 4


@_jit_inline
def tile_of(nty: int, i: int, j: int) -> int:
    """The tile of position ``(i, j)`` (``nty`` tiles a row of x): callers read
    ``dirty[tile_of(...)]`` before calling :func:`ensure_tile`, whose array arguments
    cost an atomic reference count each even inlined (measured: a quarter of the A*
    loop's CPU when it was called for every neighbour)."""
    return (i >> TILE_SHIFT) * nty + (j >> TILE_SHIFT)


@_jit_inline
def ensure_tile(free: Any, dirty: Any, nty: int, i: int, j: int, nk: int, nx: int, ny: int) -> None:
    """Mark every pose of position ``(i, j)``'s tile pending if the tile is ``dirty``.

    A lazy scene marks a tile dirty where a box moved instead of marking its poses there
    (:class:`~.scene.LazyScene`): a tile's bytes are read only after this.
    """
    t = tile_of(nty, i, j)
    if dirty[t] == 0:
        return
    side = 1 << TILE_SHIFT
    i0 = (i >> TILE_SHIFT) << TILE_SHIFT
    j0 = (j >> TILE_SHIFT) << TILE_SHIFT
    i1 = min(nx, i0 + side)
    j1 = min(ny, j0 + side)
    for k in range(nk):
        for a in range(i0, i1):
            base = (k * nx + a) * ny
            for b in range(j0, j1):
                free[base + b] = _PENDING
    dirty[t] = 0


@_jit
def tile_lists(wins: Any, nx: int, ny: int) -> Any:
    """Per tile of positions, the boxes whose window (``wins[:, 0]``) meets it, as one array.

    ``[tiles in y, tiles, start of tile 0, ..., start of tile T (the end), boxes...]``:
    tile ``t``'s boxes are ``out[out[2 + t] : out[3 + t]]``, ``t = (i >> TILE_SHIFT) *
    out[0] + (j >> TILE_SHIFT)``.
    """
    ntx = (nx + (1 << TILE_SHIFT) - 1) >> TILE_SHIFT
    nty = (ny + (1 << TILE_SHIFT) - 1) >> TILE_SHIFT
    count = np.zeros(ntx * nty, dtype=np.int64)
    for b in range(wins.shape[0]):
        i0, i1, j0, j1 = wins[b, 0, 0], wins[b, 0, 1], wins[b, 0, 2], wins[b, 0, 3]
        if i0 >= i1 or j0 >= j1:
            continue
        for ti in range(i0 >> TILE_SHIFT, ((i1 - 1) >> TILE_SHIFT) + 1):
            for tj in range(j0 >> TILE_SHIFT, ((j1 - 1) >> TILE_SHIFT) + 1):
                count[ti * nty + tj] += 1
    head = 3 + ntx * nty
    out = np.empty(head + count.sum(), dtype=np.int64)
    out[0] = nty
    out[1] = ntx * nty
    out[2] = head
    for t in range(ntx * nty):
        out[3 + t] = out[2 + t] + count[t]
    fill = out[2 : 2 + ntx * nty].copy()
    for b in range(wins.shape[0]):
        i0, i1, j0, j1 = wins[b, 0, 0], wins[b, 0, 1], wins[b, 0, 2], wins[b, 0, 3]
        if i0 >= i1 or j0 >= j1:
            continue
        for ti in range(i0 >> TILE_SHIFT, ((i1 - 1) >> TILE_SHIFT) + 1):
            for tj in range(j0 >> TILE_SHIFT, ((j1 - 1) >> TILE_SHIFT) + 1):
                t = ti * nty + tj
                out[fill[t]] = b
                fill[t] += 1
    return out


@_jit
def resolve_poses(
    free: Any,
    indices: Any,
    dims: Any,
    xs: Any,
    ys: Any,
    boxes: Any,
    wins: Any,
    trig: Any,
    lims: Any,
    tiles: Any,
    dirty: Any,
) -> None:
    """Test every pending pose among ``indices`` (:func:`pose_free`, after
    :func:`ensure_tile`); ``dims``: nk, nx, ny."""
    nk, nx, ny = dims[0], dims[1], dims[2]
    plane = nx * ny
    for u in indices:
        rem = u % plane
        if dirty[tile_of(tiles[0], rem // ny, rem % ny)]:
            ensure_tile(free, dirty, tiles[0], rem // ny, rem % ny, nk, nx, ny)
        if free[u] == _PENDING:
            free[u] = pose_free(u, dims[1], dims[2], xs, ys, boxes, wins, trig, lims, tiles)


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
