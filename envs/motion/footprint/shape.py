"""The oriented footprint of the robot and its load, and its occupancy on an (x, y, theta) lattice.

The disc model of :mod:`voot.envs.motion.planner` is conservative: the disc enclosing
the base, the arm and a carried box is much wider than the assembly, so a goal close to
a wall, or a door the assembly could pass sideways, is refused. The exact model here is
the union of oriented rectangles (:class:`Footprint`: the base square, the arm's
projection, the held object's footprint) in the frame of the planned point, which turns
with the heading. A pose collides iff one of its rectangles overlaps an obstacle
rectangle (separating-axis test, :func:`footprint_hits`); that is the test of the
planner's lattice, evaluated exactly at every lattice pose.

:class:`FootprintLattice` holds the lattice ``x_i = xmin + i * xy_step``,
``y_j = ymin + j * xy_step``, ``theta_k = k * 2 pi / headings`` over the workspace, and
computes, vectorised over all headings and a window of positions, which lattice poses
a footprint overlaps a given obstacle at (:meth:`FootprintLattice.blocked_window`).
The workspace bounds are four obstacles outside it, so a pose is free iff every
rectangle stays inside the workspace and clear of every obstacle. Occupancy of the static
obstacles is computed once per footprint; that of a movable box once per (footprint,
box) (see :mod:`voot.envs.motion.footprint.search`, which searches the lattice).
"""

from __future__ import annotations

import importlib.util
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from voot import validation as V
from voot.envs.motion.planar import Box2D, _finite

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

__all__ = ["Footprint", "FootprintConfig", "FootprintLattice", "footprint_hits"]

#: The A* loops of FootprintConfig.engine.
ENGINES = ("compiled", "python")
#: The position terms of FootprintConfig.heuristic.
HEURISTICS = ("euclidean", "geodesic")

#: Thickness (metres) of the four obstacles standing for the workspace bounds.
_BOUND_THICKNESS = 5.0


@dataclass(frozen=True)
class FootprintConfig:
    """Settings of the exact-footprint search (an option of :class:`BasePlannerConfig`).

    Attributes:
        xy_step: Lattice spacing of positions (metres), in [0.005, 0.2]. 0.025 as in the
            measurement that filed the option (issue 35).
        headings: Number of lattice headings over the full turn, in [8, 360]. 72 (5 deg)
            as in that measurement.
        static_cache_size: Footprints whose static-obstacle occupancy is kept (>= 1); one
            per carried object recurs through a search. Each takes one bit per lattice
            pose (1.35 MB on the conveyor at the default resolution). 32: more than the
            conveyor's 20 objects (a tree search visits every depth, so a smaller cache
            rebuilds an evicted occupancy, about 60 ms, again and again).
        mask_cache_size: ``(footprint, movable box)`` occupancy windows kept (>= 0).
        lazy_tile: Side (lattice positions) of the tiles in which a query's movable
            boxes are tested on demand, in [0, 256]. > 0 (32, default): each footprint
            keeps its free lattice for the last set of movable boxes, re-marks only the
            windows of boxes added or removed since, and tests a pose the first time the
            search looks at it (:mod:`.scene`): with ``engine="compiled"`` that
            pose alone, with ``engine="python"`` its tile (all headings). 0: every
            box's whole window is tested before the search, on a fresh copy of the
            static lattice (the first version). The answers are the same bit for bit;
            only the time differs. Each footprint's scene takes one more byte per
            lattice pose.
        coarse_first: False (default): the search runs on this lattice. True: it first
            runs on the lattice of twice the step and half the headings (16 times
            fewer poses, whose poses are poses of this one), and a path found there,
            each coarse move split in two and every pose of it checked free on this
            lattice, is the answer; where it finds none, or a pose fails the check,
            this lattice is searched as without the option. So "a path exists" is
            answered as without it (every returned path is a path of this lattice),
            but the path, and so its length, is another one. ``headings`` must be even.
        heuristic_weight: A* inflates its admissible heuristic by this factor, >= 1.
            1 gives the lattice's shortest path (slow where the footprint must turn to
            pass a door: A* then expands most of a room at every heading); above 1,
            weighted A*, still complete and deterministic, expands far fewer poses and
            returns a path at most that factor longer on the lattice (the original's
            RRT paths were not the shortest either). The path is pulled tight after.
        label_after: A* expansions after which the search first proves, by labelling
            the lattice's connected components, that start and goal are connected
            (>= 0, 0 never; the answer does not depend on it, only the time).
            200,000 (about 0.1 s of search): labelling the whole lattice costs 65-110 ms
            and most searches that reach 20,000 expansions (the first default) find
            their path after all; measured, 20,000 -> 200,000 took VOOT's 40 simulations
            on the conveyor from 18.8 to 13.9 CPU s and the 183 exact queries of 20
            random rollouts from 12.1 to 7.5 s.
        engine: How the A* loop (:mod:`.astar`) and the lattice's occupancy
            test (:meth:`FootprintLattice.blocked_window`) run: ``"compiled"`` (default),
            compiled with numba (a core dependency; compiled once per machine, then
            cached on disk, :mod:`.kernels`), or ``"python"``, the pure-Python
            and numpy reference. Both mark the same poses, expand them in the same order
            and return the same paths, bit for bit (tested); only the time differs.
        heuristic: The position term of A*'s heuristic: ``"euclidean"`` (default), the
            straight line to the target; ``"geodesic"``, the 8-connected lattice distance
            to it through the positions where the footprint is free at some heading among
            the static obstacles (one Dijkstra over the positions per footprint and
            target position, cached), which follows walls and doors, so far fewer poses
            are expanded where the way bends; a goal it cannot join to the start is
            answered "no path" before any search. Both are lower bounds (then weighted by
            ``heuristic_weight``), so "a path exists" is answered alike; the paths, and
            so their lengths, differ.
        scene_cache_size: Footprints whose lazy scene (``lazy_tile`` > 0) is kept
            (>= 1), each one byte per lattice pose (10.8 MB on the conveyor). An evicted
            scene starts again with every pose untested.
    """

    xy_step: float = 0.025
    headings: int = 72
    static_cache_size: int = 32
    mask_cache_size: int = 512
    heuristic_weight: float = 3.0
    label_after: int = 200_000
    lazy_tile: int = 32
    coarse_first: bool = False
    engine: str = "compiled"
    scene_cache_size: int = 8
    heuristic: str = "euclidean"

    def __post_init__(self) -> None:
        step = _finite(self.xy_step, "FootprintConfig.xy_step")
        if not 0.005 <= step <= 0.2:
            raise ValueError(f"FootprintConfig.xy_step must be in [0.005, 0.2], got {step}")
        object.__setattr__(self, "xy_step", step)
        V.integer(self.headings, "FootprintConfig.headings", 8, 360)
        V.integer(self.static_cache_size, "FootprintConfig.static_cache_size", 1)
        V.integer(self.scene_cache_size, "FootprintConfig.scene_cache_size", 1)
        V.integer(self.mask_cache_size, "FootprintConfig.mask_cache_size", 0)
        hw = _finite(self.heuristic_weight, "FootprintConfig.heuristic_weight")
        if hw < 1.0:
            raise ValueError(f"FootprintConfig.heuristic_weight must be >= 1, got {hw}")
        object.__setattr__(self, "heuristic_weight", hw)
        V.integer(self.label_after, "FootprintConfig.label_after", 0)
        V.integer(self.lazy_tile, "FootprintConfig.lazy_tile", 0, 256)
        if not isinstance(self.coarse_first, bool):
            raise ValueError(
                f"FootprintConfig.coarse_first must be True or False, got {self.coarse_first!r}"
            )
        if self.heuristic not in HEURISTICS:
            raise ValueError(
                f"FootprintConfig.heuristic must be one of {HEURISTICS}, got {self.heuristic!r}"
            )
        if self.engine not in ENGINES:
            raise ValueError(
                f"FootprintConfig.engine must be one of {ENGINES}, got {self.engine!r}"
            )
        if self.coarse_first and (self.headings % 2 or self.headings < 16 or step > 0.1):
            raise ValueError(
                "FootprintConfig.coarse_first needs even headings >= 16 and xy_step <= 0.1 "
                f"(the coarse lattice halves them), got headings={self.headings}, "
                f"xy_step={step}"
            )

    @property
    def heading_step(self) -> float:
        """The lattice's heading spacing (radians)."""
        return 2.0 * math.pi / self.headings


@dataclass(frozen=True)
class Footprint:
    """The robot and its load as oriented rectangles in the frame of the planned point.

    Attributes:
        parts: Rectangles ``Box2D(cx, cy, half_x, half_y, yaw)`` in the frame of the
            point the planner moves (for the env: the carry disc's centre, heading the
            base's heading), at least one.
    """

    parts: tuple[Box2D, ...]

    def __post_init__(self) -> None:
        parts = tuple(self.parts)
        if not parts or not all(isinstance(p, Box2D) for p in parts):
            raise ValueError(f"Footprint.parts must be one or more Box2D, got {self.parts!r}")
        object.__setattr__(self, "parts", parts)

    @cached_property
    def reach(self) -> float:
        """The largest distance from the planned point to a rectangle corner (computed once)."""
        return max(math.hypot(px, py) for p in self.parts for px, py in p.corners().tolist())

    def at(self, x: float, y: float, theta: float) -> list[Box2D]:
        """The rectangles in the world for the planned point at ``(x, y, theta)``."""
        c, s = math.cos(theta), math.sin(theta)
        return [
            Box2D.fast(x + c * p.cx - s * p.cy, y + s * p.cx + c * p.cy, p.half_x, p.half_y,
                       theta + p.yaw, p.name)
            for p in self.parts
        ]  # fmt: skip


def _rects_overlap(a: Box2D, b: Box2D, tolerance: float) -> bool:
    """Do two oriented rectangles overlap by more than ``tolerance`` (separating axes)?"""
    dx, dy = b.cx - a.cx, b.cy - a.cy
    ca, sa, cb, sb = math.cos(a.yaw), math.sin(a.yaw), math.cos(b.yaw), math.sin(b.yaw)
    for ux, uy in ((ca, sa), (-sa, ca), (cb, sb), (-sb, cb)):
        ha = a.half_x * abs(ux * ca + uy * sa) + a.half_y * abs(-ux * sa + uy * ca)
        hb = b.half_x * abs(ux * cb + uy * sb) + b.half_y * abs(-ux * sb + uy * cb)
        if abs(ux * dx + uy * dy) >= ha + hb - tolerance:
            return False
    return True


def footprint_hits(
    footprint: Footprint,
    pose: tuple[float, float, float],
    obstacles: list[Box2D] | tuple[Box2D, ...],
    workspace: tuple[float, float, float, float] | None = None,
    tolerance: float = 1e-9,
) -> bool:
    """Does ``footprint`` at ``pose`` overlap an obstacle (or leave ``workspace``)?

    Exact for rectangles: the same separating-axis test the lattice evaluates; contact
    within ``tolerance`` metres does not count.
    """
    world = footprint.at(*pose)
    if workspace is not None:
        xmin, xmax, ymin, ymax = workspace
        for r in world:
            ex = r.half_x * abs(math.cos(r.yaw)) + r.half_y * abs(math.sin(r.yaw))
            ey = r.half_x * abs(math.sin(r.yaw)) + r.half_y * abs(math.cos(r.yaw))
            if (r.cx - ex < xmin - tolerance or r.cx + ex > xmax + tolerance
                    or r.cy - ey < ymin - tolerance or r.cy + ey > ymax + tolerance):  # fmt: skip
                return True
    return any(_rects_overlap(r, b, tolerance) for r in world for b in obstacles)


def bound_boxes(workspace: tuple[float, float, float, float]) -> tuple[Box2D, ...]:
    """Four obstacles just outside ``workspace``: a rectangle leaving it overlaps one."""
    xmin, xmax, ymin, ymax = workspace
    t = _BOUND_THICKNESS
    w, h = 0.5 * (xmax - xmin) + t, 0.5 * (ymax - ymin) + t
    cx, cy = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
    return (
        Box2D(xmin - 0.5 * t, cy, 0.5 * t, h, 0.0, "workspace"),
        Box2D(xmax + 0.5 * t, cy, 0.5 * t, h, 0.0, "workspace"),
        Box2D(cx, ymin - 0.5 * t, w, 0.5 * t, 0.0, "workspace"),
        Box2D(cx, ymax + 0.5 * t, w, 0.5 * t, 0.0, "workspace"),
    )


class FootprintLattice:
    """The (heading, x, y) lattice over a workspace and footprint occupancy on it.

    Args:
        workspace: ``(xmin, xmax, ymin, ymax)``.
        config: The lattice's resolution.
        tolerance: Contact depth (metres) that does not count as a collision.
    """

    def __init__(
        self,
        workspace: tuple[float, float, float, float],
        config: FootprintConfig,
        tolerance: float = 1e-9,
    ) -> None:
        if config.engine == "compiled" and importlib.util.find_spec("numba") is None:
            raise ImportError(
                'FootprintConfig.engine="compiled" needs numba (pip install numba); '
                'engine="python" runs the same search (the same paths) without it'
            )
        self.workspace = workspace
        self.config = config
        self.tolerance = tolerance
        step = config.xy_step
        xmin, xmax, ymin, ymax = workspace
        self.nx = math.floor((xmax - xmin) / step + 1e-9) + 1
        self.ny = math.floor((ymax - ymin) / step + 1e-9) + 1
        self.nk = config.headings
        self.xs = xmin + step * np.arange(self.nx, dtype=np.float64)
        self.ys = ymin + step * np.arange(self.ny, dtype=np.float64)
        self.thetas = config.heading_step * np.arange(self.nk, dtype=np.float64)
        th = self.thetas[:, None, None]
        self._cos, self._sin = np.cos(th), np.sin(th)
        self.shape = (self.nk, self.nx, self.ny)

    def pose(self, k: int, i: int, j: int) -> tuple[float, float, float]:
        """The lattice pose of index ``(k, i, j)`` (theta wrapped to ``[-pi, pi)``)."""
        theta = float(self.thetas[k])
        if theta >= math.pi:
            theta -= 2.0 * math.pi
        return (float(self.xs[i]), float(self.ys[j]), theta)

    def nearest(self, x: float, y: float, theta: float) -> tuple[int, int, int] | None:
        """The index of the lattice pose nearest ``(x, y, theta)``, None outside."""
        step = self.config.xy_step
        i = round((x - self.workspace[0]) / step)
        j = round((y - self.workspace[2]) / step)
        if not (0 <= i < self.nx and 0 <= j < self.ny):
            return None
        k = round(theta / self.config.heading_step) % self.nk
        return (k, i, j)

    def box_window(self, footprint: Footprint, box: Box2D) -> tuple[int, int, int, int] | None:
        """The positions ``[i0, i1) x [j0, j1)`` outside which ``footprint`` clears ``box``.

        None when the window is empty (the box is out of the lattice's reach).
        """
        step = self.config.xy_step
        xmin, _, ymin, _ = self.workspace
        cb, sb = math.cos(box.yaw), math.sin(box.yaw)
        ext_x = box.half_x * abs(cb) + box.half_y * abs(sb)
        ext_y = box.half_x * abs(sb) + box.half_y * abs(cb)
        grow = footprint.reach + step
        i0 = max(0, math.floor((box.cx - ext_x - grow - xmin) / step))
        i1 = min(self.nx, math.ceil((box.cx + ext_x + grow - xmin) / step) + 1)
        j0 = max(0, math.floor((box.cy - ext_y - grow - ymin) / step))
        j1 = min(self.ny, math.ceil((box.cy + ext_y + grow - ymin) / step) + 1)
        if i0 >= i1 or j0 >= j1:
            return None
        return (i0, i1, j0, j1)

    def part_windows(
        self, footprint: Footprint, box: Box2D
    ) -> tuple[tuple[int, int, int, int], list[tuple[int, int, int, int] | None]] | None:
        """The window of :meth:`box_window` and, per part, the part's own window in it.

        A part's window is grown by the part's reach (not the footprint's): every pose
        outside it keeps the part clear of ``box``. None where the part's window is empty;
        None in all when the footprint's is.
        """
        bounds = self.box_window(footprint, box)
        if bounds is None:
            return None
        i0, i1, j0, j1 = bounds
        step = self.config.xy_step
        xmin, _, ymin, _ = self.workspace
        cb, sb = math.cos(box.yaw), math.sin(box.yaw)
        ext_x = box.half_x * abs(cb) + box.half_y * abs(sb)
        ext_y = box.half_x * abs(sb) + box.half_y * abs(cb)
        parts: list[tuple[int, int, int, int] | None] = []
        for part in footprint.parts:
            p_grow = max(math.hypot(cx, cy) for cx, cy in part.corners().tolist()) + step
            a0 = max(i0, math.floor((box.cx - ext_x - p_grow - xmin) / step))
            a1 = min(i1, math.ceil((box.cx + ext_x + p_grow - xmin) / step) + 1)
            b0 = max(j0, math.floor((box.cy - ext_y - p_grow - ymin) / step))
            b1 = min(j1, math.ceil((box.cy + ext_y + p_grow - ymin) / step) + 1)
            parts.append(None if a0 >= a1 or b0 >= b1 else (a0, a1, b0, b1))
        return bounds, parts

    def part_trig(self, part: Box2D) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Per heading: the part's centre offset ``(ox, oy)`` rotated with the heading and
        the cosine and sine of its axis (numpy's trigonometry, the one every test reads)."""
        th = self.thetas[:, None, None]
        cos_t, sin_t = self._cos, self._sin
        ox = cos_t * part.cx - sin_t * part.cy
        oy = sin_t * part.cx + cos_t * part.cy
        ang = th + part.yaw
        return ox.ravel(), oy.ravel(), np.cos(ang).ravel(), np.sin(ang).ravel()

    def blocked_window(
        self,
        footprint: Footprint,
        box: Box2D,
        within: tuple[int, int, int, int] | None = None,
    ) -> tuple[int, int, int, int, BoolArray] | None:
        """Where ``footprint`` overlaps ``box``: ``(i0, i1, j0, j1, mask)``, or None.

        ``mask`` has shape ``(headings, i1 - i0, j1 - j0)``: True at the lattice poses
        ``(k, i0 + a, j0 + b)`` whose footprint overlaps ``box`` by more than the
        tolerance (every pose outside the window is clear of it). ``within`` (positions
        ``(i0, i1, j0, j1)``) clips the window: each pose's test is computed by the same
        arithmetic whatever the window, so a clipped mask is the full one's crop, bit for
        bit (what the lazy scenes of :mod:`voot.envs.motion.footprint.scene` rely on, and
        the pose-by-pose test :func:`~.kernels.pose_free`).
        """
        windows = self.part_windows(footprint, box)
        if windows is None:
            return None
        (i0, i1, j0, j1), part_windows = windows
        if within is not None:
            i0, i1 = max(i0, within[0]), min(i1, within[1])
            j0, j1 = max(j0, within[2]), min(j1, within[3])
            if i0 >= i1 or j0 >= j1:
                return None
        cb, sb = math.cos(box.yaw), math.sin(box.yaw)
        hit = np.zeros((self.nk, i1 - i0, j1 - j0), dtype=bool)
        tol = self.tolerance
        for part, part_window in zip(footprint.parts, part_windows, strict=True):
            if part_window is None:
                continue
            a0, a1 = max(i0, part_window[0]), min(i1, part_window[1])
            b0, b1 = max(j0, part_window[2]), min(j1, part_window[3])
            if a0 >= a1 or b0 >= b1:
                continue
            # positions relative to the box centre, (1, ni, 1) and (1, 1, nj)
            px = (self.xs[a0:a1] - box.cx)[None, :, None]
            py = (self.ys[b0:b1] - box.cy)[None, None, :]
            # the part's centre offset (rotated with the heading) and its axes
            ox, oy, ca, sa = self.part_trig(part)
            if self.config.engine == "compiled":
                from voot.envs.motion.footprint.kernels import part_hits

                part_hits(
                    hit, a0 - i0, b0 - j0, px.ravel(), py.ravel(), ox, oy, ca, sa,
                    np.array([cb, sb, box.half_x, box.half_y]),
                    np.array([part.half_x, part.half_y]), tol,
                )  # fmt: skip
                continue
            ox, oy = ox[:, None, None], oy[:, None, None]
            ca, sa = ca[:, None, None], sa[:, None, None]
            part_hit = np.ones((self.nk, a1 - a0, b1 - b0), dtype=bool)
            axes = ((cb, sb), (-sb, cb), (ca, sa), (-sa, ca))
            for ux, uy in axes:
                hb = box.half_x * np.abs(ux * cb + uy * sb) + box.half_y * np.abs(
                    -ux * sb + uy * cb
                )
                hp = part.half_x * np.abs(ux * ca + uy * sa) + part.half_y * np.abs(
                    -ux * sa + uy * ca
                )
                proj = ux * (px + ox) + uy * (py + oy)
                part_hit &= np.abs(proj) < hb + hp - tol
            hit[:, a0 - i0 : a1 - i0, b0 - j0 : b1 - j0] |= part_hit
        if not hit.any():
            return None
        return (i0, i1, j0, j1, hit)

    def occupancy(self, footprint: Footprint, boxes: tuple[Box2D, ...]) -> BoolArray:
        """Lattice poses (``shape``) at which ``footprint`` overlaps one of ``boxes``."""
        blocked = np.zeros(self.shape, dtype=bool)
        for box in boxes:
            window = self.blocked_window(footprint, box)
            if window is not None:
                i0, i1, j0, j1, mask = window
                blocked[:, i0:i1, j0:j1] |= mask
        return blocked
