"""Generated kitchen floor plans: :class:`KitchenLayout` from a seed and a difficulty level.

``voot/GeneratedKitchen-v0`` (:mod:`voot.envs.kitchen.generated.env`) plays the v1 task rules in
a kitchen drawn from ``(layout_seed, difficulty)``. This module draws the floor plan as
plain numbers (no MuJoCo): the house, the static furniture, the start, the sink pose at
the end of the fixed path, the forbidden rooms and the movable objects with their shapes
and poses. :mod:`voot.envs.kitchen.generated.scene` writes it as MJCF;
:mod:`voot.envs.kitchen.generated.witness` proves the task it poses solvable.

The plan (metres; the house interior is ``x in [0, W]``, ``y in [0, D]``):

* **the kitchen** ``x in [0, Wk]`` with a counter along the north wall holding the sink
  (the goal is the base pose facing it, 0.85 m in front of the counter, as in v1), a
  fridge in its north-east corner and, on some seeds, a counter along the west wall;
* **the forbidden rooms** ``x in [Wk, W]`` behind a wall with a 1 m door, split by a wall
  with a door, a bed in one of them: placements there are infeasible (v1's rule);
* **the path's shape**: ``easy`` has a free kitchen (the fixed path is a straight segment
  from a start in the south to the sink); ``medium`` puts a free-standing **island**
  across that segment, so the path bends round it; ``hard`` puts a **peninsula** counter
  from the east wall leaving a passage of ``passage`` metres at the west, so the path
  bends twice through it (and an object carried past it must fit through);
* **the obstacles**: ``n_on_path`` movable objects on the fixed path (their footprints
  meet the swept volume of the robot's disc along it), spaced along the path, and
  ``n_clutter`` objects off the path that take away free floor for the placements.

The fixed path here is :class:`~voot.envs.motion.planner.BasePlanner`'s shortest path among
the static footprints, the one the env plans (it plans again from the compiled model and
:mod:`voot.envs.kitchen.generated.instance` checks the obstacles on it). The generator is a pure function of
``(layout_seed, difficulty, attempt)``: one :func:`numpy.random.default_rng` per call, on
a :class:`numpy.random.SeedSequence` of a fixed tag, :data:`GENERATOR_VERSION`, the level
and the two integers, so seeds are independent streams and the same numbers come out in
every process. ``attempt`` is :mod:`voot.envs.kitchen.generated.instance`'s rejection counter: an instance that is
rejected is drawn again from the next attempt's stream.

The levels (:data:`DIFFICULTIES`, a :class:`KitchenLevel` per
:class:`~voot.envs.core.names.Difficulty`; ranges are uniform draws; sizes are metres):

=================  ================  ================  ================
                   easy              medium            hard
=================  ================  ================  ================
kitchen width Wk   [5.0, 5.8]        [4.9, 5.6]        [4.3, 5.0]
house depth D      [6.4, 7.2]        [6.0, 6.8]        [6.2, 6.8]
path shape         straight          round an island   through a passage
passage width      -                 -                 [1.15, 1.4]
obstacles on path  2-3               3-5               4-5
clutter off path   0-1               2-3               3-4
object kinds       box, crate,       box, crate,       all of
                   bucket            bucket, bin, jug  the catalogue
object sizes       small, medium     small to large    medium, large
=================  ================  ================  ================

The objects are meshes (:mod:`voot.envs.assets.meshes`): each is drawn uniformly from the
entries of :data:`CATALOGUE` of the level's kinds and size classes, floor clutter sized
for a mobile manipulator (footprints 0.22-0.52 m, heights 0.4-0.75 m: the arm reaches
grasps at half to full height). A fixed catalogue, not sizes drawn per layout, so the
meshes are built once and then read from the mesh cache by every layout.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from voot import validation as V
from voot.envs.assets.mjcf import (
    COUNTER_DEPTH,
    COUNTER_HEIGHT,
    KITCHEN_WALL_HEIGHT,
    WALL_THICKNESS,
)
from voot.envs.core.generation import check_layout_seed, level_table, parse_difficulty
from voot.envs.core.names import Difficulty
from voot.envs.motion.planner import BasePlanner, BasePlannerConfig, Box2D
from voot.envs.robot.model import ROBOT_RADIUS

__all__ = [
    "CATALOGUE",
    "DIFFICULTIES",
    "GENERATOR_VERSION",
    "SIZE_CLASSES",
    "Block",
    "CatalogueItem",
    "KitchenLayout",
    "KitchenLevel",
    "LayoutError",
    "ObjectSpec",
    "generate_kitchen_layout",
]

#: Version of the generator: part of the random stream and of every cache key, so a
#: change of the drawing rules never mixes with layouts drawn by an older version.
GENERATOR_VERSION = 1
#: Tag of the random streams (ASCII "vkit"): keeps them apart from other seeded draws.
_STREAM_TAG = 0x766B6974
#: Distance of the goal base pose from the front of the north counter (v1: 0.85 m).
GOAL_SETBACK = 0.85


@dataclass(frozen=True)
class CatalogueItem:
    """An object a generated kitchen can hold: a mesh shape and its size class.

    Attributes:
        kind: The shape's kind (one of :data:`voot.envs.assets.meshes.SHAPE_KINDS`).
        size: Its bounding box ``(x, y, z)`` (metres).
        variant: The shape's variant (:class:`voot.envs.assets.meshes.ShapeSpec`).
        size_class: ``"small"``, ``"medium"`` or ``"large"`` (:data:`SIZE_CLASSES`).
    """

    kind: str
    size: tuple[float, float, float]
    variant: int
    size_class: str


#: The size classes of :data:`CATALOGUE`, smallest first.
SIZE_CLASSES = ("small", "medium", "large")
#: The objects of generated kitchens (mesh shapes; the levels draw from parts of it).
CATALOGUE: tuple[CatalogueItem, ...] = tuple(
    CatalogueItem(kind, size, variant, size_class)
    for kind, size, variant, size_class in (
        ("box", (0.30, 0.30, 0.45), 0, "small"),
        ("box", (0.34, 0.28, 0.55), 1, "small"),
        ("crate", (0.36, 0.30, 0.40), 0, "small"),
        ("bucket", (0.30, 0.30, 0.40), 0, "small"),
        ("jug", (0.24, 0.22, 0.45), 0, "small"),
        ("bin", (0.32, 0.28, 0.50), 0, "small"),
        ("box", (0.40, 0.36, 0.60), 2, "medium"),
        ("crate", (0.44, 0.34, 0.45), 1, "medium"),
        ("bin", (0.38, 0.32, 0.60), 1, "medium"),
        ("bucket", (0.36, 0.36, 0.45), 1, "medium"),
        ("jug", (0.28, 0.26, 0.55), 1, "medium"),
        ("bottle", (0.26, 0.26, 0.60), 0, "medium"),
        ("box", (0.48, 0.42, 0.75), 3, "large"),
        ("crate", (0.52, 0.40, 0.50), 2, "large"),
        ("bin", (0.46, 0.38, 0.70), 2, "large"),
        ("bucket", (0.42, 0.42, 0.50), 2, "large"),
    )
)
#: Gap kept between objects, and between an object and the furniture (metres).
OBJECT_GAP = 0.08
#: How far beyond the peninsula's sides the passage zone reaches (metres): no object
#: stands in the passage (the robot could not carry it out).
PASSAGE_MARGIN = 0.45
#: Width of the passages on both sides of an island (metres).
ISLAND_PASSAGE = 1.7


class LayoutError(ValueError):
    """The drawn numbers do not make a kitchen (no fixed path, no room for an object).

    :mod:`voot.envs.kitchen.generated.instance` counts it as a rejection and draws the
    next attempt.
    """


@dataclass(frozen=True)
class KitchenLevel:
    """The ranges of one difficulty level of the generated kitchens (see the table in the module docstring).

    Attributes:
        name: The level.
        kitchen_width: Range of the kitchen's width ``Wk`` (x extent, metres).
        depth: Range of the house's depth ``D`` (y extent, metres).
        rooms_width: Range of the forbidden rooms' width (x extent, metres).
        shape: The path's shape: ``"straight"``, ``"island"`` or ``"passage"``.
        passage: Range of the passage's width beside the peninsula (``"passage"`` only).
        on_path: Inclusive range of the number of obstacles on the path.
        clutter: Inclusive range of the number of objects off the path.
        kinds: The object kinds drawn (of :data:`CATALOGUE`).
        sizes: The size classes drawn (of :data:`SIZE_CLASSES`).
    """

    name: Difficulty
    kitchen_width: tuple[float, float]
    depth: tuple[float, float]
    rooms_width: tuple[float, float]
    shape: str
    passage: tuple[float, float]
    on_path: tuple[int, int]
    clutter: tuple[int, int]
    kinds: tuple[str, ...]
    sizes: tuple[str, ...]

    def __post_init__(self) -> None:
        for name in ("kitchen_width", "depth", "rooms_width"):
            V.range_pair(f"KitchenLevel.{name}", getattr(self, name))
        if self.shape == "passage":
            V.range_pair("KitchenLevel.passage", self.passage)
        V.one_of(self.shape, "KitchenLevel.shape", PATH_SHAPES)
        for name in ("on_path", "clutter"):
            lo, hi = getattr(self, name)
            V.integer(lo, f"KitchenLevel.{name}[0]", 0)
            V.integer(hi, f"KitchenLevel.{name}[1]", lo)
        if self.on_path[0] < 1:
            raise ValueError(f"KitchenLevel.on_path must start at >= 1, got {self.on_path}")
        kinds = {item.kind for item in CATALOGUE}
        for kind in self.kinds:
            V.one_of(kind, "KitchenLevel.kinds", sorted(kinds))
        for size in self.sizes:
            V.one_of(size, "KitchenLevel.sizes", SIZE_CLASSES)
        if not self.items():
            raise ValueError(
                f"KitchenLevel '{self.name}': no catalogue object is of kinds {self.kinds}"
                f" and sizes {self.sizes}"
            )

    def items(self) -> tuple[CatalogueItem, ...]:
        """The catalogue entries this level draws from."""
        return tuple(i for i in CATALOGUE if i.kind in self.kinds and i.size_class in self.sizes)


#: The path's shapes a level can ask for.
PATH_SHAPES = ("straight", "island", "passage")
#: The difficulty levels, easiest first.
DIFFICULTIES: Mapping[Difficulty, KitchenLevel] = level_table(
    KitchenLevel,
    {  # field: (easy, medium, hard)
        "name": tuple(Difficulty),
        "kitchen_width": ((5.0, 5.8), (4.9, 5.6), (4.3, 5.0)),
        "depth": ((6.4, 7.2), (6.0, 6.8), (6.2, 6.8)),
        "rooms_width": ((2.2, 3.0), (2.2, 3.0), (2.2, 3.0)),
        "shape": ("straight", "island", "passage"),
        "passage": ((0.0, 0.0), (0.0, 0.0), (1.15, 1.4)),
        "on_path": ((2, 3), (3, 5), (4, 5)),
        "clutter": ((0, 1), (2, 3), (3, 4)),
        "kinds": (
            ("box", "crate", "bucket"),
            ("box", "crate", "bucket", "bin", "jug"),
            ("box", "crate", "bucket", "bin", "jug", "bottle"),
        ),
        "sizes": (("small", "medium"), SIZE_CLASSES, ("medium", "large")),
    },
)


@dataclass(frozen=True)
class Block:
    """A static block standing on the floor (a wall, a counter, furniture).

    Attributes:
        name: Geom name in the scene.
        kind: ``"wall"``, ``"counter"``, ``"fridge"``, ``"island"`` or ``"furniture"``
            (the scene's material).
        rect: ``(xmin, xmax, ymin, ymax)``.
        height: Its height (metres).
    """

    name: str
    kind: str
    rect: tuple[float, float, float, float]
    height: float

    def footprint(self) -> Box2D:
        """Its footprint as the planner's box."""
        x0, x1, y0, y1 = self.rect
        return Box2D(
            0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (x1 - x0), 0.5 * (y1 - y0), 0.0, self.name
        )


@dataclass(frozen=True)
class ObjectSpec:
    """A movable object of the layout.

    Attributes:
        name: Body name (``obj_*``).
        kind: Its mesh kind (:data:`voot.envs.assets.meshes.SHAPE_KINDS`).
        size: ``(x, y, z)`` extents of its bounding box (metres).
        variant: Its mesh variant.
        pose: ``(x, y, yaw)`` of its body on the floor.
        on_path: Drawn on the fixed path (an obstacle) or off it (clutter).
    """

    name: str
    kind: str
    size: tuple[float, float, float]
    variant: int
    pose: tuple[float, float, float]
    on_path: bool

    @property
    def radius(self) -> float:
        """Circumradius of its footprint."""
        return 0.5 * math.hypot(self.size[0], self.size[1])


@dataclass(frozen=True)
class KitchenLayout:
    """A generated kitchen (see the module docstring).

    Attributes:
        layout_seed: The seed it was drawn from.
        difficulty: Its level.
        attempt: The attempt of that seed it was drawn in (0 unless earlier ones were
            rejected).
        house: The house interior ``(xmin, xmax, ymin, ymax)``.
        forbidden: The rooms behind the door ``(xmin, xmax, ymin, ymax)``.
        kitchen_width: ``Wk``: the kitchen is ``x in [0, Wk]``.
        start: The robot's initial base pose ``(x, y, theta)``.
        goal: The base pose at the sink (the fixed path's end).
        sink: ``(x, y)`` of the sink on the north counter.
        shape: The path's shape (:data:`PATH_SHAPES`).
        blocks: The static blocks (walls, counters, furniture).
        objects: The movable objects, on-path ones first.
        path: The fixed path's waypoints ``(x, y)`` as the generator planned it.
    """

    layout_seed: int
    difficulty: Difficulty
    attempt: int
    house: tuple[float, float, float, float]
    forbidden: tuple[float, float, float, float]
    kitchen_width: float
    start: tuple[float, float, float]
    goal: tuple[float, float, float]
    sink: tuple[float, float]
    shape: str
    blocks: tuple[Block, ...]
    objects: tuple[ObjectSpec, ...]
    path: tuple[tuple[float, float], ...]

    @property
    def n_on_path(self) -> int:
        """The number of obstacles drawn on the path."""
        return sum(o.on_path for o in self.objects)

    def static_footprints(self) -> list[Box2D]:
        """The blocks' footprints (the planner's static obstacles)."""
        return [b.footprint() for b in self.blocks]


def difficulty_level(difficulty: str) -> KitchenLevel:
    """The :class:`KitchenLevel` of ``difficulty`` (an error names the valid ones)."""
    return DIFFICULTIES[parse_difficulty(difficulty, DIFFICULTIES)]


def layout_rng(layout_seed: int, difficulty: str, attempt: int) -> np.random.Generator:
    """The random stream of one attempt: independent per (seed, level, attempt, version)."""
    level = list(DIFFICULTIES).index(Difficulty(difficulty))
    entropy = [_STREAM_TAG, GENERATOR_VERSION, level, int(layout_seed), int(attempt)]
    return np.random.default_rng(np.random.SeedSequence(entropy))


def _r(x: float) -> float:
    """Round to millimetres: the layout's numbers are what the MJCF writes."""
    return round(float(x), 3)


def _uniform(rng: np.random.Generator, lo_hi: tuple[float, float]) -> float:
    lo, hi = lo_hi
    return float(rng.uniform(lo, hi)) if hi > lo else float(lo)


def generate_kitchen_layout(layout_seed: int, difficulty: str, attempt: int = 0) -> KitchenLayout:
    """The kitchen of ``(layout_seed, difficulty)``'s attempt ``attempt`` (deterministic).

    Raises:
        ValueError: a bad seed, level or attempt.
        LayoutError: the drawn numbers leave no fixed path or no room for an object
            (:mod:`voot.envs.kitchen.generated.instance` then draws the next attempt).
    """
    seed = check_layout_seed(layout_seed)
    attempt = V.integer(attempt, "attempt", 0)
    level = difficulty_level(difficulty)
    rng = layout_rng(seed, level.name, attempt)
    wk = _r(_uniform(rng, level.kitchen_width))
    depth = _r(_uniform(rng, level.depth))
    width = _r(wk + _uniform(rng, level.rooms_width))
    house = (0.0, width, 0.0, depth)
    forbidden = (wk, width, 0.0, depth)
    blocks = _walls(rng, wk, width, depth)
    # the north counter with the sink, the fridge, the optional west counter
    counter_y = _r(depth - COUNTER_DEPTH)
    fridge_x = _r(wk - 0.75)
    blocks.append(
        Block("counter_north", "counter", (0.0, fridge_x, counter_y, depth), COUNTER_HEIGHT)
    )
    blocks.append(Block("fridge", "fridge", (fridge_x, wk, _r(depth - 0.7), depth), 1.8))
    goal_y = _r(counter_y - GOAL_SETBACK)
    sink_x = _r(rng.uniform(1.35, fridge_x - 0.9))
    goal = (sink_x, goal_y, math.pi / 2)
    start_y = _r(rng.uniform(0.8, 1.15))
    obstacle_zone_top = goal_y - 1.3  # the island or peninsula stays below this
    if level.shape == "passage":
        start_x = _r(rng.uniform(0.6 * wk, wk - 0.75))
    else:
        start_x = _r(rng.uniform(0.75, wk - 0.75))
    start = (start_x, start_y, math.pi / 2)
    if level.shape == "island":
        blocks.append(_island(rng, start, goal, wk))
    elif level.shape == "passage":
        blocks.append(_peninsula(rng, level, start_y, obstacle_zone_top, wk))
    west_bottom = _west_counter_bottom(blocks, counter_y)
    if west_bottom is not None and rng.uniform() < 0.6 and sink_x > COUNTER_DEPTH + 0.75:
        blocks.append(
            Block(
                "counter_west",
                "counter",
                (0.0, COUNTER_DEPTH, west_bottom, counter_y),
                COUNTER_HEIGHT,
            )
        )
    statics = [b.footprint() for b in blocks]
    planner = BasePlanner(house, statics, BasePlannerConfig())
    planned = planner.plan(start, goal, ROBOT_RADIUS, ())
    if planned is None:
        raise LayoutError(f"no fixed path from {start} to {goal}")
    path = np.asarray(planned.waypoints, dtype=np.float64)[:, :2]
    n_on = int(rng.integers(level.on_path[0], level.on_path[1] + 1))
    n_clutter = int(rng.integers(level.clutter[0], level.clutter[1] + 1))
    objects = _draw_objects(rng, level, n_on, n_clutter, path, blocks, (0.0, wk, 0.0, depth), start)
    return KitchenLayout(
        layout_seed=seed,
        difficulty=level.name,
        attempt=attempt,
        house=house,
        forbidden=forbidden,
        kitchen_width=wk,
        start=start,
        goal=goal,
        sink=(sink_x, _r(depth - 0.5 * COUNTER_DEPTH)),
        shape=level.shape,
        blocks=tuple(blocks),
        objects=tuple(objects),
        path=tuple((float(x), float(y)) for x, y in path),
    )


def _walls(rng: np.random.Generator, wk: float, width: float, depth: float) -> list[Block]:
    """The outer walls (outside the interior), the rooms' wall with its 1 m door, the wall
    between the rooms with its door, and a bed in the north room."""
    t, h = WALL_THICKNESS, KITCHEN_WALL_HEIGHT
    door_y = _r(rng.uniform(0.9, depth - 2.0))
    mid_y = _r(0.5 * depth)
    door_x = _r(rng.uniform(wk + t + 0.2, width - 1.2))
    return [
        Block("wall_west", "wall", (-t, 0.0, -t, depth + t), h),
        Block("wall_east", "wall", (width, width + t, -t, depth + t), h),
        Block("wall_south", "wall", (0.0, width, -t, 0.0), h),
        Block("wall_north", "wall", (0.0, width, depth, depth + t), h),
        Block("wall_rooms_s", "wall", (wk, _r(wk + t), 0.0, door_y), h),
        Block("wall_rooms_n", "wall", (wk, _r(wk + t), _r(door_y + 1.0), depth), h),
        Block(
            "wall_between_w", "wall", (_r(wk + t), door_x, _r(mid_y - 0.05), _r(mid_y + 0.05)), h
        ),
        Block(
            "wall_between_e",
            "wall",
            (_r(door_x + 0.9), width, _r(mid_y - 0.05), _r(mid_y + 0.05)),
            h,
        )
        if door_x + 0.9 < width
        else Block(
            "wall_between_e",
            "wall",
            (_r(width - 0.05), width, _r(mid_y - 0.05), _r(mid_y + 0.05)),
            h,
        ),
        Block("bed", "furniture", (_r(width - 1.4), width, _r(depth - 2.0), depth), 0.5),
    ]


def _island(
    rng: np.random.Generator,
    start: tuple[float, float, float],
    goal: tuple[float, float, float],
    wk: float,
) -> Block:
    """A free-standing island across the straight start-goal segment, off its centre so
    the path bends round one side (a passage of at least :data:`ISLAND_PASSAGE` stays on
    both sides: the robot carrying an object needs about 1.5 m)."""
    w = _uniform(rng, (1.0, 1.5))
    d = _uniform(rng, (0.6, 0.85))
    frac = _uniform(rng, (0.4, 0.6))
    cy = start[1] + frac * (goal[1] - start[1])
    cx_line = start[0] + frac * (goal[0] - start[0])
    cx = cx_line + _uniform(rng, (-0.3, 0.3)) * w
    lo, hi = ISLAND_PASSAGE + 0.5 * w, wk - ISLAND_PASSAGE - 0.5 * w
    if lo > hi:
        raise LayoutError("the island does not fit across the kitchen")
    cx = min(max(cx, lo), hi)
    return Block(
        "island",
        "island",
        (_r(cx - 0.5 * w), _r(cx + 0.5 * w), _r(cy - 0.5 * d), _r(cy + 0.5 * d)),
        COUNTER_HEIGHT,
    )


def _peninsula(
    rng: np.random.Generator, level: KitchenLevel, start_y: float, top: float, wk: float
) -> Block:
    """A counter from the kitchen's east wall to ``passage`` metres from the west wall:
    the start's side and the sink's side meet only through that passage."""
    d = _uniform(rng, (0.6, 0.8))
    lo, hi = start_y + 1.5, top
    if lo > hi:
        raise LayoutError("the peninsula does not fit between the start and the sink")
    cy = _uniform(rng, (lo, hi))
    passage = _uniform(rng, level.passage)
    return Block(
        "peninsula", "island", (_r(passage), wk, _r(cy - 0.5 * d), _r(cy + 0.5 * d)), COUNTER_HEIGHT
    )


def _west_counter_bottom(blocks: list[Block], counter_y: float) -> float | None:
    """Where a counter along the west wall may start (y), keeping 1.3 m clear above an
    island or peninsula, or None if it would be shorter than 1.2 m."""
    low = 1.6
    for b in blocks:
        if b.kind == "island":
            low = max(low, b.rect[3] + 1.3)
    return _r(low) if counter_y - low >= 1.2 else None


def _passage_zone(peninsula: Block) -> tuple[float, float, float, float]:
    """The passage beside the peninsula, widened by :data:`PASSAGE_MARGIN` along y."""
    x0, _, y0, y1 = peninsula.rect
    return (0.0, x0, y0 - PASSAGE_MARGIN, y1 + PASSAGE_MARGIN)


def _segment_distances(p: np.ndarray, path: np.ndarray) -> np.ndarray:
    """Distance of each point ``p`` (n, 2) to the polyline ``path`` (m, 2)."""
    a, b = path[:-1], path[1:]
    d = b - a
    seg2 = np.maximum((d * d).sum(axis=1), 1e-12)
    rel = p[:, None, :] - a[None, :, :]
    t = np.clip((rel * d[None]).sum(axis=2) / seg2[None], 0.0, 1.0)
    near = a[None] + t[..., None] * d[None]
    dist: np.ndarray = np.hypot(*(p[:, None, :] - near).transpose(2, 0, 1)).min(axis=1)
    return dist


def _rect_distance(x: float, y: float, rect: tuple[float, float, float, float]) -> float:
    """Distance from ``(x, y)`` to an axis-aligned rectangle (0 inside)."""
    x0, x1, y0, y1 = rect
    dx = max(x0 - x, 0.0, x - x1)
    dy = max(y0 - y, 0.0, y - y1)
    return math.hypot(dx, dy)


def _draw_item(rng: np.random.Generator, level: KitchenLevel) -> CatalogueItem:
    """One of the level's catalogue entries, uniformly."""
    items = level.items()
    return items[int(rng.integers(len(items)))]


def _fits(
    x: float,
    y: float,
    radius: float,
    placed: list[ObjectSpec],
    blocks: list[Block],
    kitchen: tuple[float, float, float, float],
) -> bool:
    """Is an object's circumscribed disc at ``(x, y)`` in the kitchen and clear of the
    furniture and the objects placed so far (by :data:`OBJECT_GAP`)?"""
    x0, x1, y0, y1 = kitchen
    r = radius + OBJECT_GAP
    if not (x0 + r <= x <= x1 - r and y0 + r <= y <= y1 - r):
        return False
    for b in blocks:
        if b.kind != "wall" and _rect_distance(x, y, b.rect) < r:
            return False
        if b.name == "peninsula" and _rect_distance(x, y, _passage_zone(b)) < r:
            return False
    return all(math.hypot(x - o.pose[0], y - o.pose[1]) >= r + o.radius for o in placed)


def _draw_objects(
    rng: np.random.Generator,
    level: KitchenLevel,
    n_on: int,
    n_clutter: int,
    path: np.ndarray,
    blocks: list[Block],
    kitchen: tuple[float, float, float, float],
    start: tuple[float, float, float],
) -> list[ObjectSpec]:
    """``n_on`` objects on the path (within 0.3 m of it, past the first metre) and
    ``n_clutter`` off it (further than the swept disc from it), 200 draws each; every
    object keeps its gaps (:func:`_fits`)."""
    seg = np.hypot(*np.diff(path, axis=0).T)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    length = float(cum[-1])
    placed: list[ObjectSpec] = []
    free_start = ROBOT_RADIUS + 0.1
    # the obstacles: arc positions past the first metre
    s_lo, s_hi = 1.0, length - 0.35
    if s_hi <= s_lo:
        raise LayoutError(f"the fixed path is too short ({length:.2f} m) for obstacles")
    x0, x1, y0, y1 = kitchen
    # the obstacles first, then the clutter; object k is named obj_<kind><k>
    for k in range(n_on + n_clutter):
        on_path = k < n_on
        item = _draw_item(rng, level)
        radius = 0.5 * math.hypot(item.size[0], item.size[1])
        for _ in range(200):
            if on_path:  # within 0.3 m of the path
                s = float(rng.uniform(s_lo, s_hi))
                i = int(np.clip(np.searchsorted(cum, s) - 1, 0, len(seg) - 1))
                u = (s - cum[i]) / max(seg[i], 1e-12)
                p = path[i] + u * (path[i + 1] - path[i])
                dxy = (path[i + 1] - path[i]) / max(seg[i], 1e-12)
                off = float(rng.uniform(-0.3, 0.3))
                x, y = float(p[0] - off * dxy[1]), float(p[1] + off * dxy[0])
            else:
                x, y = float(rng.uniform(x0, x1)), float(rng.uniform(y0, y1))
            yaw = _r(rng.uniform(0.0, 2.0 * math.pi))
            if not on_path and (
                _segment_distances(np.array([[x, y]]), path)[0] < ROBOT_RADIUS + radius + 0.1
            ):
                continue  # clutter stays clear of the swept disc
            if math.hypot(x - start[0], y - start[1]) < free_start + radius:
                continue
            if _fits(x, y, radius, placed, blocks, kitchen):
                pose = (_r(x), _r(y), yaw)
                spec = ObjectSpec(
                    f"obj_{item.kind}{k}", item.kind, item.size, item.variant, pose, on_path
                )
                placed.append(spec)
                break
        else:
            what = f"obstacle {k} on the path" if on_path else f"clutter object {k - n_on}"
            raise LayoutError(f"no room for {what}")
    return placed
