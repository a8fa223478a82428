"""A* over the exact-footprint lattice: the reference Python loop and the compiled one.

:class:`voot.envs.motion.footprint.search.FootprintSearch` runs one of two engines
(``FootprintConfig.engine``) that expand the same poses in the same order and return the
same path, bit for bit:

* ``"python"`` (:func:`astar_python`): the reference, plain CPython (7-10 us an expansion);
* ``"compiled"`` (:func:`astar_compiled`): the same loop compiled with numba
  (:mod:`.kernels`), which stops to let Python test a pending tile of the lazy
  scene, ask the disc hub, or prove connectivity, and resumes where it stopped.

The search: from ``si`` to ``gi`` over the free lattice poses, each joined to its 8
neighbours in (x, y) at its heading (cost ``xy_step``, ``xy_step * sqrt 2`` diagonally)
and to the two neighbouring headings (cost ``w``); the heuristic ``eps * (xy_step *
hypot(di, dj) + w * dk)``; the open list a heap of ``(f, index)`` (ties by index). With a
hub (:class:`DiscHub`), it also stops at the first pose whose position the disc reaches
from the query's start. After ``label_after`` expansions, ``connected()`` is asked once
and a False answer ends the search (no path).

With a position table ``hpos`` (``FootprintConfig.heuristic="geodesic"``), the
heuristic's position term is ``eps * xy_step * hpos[i, j]`` instead of the straight
line: :func:`~.geodesic.geodesic_steps`, the 8-connected lattice distance (in steps) from the
target's position through the positions where the footprint is free at some heading
among the static obstacles. Every lattice path projects to such a walk (and a turn costs
nothing there), so the term is still a lower bound, and much tighter where walls and
doors bend the way. A position it cannot reach (infinite) is not entered: no lattice
path from there reaches the target.
"""

from __future__ import annotations

import heapq
import importlib.util
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from voot.envs.motion.footprint.geodesic import geodesic_steps
from voot.envs.motion.footprint.scene import PENDING, KernelData, LatticeBytes

FloatArray = NDArray[np.float64]

__all__ = [
    "AStarSpec",
    "DiscHub",
    "astar_compiled",
    "astar_python",
    "dense_tables",
    "geodesic_steps",
    "numba_available",
    "warm_compiled",
]

_SQRT2 = math.sqrt(2.0)

#: A lazy scene's arrays for the compiled loop (:attr:`.scene.LazyScene.kernel_data`).
SceneData = KernelData

#: The compiled loop's per-pose g (float64) and move (uint8) tables (:func:`dense_tables`).
DenseTables = tuple[NDArray[np.float64], NDArray[np.uint8]]

#: (path from si to the last pose, the disc's head or None), or None when there is no path.
Found = tuple[list[int], FloatArray | None] | None


class DiscHub(Protocol):
    """The disc's free positions reachable from the query's start (see :meth:`FootprintSearch.plan`)."""

    def is_free(self, x: float, y: float) -> bool:
        """Is the disc centred at ``(x, y)`` free (then every heading is free there)?"""

    def connect(self, pose: tuple[float, float, float]) -> FloatArray | None:
        """The disc's waypoints ``(k, 3)`` from the start to ``pose``, or None."""


# A hub may also have ``disc_data() -> (start free, hit radius, (xmin, xmax, ymin, ymax),
# boxes (7, n))``: :meth:`DiscHub.is_free`'s numbers (``DiscProbe.blocked_data``), so that
# the compiled loop tests the disc itself instead of asking the hub position by position.


@dataclass(frozen=True)
class AStarSpec:
    """The lattice and costs of a search (what both engines read).

    Attributes:
        shape: ``(headings, nx, ny)``.
        xs: The lattice's x coordinates.
        ys: The lattice's y coordinates.
        pose: The lattice's ``pose(k, i, j)`` (what the hub's ``connect`` is given).
        step: ``xy_step``.
        w: The cost of a heading move (``rotation_weight * heading_step``).
        eps: The heuristic's weight.
        label_after: Expansions after which connectivity is proved (0: never).
    """

    shape: tuple[int, int, int]
    xs: list[float]
    ys: list[float]
    pose: Callable[[int, int, int], tuple[float, float, float]]
    step: float
    w: float
    eps: float
    label_after: int


def astar_python(
    spec: AStarSpec,
    si: int,
    gi: int,
    free_bytes: LatticeBytes,
    closed: LatticeBytes,
    resolve: Callable[[int], int] | None,
    connected: Callable[[], bool],
    hub: DiscHub | None,
    hpos: FloatArray | None = None,
) -> tuple[Found, int]:
    """The reference loop: the path (see :data:`Found`) and the expansions.

    ``closed`` (one byte per pose, all 0) is 0 again on return. Written for CPython's
    speed: the neighbours are enumerated inline, the heuristic's two terms looked up per
    position and heading, the disc asked once per position; the order of expansions is
    that of the plain A*.
    """
    best: dict[int, float] = {si: 0.0}
    try:
        return _python_loop(spec, si, gi, free_bytes, closed, resolve, connected, hub, best, hpos)
    finally:
        for u in best:
            closed[u] = 0


def _python_loop(
    spec: AStarSpec,
    si: int,
    gi: int,
    free_bytes: LatticeBytes,
    closed: LatticeBytes,
    resolve: Callable[[int], int] | None,
    connected: Callable[[], bool],
    hub: DiscHub | None,
    best: dict[int, float],
    hpos: FloatArray | None,
) -> tuple[Found, int]:
    """:func:`astar_python`'s loop; every pose it closes is a key of ``best``."""
    nk, nx, ny = spec.shape
    step, w, eps = spec.step, spec.w, spec.eps
    plane = nx * ny
    gk, grem = divmod(gi, plane)
    gx, gy = divmod(grem, ny)
    h_step = eps * step
    diag = step * _SQRT2
    # (delta, d_i, d_j, cost) in the order of the plain loop (d_i, then d_j)
    moves = [
        (d_i * ny + d_j, d_i, d_j, diag if d_i and d_j else step)
        for d_i in (-1, 0, 1)
        for d_j in (-1, 0, 1)
        if d_i or d_j
    ]
    h_head = _h_head(spec, gk)
    # the position term per position (rem): the geodesic table's, else None (the line's)
    geo: list[float] | None = None if hpos is None else hpos.ravel().tolist()
    parent: dict[int, int] = {si: -1}
    heap: list[tuple[float, int]] = [(0.0, si)]
    heappop, heappush, hypot = heapq.heappop, heapq.heappush, math.hypot
    inf = math.inf
    label_after = spec.label_after
    hub_failed: set[int] = set()
    disc_free: dict[int, bool] = {}
    hub_nbrs = [d_i * ny + d_j for d_i in (-1, 0, 1) for d_j in (-1, 0, 1) if d_i or d_j]
    xs, ys = spec.xs, spec.ys
    expansions = 0
    while heap:
        v = heappop(heap)[1]
        if closed[v]:
            continue
        k, rem = divmod(v, plane)
        i, j = divmod(rem, ny)
        head = None
        if v != gi and hub is not None and rem not in hub_failed:
            dfree = disc_free.get(rem)
            if dfree is None:
                dfree = disc_free[rem] = hub.is_free(xs[i], ys[j])
            if dfree:
                # a disc position next to one the disc cannot reach from the start is
                # (almost always) in the same region: not asked again (skipping a hub
                # costs time, never completeness)
                near = any(rem + d in hub_failed for d in hub_nbrs)
                head = None if near else hub.connect(spec.pose(k, i, j))
                if head is None:
                    hub_failed.add(rem)
        if v == gi or head is not None:
            out = []
            while v >= 0:
                out.append(v)
                v = parent[v]
            return (out[::-1], head), expansions
        closed[v] = 1
        expansions += 1
        if expansions == label_after and not connected():
            return None, expansions
        gv = best[v]
        hk = h_head[k]
        inner = 0 < i < nx - 1 and 0 < j < ny - 1
        for delta, d_i, d_j, cost in moves:
            u = v + delta
            if not inner:
                ii, jj = i + d_i, j + d_j
                if not (0 <= ii < nx and 0 <= jj < ny):
                    continue
            f = free_bytes[u]
            if not f or closed[u]:
                continue
            if f == PENDING and not resolve(u):  # type: ignore[misc]
                continue
            gu = gv + cost
            if geo is not None:
                hp = geo[rem + delta]
                if hp == inf:
                    continue
            if gu < best.get(u, inf):
                best[u] = gu
                parent[u] = v
                if geo is not None:
                    heappush(heap, (gu + (h_step * hp + hk), u))
                else:
                    heappush(heap, (gu + (h_step * hypot(i + d_i - gx, j + d_j - gy) + hk), u))
        for dk in (-1, 1):
            kk = (k + dk) % nk
            u = kk * plane + rem
            f = free_bytes[u]
            if not f or closed[u]:
                continue
            if f == PENDING and not resolve(u):  # type: ignore[misc]
                continue
            gu = gv + w
            if gu < best.get(u, inf):
                best[u] = gu
                parent[u] = v
                if geo is not None:
                    heappush(heap, (gu + (h_step * geo[rem] + h_head[kk]), u))
                else:
                    heappush(heap, (gu + (h_step * hypot(i - gx, j - gy) + h_head[kk]), u))
    return None, expansions


def _h_head(spec: AStarSpec, gk: int) -> list[float]:
    """The heuristic's heading term per heading."""
    nk = spec.shape[0]
    return [spec.eps * spec.w * min(abs(kk - gk), nk - abs(kk - gk)) for kk in range(nk)]


def dense_tables(n: int) -> DenseTables:
    """Uninitialised g and move tables for a lattice of ``n`` poses (9 bytes a pose, of
    which the memory holds only the pages a search has touched)."""
    return np.empty(n, dtype=np.float64), np.empty(n, dtype=np.uint8)


def numba_available() -> bool:
    """Can the compiled engine run (is numba importable)?"""
    return importlib.util.find_spec("numba") is not None


_HYPOT: dict[tuple[int, int], FloatArray] = {}


def hypot_table(nx: int, ny: int) -> FloatArray:
    """``math.hypot(a, b)`` for ``0 <= a < nx``, ``0 <= b < ny`` (CPython's, once per shape)."""
    table = _HYPOT.get((nx, ny))
    if table is None:
        hypot = math.hypot
        table = np.array([[hypot(a, b) for b in range(ny)] for a in range(nx)], dtype=np.float64)
        _HYPOT[(nx, ny)] = table
    return table


def warm_compiled() -> None:
    """Compile (or load from numba's disk cache) every kernel now, on a tiny lattice.

    The first compiled search of a process otherwise pays it (benchmarks time it apart).
    """
    spec = AStarSpec((8, 3, 3), [0.0, 1.0, 2.0], [0.0, 1.0, 2.0], lambda k, i, j: (i, j, k), 1.0,
                     0.5, 1.0, 0)  # fmt: skip
    free = bytearray(b"\x01" * 72)
    free[4] = PENDING
    closed = bytearray(72)

    def resolve(u: int) -> int:
        free[u] = 1
        return 1

    astar_compiled(spec, 0, 71, free, closed, resolve, lambda: True, None)
    from voot.envs.motion.footprint import kernels as K

    K.geodesic(np.ones((3, 3), dtype=np.bool_), 1, 1)
    K.same_component(np.ones(72, dtype=np.bool_), 8, 3, 3, 0, 71)  # the connectivity proof
    # the lattice's occupancy test and the tightening's segment checks
    K.part_hits(np.zeros((1, 1, 1), dtype=bool), 0, 0, np.zeros(1), np.zeros(1), np.zeros(1),
                np.zeros(1), np.ones(1), np.zeros(1), np.ones(4), np.ones(2), 0.0)  # fmt: skip
    K.segments_free(np.frombuffer(free, dtype=np.uint8), np.zeros(3), np.zeros((1, 3)),
                    np.array([2], dtype=np.int64), np.zeros(1), np.array([0.0, 0.0, 1.0, 1.0]),
                    np.array([8, 3, 3, 0], dtype=np.int64), 0, np.zeros(3), np.zeros(3),
                    np.zeros((0, 6)), np.zeros((0, 1, 4), dtype=np.int64), np.zeros((0, 4, 8)),
                    np.zeros((0, 0, 8, 4)), np.zeros(0, dtype=np.int64),
                    np.zeros(0, dtype=np.uint8))  # fmt: skip
    # the pose-by-pose test of a lazy scene (inside the loops above too)
    K.resolve_poses(np.frombuffer(free, dtype=np.uint8), np.array([4], dtype=np.int64),
                    np.array([8, 3, 3], dtype=np.int64), np.zeros(3), np.zeros(3),
                    np.zeros((1, 6)), np.zeros((1, 2, 4), dtype=np.int64), np.zeros((1, 4, 8)),
                    K.part_limits(np.zeros(6), np.zeros((1, 4, 8)), np.ones((1, 2)), 0.0)[None],
                    K.tile_lists(np.zeros((1, 2, 4), dtype=np.int64), 3, 3),
                    np.ones(1, dtype=np.uint8))  # fmt: skip


def astar_compiled(
    spec: AStarSpec,
    si: int,
    gi: int,
    free_bytes: LatticeBytes,
    closed: LatticeBytes,
    resolve: Callable[[int], int] | None,
    connected: Callable[[], bool],
    hub: DiscHub | None,
    hpos: FloatArray | None = None,
    scene: SceneData | None = None,
    dense: DenseTables | None = None,
) -> tuple[Found, int]:
    """:func:`astar_python`'s result, by the compiled loop of :mod:`.kernels`.

    With ``scene`` (:attr:`.scene.LazyScene.kernel_data`),
    the loop tests pending poses itself and ``resolve`` is not called. ``dense``: the
    per-pose g and move tables (:func:`dense_tables`, kept by the caller across searches:
    only the poses a search reaches are read or written), or None to allocate them.
    """
    from voot.envs.motion.footprint import kernels as K

    nk, nx, ny = spec.shape
    plane = nx * ny
    free = np.frombuffer(free_bytes, dtype=np.uint8)
    closed_view = np.frombuffer(closed, dtype=np.uint8)
    disc, failed = K.new_maps(plane)
    gval, move = dense_tables(nk * plane) if dense is None else dense
    touched = np.empty(8192, dtype=np.int64)
    keys = np.empty(1024, dtype=np.float64)
    vals = np.empty(1024, dtype=np.int64)
    keys[0], vals[0] = 0.0, si
    state = np.array([0, 0, -1, 1, 1], dtype=np.int64)
    dims = np.array(
        [nk, nx, ny, si, gi, hub is not None, spec.label_after, hpos is not None,
         scene is not None],
        dtype=np.int64,
    )  # fmt: skip
    geo = np.zeros(1) if hpos is None else np.ascontiguousarray(hpos, dtype=np.float64).ravel()
    if scene is None:
        sboxes, swins = np.zeros((0, 6)), np.zeros((0, 1, 4), dtype=np.int64)
        strig, slims, stiles = np.zeros((0, 4, nk)), np.zeros((0, 0, nk, 4)), np.zeros(0, np.int64)
        sdirty = np.zeros(0, dtype=np.uint8)
    else:
        sboxes, swins, strig, slims, stiles, sdirty = scene
    costs = np.array([spec.step, spec.step * _SQRT2, spec.w, spec.eps * spec.step])
    h_head = np.array(_h_head(spec, gi // plane), dtype=np.float64)
    hyp = hypot_table(nx, ny)
    xs = np.asarray(spec.xs, dtype=np.float64)
    ys = np.asarray(spec.ys, dtype=np.float64)
    # the hub's disc test, computed in the loop where the hub gives its numbers
    disc_data = getattr(hub, "disc_data", None)
    if disc_data is not None:
        start_free, r_hit, (xmin, xmax, ymin, ymax), disc_boxes = disc_data()
        disc_par = np.array([1.0, float(start_free), r_hit, xmin, xmax, ymin, ymax])
        disc_boxes = np.ascontiguousarray(disc_boxes, dtype=np.float64).reshape(7, -1)
    else:
        disc_par = np.zeros(7)
        disc_boxes = np.zeros((7, 0))
    # the start, reached (the finally below resets every pose reached, this one too)
    touched[0] = si
    closed_view[si] = 2
    gval[si] = 0.0
    move[si] = 255
    try:
        while True:
            status = K.search(
                free, closed_view, keys, vals, gval, move, touched, disc, failed, state, dims, costs,
                h_head, hyp, geo, xs, ys, disc_par, disc_boxes, sboxes, swins, strig, slims,
                stiles, sdirty,
            )  # fmt: skip
            v = int(state[2])
            if status == K.FOUND:
                return (K.path_to(move, dims, v).tolist(), None), int(state[0])
            if status == K.EXHAUSTED:
                return None, int(state[0])
            if status == K.RESOLVE:
                resolve(v)  # type: ignore[misc]
            elif status == K.DISC:
                assert hub is not None
                rem = v % plane
                disc[rem] = 1 if hub.is_free(spec.xs[rem // ny], spec.ys[rem % ny]) else 0
            elif status == K.CONNECT:
                assert hub is not None
                rem = v % plane
                head = hub.connect(spec.pose(v // plane, rem // ny, rem % ny))
                if head is not None:
                    return (K.path_to(move, dims, v).tolist(), head), int(state[0])
                failed[rem] = 1
            elif status == K.LABEL:
                if not connected():
                    return None, spec.label_after
                state[1] = 1
            else:  # GROW: the heap or the list of poses reached
                if int(state[3]) + 11 > keys.shape[0]:
                    keys = np.concatenate([keys, np.empty_like(keys)])
                    vals = np.concatenate([vals, np.empty_like(vals)])
                if int(state[4]) + 11 > touched.shape[0]:
                    touched = np.concatenate([touched, np.empty_like(touched)])
    finally:
        K.clear_closed(closed_view, touched, int(state[4]))
