"""Exact-footprint base paths: A* over the (x, y, theta) lattice of :mod:`.shape`.

The search behind :meth:`voot.envs.motion.planner.BasePlanner.plan_footprint`, run when
the disc finds no path (a disc path is a footprint path, so the disc stays the fast
sufficient test). It is deterministic and complete at its resolution:

1. The exact start and goal poses must be free (:func:`footprint_hits`), and so must
   their nearest lattice poses.
2. The lattice's free poses are those whose footprint clears the static obstacles and
   the movable boxes, exactly at each lattice pose, tested where the search looks
   (:mod:`.scene`: pose by pose with the compiled engine, tile by tile with
   the Python one; ``lazy_tile`` 0 tests every box's whole window first, on the static
   occupancy computed once per footprint, with the same answers).
3. A* from the start's lattice pose to the goal's over the free poses, each joined to
   its 8 neighbours in (x, y) at the same heading and to the two neighbouring headings
   at the same position; a move costs its SE(2) length (``|dp| + w |dtheta|``), the
   heuristic is the straight-line SE(2) distance (admissible), ties are broken by the
   lattice index. After ``label_after`` expansions the search asks once whether start
   and goal are in one connected component of the free lattice (:mod:`.components`),
   so that "no path" is proved without expanding a whole room pose by pose.
4. The lattice path is pulled tight: from each kept waypoint the next kept one is the
   farthest along the path joined to it by a straight SE(2) segment whose samples (at
   most ``xy_step`` / 2 and a half heading step apart) all snap to free lattice poses;
   the path's length is the original's sum of SE(2) distances (:func:`path_length`)
   of the tightened path, from the exact start to the exact goal.

With ``coarse_first``, steps 2-3 run first on the lattice of twice the step and half
the headings, whose poses are poses of this one; its path, each move split in two (or
joined by a breadth-first search within one pose of the move where the middle pose is
blocked) and checked free pose by pose here, is the lattice path; where the coarse
lattice has no path or the check fails, steps 2-3 run here. Every returned path is a
path of this lattice, so "a path exists" is answered as without the option.

Guarantee: every lattice pose on the returned path is free exactly (the separating-axis
test of oriented rectangles). Between two lattice poses the footprint moves by at most
``xy_step * sqrt(2)`` or turns by one heading step (at its farthest corner
``reach * heading_step``): the tolerance of the resolution, as for any lattice planner.
"""

from __future__ import annotations

import itertools
import math
import time
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from voot.envs.motion.footprint.astar import (
    AStarSpec,
    DenseTables,
    DiscHub,
    astar_compiled,
    astar_python,
    dense_tables,
    geodesic_steps,
    hypot_table,
    warm_compiled,
)
from voot.envs.motion.footprint.components import connected_labelled
from voot.envs.motion.footprint.moves import Pose, join_locally, step_between
from voot.envs.motion.footprint.scene import (
    PENDING,
    Entry,
    LatticeBytes,
    LazyScene,
    lattice_bytes,
    pack_static,
    unpack_static,
)
from voot.envs.motion.footprint.shape import (
    BoolArray,
    Footprint,
    FootprintConfig,
    FootprintLattice,
    bound_boxes,
    footprint_hits,
)
from voot.envs.motion.planar import Box2D

FloatArray = NDArray[np.float64]

__all__ = ["DiscHub", "FootprintSearch"]


class FootprintSearch:
    """Exact-footprint paths among static and movable rectangles (see the module doc).

    Args:
        workspace: ``(xmin, xmax, ymin, ymax)``: every rectangle must stay inside.
        static_obstacles: Footprints that never move.
        config: The lattice's resolution and caches.
        rotation_weight: Weight of ``|dtheta|`` in the path length and the move costs.
        tolerance: Contact depth (metres) that does not count as a collision.
    """

    def __init__(
        self,
        workspace: tuple[float, float, float, float],
        static_obstacles: tuple[Box2D, ...],
        config: FootprintConfig,
        rotation_weight: float = 1.0,
        tolerance: float = 1e-9,
    ) -> None:
        self.workspace = workspace
        self.config = config
        self.rotation_weight = rotation_weight
        self.tolerance = tolerance
        self.static_obstacles = tuple(static_obstacles)
        self.lattice = FootprintLattice(workspace, config, tolerance)
        self._static_boxes = self.static_obstacles + bound_boxes(workspace)
        self._static: OrderedDict[Footprint, NDArray[np.uint8]] = OrderedDict()
        self._masks: OrderedDict[
            tuple[Footprint, Box2D], tuple[int, int, int, int, BoolArray] | None
        ] = OrderedDict()
        self._scene: tuple[tuple[Footprint, tuple[Box2D, ...]], bytearray, BoolArray] | None = None
        #: The coarse lattice searched first (FootprintConfig.coarse_first), or None.
        self._coarse: FootprintSearch | None = None
        if config.coarse_first:
            coarse = replace(
                config, xy_step=2.0 * config.xy_step, headings=config.headings // 2,
                coarse_first=False,
            )  # fmt: skip
            self._coarse = FootprintSearch(
                workspace, static_obstacles, coarse, rotation_weight, tolerance
            )
        self._lazy: OrderedDict[Footprint, LazyScene] = OrderedDict()
        # per footprint, the boxes' windows its lazy scenes test (kept like the static)
        self._entries: OrderedDict[Footprint, dict[Box2D, Entry | None]] = OrderedDict()
        # the geodesic heuristic: per footprint, the positions free at some heading; per
        # (footprint, target position), the distances
        self._passable: OrderedDict[Footprint, NDArray[np.bool_]] = OrderedDict()
        self._geo: OrderedDict[tuple[Footprint, int], FloatArray] = OrderedDict()
        # A*'s closed set, one byte per lattice pose: allocated once (10.8 MB on the
        # conveyor, whose first touch costs more than most searches) and cleared after
        # each search at the poses it closed
        self._closed: LatticeBytes | None = None
        # the compiled loop's g and move per pose (9 bytes a pose, untouched pages free)
        self._dense: DenseTables | None = None
        lat = self.lattice
        self._spec = AStarSpec(
            lat.shape, lat.xs.tolist(), lat.ys.tolist(), lat.pose, config.xy_step,
            rotation_weight * config.heading_step, config.heuristic_weight, config.label_after,
        )  # fmt: skip
        #: A* expansions of the last exact query (for the benchmark's statistics).
        self.last_expansions = 0
        #: When a list, :meth:`plan` appends each query's CPU seconds to it (benchmarks).
        self.timings: list[float] | None = None

    def free_grid(self, footprint: Footprint, movable: tuple[Box2D, ...]) -> BoolArray:
        """The lattice poses (``(headings, nx, ny)``) where ``footprint`` is free."""
        return self._free(footprint, movable)[1]

    def is_free(
        self, footprint: Footprint, pose: tuple[float, float, float], movable: tuple[Box2D, ...]
    ) -> bool:
        """Is ``footprint`` at ``pose`` inside the workspace and clear of every obstacle?"""
        return not footprint_hits(
            footprint, pose, self.static_obstacles + movable, self.workspace, self.tolerance
        )

    def plan(
        self,
        start: tuple[float, float, float],
        goal: tuple[float, float, float],
        footprint: Footprint,
        movable: tuple[Box2D, ...],
        hub: DiscHub | None = None,
    ) -> FloatArray | None:
        """Waypoints ``(k, 3)`` from ``start`` to ``goal`` (exactly), or None if none exists.

        With a ``hub`` (the disc's free positions reachable from ``start``), the search
        runs from the goal and stops at the first lattice pose whose position is one: the
        disc's path from the start to it (on which any heading is free) is joined to the
        lattice path. The answer "a path exists" is the same; the search is local to
        the goal.
        """
        if self.timings is None:
            return self._plan(start, goal, footprint, movable, hub)
        t0 = time.process_time()
        out = self._plan(start, goal, footprint, movable, hub)
        self.timings.append(time.process_time() - t0)
        return out

    def _plan(
        self,
        start: tuple[float, float, float],
        goal: tuple[float, float, float],
        footprint: Footprint,
        movable: tuple[Box2D, ...],
        hub: DiscHub | None,
    ) -> FloatArray | None:
        """:meth:`plan` untimed."""
        self.last_expansions = 0
        if not (self.is_free(footprint, start, movable) and self.is_free(footprint, goal, movable)):
            return None
        found = self._find(start, goal, footprint, movable, hub)
        if found is None:
            return None
        return self._finish(found[0], found[1], start, goal, footprint, movable)

    def _find(
        self,
        start: tuple[float, float, float],
        goal: tuple[float, float, float],
        footprint: Footprint,
        movable: tuple[Box2D, ...],
        hub: DiscHub | None,
    ) -> tuple[list[int], FloatArray | None] | None:
        """:meth:`_search`, after the coarse lattice's path if it has one that refines."""
        if self._coarse is not None:
            ends = self._coarse_ends(start, goal)
            found = None if ends is None else self._coarse._search(*ends, footprint, movable, hub)
            self.last_expansions = self._coarse.last_expansions
            if found is not None:
                cells = self._refine(found[0], start, goal, found[1] is None, footprint, movable)
                if cells is not None:
                    return cells, found[1]
        lat = self.lattice
        s = lat.nearest(*start)
        g = lat.nearest(*goal)
        if s is None or g is None:
            return None
        return self._search([s], [g], footprint, movable, hub)

    def _coarse_ends(
        self, start: tuple[float, float, float], goal: tuple[float, float, float]
    ) -> tuple[list[Pose], list[Pose]] | None:
        """The coarse lattice poses next to the lattice poses nearest ``start`` and ``goal``.

        Up to 8 each (the coarse poses at most one move of this lattice away in position
        and in heading), in a fixed order; the coarse search starts from the first free one.
        """
        assert self._coarse is not None
        lat, clat = self.lattice, self._coarse.lattice
        out = []
        for pose in (start, goal):
            near = lat.nearest(*pose)
            if near is None:
                return None
            k, i, j = near
            ks = sorted({k // 2, ((k + 1) // 2) % clat.nk})
            i_s = [a for a in sorted({i // 2, (i + 1) // 2}) if a < clat.nx]
            j_s = [b for b in sorted({j // 2, (j + 1) // 2}) if b < clat.ny]
            out.append([(a, b, c) for a in ks for b in i_s for c in j_s])
        return out[0], out[1]

    def _scene_bytes(
        self, footprint: Footprint, movable: tuple[Box2D, ...]
    ) -> tuple[LatticeBytes, Callable[[int], int] | None, LazyScene | None]:
        """The scene's bytes, the test of a :data:`PENDING` pose, and the lazy scene (or None)."""
        if self.config.lazy_tile > 0:
            scene = self._lazy_scene(footprint, movable)
            return scene.buffer, scene.resolve, scene
        return self._free(footprint, movable)[0], None, None

    def _search(
        self,
        starts: list[Pose],
        goals: list[Pose],
        footprint: Footprint,
        movable: tuple[Box2D, ...],
        hub: DiscHub | None,
    ) -> tuple[list[int], FloatArray | None] | None:
        """A* on this lattice (:mod:`.astar`) between the first free of ``starts`` and of ``goals``."""
        lat = self.lattice
        nx, ny = lat.nx, lat.ny
        free_bytes, resolve, scene = self._scene_bytes(footprint, movable)
        ends = []
        for candidates in (starts, goals):
            for k, i, j in candidates:
                index = (k * nx + i) * ny + j
                if scene is not None:
                    scene.value(index)
                if free_bytes[index]:
                    ends.append(index)
                    break
            else:
                return None
        si, gi = ends

        def full() -> BoolArray:
            return self._free(footprint, movable)[1]

        def connected() -> bool:
            return self._connected(gi, si, full())

        hpos = None
        if self.config.heuristic == "geodesic":
            plane = nx * ny
            hpos = self._geodesic(footprint, si % plane)
            if hpos.flat[gi % plane] == np.inf:
                return None  # not joined even where any heading may pass
        if self._closed is None:
            self._closed = self._new_closed()
        # search from the goal: to the start, or to the first hub
        if self.config.engine == "compiled":
            data = None if scene is None else scene.kernel_data
            if self._dense is None:
                self._dense = dense_tables(len(self._closed))
            found, self.last_expansions = astar_compiled(
                self._spec, gi, si, free_bytes, self._closed, resolve, connected, hub, hpos, data,
                self._dense,
            )  # fmt: skip
        else:
            found, self.last_expansions = astar_python(
                self._spec, gi, si, free_bytes, self._closed, resolve, connected, hub, hpos
            )
        return found

    def _geodesic(self, footprint: Footprint, target: int) -> FloatArray:
        """The geodesic position term to the position ``target`` (cached, LRU)."""
        key = (footprint, target)
        table = self._geo.get(key)
        if table is not None:
            self._geo.move_to_end(key)
            return table
        passable = self._passable.get(footprint)
        if passable is None:
            static = unpack_static(self._static_packed(footprint), self.lattice.ny)
            passable = np.asarray(static.any(axis=0), dtype=np.bool_)
            self._passable[footprint] = passable
            if len(self._passable) > self.config.static_cache_size:
                self._passable.popitem(last=False)
        gx, gy = divmod(target, self.lattice.ny)
        if self.config.engine == "compiled":
            from voot.envs.motion.footprint.kernels import geodesic

            table = geodesic(passable, gx, gy)
        else:
            table = geodesic_steps(passable, gx, gy)
        self._geo[key] = table
        if len(self._geo) > self.config.static_cache_size:
            self._geo.popitem(last=False)
        return table

    def _refine(
        self,
        coarse: list[int],
        start: tuple[float, float, float],
        goal: tuple[float, float, float],
        to_start: bool,
        footprint: Footprint,
        movable: tuple[Box2D, ...],
    ) -> list[int] | None:
        """The coarse lattice path ``coarse`` as a path of this lattice, or None.

        A coarse pose ``(k, i, j)`` is this lattice's ``(2k, 2i, 2j)`` (twice the step,
        half the headings); each coarse move is two moves here, whose middle pose must
        be free, and the ends are joined to the poses nearest ``goal`` (and ``start``
        when ``to_start``) by at most one move in position and one in heading. Every
        pose of the result is free on this lattice, so it is a path this lattice's
        search could have returned; None if one is not.
        """
        assert self._coarse is not None
        lat, clat = self.lattice, self._coarse.lattice
        nk, nx, ny = lat.shape
        cplane = clat.nx * clat.ny
        g = lat.nearest(*goal)
        s = lat.nearest(*start)
        if g is None or s is None:
            return None
        poses = [g]
        for c in coarse:
            k, rem = divmod(c, cplane)
            i, j = divmod(rem, clat.ny)
            poses.append((2 * k, 2 * i, 2 * j))
        if to_start:
            poses.append(s)
        free_bytes, _, scene = self._scene_bytes(footprint, movable)

        def free(k: int, i: int, j: int) -> bool:
            u = (k * nx + i) * ny + j
            return bool(free_bytes[u] if scene is None else scene.value(u))

        if not free(*poses[0]):
            return None
        path = [poses[0]]
        for a, b in itertools.pairwise(poses):
            step = step_between(a, b, nk, free) or join_locally(a, b, lat.shape, free)
            if step is None:
                return None
            path.extend(step)
        return [(k * nx + i) * ny + j for k, i, j in path]

    def _finish(
        self,
        cells: list[int],
        head: FloatArray | None,
        start: tuple[float, float, float],
        goal: tuple[float, float, float],
        footprint: Footprint,
        movable: tuple[Box2D, ...],
    ) -> FloatArray:
        """The waypoints of the lattice path ``cells`` (goal first) and the disc's ``head``."""
        lat = self.lattice
        free_bytes, _, scene = self._scene_bytes(footprint, movable)
        plane = lat.nx * lat.ny
        poses = [lat.pose(c // plane, (c % plane) // lat.ny, c % lat.ny) for c in reversed(cells)]
        if head is None:
            return self._tighten([start, *poses, goal], free_bytes, scene)
        tail = self._tighten([*poses, goal], free_bytes, scene)
        return np.concatenate([head[:-1], tail])

    # ----- internals ----------------------------------------------------------------------
    def _free(
        self, footprint: Footprint, movable: tuple[Box2D, ...]
    ) -> tuple[bytearray, BoolArray]:
        """The free lattice of the scene as bytes (A*'s lookups) and as an array (a view)."""
        key = (footprint, movable)
        if self._scene is not None and self._scene[0] == key:
            return self._scene[1], self._scene[2]
        packed = self._static_packed(footprint)
        buffer = bytearray(unpack_static(packed, self.lattice.ny).tobytes())
        free = np.frombuffer(buffer, dtype=bool).reshape(self.lattice.shape)
        for box in movable:
            window = self._mask(footprint, box)
            if window is not None:
                i0, i1, j0, j1, mask = window
                free[:, i0:i1, j0:j1] &= ~mask
        self._scene = (key, buffer, free)
        return buffer, free

    def _static_packed(self, footprint: Footprint) -> NDArray[np.uint8]:
        """The static obstacles' free lattice of ``footprint``, packed (cached, LRU)."""
        static = self._static.get(footprint)
        if static is None:
            static = pack_static(~self.lattice.occupancy(footprint, self._static_boxes))
            self._static[footprint] = static
            if len(self._static) > self.config.static_cache_size:
                self._static.popitem(last=False)
        else:
            self._static.move_to_end(footprint)
        return static

    def _lazy_scene(self, footprint: Footprint, movable: tuple[Box2D, ...]) -> LazyScene:
        """``footprint``'s :class:`LazyScene`, updated to ``movable`` (cached like the static)."""
        scene = self._lazy.get(footprint)
        if scene is None:
            entries = self._entries.get(footprint)
            if entries is None:
                entries = self._entries[footprint] = {}
                if len(self._entries) > self.config.static_cache_size:
                    self._entries.popitem(last=False)
            else:
                self._entries.move_to_end(footprint)
            scene = LazyScene(
                self.lattice, footprint, self._static_boxes, self.config.lazy_tile,
                self.config.engine, entries,
            )  # fmt: skip
            self._lazy[footprint] = scene
            if len(self._lazy) > self.config.scene_cache_size:
                self._lazy.popitem(last=False)
        else:
            self._lazy.move_to_end(footprint)
        scene.update(movable)
        return scene

    def warm(self, footprint: Footprint) -> None:
        """Build what a first query with ``footprint`` would (benchmarks: the one-off cost).

        Its scene; its static occupancy of the whole lattice where a query reads it
        (``lazy_tile`` 0 or the geodesic heuristic; a lazy scene tests the static
        obstacles pose by pose); with ``coarse_first``, the coarse lattice's too; with
        ``engine="compiled"``, the compiled loops are compiled (or loaded from numba's
        cache) too.
        """
        if self.config.engine == "compiled":
            warm_compiled()
            hypot_table(self.lattice.nx, self.lattice.ny)
        if self._coarse is not None:
            self._coarse.warm(footprint)
        if self.config.lazy_tile > 0:
            self._lazy_scene(footprint, ())
        if self.config.lazy_tile == 0 or self.config.heuristic == "geodesic":
            self._static_packed(footprint)
        if self._closed is None:
            self._closed = self._new_closed()

    def _new_closed(self) -> LatticeBytes:
        """The search's per-pose state table (:func:`~.astar.astar_compiled`'s ``closed``)."""
        n = self.lattice.nk * self.lattice.nx * self.lattice.ny
        return lattice_bytes(n) if self.config.engine == "compiled" else bytearray(n)

    def _mask(
        self, footprint: Footprint, box: Box2D
    ) -> tuple[int, int, int, int, BoolArray] | None:
        key = (footprint, box)
        if key in self._masks:
            self._masks.move_to_end(key)
            return self._masks[key]
        window = self.lattice.blocked_window(footprint, box)
        if self.config.mask_cache_size > 0:
            self._masks[key] = window
            if len(self._masks) > self.config.mask_cache_size:
                self._masks.popitem(last=False)
        return window

    def _connected(self, si: int, gi: int, free: BoolArray) -> bool:
        """Are the lattice poses ``si`` and ``gi`` in one connected component of ``free``?

        (:mod:`.components`: by joining runs, compiled, with ``engine="compiled"``; by
        labelling otherwise. The same answer.)"""
        if self.config.engine == "compiled":
            from voot.envs.motion.footprint.kernels import same_component

            return bool(same_component(free.reshape(-1), *free.shape, si, gi))
        return connected_labelled(free, si, gi)

    def _segments_free(
        self,
        a: tuple[float, float, float],
        ends: list[tuple[float, float, float]],
        free_bytes: LatticeBytes,
        scene: LazyScene | None,
    ) -> int:
        """How many of the straight SE(2) segments from ``a`` to ``ends`` are free, in order.

        A segment is free iff its samples (at most ``xy_step`` / 2 and half a heading step
        apart, both ends included) snap to free lattice poses; the count stops at the
        first segment that is not. All segments are sampled in one pass of numpy (each
        sample by the arithmetic of a segment on its own).
        """
        lat = self.lattice
        step = self.config.xy_step
        half_turn = 0.5 * self.config.heading_step
        counts, dthetas = [], []
        for b in ends:
            dtheta = (b[2] - a[2] + math.pi) % (2.0 * math.pi) - math.pi
            n = max(
                1,
                math.ceil(math.hypot(b[0] - a[0], b[1] - a[1]) / (0.5 * step)),
                math.ceil(abs(dtheta) / half_turn),
            )
            counts.append(n + 1)
            dthetas.append(dtheta)
        if self.config.engine == "compiled":
            return self._segments_free_compiled(a, ends, counts, dthetas, free_bytes, scene)
        ts = [np.linspace(0.0, 1.0, n) for n in counts]
        t = np.concatenate(ts)
        which = np.repeat(np.arange(len(ends)), counts)
        bx = np.array([b[0] for b in ends], dtype=np.float64)[which]
        by = np.array([b[1] for b in ends], dtype=np.float64)[which]
        x = a[0] + t * (bx - a[0])
        y = a[1] + t * (by - a[1])
        th = a[2] + t * np.array(dthetas, dtype=np.float64)[which]
        i = np.rint((x - self.workspace[0]) / step).astype(np.intp)
        j = np.rint((y - self.workspace[2]) / step).astype(np.intp)
        outside = (i < 0) | (j < 0) | (i >= lat.nx) | (j >= lat.ny)
        k = np.rint(th / self.config.heading_step).astype(np.intp) % lat.nk
        flat = (k * lat.nx + np.clip(i, 0, lat.nx - 1)) * lat.ny + np.clip(j, 0, lat.ny - 1)
        view = np.frombuffer(free_bytes, dtype=np.uint8)
        values = view[flat]
        blocked = outside | (values == 0)
        pending = values == PENDING
        free = 0
        offset = 0
        for count in counts:
            part = slice(offset, offset + count)
            offset += count
            if blocked[part].any():
                break
            if scene is not None and pending[part].any():
                scene.resolve_all(flat[part])
                if not view[flat[part]].all():
                    break
            free += 1
        return free

    def _segments_free_compiled(
        self,
        a: tuple[float, float, float],
        ends: list[tuple[float, float, float]],
        counts: list[int],
        dthetas: list[float],
        free_bytes: LatticeBytes,
        scene: LazyScene | None,
    ) -> int:
        """:meth:`_segments_free` by :func:`.kernels.segments_free` (the same count)."""
        from voot.envs.motion.footprint.kernels import segments_free

        lat = self.lattice
        grid = np.array(
            [self.workspace[0], self.workspace[2], self.config.xy_step, self.config.heading_step]
        )
        if scene is None:  # the eager scene: nothing pending
            data = (np.zeros((0, 6)), np.zeros((0, 1, 4), dtype=np.int64),
                    np.zeros((0, 4, lat.nk)), np.zeros((0, 0, lat.nk, 4)),
                    np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.uint8))  # fmt: skip
        else:
            data = scene.kernel_data
        args = (
            np.frombuffer(free_bytes, dtype=np.uint8), np.array(a, dtype=np.float64),
            np.array(ends, dtype=np.float64).reshape(-1, 3), np.array(counts, dtype=np.int64),
            np.array(dthetas, dtype=np.float64), grid,
            np.array([*lat.shape, scene is not None], dtype=np.int64),
        )  # fmt: skip
        first = 0
        while True:
            first, pending = segments_free(*args, first, lat.xs, lat.ys, *data)
            if pending < 0:
                return int(first)
            assert scene is not None
            scene.resolve(int(pending))

    def _tighten(
        self,
        path: list[tuple[float, float, float]],
        free_bytes: LatticeBytes,
        scene: LazyScene | None,
    ) -> FloatArray:
        """Pull the lattice path tight (see the module doc); the ends stay exact.

        From each kept waypoint ``path[a]`` the next is ``path[b]``, the last of the
        waypoints after ``a`` to which every segment from ``path[a]`` is free, in order
        (asked in batches of growing size: the answer is that of one segment at a time).
        """
        kept = [path[0]]
        a = 0
        last = len(path) - 1
        while a < last:
            b = a + 1
            batch = 4
            while b < last:
                m = min(batch, last - b)
                n = self._segments_free(path[a], path[b + 1 : b + 1 + m], free_bytes, scene)
                b += n
                if n < m:
                    break
                batch = min(2 * batch, 64)
            kept.append(path[b])
            a = b
        return np.array(kept, dtype=np.float64)
