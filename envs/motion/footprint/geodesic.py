"""Lattice distances around obstacles: the geodesic heuristic of the exact-footprint search.

:func:`geodesic_steps` is the position term of ``FootprintConfig.heuristic="geodesic"``
(:mod:`.astar`): plain Python and numpy, the reference of the compiled engine's
faster Dijkstra (:func:`.kernels.geodesic`, tested equal), so both engines read the same
table, bit for bit. It imports nothing of voot, so both engines' modules can import it.
"""

from __future__ import annotations

import heapq
import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["geodesic_steps"]


def geodesic_steps(passable: NDArray[np.bool_], gx: int, gy: int) -> NDArray[np.float64]:
    """Lattice distances (in steps: 1 straight, sqrt 2 diagonal) from position ``(gx, gy)``
    over the ``passable`` positions ``(nx, ny)``, 8-connected; infinite where unreachable.

    Dijkstra with a heap of ``(distance, index)`` (Python's tuple order): the compiled
    engine runs a faster Dijkstra with the same answer (:func:`.kernels.geodesic`), so
    both engines read the same table, bit for bit.
    """
    nx, ny = passable.shape
    dist = np.full(nx * ny, np.inf)
    start = gx * ny + gy
    if not passable[gx, gy]:
        return dist.reshape(nx, ny)
    diag = math.sqrt(2.0)
    dist[start] = 0.0
    heap = [(0.0, start)]
    while heap:
        d, v = heapq.heappop(heap)
        if d > dist[v]:
            continue
        i = v // ny
        j = v % ny
        for d_i in range(-1, 2):
            for d_j in range(-1, 2):
                if d_i == 0 and d_j == 0:
                    continue
                ii = i + d_i
                jj = j + d_j
                if ii < 0 or ii >= nx or jj < 0 or jj >= ny or not passable[ii, jj]:
                    continue
                nd = d + (diag if d_i != 0 and d_j != 0 else 1.0)
                u = ii * ny + jj
                if nd < dist[u]:
                    dist[u] = nd
                    heapq.heappush(heap, (nd, u))
    return dist.reshape(nx, ny)
