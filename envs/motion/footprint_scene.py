"""One footprint's free lattice among the static obstacles and a changing set of movable boxes.

The exact-footprint search (:mod:`voot.envs.motion.footprint_search`) asks, pose by pose,
whether a footprint is free on the lattice of :class:`~.footprint.FootprintLattice`. The
first version built that answer for the whole lattice before every query: a fresh copy
of the static occupancy (10.8 million bytes on the conveyor) and the full occupancy
window of every movable box (about 10 ms per new ``(footprint, box)`` pair), most of
which the search never looked at. A :class:`LazyScene` gives the same answers, bit for
bit, at a fraction of that cost:

* it is kept per footprint and holds the free lattice for the *last* set of movable
  boxes; a new set re-marks only the windows of the boxes added or removed (a tree
  search moves a few boxes per step; restoring a snapshot changes a few more);
* a re-marked pose that the static obstacles leave free holds :data:`PENDING` until the
  search looks at it; then its whole tile (``tile x tile`` positions, every heading) is
  tested against every movable box whose window meets the tile
  (:meth:`FootprintLattice.blocked_window` clipped to the tile, which computes each pose
  exactly as the full window does).

So a pose's value is always a function of the footprint, the static obstacles and the
current movable set alone: restoring an earlier set restores the earlier answers.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from voot.envs.motion.footprint import Footprint, FootprintLattice
from voot.envs.motion.planar import Box2D

__all__ = ["PENDING", "LazyScene", "pack_static", "unpack_static"]

#: Byte of a pose the static obstacles leave free and the movable boxes are yet to be tested at.
PENDING = 2


def pack_static(free: NDArray[np.bool_]) -> NDArray[np.uint8]:
    """A free lattice ``(headings, nx, ny)`` kept at one bit per pose (packed along y).

    The static occupancy of a footprint is built once (about 60 ms on the conveyor) and
    kept for every carried object; at a bit per pose (1.35 MB on the conveyor instead of
    10.8) a search keeps every object's.
    """
    return np.packbits(free, axis=-1)


def unpack_static(
    packed: NDArray[np.uint8], ny: int, window: tuple[int, int, int, int] | None = None
) -> NDArray[np.uint8]:
    """The bytes (1 free, 0 blocked) of :func:`pack_static`'s lattice with ``ny`` columns,
    or of its ``(i0, i1, j0, j1)`` window (every heading)."""
    if window is None:
        return np.unpackbits(packed, axis=-1, count=ny)
    i0, i1, j0, j1 = window
    b0 = j0 // 8
    bits = np.unpackbits(packed[:, i0:i1, b0 : (j1 + 7) // 8], axis=-1)
    return bits[:, :, j0 - 8 * b0 : j1 - 8 * b0]


class LazyScene:
    """The free lattice of ``footprint``: 1 free, 0 blocked, :data:`PENDING` not yet known.

    Args:
        lattice: The lattice.
        footprint: The footprint the scene is of.
        static: The static obstacles' free lattice of ``footprint``, packed
            (:func:`pack_static`).
        tile: Side of a tile, in lattice positions (>= 1).
    """

    def __init__(
        self,
        lattice: FootprintLattice,
        footprint: Footprint,
        static: NDArray[np.uint8],
        tile: int,
    ) -> None:
        if tile < 1:
            raise ValueError(f"tile must be >= 1, got {tile}")
        self.lattice = lattice
        self.footprint = footprint
        self.tile = tile
        self._static = static
        #: The scene, one byte per lattice pose (what the search indexes).
        self.buffer = bytearray(unpack_static(static, lattice.ny).tobytes())
        self._view: NDArray[np.uint8] = np.frombuffer(self.buffer, dtype=np.uint8).reshape(
            lattice.shape
        )
        #: The movable boxes the scene is of.
        self.movable: tuple[Box2D, ...] = ()
        self._windows: dict[Box2D, tuple[int, int, int, int] | None] = {}
        self._active: list[tuple[Box2D, tuple[int, int, int, int]]] = []

    def _window(self, box: Box2D) -> tuple[int, int, int, int] | None:
        if box not in self._windows:
            if len(self._windows) > 4096:
                self._windows.clear()
            self._windows[box] = self.lattice.box_window(self.footprint, box)
        return self._windows[box]

    def update(self, movable: tuple[Box2D, ...]) -> None:
        """Make the scene that of ``movable``: re-mark the windows of the boxes that changed."""
        if movable == self.movable:
            return
        old, new = set(self.movable), set(movable)
        for box in sorted(old ^ new, key=repr):
            bounds = self._window(box)
            if bounds is not None:
                i0, i1, j0, j1 = bounds
                static = unpack_static(self._static, self.lattice.ny, bounds)
                self._view[:, i0:i1, j0:j1] = static * np.uint8(PENDING)
        self.movable = movable
        active = []
        for box in movable:
            bounds = self._window(box)
            if bounds is not None:
                active.append((box, bounds))
        self._active = active

    def resolve(self, index: int) -> int:
        """Test the tile of the flat lattice index ``index``; its byte after (0 or 1)."""
        lat = self.lattice
        plane = lat.nx * lat.ny
        i, j = divmod(index % plane, lat.ny)
        t = self.tile
        a0, b0 = (i // t) * t, (j // t) * t
        a1, b1 = min(lat.nx, a0 + t), min(lat.ny, b0 + t)
        sub = self._view[:, a0:a1, b0:b1]
        pending = sub == PENDING
        blocked = np.zeros(sub.shape, dtype=bool)
        for box, (i0, i1, j0, j1) in self._active:
            if i0 >= a1 or i1 <= a0 or j0 >= b1 or j1 <= b0:
                continue
            window = lat.blocked_window(self.footprint, box, (a0, a1, b0, b1))
            if window is not None:
                c0, c1, d0, d1, mask = window
                blocked[:, c0 - a0 : c1 - a0, d0 - b0 : d1 - b0] |= mask
        sub[pending] = np.where(blocked[pending], 0, 1).astype(np.uint8)
        return self.buffer[index]

    def resolve_all(self, indices: NDArray[np.intp]) -> None:
        """Test the tiles of every pending pose among the flat ``indices``."""
        flat = np.frombuffer(self.buffer, dtype=np.uint8)
        for index in indices[flat[indices] == PENDING].tolist():
            if self.buffer[index] == PENDING:
                self.resolve(index)
