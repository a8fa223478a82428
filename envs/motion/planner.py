"""Deterministic base motion planning for a holonomic mobile base in a 2-D floor plan.

The benchmark environments need, for every place action, a collision-free path of the
mobile base from its current pose to the new one, and the length of that path (the
kitchen reward is ``min(1/L, 2)`` or ``max(-L, -2)``, the conveyor reward
``exp(-0.1 L)``). The planner must be deterministic (same inputs, same path, also in
another process) and fast (a place action, including its path, in under 5 ms).

This module is the planner's facade: :class:`BasePlanner` (its queries and caches),
:class:`BasePlannerConfig` and :class:`DiscProbe`. The concepts it is built from live
one per module:

* :mod:`voot.envs.motion.planar`: the values, :class:`Pose2D`, :class:`Box2D`,
  :class:`BasePath`, and the SE(2) path length (re-exported here, where the API
  reference documents them);
* :mod:`voot.envs.motion.disc_geometry`: exact collision tests of a disc against boxes, as
  arrays and as bit-identical float shortcuts;
* :mod:`voot.envs.motion.visibility_graph`: the reduced visibility graph and its construction
  (cached per radius, layered or in one pass);
* :mod:`voot.envs.motion.graph_search`: connecting start and goal to the graph, A*, and the
  no-path shortcut.

Model
-----
* The floor plan is a rectangle ``workspace = (xmin, xmax, ymin, ymax)`` holding
  obstacles whose footprints are oriented rectangles (:class:`Box2D`): *static* ones
  (walls, counters, furniture), given once, and *movable* ones (the objects), given per
  call.
* The robot, together with the object it carries, is a **disc** of radius
  ``robot_radius`` (the circumscribed radius of its footprint) plus
  :attr:`BasePlannerConfig.clearance`. A disc is rotation-invariant, so the
  configuration-space obstacles are the rectangles grown by the radius (rounded
  rectangles) and the heading can be turned anywhere along the path. The model is
  conservative: a door of width ``w`` lets the robot through iff
  ``w > 2 * (robot_radius + clearance)``. That is how "a door too narrow for the robot"
  (kitchen) and "a door too narrow for the two big boxes" (storage rooms: carrying a big
  box gives a larger radius) arise.
* Path length is the original's "sum of SE(2) distances" between consecutive waypoints
  (:func:`path_length`), with ``rotation_weight`` 1 as in the original.

A query
-------
Two shortcuts answer exactly as the full search would: a query whose start or goal is in
collision, or whose straight segment is free, is decided by single-point and
single-segment tests on Python floats; and a query is answered "no path" without A* when
the goal sees no graph node in a connected component the start sees
(:func:`voot.envs.motion.graph_search.no_path`). Otherwise A* over the visibility graph of the
query's ``(radius, movable)`` scene (built once per scene and cached: tree search
queries many goals from the same state) gives the shortest polyline; headings are
interpolated linearly in travelled distance along it by the shortest turn from the start
to the goal heading. Every returned path is collision-free under the exact disc model.

Why not OMPL or an RRT
----------------------
The original planned with a bidirectional RRT with shortcutting, retried with growing
caps. OMPL's Python bindings (``ompl`` 2.0.1 on PyPI, nanobind) offer the same
(``RRTConnect`` in ``SE2StateSpace``) and are deterministic when
``ompl.util.RNG.setSeed`` is called before each plan, but every state-validity check is
a Python callback: through the kitchen-sized floor plan's 1.0 m door a plan took 5-9 s
and 20,000-33,000 callbacks (``docs/motion-planning.md``), against about 2 ms here. A
sampling planner also cannot prove that no path exists (the answer for most infeasible
place actions: it runs to its time limit), and its path length, which is the reward,
varies with the seed. The visibility graph is exact for the disc model, complete,
answers "no path" as fast as "a path", gives the shortest path (so the reward's path
length is a property of the state, not of a random seed) and needs only numpy.
"""

from __future__ import annotations

import itertools
import math
import struct
from collections import OrderedDict
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V
from voot.envs.motion.disc_geometry import (
    BoxArrays,
    _point_hit_indices,
    _point_hits_any,
    _segment_hits_any,
    points_hit_boxes,
    points_inside,
    segments_hit_any,
)
from voot.envs.motion.footprint import Footprint, FootprintConfig
from voot.envs.motion.footprint.search import FootprintSearch
from voot.envs.motion.graph_search import no_path, search
from voot.envs.motion.planar import (
    BasePath,
    Box2D,
    Pose2D,
    _finite,
    path_length,
    se2_distance,
    wrap_angle,
)
from voot.envs.motion.visibility_graph import VisibilityGraphs, _box_lists, _Scene

FloatArray = NDArray[np.float64]

__all__ = [
    "BasePath",
    "BasePlanner",
    "BasePlannerConfig",
    "Box2D",
    "DiscProbe",
    "Footprint",
    "FootprintConfig",
    "Pose2D",
    "path_length",
    "se2_distance",
    "wrap_angle",
]


@dataclass(frozen=True)
class BasePlannerConfig:
    """Settings of :class:`BasePlanner` (all validated).

    Attributes:
        rotation_weight: Weight of ``|dtheta|`` (radians) against metres in the path
            length. 1.0 as in the original's ``se2_distance(a, b, 1, 1)``; >= 0.
        clearance: Safety distance (metres) added to every robot radius; >= 0. 0 keeps the
            door rule ``width > 2 * robot_radius`` exact.
        corner_segments: Tangent segments approximating each quarter-circle corner of a
            grown rectangle, in [1, 8]. More means shorter paths around corners (within a
            factor ``1 / cos(pi / (4 n))``: 1.17, 1.08, 1.035, 1.02 for n = 1..4) and more
            graph nodes (``4 n`` per obstacle).
        vertex_margin: How far (metres) graph nodes are pushed out beyond the grown
            obstacles, so that edges grazing an obstacle are robustly free; in (0, 1e-3].
            A door passes iff ``width > 2 * (radius + clearance + vertex_margin)``.
        contact_tolerance: Numerical slack (metres) of collision tests: a disc collides
            iff it is deeper than this inside an obstacle; in [0, vertex_margin).
        radius_step: 0 (default) plans with the exact radius. A positive step (metres,
            <= 0.05) rounds every inflated radius *up* to a multiple of it, so that
            nearly equal radii (a carried object's enclosing disc varies with the grasp)
            share cached graphs; conservative, it narrows doors by at most ``2 * step``.
        static_cache_size: Number of radii whose static visibility graph is kept; >= 1.
        graph_cache_size: Number of ``(radius, movable obstacles)`` graphs kept; >= 0
            (0 disables the cache: every query rebuilds the movable part).
        footprint: None (default): :meth:`BasePlanner.plan_footprint` is the disc's
            :meth:`BasePlanner.plan`. A :class:`FootprintConfig`: where the disc finds no
            path, :meth:`BasePlanner.plan_footprint` searches the exact oriented
            footprint of robot and load on an (x, y, theta) lattice at that resolution
            (:mod:`voot.envs.motion.footprint.search`).
    """

    rotation_weight: float = 1.0
    clearance: float = 0.0
    corner_segments: int = 2
    vertex_margin: float = 1e-6
    contact_tolerance: float = 1e-9
    radius_step: float = 0.0
    static_cache_size: int = 8
    graph_cache_size: int = 32
    footprint: FootprintConfig | None = None

    def __post_init__(self) -> None:
        rw = _finite(self.rotation_weight, "BasePlannerConfig.rotation_weight")
        if rw < 0.0:
            raise ValueError(f"BasePlannerConfig.rotation_weight must be >= 0, got {rw}")
        cl = _finite(self.clearance, "BasePlannerConfig.clearance")
        if cl < 0.0:
            raise ValueError(f"BasePlannerConfig.clearance must be >= 0, got {cl}")
        if isinstance(self.corner_segments, bool) or not isinstance(self.corner_segments, int):
            raise ValueError(
                f"BasePlannerConfig.corner_segments must be an int in [1, 8], got "
                f"{self.corner_segments!r}"
            )
        if not 1 <= self.corner_segments <= 8:
            raise ValueError(
                f"BasePlannerConfig.corner_segments must be in [1, 8], got {self.corner_segments}"
            )
        vm = _finite(self.vertex_margin, "BasePlannerConfig.vertex_margin")
        if not 0.0 < vm <= 1e-3:
            raise ValueError(f"BasePlannerConfig.vertex_margin must be in (0, 1e-3], got {vm}")
        ct = _finite(self.contact_tolerance, "BasePlannerConfig.contact_tolerance")
        if not 0.0 <= ct < vm:
            raise ValueError(
                f"BasePlannerConfig.contact_tolerance must be in [0, vertex_margin={vm}), got {ct}"
            )
        rs = _finite(self.radius_step, "BasePlannerConfig.radius_step")
        if not 0.0 <= rs <= 0.05:
            raise ValueError(f"BasePlannerConfig.radius_step must be in [0, 0.05], got {rs}")
        object.__setattr__(self, "radius_step", rs)
        for name, low in (("static_cache_size", 1), ("graph_cache_size", 0)):
            value = getattr(self, name)
            V.integer(value, f"BasePlannerConfig.{name}", low)
        object.__setattr__(self, "rotation_weight", rw)
        object.__setattr__(self, "clearance", cl)
        object.__setattr__(self, "vertex_margin", vm)
        object.__setattr__(self, "contact_tolerance", ct)
        if self.footprint is not None and not isinstance(self.footprint, FootprintConfig):
            raise ValueError(
                "BasePlannerConfig.footprint must be None or a FootprintConfig, got "
                f"{type(self.footprint).__name__}"
            )


class DiscProbe:
    """The planner's start and goal tests of a disc, for one set of obstacles.

    :meth:`blocked` is exactly the test that makes :meth:`BasePlanner.plan` return None
    for an end point (and :meth:`BasePlanner.colliding` non-empty): the disc leaves the
    workspace or overlaps an obstacle. :meth:`verdict` answers the same question for a
    centre and radius that the caller knows only to within ``margin`` (computed on
    Python floats where the exact numbers come from numpy, whose rounding may differ in
    the last bits): True or False when the answer is the same for every disc within
    ``margin``, None when it is too close to tell (ask the exact test then).
    """

    __slots__ = ("_blocked_hint", "_lists", "_planner", "_verdict_hint")

    def __init__(self, planner: BasePlanner, lists: tuple[list[float], ...]) -> None:
        self._planner = planner
        self._lists = lists
        # the box that decided the last answer, tried first (the answers do not depend on
        # the order of the boxes)
        self._blocked_hint = [0]
        self._verdict_hint = [0]

    def blocked(self, x: float, y: float, robot_radius: float) -> bool:
        """Does the disc at ``(x, y)`` leave the workspace or touch an obstacle? (exact)"""
        planner = self._planner
        r_hit = planner._inflated_radius(robot_radius) - planner.config.contact_tolerance
        return not planner._inside_xy(x, y, r_hit) or _point_hits_any(
            x, y, self._lists, r_hit, self._blocked_hint
        )

    def blocked_data(self, robot_radius: float) -> tuple[float, NDArray[np.float64]]:
        """:meth:`blocked`'s numbers for one radius: the hit radius and the boxes (7, n).

        The rows are the centres' x and y, cos and sin of the yaw, the half sizes and the
        reach, as :func:`_point_hits_any` reads them (what a compiled copy of the test
        needs to give the same answers).
        """
        planner = self._planner
        r_hit = planner._inflated_radius(robot_radius) - planner.config.contact_tolerance
        return r_hit, np.array(self._lists, dtype=np.float64).reshape(7, -1)

    def blocked_test(self, robot_radius: float) -> Callable[[float, float], bool]:
        """:meth:`blocked` for one radius, as a function of ``(x, y)`` (the radius checked once)."""
        planner = self._planner
        r_hit = planner._inflated_radius(robot_radius) - planner.config.contact_tolerance
        inside, lists, hint = planner._inside_xy, self._lists, self._blocked_hint

        def blocked(x: float, y: float) -> bool:
            return not inside(x, y, r_hit) or _point_hits_any(x, y, lists, r_hit, hint)

        return blocked

    def verdict(self, x: float, y: float, robot_radius: float, margin: float) -> bool | None:
        """:meth:`blocked` for a disc known to within ``margin`` metres; None if unsure."""
        planner = self._planner
        cfg = planner.config
        if cfg.radius_step > 0.0:
            return None  # rounding the radius up to a step is not continuous
        r_hit = robot_radius + cfg.clearance - cfg.contact_tolerance
        xmin, xmax, ymin, ymax = planner.workspace
        lo, hi = r_hit - margin, r_hit + margin
        if not (xmin + lo <= x <= xmax - lo and ymin + lo <= y <= ymax - lo):
            return True
        unsure = not (xmin + hi <= x <= xmax - hi and ymin + hi <= y <= ymax - hi)
        bcx, bcy, bcos, bsin, bhx, bhy, breach = self._lists
        lo2, hi2 = lo * lo, hi * hi
        hint = self._verdict_hint
        n = len(bcx)
        first = hint[0] if hint[0] < n else 0
        for k in itertools.chain(range(first, n), range(first)):
            rx = x - bcx[k]
            ry = y - bcy[k]
            far = breach[k] + hi + 1e-6
            if rx * rx + ry * ry > far * far:
                continue
            c, s = bcos[k], bsin[k]
            lx = rx * c + ry * s
            ly = -rx * s + ry * c
            dx = max(abs(lx) - bhx[k], 0.0)
            dy = max(abs(ly) - bhy[k], 0.0)
            d2 = dx * dx + dy * dy
            if d2 < lo2:
                hint[0] = k
                return True
            if d2 <= hi2:
                unsure = True
        return None if unsure else False


class _DiscHub:
    """The disc's free positions reachable from a start (:class:`DiscHub` of a query)."""

    def __init__(
        self, planner: BasePlanner, start: Pose2D, radius: float, movable: tuple[Box2D, ...]
    ) -> None:
        self._planner = planner
        self._start = start
        self._radius = radius
        self._movable = movable
        self._probe = planner.disc_probe(movable)
        self._blocked = self._probe.blocked_test(radius)
        self._start_free = not self._blocked(start.x, start.y)

    def is_free(self, x: float, y: float) -> bool:
        return self._start_free and not self._blocked(x, y)

    def disc_data(self) -> tuple[bool, float, tuple[float, float, float, float], FloatArray]:
        """:meth:`is_free`'s numbers: start free, hit radius, workspace, boxes (7, n)."""
        r_hit, boxes = self._probe.blocked_data(self._radius)
        return self._start_free, r_hit, self._planner.workspace, boxes

    def connect(self, pose: tuple[float, float, float]) -> FloatArray | None:
        path = self._planner.plan(self._start, pose, self._radius, self._movable)
        return None if path is None else path.waypoints


class BasePlanner:
    """Shortest collision-free paths of a disc-shaped holonomic base (see the module doc).

    Args:
        workspace: ``(xmin, xmax, ymin, ymax)``: the disc must stay inside it.
        static_obstacles: Footprints that never move (walls, furniture).
        config: Settings; defaults to :class:`BasePlannerConfig`.

    Deterministic: no randomness; caches only store results that are recomputed
    identically, so the same inputs give the same path whatever was planned before.
    """

    def __init__(
        self,
        workspace: tuple[float, float, float, float],
        static_obstacles: Sequence[Box2D],
        config: BasePlannerConfig | None = None,
    ) -> None:
        if config is None:
            config = BasePlannerConfig()
        if not isinstance(config, BasePlannerConfig):
            raise ValueError(f"config must be a BasePlannerConfig, got {type(config).__name__}")
        ws = tuple(float(v) for v in workspace)
        if len(ws) != 4 or not all(math.isfinite(v) for v in ws):
            raise ValueError(
                f"workspace must be 4 finite numbers (xmin, xmax, ymin, ymax), got {workspace!r}"
            )
        if not (ws[0] < ws[1] and ws[2] < ws[3]):
            raise ValueError(f"workspace needs xmin < xmax and ymin < ymax, got {ws}")
        self.workspace: tuple[float, float, float, float] = (ws[0], ws[1], ws[2], ws[3])
        self.config = config
        self.static_obstacles: tuple[Box2D, ...] = tuple(static_obstacles)
        self._static = BoxArrays.from_boxes(self.static_obstacles)
        self._graphs = VisibilityGraphs(
            self.workspace,
            self._static,
            config.corner_segments,
            config.vertex_margin,
            config.contact_tolerance,
            config.static_cache_size,
        )
        self._static_lists: tuple[list[float], ...] | None = None
        self._last_plan: tuple[bytes, tuple[Box2D, ...], BasePath | None] | None = None
        self._lists_cache: dict[tuple[Box2D, ...], tuple[tuple[list[float], ...], list[str]]] = {}
        self._arrays_cache: dict[tuple[Box2D, ...], tuple[BoxArrays, BoxArrays]] = {}
        self._graph_cache: OrderedDict[tuple[float, tuple[Box2D, ...]], _Scene] = OrderedDict()
        self._footprint_search: FootprintSearch | None = None

    # ----- public API -------------------------------------------------------------------
    def plan(
        self,
        start: Pose2D | ArrayLike,
        goal: Pose2D | ArrayLike,
        robot_radius: float,
        movable: Sequence[Box2D] = (),
    ) -> BasePath | None:
        """Shortest collision-free path from ``start`` to ``goal``, or None.

        Args:
            start: Start base pose (a :class:`Pose2D` or ``(x, y, theta)``).
            goal: Goal base pose.
            robot_radius: Radius of the disc enclosing the robot and what it carries (> 0).
            movable: Footprints of the movable objects (leave out the carried one).

        Returns:
            The path (first waypoint ``start``, last ``goal``, exactly), or None if start or
            goal is in collision or outside the workspace, or no path exists. A query
            repeating the last one (the same numbers, bit for bit, and the same box
            objects) returns the last answer itself: an env's pre-screen plans the path
            its step then plans again.
        """
        s = Pose2D.coerce(start, "start")
        g = Pose2D.coerce(goal, "goal")
        mov = self._movable(movable)
        key = struct.pack("<7d", s.x, s.y, s.theta, g.x, g.y, g.theta, float(robot_radius))
        last = self._last_plan
        if (
            last is not None
            and last[0] == key
            and len(last[1]) == len(mov)
            and all(a is b for a, b in zip(last[1], mov, strict=True))
        ):
            return last[2]
        path = self._plan(s, g, robot_radius, mov)
        self._last_plan = (key, mov, path)
        return path

    def plan_footprint(
        self,
        start: Pose2D | ArrayLike,
        goal: Pose2D | ArrayLike,
        robot_radius: float,
        footprint: Footprint,
        movable: Sequence[Box2D] = (),
    ) -> BasePath | None:
        """:meth:`plan` for the disc, then, if it fails, the exact ``footprint``'s path.

        The disc of ``robot_radius`` encloses ``footprint`` (given in the frame of the
        planned point, turning with its heading), so a disc path is a footprint path and
        is returned as is. Where the disc finds none and
        :attr:`BasePlannerConfig.footprint` is set, the lattice search of
        :class:`~voot.envs.motion.footprint.search.FootprintSearch` decides (deterministic,
        complete at its resolution); with the option unset this is :meth:`plan`.
        """
        path = self.plan(start, goal, robot_radius, movable)
        fcfg = self.config.footprint
        if path is not None or fcfg is None:
            return path
        if not isinstance(footprint, Footprint):
            raise ValueError(f"footprint must be a Footprint, got {type(footprint).__name__}")
        s = Pose2D.coerce(start, "start")
        g = Pose2D.coerce(goal, "goal")
        mov = self._movable(movable)
        hub = _DiscHub(self, s, robot_radius, mov)
        waypoints = self.footprint_search().plan(
            (s.x, s.y, s.theta), (g.x, g.y, g.theta), footprint, mov, hub
        )
        if waypoints is None:
            return None
        return BasePath._from_owned(waypoints, self.config.rotation_weight)

    def footprint_search(self) -> FootprintSearch:
        """The exact-footprint search of this floor plan (made on first use).

        Raises:
            ValueError: If :attr:`BasePlannerConfig.footprint` is None.
        """
        fcfg = self.config.footprint
        if fcfg is None:
            raise ValueError("BasePlannerConfig.footprint is None: no exact-footprint search")
        if self._footprint_search is None:
            self._footprint_search = FootprintSearch(
                self.workspace,
                self.static_obstacles,
                fcfg,
                self.config.rotation_weight,
                self.config.contact_tolerance,
            )
        return self._footprint_search

    def _plan(
        self, s: Pose2D, g: Pose2D, robot_radius: float, mov: tuple[Box2D, ...]
    ) -> BasePath | None:
        """:meth:`plan` without its memory of the last query."""
        scene = self._scene(self._inflated_radius(robot_radius), mov)
        r_hit = scene.radius - self.config.contact_tolerance
        if not (self._inside_xy(s.x, s.y, r_hit) and self._inside_xy(g.x, g.y, r_hit)):
            return None
        lists = _box_lists(scene)
        if _point_hits_any(s.x, s.y, lists, r_hit) or _point_hits_any(g.x, g.y, lists, r_hit):
            return None
        ends = np.array([[s.x, s.y], [g.x, g.y]])
        if not _segment_hits_any(s.x, s.y, g.x, g.y, lists, r_hit):
            return self._make_path(s, g, ends)
        if scene.graph is None:
            scene.graph = self._graphs.build(scene)
        if no_path(scene, s.x, s.y, g.x, g.y, r_hit):
            return None
        polyline = search(scene.graph, ends, scene.boxes, r_hit)
        if polyline is None:
            return None
        return self._make_path(s, g, polyline)

    def is_free(
        self, pose: Pose2D | ArrayLike, robot_radius: float, movable: Sequence[Box2D] = ()
    ) -> bool:
        """Is the disc at ``pose`` inside the workspace and clear of every obstacle?"""
        p = Pose2D.coerce(pose, "pose")
        scene = self._scene(self._inflated_radius(robot_radius), self._movable(movable))
        r_hit = scene.radius - self.config.contact_tolerance
        if not self._inside_xy(p.x, p.y, r_hit):
            return False
        return not bool(points_hit_boxes(np.array([[p.x, p.y]]), scene.boxes, r_hit).any())

    def colliding(
        self, pose: Pose2D | ArrayLike, robot_radius: float, movable: Sequence[Box2D] = ()
    ) -> list[str]:
        """Names of the obstacles (static first, then movable) the disc at ``pose`` overlaps.

        ``"workspace"`` is listed first if the disc leaves the workspace. Useful for an
        environment's "collision with what" diagnostics.
        """
        p = Pose2D.coerce(pose, "pose")
        radius = self._inflated_radius(robot_radius)
        mov = self._movable(movable)
        r_hit = radius - self.config.contact_tolerance
        # the point test of points_hit_boxes box by box on floats; a one-off radius (a
        # carried object's disc) needs no scene in the graph cache
        scene = self._graph_cache.get((radius, mov))
        lists, names = self._lists_and_names(mov)
        if scene is not None:
            lists = _box_lists(scene)
        out = [names[k] for k in _point_hit_indices(p.x, p.y, lists, r_hit)]
        if not self._inside_xy(p.x, p.y, r_hit):
            out.insert(0, "workspace")
        return out

    def _lists_and_names(
        self, movable: tuple[Box2D, ...]
    ) -> tuple[tuple[list[float], ...], list[str]]:
        """:meth:`_box_lists_of` ``movable`` and the boxes' names, static first.

        Remembered for the last few obstacle sets (a pure function of the boxes): an
        env asks :meth:`colliding` with one set of objects and a new radius (a carried
        object's disc) at every pick it checks.
        """
        hit = self._lists_cache.get(movable)
        if hit is None:
            names = [*(b.name for b in self.static_obstacles), *(b.name for b in movable)]
            hit = (self._box_lists_of(movable), names)
            if len(self._lists_cache) >= 16:
                self._lists_cache.clear()
            self._lists_cache[movable] = hit
        return hit

    def _box_lists_of(self, movable: tuple[Box2D, ...]) -> tuple[list[float], ...]:
        """:func:`_box_lists` of the static boxes followed by ``movable``, without a scene.

        Cosines and sines come from numpy over the movable yaws, as
        :meth:`BoxArrays.from_boxes` computes them; the rest are the boxes' own fields.
        """
        if self._static_lists is None:
            st = self._static
            self._static_lists = (
                st.center[:, 0].tolist(), st.center[:, 1].tolist(), st.cos.tolist(),
                st.sin.tolist(), st.half[:, 0].tolist(), st.half[:, 1].tolist(),
                st.reach.tolist(),
            )  # fmt: skip
        if not movable:
            return self._static_lists
        yaw = np.array([b.yaw for b in movable], dtype=np.float64)
        half = np.array([[b.half_x, b.half_y] for b in movable], dtype=np.float64)
        extra = (
            [b.cx for b in movable], [b.cy for b in movable], np.cos(yaw).tolist(),
            np.sin(yaw).tolist(), [b.half_x for b in movable], [b.half_y for b in movable],
            np.hypot(half[:, 0], half[:, 1]).tolist(),
        )  # fmt: skip
        return tuple(a + b for a, b in zip(self._static_lists, extra, strict=True))

    def path_is_free(
        self, waypoints: ArrayLike, robot_radius: float, movable: Sequence[Box2D] = ()
    ) -> bool:
        """Is the disc swept along the polyline ``waypoints`` (``(k, 2)`` or ``(k, 3)``) free?"""
        w = np.asarray(waypoints, dtype=np.float64)
        if w.ndim != 2 or w.shape[1] not in (2, 3) or w.shape[0] < 1:
            raise ValueError(f"waypoints must have shape (k, 2) or (k, 3), got {w.shape}")
        xy = w[:, :2]
        scene = self._scene(self._inflated_radius(robot_radius), self._movable(movable))
        r_hit = scene.radius - self.config.contact_tolerance
        if not np.all(points_inside(xy, self.workspace, r_hit)):
            return False
        if points_hit_boxes(xy, scene.boxes, r_hit).any():
            return False
        return not bool(segments_hit_any(xy[:-1], xy[1:], scene.boxes, r_hit).any())

    def disc_probe(self, movable: Sequence[Box2D] = ()) -> DiscProbe:
        """Point tests of a disc among the static obstacles and ``movable`` (see :class:`DiscProbe`).

        For callers that test many disc positions against one set of obstacles (an env's
        pre-screen at one state): the obstacle lists are looked up once.
        """
        mov = self._movable(movable)
        lists, _ = self._lists_and_names(mov)
        return DiscProbe(self, lists)

    def clear_caches(self) -> None:
        """Drop the cached graphs (results do not change; only the next query's time)."""
        self._graphs.clear()
        self._graph_cache.clear()
        self._lists_cache.clear()
        self._arrays_cache.clear()
        self._last_plan = None

    # ----- internals --------------------------------------------------------------------
    def _inflated_radius(self, robot_radius: float) -> float:
        r = _finite(robot_radius, "robot_radius")
        if r <= 0.0:
            raise ValueError(f"robot_radius must be > 0, got {robot_radius}")
        r += self.config.clearance
        step = self.config.radius_step
        if step > 0.0:
            # round up; the 1e-9 keeps exact multiples (0.48 / 0.01 = 47.999...) in place
            r = math.ceil(r / step - 1e-9) * step
        return r

    @staticmethod
    def _movable(movable: Sequence[Box2D]) -> tuple[Box2D, ...]:
        mov = tuple(movable)
        for i, b in enumerate(mov):
            if not isinstance(b, Box2D):
                raise ValueError(f"movable[{i}] must be a Box2D, got {type(b).__name__}")
        return mov

    def _inside_xy(self, x: float, y: float, radius: float) -> bool:
        xmin, xmax, ymin, ymax = self.workspace
        return xmin + radius <= x <= xmax - radius and ymin + radius <= y <= ymax - radius

    def _scene(self, radius: float, movable: tuple[Box2D, ...]) -> _Scene:
        """The (cached) obstacle arrays and graph slot for ``(radius, movable)``."""
        key = (radius, movable)
        scene = self._graph_cache.get(key)
        if scene is not None:
            self._graph_cache.move_to_end(key)
            return scene
        arrays = self._arrays_cache.get(movable)
        if arrays is None:  # one obstacle set meets many radii (one per grasp)
            movable_arrays = BoxArrays.from_boxes(movable)
            arrays = (movable_arrays, self._static.concat(movable_arrays))
            if len(self._arrays_cache) >= 16:
                self._arrays_cache.clear()
            self._arrays_cache[movable] = arrays
        scene = _Scene(radius, *arrays)
        if self.config.graph_cache_size > 0:
            self._graph_cache[key] = scene
            if len(self._graph_cache) > self.config.graph_cache_size:
                self._graph_cache.popitem(last=False)
        return scene

    def _make_path(self, start: Pose2D, goal: Pose2D, polyline: FloatArray) -> BasePath:
        """Add headings turning linearly in travelled distance by the shortest way."""
        if len(polyline) == 2:
            # the two ends keep their own headings (the interpolation below is
            # overwritten at both ends): the straight path needs no arithmetic
            waypoints = np.array([[start.x, start.y, start.theta], [goal.x, goal.y, goal.theta]])
            return BasePath._from_owned(waypoints, self.config.rotation_weight)
        xy = np.array(polyline, dtype=np.float64)
        xy[0] = (start.x, start.y)
        xy[-1] = (goal.x, goal.y)
        seg = np.hypot(np.diff(xy[:, 0]), np.diff(xy[:, 1]))
        total = float(np.sum(seg))
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        frac = cum / total if total > 0.0 else np.linspace(0.0, 1.0, xy.shape[0])
        dtheta = float(wrap_angle(goal.theta - start.theta))
        theta = wrap_angle(start.theta + frac * dtheta)
        theta[0] = start.theta
        theta[-1] = goal.theta
        waypoints = np.column_stack([xy, theta])
        return BasePath._from_owned(waypoints, self.config.rotation_weight)
