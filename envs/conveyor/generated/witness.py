"""Proof that a generated storage layout can be packed: a constructive witness plan.

Every generated instance of ``voot/GeneratedStorage-v0`` must be solvable. The proof
does not use a planner: :func:`find_witness` packs the boxes with a fixed, deterministic
greedy rule and executes the result through the env's own :meth:`step`; the layout is
accepted iff every box is placed (the episode terminates), and the plan it executed, the
**witness**, is kept (:attr:`Witness.actions`, the env's normalised actions). A failed
search rejects the layout (:mod:`voot.envs.conveyor.generated.instance` draws the next attempt),
even though a cleverer packing might exist: the check is sufficient, not necessary.

The greedy rule. Each room has a *facing*: the heading pointing into it from the door
the spanning tree enters it by (:attr:`voot.envs.conveyor.generated.layout.Room.facing`). Boxes are
put down facing that way, in rows across the room from its back wall towards that door,
each row filled side to side before the next, so the robot always comes from the open
side of the room. The slots are fixed per room from the sizes of all the boxes (so rows
line up): a row is as deep as the deepest box plus how far the deepest carry disc
reaches ahead of its box (the disc must not touch the row before), columns are as wide
as the largest carry disc's radius plus the widest box's half width (a disc must not
touch the box beside it). For each box in belt order, the rooms are tried deepest
first (most doors from the entrance: filling them first keeps the way to them open),
and in each room its free slots in order, at most ``tries_per_room`` of them through
the env's check (the exact check a step makes: region, collision, base path of the
carry disc from the start); the first feasible slot is taken. Three boxes make an
action, which is then executed by :meth:`~voot.envs.conveyor.env.ConveyorPackingEnv.step`.

Cost: one env check per slot tried (a collision check and a base plan, a few
milliseconds), about ``boxes x (1 + failures)`` checks; measured in
docs/environments.md ("Generated storage rooms").
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.envs.conveyor.env import OBJECTS_PER_ACTION, ConveyorPackingEnv
from voot.envs.conveyor.generated.layout import StorageLayout
from voot.envs.core.scene import object_footprint
from voot.envs.core.units import denormalize, normalize
from voot.envs.motion.planar import Box2D
from voot.envs.motion.rects import rect_inside

FloatArray = NDArray[np.float64]

#: Gap (metres) kept between a slot's box or carry disc and what is ahead of it.
SLOT_GAP = 0.03
#: Slots of one room tried through the env per box before the next room.
TRIES_PER_ROOM = 3


@dataclass(frozen=True)
class Witness:
    """The outcome of :func:`find_witness`.

    Attributes:
        solved: Every box was placed (the witness proves the layout solvable).
        actions: The executed actions, normalised (9 numbers each).
        placements: Each placed box's ``(x, y, theta)``, in belt order.
        rooms: The room each placed box went to.
        checks: Env checks made while searching (slots tried).
        total_return: Sum of the executed actions' rewards.
        reason: Why the search failed (``""`` if solved).
    """

    solved: bool
    actions: tuple[tuple[float, ...], ...]
    placements: tuple[tuple[float, float, float], ...]
    rooms: tuple[int, ...]
    checks: int
    total_return: float
    reason: str = ""

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict (floats round-trip exactly through ``json``)."""
        return {
            "solved": self.solved,
            "actions": [list(a) for a in self.actions],
            "placements": [list(p) for p in self.placements],
            "rooms": list(self.rooms),
            "checks": self.checks,
            "total_return": self.total_return,
            "reason": self.reason,
        }

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Witness:
        """The inverse of :meth:`to_json`."""
        return cls(
            solved=bool(data["solved"]),
            actions=tuple(tuple(float(v) for v in a) for a in data["actions"]),
            placements=tuple((float(x), float(y), float(t)) for x, y, t in data["placements"]),
            rooms=tuple(int(v) for v in data["rooms"]),
            checks=int(data["checks"]),
            total_return=float(data["total_return"]),
            reason=str(data["reason"]),
        )


@dataclass(frozen=True)
class _Reach:
    """How far box ``i`` and its carry disc reach around the box's centre, box frame."""

    ahead: float  # forward, past the box's centre (box or disc, plus the gap)
    back: float  # backward: the box's half depth
    side: float  # sideways: the disc (it holds the box)
    half_width: float  # the box's half width


def _reach(env: ConveyorPackingEnv, i: int) -> _Reach:
    obj = env.objects[i]
    pick = env.picks[i]
    hx, hy = (float(v) for v in obj.half)
    dx = float(pick.disc.offset[0]) - pick.rel[0]
    dy = float(pick.disc.offset[1]) - pick.rel[1]
    r = float(pick.disc.radius)
    return _Reach(
        ahead=max(hx, dx + r) + SLOT_GAP,
        back=hx,
        side=abs(dy) + r,
        half_width=hy,
    )


def room_slots(
    interior: tuple[float, float, float, float],
    facing: float,
    depth: float,
    pitch: float,
    margin: float,
) -> list[tuple[float, float, float]]:
    """A room's slots: ``(row_offset, lateral, facing)`` in order, rows back to front.

    ``row_offset`` is where the row's front line lies, measured back from the interior's
    back edge (the far side in ``facing``); ``lateral`` the slot's position across the
    room. A box is centred ``ahead`` behind its row's front line.
    """
    xmin, xmax, ymin, ymax = interior
    c, s = math.cos(facing), math.sin(facing)
    corners = [(xmin, ymin), (xmax, ymin), (xmax, ymax), (xmin, ymax)]
    along = [x * c + y * s for x, y in corners]
    across = [-x * s + y * c for x, y in corners]
    length = max(along) - min(along)
    lo, hi = min(across) + margin, max(across) - margin
    if hi < lo:
        return []
    n_cols = math.floor((hi - lo) / pitch + 1e-9) + 1
    # centre the columns in the room
    start = lo + 0.5 * ((hi - lo) - (n_cols - 1) * pitch)
    cols = [start + k * pitch for k in range(n_cols)]
    n_rows = max(0, math.floor(length / depth))
    return [(k * depth, lat, facing) for k in range(n_rows) for lat in cols]


def _slot_pose(
    interior: tuple[float, float, float, float],
    slot: tuple[float, float, float],
    ahead: float,
) -> tuple[float, float, float]:
    """World ``(x, y, theta)`` of a box at ``slot`` whose front reach is ``ahead``."""
    row, lateral, facing = slot
    xmin, xmax, ymin, ymax = interior
    c, s = math.cos(facing), math.sin(facing)
    back = max(x * c + y * s for x in (xmin, xmax) for y in (ymin, ymax))
    a = back - row - ahead
    return (a * c - lateral * s, a * s + lateral * c, facing % (2.0 * math.pi))


def find_witness(
    env: ConveyorPackingEnv, layout: StorageLayout, tries_per_room: int = TRIES_PER_ROOM
) -> Witness:
    """Pack every box of ``env`` (built on ``layout``) by the greedy rule; see the module.

    ``env`` is reset (seed 0) and stepped: use an env made for the search.
    """
    env.reset(seed=0)
    cfg = env.config
    n = env.n
    reach = [_reach(env, i) for i in range(n)]
    depth = max(r.ahead + r.back for r in reach) + SLOT_GAP
    pitch = max(r.side for r in reach) + max(r.half_width for r in reach) + SLOT_GAP
    margin = max(max(r.side, r.half_width) for r in reach) + SLOT_GAP
    order = sorted(range(len(layout.rooms)), key=lambda k: (-layout.rooms[k].depth, k))
    interiors = {k: layout.rooms[k].interior() for k in order}
    slots = {
        k: room_slots(interiors[k], layout.rooms[k].facing, depth, pitch, margin) for k in order
    }
    used: set[tuple[int, int]] = set()
    footprints: list[Box2D] = []
    actions: list[tuple[float, ...]] = []
    placements: list[tuple[float, float, float]] = []
    rooms: list[int] = []
    checks = 0
    total = 0.0
    ranges = cfg.place_ranges

    def outcome(reason: str) -> Witness:
        """The witness so far: solved iff no ``reason`` to fail."""
        placed = (tuple(actions), tuple(placements), tuple(rooms), checks, total)
        return Witness(not reason, *placed, reason)

    while env.task.placed < n:
        placed = env.task.placed
        m = min(OBJECTS_PER_ACTION, n - placed)
        action = np.zeros(3 * OBJECTS_PER_ACTION)
        moved: dict[int, tuple[float, float, float, float]] = {}
        lengths: list[float] = []
        paths: list[FloatArray] = []
        for k in range(m):
            i = placed + k
            chosen = None
            for room in order:
                tries = 0
                for s, slot in enumerate(slots[room]):
                    if tries >= tries_per_room:
                        break
                    if (room, s) in used:
                        continue
                    pose = _slot_pose(interiors[room], slot, reach[i].ahead)
                    a = normalize(pose, ranges)
                    xyt = denormalize(a, ranges)  # what the step will see
                    box = object_footprint(env.objects[i], *(float(v) for v in xyt))
                    if not rect_inside(box, interiors[room]) or any(
                        _overlap(box, f) for f in footprints
                    ):
                        continue
                    tries += 1
                    checks += 1
                    reason, _, _ = env._check_place(i, xyt, moved, lengths, paths)
                    if not reason:
                        chosen = (room, s, a, xyt, box)
                        break
                if chosen is not None:
                    break
            if chosen is None:
                return outcome(f"{env.objects[i].name} fits in no room")
            room, s, a, xyt, box = chosen
            used.add((room, s))
            footprints.append(box)
            action[3 * k : 3 * k + 3] = a
            placements.append((float(xyt[0]), float(xyt[1]), float(xyt[2])))
            rooms.append(room)
        _, reward, _, _, info = env.step(action)
        if not info["feasible"]:  # pragma: no cover - the step repeats the same checks
            return outcome(f"the step refused the packing: {info['reason']}")
        total += float(reward)
        actions.append(tuple(float(v) for v in action))
    return outcome("")


def _overlap(a: Box2D, b: Box2D) -> bool:
    """Do two footprints come closer than :data:`SLOT_GAP` (bounding circles, cheap)?"""
    ra = math.hypot(a.half_x, a.half_y)
    rb = math.hypot(b.half_x, b.half_y)
    if math.hypot(a.cx - b.cx, a.cy - b.cy) >= ra + rb + SLOT_GAP:
        return False
    # axis-aligned here (the slots face the axes): compare the extents
    ax, ay = _extent(a)
    bx, by = _extent(b)
    return abs(a.cx - b.cx) < ax + bx + SLOT_GAP and abs(a.cy - b.cy) < ay + by + SLOT_GAP


def _extent(b: Box2D) -> tuple[float, float]:
    c, s = abs(math.cos(b.yaw)), abs(math.sin(b.yaw))
    return b.half_x * c + b.half_y * s, b.half_x * s + b.half_y * c
