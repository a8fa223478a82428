"""Connectivity of the free lattice: are two poses in one connected component?

The exact search's proof of "no path" (:mod:`.search`, after ``label_after`` A*
expansions) asks it once of the whole free lattice ``(nk, nx, ny)``, whose poses are
joined as the A* joins them: to the 8 neighbours in (x, y) at the same heading and to the
two neighbouring headings at the same position, the heading wrapping round. Two answers,
always the same boolean:

* :func:`connected_labelled` labels every component (``scipy.ndimage.label``) and joins
  the labels across the heading's wrap: the reference, and the pure-Python engine's;
* :func:`same_component` joins runs instead of poses: the maximal free intervals along
  y of each (heading, x) row, joined by a union-find where two runs of neighbouring rows
  touch. A lattice has far fewer runs than poses (24,600 runs for 10.8 million poses
  on the authors' conveyor), so after one pass over the poses the joins cost little.
  It is written for numba (:mod:`.kernels` compiles it, for ``engine="compiled"``) and
  is plain Python here (tests on small lattices).

Two runs ``[a0, a1)`` and ``[b0, b1)`` of rows ``x`` and ``x + 1`` at one heading touch
(8-neighbourhood) when ``a0 < b1 + 1`` and ``b0 < a1 + 1``; of the same x at neighbouring
headings (same position) when ``a0 < b1`` and ``b0 < a1``. Both rows' runs are sorted
and at least one blocked pose apart, so one merge-like pass finds every touching pair.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import ndimage

BoolArray = Any


def connected_labelled(free: BoolArray, a: int, b: int) -> bool:
    """Are the free poses of flat indices ``a`` and ``b`` of ``free`` (``(nk, nx, ny)``)
    in one component? False where either is blocked. By labelling (scipy)."""
    flat_free = free.reshape(-1)
    if not (flat_free[a] and flat_free[b]):
        return False
    structure = np.zeros((3, 3, 3), dtype=bool)
    structure[1] = True  # 8 neighbours in (x, y) at one heading
    structure[0, 1, 1] = structure[2, 1, 1] = True  # the neighbouring headings
    # the heading wraps: label with the first heading repeated after the last one
    wrapped = np.concatenate([free, free[:1]], axis=0)
    labels, _ = ndimage.label(wrapped, structure=structure)
    first, last = labels[0].ravel(), labels[-1].ravel()
    # the distinct (first, last) label pairs, sorted as np.unique(..., axis=0) sorts
    # them, by one 1-D sort of a combined key (the 2-D row sort was a third of the time)
    joined = first > 0
    base = np.int64(labels.max()) + 1
    keys = np.unique(first[joined].astype(np.int64) * base + last[joined])
    pairs = np.stack([keys // base, keys % base], axis=1)
    # union-find over the labels joined across the wrap
    root: dict[int, int] = {}

    def find(v: int) -> int:
        while root.get(v, v) != v:
            v = root[v]
        return v

    for p, q in pairs.tolist():
        rp, rq = find(p), find(q)
        if rp != rq:
            root[max(rp, rq)] = min(rp, rq)
    flat = labels[:-1].ravel()
    return find(int(flat[a])) == find(int(flat[b]))


def same_component(free: Any, nk: int, nx: int, ny: int, a: int, b: int) -> bool:
    """:func:`connected_labelled`'s answer for ``free`` flat (``nk * nx * ny`` bools or
    bytes), by joining runs (module doc). Written for numba (self-contained: a compiled
    function calls only compiled ones); plain Python here."""
    rows = nk * nx
    # two passes, counting then filling: arrays grown in the loop cost numba 20x
    n = 0
    for fill in range(2):
        if fill == 1:
            starts = np.empty(n, dtype=np.int64)
            ends = np.empty(n, dtype=np.int64)
            row_first = np.empty(rows + 1, dtype=np.int64)
        n = 0
        for row in range(rows):
            if fill == 1:
                row_first[row] = n
            base = row * ny
            j = 0
            while j < ny:
                if free[base + j]:
                    s = j
                    j += 1
                    while j < ny and free[base + j]:
                        j += 1
                    if fill == 1:
                        starts[n] = s
                        ends[n] = j
                    n += 1
                else:
                    j += 1
    row_first[rows] = n
    # the runs holding a and b (-1: blocked)
    held = np.full(2, -1, dtype=np.int64)
    for e in range(2):
        v = a if e == 0 else b
        row, j = v // ny, v % ny
        for r in range(row_first[row], row_first[row + 1]):
            if starts[r] <= j < ends[r]:
                held[e] = r
    if held[0] < 0 or held[1] < 0:
        return False
    parent = np.arange(n)
    for k in range(nk):
        up = (k + 1) % nk
        for i in range(nx):
            row = k * nx + i
            # the next x at this heading (8-neighbourhood, slack 1), then the next heading
            # at this x (the same positions, slack 0; wrapping round)
            for kind in range(2):
                if kind == 0:
                    if i + 1 >= nx:
                        continue
                    other, slack = row + 1, 1
                else:
                    if up == k:
                        continue
                    other, slack = up * nx + i, 0
                x, x_end = row_first[row], row_first[row + 1]
                y, y_end = row_first[other], row_first[other + 1]
                while x < x_end and y < y_end:
                    if starts[x] < ends[y] + slack and starts[y] < ends[x] + slack:
                        rx = x  # the roots, by path halving
                        while parent[rx] != rx:
                            parent[rx] = parent[parent[rx]]
                            rx = parent[rx]
                        ry = y
                        while parent[ry] != ry:
                            parent[ry] = parent[parent[ry]]
                            ry = parent[ry]
                        if rx < ry:
                            parent[ry] = rx
                        elif ry < rx:
                            parent[rx] = ry
                    # the run that ends first touches no later run of the other row
                    if ends[x] <= ends[y]:
                        x += 1
                    else:
                        y += 1
    roots = np.empty(2, dtype=np.int64)
    for e in range(2):
        r = held[e]
        while parent[r] != r:
            r = parent[r]
        roots[e] = r
    return bool(roots[0] == roots[1])
