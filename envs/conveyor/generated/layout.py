"""Generated storage rooms: a floor plan and a box list drawn from a seed (pure numpy).

``voot/GeneratedStorage-v0`` (:mod:`voot.envs.conveyor.generated.env`) packs the boxes of a belt
into storage rooms that are generated, not fixed. This module draws one layout,
:func:`generate_storage_layout` ``(layout_seed, difficulty, attempt)``, as a frozen
:class:`StorageLayout`: no MuJoCo, deterministic (the same arguments give the same layout
in any process), and independent per argument (the generator is seeded with the
:class:`numpy.random.SeedSequence` of ``(layout_seed, level, attempt, version)``, so
neighbouring seeds share nothing).

What stays fixed (the v1 scene's): the robot's start (0, 1.05, 0) facing the belt, the
belt with its queue, the hall between them (x in [-0.6, 1.5], y in [-1, 3]) and the
2.6 m entrance (y in [0, 2.6]) in the storage area's east wall x = -0.7. What is drawn:

* the storage area west of the entrance, x in [-0.7 - W, -0.7], y in [3 - D, 3];
* its **rooms**: the area is cut by a guillotine partition (the largest room that can
  be split is split across its longer side at a fraction in [0.35, 0.65]; no room side
  under :data:`MIN_ROOM_SIDE`; no cut crosses the entrance);
* the **doors**: a random spanning tree of the rooms' adjacency grown from the room
  behind the entrance (breadth first), one door per tree edge, at a random position
  along the shared wall, of a drawn **width**; easier levels add doors on other shared
  walls (loops);
* the **boxes**: their count, how many are big, where the big ones stand in the queue,
  every size, and each one's shape: a closed cardboard box or an open-top crate
  (:data:`BOX_KINDS`, a share :data:`CRATE_SHARE` of crates), with a shape variant
  (bevels, wall thickness, taper: :mod:`voot.envs.assets.meshes` builds the meshes). Every shape
  fills its bounding box's footprint, so the boxes' footprint rectangles, the fixed
  grasp and the carry discs are those of the box sizes.

A door of width ``w`` passes the robot carrying a box iff ``w > 2 r`` for the carry
disc's radius ``r`` (:mod:`voot.envs.robot.model`): with the fixed grasp a small box gives
r = 0.70 to 0.78 m, a big one 0.83 to 0.87 m (1.40 to 1.56 m and 1.66 to 1.75 m of door),
so the drawn door widths decide which rooms a box can reach: every easy door passes
every box, medium doors (1.65 to 2.0 m) stop some big boxes, most hard doors (1.55 to
1.8 m) stop the big ones and a few stop the largest small ones. Whether every box can be packed is not decided here:
:mod:`voot.envs.conveyor.generated.witness` proves it for each layout (or the layout is rejected and
the next ``attempt`` drawn, :mod:`voot.envs.conveyor.generated.instance`).

The difficulty levels (:data:`DIFFICULTIES`, a :class:`StorageLevel` per
:class:`~voot.envs.core.names.Difficulty`) go from a large area with few rooms, wide
doors and a few small boxes (``"easy"``) to a smaller area cut into more, smaller rooms
behind narrower doors, holding more and bigger boxes (``"hard"``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from voot import validation as V
from voot.envs.assets.mjcf import WALL_THICKNESS
from voot.envs.core.generation import check_layout_seed, level_table, parse_difficulty
from voot.envs.core.names import Difficulty

#: Version of the generator: part of every cache key; bump it when a layout changes.
GENERATOR_VERSION = 1
#: East edge (x) of the storage area's interior: the inner face of the entrance wall.
AREA_EAST = -0.7
#: North edge (y) of the storage area's interior.
AREA_NORTH = 3.0
#: The entrance in the east wall: y range (the v1 scene's).
ENTRANCE = (0.0, 2.6)
#: The shortest side of a room (metres): room for a row of boxes and the carry disc.
MIN_ROOM_SIDE = 2.6
#: Wall kept on either side of a door (metres).
DOOR_JAMB = 0.25
#: Most boxes a belt carries (:class:`voot.envs.conveyor.config.ConveyorConfig` allows 20).
MAX_BOXES = 20
#: The shapes of the boxes (:data:`voot.envs.assets.meshes.SHAPE_KINDS` names).
BOX_KINDS = ("box", "crate")
#: Share of open-top crates among the boxes.
CRATE_SHARE = 1.0 / 3.0
#: Shape variants drawn per box (:attr:`voot.envs.assets.meshes.ShapeSpec.variant`).
SHAPE_VARIANTS = 4
#: Seed-sequence salt of this generator (keeps its streams apart from other users').
_SALT = 0x5707A6E


@dataclass(frozen=True)
class StorageLevel:
    """The ranges one difficulty level of the storage rooms draws a layout from (all
    inclusive).

    Attributes:
        rooms: Fewest and most rooms.
        width: Storage area's extent along x (metres).
        depth: Storage area's extent along y (metres).
        door_width: Door widths (metres).
        extra_door: Probability of a door on a shared wall outside the spanning tree.
        boxes: Fewest and most boxes.
        big_boxes: Fewest and most big boxes among them.
        small_x: Depth (x size, along the grasp's approach) of the small boxes.
        small_y: Width (y size) of the small boxes.
        big_x: Depth of the big boxes.
        big_y: Width of the big boxes.
        height: Heights of every box.
    """

    rooms: tuple[int, int]
    width: tuple[float, float]
    depth: tuple[float, float]
    door_width: tuple[float, float]
    extra_door: float
    boxes: tuple[int, int]
    big_boxes: tuple[int, int]
    small_x: tuple[float, float]
    small_y: tuple[float, float]
    big_x: tuple[float, float] = (0.6, 0.7)
    big_y: tuple[float, float] = (0.7, 0.7)
    height: tuple[float, float] = (0.7, 1.0)

    def __post_init__(self) -> None:
        for name in ("rooms", "boxes", "big_boxes"):
            lo, hi = getattr(self, name)
            V.integer(lo, f"StorageLevel.{name}[0]", 0 if name == "big_boxes" else 1)
            V.integer(hi, f"StorageLevel.{name}[1]", lo)
        V.integer(self.boxes[1], "StorageLevel.boxes[1]", high=MAX_BOXES)
        V.integer(self.big_boxes[1], "StorageLevel.big_boxes[1]", high=self.boxes[0])
        for name in ("width", "depth", "door_width", "small_x", "small_y", "big_x", "big_y"):
            lo, hi = getattr(self, name)
            V.positive(lo, f"StorageLevel.{name}[0]")
            V.number(hi, f"StorageLevel.{name}[1]", lo)
        V.probability(self.extra_door, "StorageLevel.extra_door")


#: The named difficulty levels, easiest first. Harder: a smaller area cut into more and
#: smaller rooms, narrower doors, more boxes, more of them big, bigger small boxes.
DIFFICULTIES: Mapping[Difficulty, StorageLevel] = level_table(
    StorageLevel,
    {  # field: (easy, medium, hard); the big boxes' sizes and the heights are the defaults
        "rooms": ((2, 3), (3, 4), (4, 5)),
        "width": ((6.0, 7.5), (5.8, 7.0), (5.6, 6.8)),
        "depth": ((8.0, 10.0), (7.5, 9.5), (7.0, 9.0)),
        "door_width": ((1.9, 2.3), (1.65, 2.0), (1.55, 1.8)),
        "extra_door": (0.5, 0.25, 0.0),
        "boxes": ((8, 10), (12, 15), (16, 20)),
        "big_boxes": ((0, 1), (1, 2), (2, 4)),
        "small_x": ((0.35, 0.45), (0.4, 0.5), (0.42, 0.52)),
        "small_y": ((0.45, 0.55), (0.5, 0.6), (0.52, 0.62)),
    },
)


@dataclass(frozen=True)
class Room:
    """One room: its interior between the wall lines, and how it is entered.

    Attributes:
        xmin: West wall line.
        xmax: East wall line.
        ymin: South wall line.
        ymax: North wall line.
        depth: Doors between the entrance and the room along the spanning tree (0: the
            room behind the entrance).
        entry: Index of the door the tree enters the room by (-1: the entrance).
        facing: Heading pointing into the room from that door (0 east, pi/2 north...):
            the way a box put down just inside faces when the robot walks straight in.
    """

    xmin: float
    xmax: float
    ymin: float
    ymax: float
    depth: int
    entry: int
    facing: float

    @property
    def area(self) -> float:
        return (self.xmax - self.xmin) * (self.ymax - self.ymin)

    def interior(self, margin: float = 0.5 * WALL_THICKNESS) -> tuple[float, float, float, float]:
        """``(xmin, xmax, ymin, ymax)`` shrunk by ``margin`` (default: half a wall)."""
        return (self.xmin + margin, self.xmax - margin, self.ymin + margin, self.ymax - margin)


@dataclass(frozen=True)
class Door:
    """An opening in the wall between two rooms.

    Attributes:
        axis: ``"x"`` for a wall along a line of constant x, ``"y"`` for constant y.
        at: The wall line's coordinate.
        lo: Start of the opening along the wall.
        hi: End of the opening along the wall.
        rooms: The two rooms it joins (the tree's parent first).
    """

    axis: str
    at: float
    lo: float
    hi: float
    rooms: tuple[int, int]

    @property
    def width(self) -> float:
        return self.hi - self.lo

    @property
    def center(self) -> tuple[float, float]:
        mid = 0.5 * (self.lo + self.hi)
        return (self.at, mid) if self.axis == "x" else (mid, self.at)


@dataclass(frozen=True)
class Wall:
    """A static wall block: name and its axis-aligned footprint (standing on the floor)."""

    name: str
    xmin: float
    xmax: float
    ymin: float
    ymax: float


@dataclass(frozen=True)
class BoxSpec:
    """A box on the belt.

    Attributes:
        size: Its bounding box ``(x, y, z)`` in metres (x: depth along the grasp's
            approach, y: width).
        big: Whether it is one of the big boxes.
        kind: Its shape, one of :data:`BOX_KINDS`.
        variant: Its shape variant (0 .. :data:`SHAPE_VARIANTS` - 1).
    """

    size: tuple[float, float, float]
    big: bool
    kind: str = "box"
    variant: int = 0


@dataclass(frozen=True)
class StorageLayout:
    """One generated instance of the storage rooms (see the module docstring).

    Attributes:
        layout_seed: The seed it was drawn from.
        difficulty: The level (a key of :data:`DIFFICULTIES`).
        attempt: Which draw of this seed and level it is (0 first; the solvability check
            rejects a layout by moving to the next attempt).
        area: The storage area's interior ``(xmin, xmax, ymin, ymax)``.
        rooms: The rooms, in the order they were cut.
        doors: The doors between rooms (the spanning tree's first, then the extra ones).
        walls: Every static wall block, outer walls first.
        boxes: The boxes in belt order.
    """

    layout_seed: int
    difficulty: Difficulty
    attempt: int
    area: tuple[float, float, float, float]
    rooms: tuple[Room, ...]
    doors: tuple[Door, ...]
    walls: tuple[Wall, ...]
    boxes: tuple[BoxSpec, ...]

    @property
    def n_boxes(self) -> int:
        return len(self.boxes)

    @property
    def loading_region(self) -> tuple[float, float, float, float]:
        """Where boxes may be placed: the area and the hall's west edge (as v1's)."""
        x0, _, y0, y1 = self.area
        return (x0, -0.5, y0, y1)

    @property
    def workspace(self) -> tuple[float, float, float, float]:
        """Where the robot's base may go: the area, the hall, up to the belt (x 1.5)."""
        x0, _, y0, y1 = self.area
        return (x0, 1.5, y0, y1)

    def room_at(self, x: float, y: float) -> int:
        """Index of the room whose wall lines enclose ``(x, y)`` (-1: none)."""
        for k, r in enumerate(self.rooms):
            if r.xmin <= x <= r.xmax and r.ymin <= y <= r.ymax:
                return k
        return -1


def difficulty_level(difficulty: str) -> StorageLevel:
    """The :class:`StorageLevel` of ``difficulty`` (an error names the valid ones)."""
    return DIFFICULTIES[parse_difficulty(difficulty, DIFFICULTIES)]


def layout_rng(layout_seed: int, difficulty: str, attempt: int) -> np.random.Generator:
    """The generator of one draw: independent streams for every seed, level and attempt."""
    level = list(DIFFICULTIES).index(Difficulty(difficulty))
    entropy = [int(layout_seed), level, int(attempt), GENERATOR_VERSION, _SALT]
    return np.random.default_rng(np.random.SeedSequence(entropy))


def generate_storage_layout(
    layout_seed: int, difficulty: str = "easy", attempt: int = 0
) -> StorageLayout:
    """Draw the layout of ``(layout_seed, difficulty, attempt)`` (see the module docstring).

    Raises:
        ValueError: An unknown difficulty (the error names the valid ones), a seed or an
            attempt that is not an integer >= 0.
    """
    seed = check_layout_seed(layout_seed)
    difficulty = parse_difficulty(difficulty, DIFFICULTIES)
    level = DIFFICULTIES[difficulty]
    attempt = V.integer(attempt, "attempt", 0)
    rng = layout_rng(seed, difficulty, attempt)
    # a partition whose rooms cannot all be joined by doors is redrawn from the same
    # stream (deterministic); it is rare (a sliver of shared wall) and bounded here
    for _ in range(100):
        width = _round(rng.uniform(*level.width))
        depth = _round(rng.uniform(*level.depth))
        area = (_round(AREA_EAST - width), AREA_EAST, _round(AREA_NORTH - depth), AREA_NORTH)
        n_rooms = int(rng.integers(level.rooms[0], level.rooms[1] + 1))
        rects, cuts = _partition(area, n_rooms, rng)
        plan = _connect(rects, level, rng)
        if plan is not None:
            break
    else:  # pragma: no cover - the ranges make this practically impossible
        raise RuntimeError(f"no connected partition for layout {seed} at {difficulty}")
    rooms, doors = plan
    walls = _outer_walls(area) + _inner_walls(cuts, doors)
    boxes = _draw_boxes(level, rng)
    return StorageLayout(
        layout_seed=seed,
        difficulty=difficulty,
        attempt=attempt,
        area=area,
        rooms=rooms,
        doors=doors,
        walls=walls,
        boxes=boxes,
    )


# ----- the steps ------------------------------------------------------------------------
def _round(x: float, step: float = 0.01) -> float:
    """``x`` rounded to centimetres (readable numbers; the same in every process)."""
    return round(round(float(x) / step) * step, 6)


#: A cut: the axis of its wall line, the line's coordinate and its extent along the line.
_Cut = tuple[str, float, float, float]
_Rect = tuple[float, float, float, float]


def _partition(
    area: _Rect, n_rooms: int, rng: np.random.Generator
) -> tuple[list[_Rect], list[_Cut]]:
    """Guillotine cuts of ``area`` into up to ``n_rooms`` rooms; the rooms and the cuts."""
    rects: list[_Rect] = [area]
    cuts: list[_Cut] = []
    while len(rects) < n_rooms:
        order = sorted(range(len(rects)), key=lambda k: -_rect_area(rects[k]))
        for k in order:
            split = _split(rects[k], rng)
            if split is not None:
                a, b, cut = split
                rects[k : k + 1] = [a, b]
                cuts.append(cut)
                break
        else:
            break  # nothing can be split further: fewer rooms than drawn
    return rects, cuts


def _rect_area(r: _Rect) -> float:
    return (r[1] - r[0]) * (r[3] - r[2])


def _split(r: _Rect, rng: np.random.Generator) -> tuple[_Rect, _Rect, _Cut] | None:
    """Cut ``r`` across its longer side (else its other side), or None if it cannot be."""
    xmin, xmax, ymin, ymax = r
    w, h = xmax - xmin, ymax - ymin
    axes = ["x", "y"] if w >= h else ["y", "x"]
    fraction = float(rng.uniform(0.35, 0.65))
    for axis in axes:
        lo, hi = (xmin, xmax) if axis == "x" else (ymin, ymax)
        c = _round(lo + fraction * (hi - lo))
        c = min(max(c, lo + MIN_ROOM_SIDE), hi - MIN_ROOM_SIDE)
        if hi - lo < 2 * MIN_ROOM_SIDE:
            continue
        if axis == "y" and xmax == AREA_EAST and c > ENTRANCE[0] - 0.2:
            # the wall would cross the entrance: cut south of it if the room allows
            c = ENTRANCE[0] - 0.2
            if c - lo < MIN_ROOM_SIDE:
                continue
        if axis == "x":
            return (xmin, c, ymin, ymax), (c, xmax, ymin, ymax), ("x", c, ymin, ymax)
        return (xmin, xmax, ymin, c), (xmin, xmax, c, ymax), ("y", c, xmin, xmax)
    return None


def _shared(a: _Rect, b: _Rect) -> tuple[str, float, float, float] | None:
    """The wall two rooms share: ``(axis, at, lo, hi)``, or None if they do not touch."""
    if a[1] == b[0] or a[0] == b[1]:
        at = a[1] if a[1] == b[0] else a[0]
        lo, hi = max(a[2], b[2]), min(a[3], b[3])
        return ("x", at, lo, hi) if hi > lo else None
    if a[3] == b[2] or a[2] == b[3]:
        at = a[3] if a[3] == b[2] else a[2]
        lo, hi = max(a[0], b[0]), min(a[1], b[1])
        return ("y", at, lo, hi) if hi > lo else None
    return None


def _door(
    shared: tuple[str, float, float, float],
    pair: tuple[int, int],
    level: StorageLevel,
    rng: np.random.Generator,
) -> Door | None:
    """A door of a drawn width at a drawn place on a shared wall (None if it cannot fit)."""
    axis, at, lo, hi = shared
    width = _round(rng.uniform(*level.door_width))
    room = (hi - lo) - 2 * DOOR_JAMB - width
    if room < 0:
        return None
    start = _round(lo + DOOR_JAMB + float(rng.uniform(0.0, 1.0)) * room)
    start = min(start, hi - DOOR_JAMB - width)
    return Door(axis, at, start, _round(start + width), pair)


def _facing(room: _Rect, door: Door | None) -> float:
    """The heading pointing into ``room`` from ``door`` (None: the entrance, east)."""
    if door is None:
        return math.pi
    if door.axis == "x":
        return 0.0 if door.at == room[0] else math.pi
    return 0.5 * math.pi if door.at == room[2] else -0.5 * math.pi


def _connect(
    rects: list[_Rect], level: StorageLevel, rng: np.random.Generator
) -> tuple[tuple[Room, ...], tuple[Door, ...]] | None:
    """Doors along a random breadth-first spanning tree from the entrance room, then
    extra doors; the rooms with their depth and facing. None if some room stays cut off."""
    root = next(
        k
        for k, r in enumerate(rects)
        if r[1] == AREA_EAST and r[2] <= ENTRANCE[0] and r[3] >= ENTRANCE[1]
    )
    n = len(rects)
    depth = {root: 0}
    entry: dict[int, int] = {root: -1}
    doors: list[Door] = []
    queue = [root]
    while queue:
        k = queue.pop(0)
        for j in [int(v) for v in rng.permutation(n)]:
            if j in depth:
                continue
            shared = _shared(rects[k], rects[j])
            if shared is None:
                continue
            door = _door(shared, (k, j), level, rng)
            if door is None:
                continue
            entry[j] = len(doors)
            doors.append(door)
            depth[j] = depth[k] + 1
            queue.append(j)
    if len(depth) < n:
        return None
    tree = {frozenset(d.rooms) for d in doors}
    for a in range(n):
        for b in range(a + 1, n):
            if frozenset((a, b)) in tree:
                continue
            shared = _shared(rects[a], rects[b])
            if shared is None or rng.uniform() >= level.extra_door:
                continue
            door = _door(shared, (a, b), level, rng)
            if door is not None:
                doors.append(door)
    rooms = tuple(
        Room(
            *rects[k],
            depth=depth[k],
            entry=entry[k],
            facing=_facing(rects[k], doors[entry[k]] if entry[k] >= 0 else None),
        )
        for k in range(n)
    )
    return rooms, tuple(doors)


def _outer_walls(area: _Rect) -> tuple[Wall, ...]:
    """The area's outer walls (outside its interior, as in v1) and the hall's south wall."""
    x0, x1, y0, y1 = area
    t = WALL_THICKNESS
    return (
        Wall("wall_west", x0 - t, x0, y0 - t, y1 + t),
        Wall("wall_south", x0, x1 + t, y0 - t, y0),
        Wall("wall_north", x0, 1.5, y1, y1 + t),
        Wall("wall_east_s", x1, x1 + t, y0, ENTRANCE[0]),
        Wall("wall_east_n", x1, x1 + t, ENTRANCE[1], y1),
        Wall("wall_hall_s", x1 + t, 1.5, -1.1, -1.0),
    )


def _inner_walls(cuts: list[_Cut], doors: tuple[Door, ...]) -> tuple[Wall, ...]:
    """Each cut's wall (centred on its line) with the doors on it left open."""
    half = 0.5 * WALL_THICKNESS
    out: list[Wall] = []
    for k, (axis, at, lo, hi) in enumerate(cuts):
        gaps = sorted(
            (d.lo, d.hi) for d in doors if d.axis == axis and d.at == at and lo <= d.lo < hi
        )
        pieces, start = [], lo
        for g0, g1 in gaps:
            pieces.append((start, g0))
            start = g1
        pieces.append((start, hi))
        for p, (a, b) in enumerate(q for q in pieces if q[1] - q[0] > 1e-6):
            name = f"wall_{k}_{p}"
            if axis == "x":
                out.append(Wall(name, at - half, at + half, a, b))
            else:
                out.append(Wall(name, a, b, at - half, at + half))
    return tuple(out)


def _draw_boxes(level: StorageLevel, rng: np.random.Generator) -> tuple[BoxSpec, ...]:
    """The boxes in belt order: the count, which are big, every size (millimetres),
    shape and variant."""
    n = int(rng.integers(level.boxes[0], level.boxes[1] + 1))
    n_big = int(rng.integers(level.big_boxes[0], level.big_boxes[1] + 1))
    big = set(int(v) for v in rng.permutation(n)[:n_big])
    out = []
    for i in range(n):
        xs, ys = (level.big_x, level.big_y) if i in big else (level.small_x, level.small_y)
        size = (rng.uniform(*xs), rng.uniform(*ys), rng.uniform(*level.height))
        kind = BOX_KINDS[1] if rng.uniform() < CRATE_SHARE else BOX_KINDS[0]
        variant = int(rng.integers(0, SHAPE_VARIANTS))
        rounded = tuple(round(float(v), 3) for v in size)
        out.append(BoxSpec(rounded, i in big, kind, variant))  # type: ignore[arg-type]
    return tuple(out)
