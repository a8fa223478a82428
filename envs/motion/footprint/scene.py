"""One footprint's free lattice among the static obstacles and a changing set of movable boxes.

The exact-footprint search (:mod:`voot.envs.motion.footprint.search`) asks, pose by pose,
whether a footprint is free on the lattice of :class:`~.shape.FootprintLattice`. The
first version built that answer for the whole lattice before every query: a copy of the
static occupancy (10.8 million bytes on the conveyor, itself 60-130 ms to compute per
footprint) and the full occupancy window of every movable box (about 10 ms per new
``(footprint, box)`` pair), most of which the search never looked at. A
:class:`LazyScene` gives the same answers, bit for bit, at a fraction of that cost:

* it is kept per footprint and holds the free lattice for the *last* set of movable
  boxes; a new set marks only the windows of the boxes added or removed as
  :data:`PENDING` (a tree search moves a few boxes per step; restoring a snapshot
  changes a few more); a new scene starts with every pose pending;
* a pending pose is tested when the search first looks at it, against every obstacle,
  static or movable, whose window holds it: with ``engine="compiled"`` that one pose
  (:func:`~.kernels.pose_free`, inside the compiled A* loop and the path's
  tightening), with ``engine="python"`` its whole tile (``tile x tile`` positions, every
  heading; :meth:`FootprintLattice.blocked_window` clipped to the tile). Both compute
  each pose as the full window does.

So a pose's value is always a function of the footprint, the static obstacles and the
current movable set alone: restoring an earlier set restores the earlier answers, and
no query needs the footprint's static occupancy of the whole lattice.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from voot.envs.motion.footprint.shape import Footprint, FootprintLattice
from voot.envs.motion.planar import Box2D

__all__ = ["PENDING", "LatticeBytes", "LazyScene", "lattice_bytes", "pack_static", "unpack_static"]

#: A box's row of :func:`~.kernels.pose_free`'s ``boxes``, its ``wins`` and ``lims``.
Entry = tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float64]]

#: :func:`~.kernels.pose_free`'s arrays: boxes, windows, the parts' trigonometry,
#: the separating-axis limits and the boxes per tile (:func:`~.kernels.tile_lists`),
#: and the scene's dirty tiles (:func:`~.kernels.ensure_tile`).
KernelData = tuple[
    NDArray[np.float64], NDArray[np.int64], NDArray[np.float64], NDArray[np.float64],
    NDArray[np.int64], NDArray[np.uint8],
]  # fmt: skip

#: Byte of a pose not yet tested (against the static obstacles and the movable boxes).
PENDING = 2

#: A table of one byte per lattice pose: a bytearray (the pure-Python engine indexes it
#: fastest) or a numpy array (:func:`lattice_bytes`, the compiled engine's).
LatticeBytes = bytearray | NDArray[np.uint8]


def lattice_bytes(n: int) -> NDArray[np.uint8]:
    """``n`` zero bytes for a table the compiled engine reads pose by pose.

    A numpy array rather than a bytearray: numpy asks Linux for transparent huge pages
    under arrays of 4 MiB or more, and calloc leaves the pages untouched until first
    written. An A* search's reads, scattered over the 10.8 million poses, then miss the
    TLB less: 8% less CPU for VOOT in the authors' domain (docs/motion-planning.md).
    """
    return np.zeros(n, dtype=np.uint8)


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
        static: The static obstacles (with the workspace's bounds,
            :func:`~.shape.bound_boxes`).
        tile: Side of a tile, in lattice positions (>= 1): what ``engine="python"``
            tests at once.
        engine: ``"compiled"``: pending poses are tested one by one by
            :func:`~.kernels.pose_free` (also inside the compiled loops, which
            take :attr:`kernel_data`); ``"python"``: tile by tile with numpy.
        entries: The boxes' windows for ``footprint`` on ``lattice``, kept by the caller
            across scenes of the same footprint (a dict this scene fills), or None.
    """

    def __init__(
        self,
        lattice: FootprintLattice,
        footprint: Footprint,
        static: tuple[Box2D, ...],
        tile: int,
        engine: str = "compiled",
        entries: dict[Box2D, Entry | None] | None = None,
    ) -> None:
        if tile < 1:
            raise ValueError(f"tile must be >= 1, got {tile}")
        self.lattice = lattice
        self.footprint = footprint
        self.tile = tile
        self.compiled = engine == "compiled"
        self.static = tuple(static)
        n = lattice.nk * lattice.nx * lattice.ny
        #: The scene, one byte per lattice pose (what the search indexes). With the
        #: compiled engine a tile's bytes are stale while it is marked dirty (read them
        #: through :meth:`value`); every tile starts dirty, the buffer untouched.
        self.buffer: LatticeBytes = (
            lattice_bytes(n) if self.compiled else bytearray(bytes([PENDING])) * n
        )
        self._dirty = np.zeros(0, dtype=np.uint8)
        if self.compiled:
            from voot.envs.motion.footprint.kernels import TILE_SHIFT

            side = 1 << TILE_SHIFT
            self._tile_shape = (-(-lattice.nx // side), -(-lattice.ny // side))
            self._dirty = np.ones(self._tile_shape[0] * self._tile_shape[1], dtype=np.uint8)
        self._flat: NDArray[np.uint8] = np.frombuffer(self.buffer, dtype=np.uint8)
        self._view = self._flat.reshape(lattice.shape)
        #: The movable boxes the scene is of.
        self.movable: tuple[Box2D, ...] = ()
        self._entries: dict[Box2D, Entry | None] = {} if entries is None else entries
        trig = [np.stack(lattice.part_trig(part)) for part in footprint.parts]
        self._trig = np.ascontiguousarray(np.stack(trig))
        self._half = np.array([[p.half_x, p.half_y] for p in footprint.parts], dtype=np.float64)
        self._dims = np.array(lattice.shape, dtype=np.int64)
        self._static_entries = [e for e in map(self._entry, self.static) if e is not None]
        self._active: list[Box2D] = []
        self.kernel_data = self._data([])

    def _entry(self, box: Box2D) -> Entry | None:
        """The box's row for :func:`~.kernels.pose_free` and its windows (cached)."""
        if box not in self._entries:
            if len(self._entries) > 4096:
                self._entries.clear()
            windows = self.lattice.part_windows(self.footprint, box)
            if windows is None:
                self._entries[box] = None
            else:
                bounds, parts = windows
                wins = np.array(
                    [bounds, *(w if w is not None else (0, 0, 0, 0) for w in parts)],
                    dtype=np.int64,
                )
                row = np.array(
                    [box.cx, box.cy, math.cos(box.yaw), math.sin(box.yaw), box.half_x,
                     box.half_y], dtype=np.float64,
                )  # fmt: skip
                lims = np.zeros((len(self.footprint.parts), self.lattice.nk, 4))
                if self.compiled:
                    from voot.envs.motion.footprint.kernels import part_limits

                    lims = part_limits(row, self._trig, self._half, self.lattice.tolerance)
                self._entries[box] = (row, wins, lims)
        return self._entries[box]

    def _data(self, movable: list[Entry]) -> KernelData:
        """:attr:`kernel_data` for the static obstacles and ``movable``'s entries."""
        entries = self._static_entries + movable
        p = len(self.footprint.parts)
        if entries:
            boxes = np.stack([e[0] for e in entries])
            wins = np.stack([e[1] for e in entries])
            lims = np.stack([e[2] for e in entries])
        else:
            boxes, wins = np.zeros((0, 6)), np.zeros((0, 1 + p, 4), dtype=np.int64)
            lims = np.zeros((0, p, self.lattice.nk, 4))
        tiles = np.zeros(0, dtype=np.int64)
        if self.compiled:
            from voot.envs.motion.footprint.kernels import tile_lists

            tiles = tile_lists(wins, self.lattice.nx, self.lattice.ny)
        return boxes, wins, self._trig, lims, tiles, self._dirty

    def update(self, movable: tuple[Box2D, ...]) -> None:
        """Make the scene that of ``movable``: mark the windows of the boxes that changed."""
        if movable == self.movable:
            return
        old, new = set(self.movable), set(movable)
        if self.compiled:
            from voot.envs.motion.footprint.kernels import TILE_SHIFT

            dirty = self._dirty.reshape(self._tile_shape)
        for box in old ^ new:
            entry = self._entry(box)
            if entry is not None:
                i0, i1, j0, j1 = entry[1][0].tolist()
                if self.compiled:  # the tiles, marked when a search first reads them
                    dirty[i0 >> TILE_SHIFT : ((i1 - 1) >> TILE_SHIFT) + 1,
                          j0 >> TILE_SHIFT : ((j1 - 1) >> TILE_SHIFT) + 1] = 1  # fmt: skip
                else:
                    self._view[:, i0:i1, j0:j1] = PENDING
        self.movable = movable
        self._active = [box for box in movable if self._entry(box) is not None]
        entries = [e for e in map(self._entry, self._active) if e is not None]
        self.kernel_data = self._data(entries)

    def value(self, index: int) -> int:
        """The pose's byte, tested first if need be: 1 free, 0 blocked."""
        if self.compiled or self.buffer[index] == PENDING:
            return self.resolve(index)
        return self.buffer[index]

    def resolve(self, index: int) -> int:
        """Test the pose of the flat lattice index ``index`` (its tile with the python
        engine); its byte after (0 or 1)."""
        if self.compiled:
            self.resolve_all(np.array([index], dtype=np.intp))
            return self.buffer[index]
        lat = self.lattice
        plane = lat.nx * lat.ny
        i, j = divmod(index % plane, lat.ny)
        t = self.tile
        a0, b0 = (i // t) * t, (j // t) * t
        a1, b1 = min(lat.nx, a0 + t), min(lat.ny, b0 + t)
        sub = self._view[:, a0:a1, b0:b1]
        pending = sub == PENDING
        blocked = np.zeros(sub.shape, dtype=bool)
        for box in self.static + tuple(self._active):
            window = lat.blocked_window(self.footprint, box, (a0, a1, b0, b1))
            if window is not None:
                c0, c1, d0, d1, mask = window
                blocked[:, c0 - a0 : c1 - a0, d0 - b0 : d1 - b0] |= mask
        sub[pending] = np.where(blocked[pending], 0, 1).astype(np.uint8)
        return self.buffer[index]

    def resolve_all(self, indices: NDArray[np.intp]) -> None:
        """Test every pending pose among the flat ``indices`` (and, compiled, every
        pose of a dirty tile among them)."""
        if self.compiled:
            from voot.envs.motion.footprint.kernels import resolve_poses

            lat = self.lattice
            resolve_poses(
                self._flat, np.asarray(indices, dtype=np.int64), self._dims, lat.xs, lat.ys,
                *self.kernel_data,
            )  # fmt: skip
            return
        flat = self._flat
        for index in indices[flat[indices] == PENDING].tolist():
            if self.buffer[index] == PENDING:
                self.resolve(index)
