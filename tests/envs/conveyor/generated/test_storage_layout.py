"""Tests of voot.envs.conveyor.generated.layout: generated storage layouts (pure numpy)."""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest

from voot.envs.conveyor.generated.layout import (
    AREA_EAST,
    AREA_NORTH,
    BOX_KINDS,
    CRATE_SHARE,
    DIFFICULTIES,
    DOOR_JAMB,
    ENTRANCE,
    MIN_ROOM_SIDE,
    SHAPE_VARIANTS,
    StorageLayout,
    StorageLevel,
    difficulty_level,
    generate_storage_layout,
)

SEEDS = range(40)


def _connected(layout: StorageLayout) -> bool:
    seen, stack = {0}, [0]
    while stack:
        k = stack.pop()
        for d in layout.doors:
            if k in d.rooms:
                j = d.rooms[1] if d.rooms[0] == k else d.rooms[0]
                if j not in seen:
                    seen.add(j)
                    stack.append(j)
    return len(seen) == len(layout.rooms)


@pytest.mark.parametrize("difficulty", list(DIFFICULTIES))
def test_layouts_are_well_formed(difficulty: str) -> None:
    level = DIFFICULTIES[difficulty]
    for seed in SEEDS:
        lay = generate_storage_layout(seed, difficulty)
        x0, x1, y0, y1 = lay.area
        assert x1 == AREA_EAST and y1 == AREA_NORTH
        assert level.width[0] - 0.01 <= x1 - x0 <= level.width[1] + 0.01
        # the rooms tile the area: areas add up, each inside it, none too small
        assert sum(r.area for r in lay.rooms) == pytest.approx((x1 - x0) * (y1 - y0))
        for r in lay.rooms:
            assert x0 <= r.xmin < r.xmax <= x1 and y0 <= r.ymin < r.ymax <= y1
            assert min(r.xmax - r.xmin, r.ymax - r.ymin) >= MIN_ROOM_SIDE - 1e-9
        assert level.rooms[0] <= len(lay.rooms) <= level.rooms[1]
        # exactly one room lies behind the entrance, at depth 0, entered from the east
        roots = [r for r in lay.rooms if r.depth == 0]
        assert len(roots) == 1 and roots[0].entry == -1 and roots[0].facing == np.pi
        assert roots[0].xmax == AREA_EAST and roots[0].ymin < ENTRANCE[0]
        # doors: within the level's widths, on a wall both rooms share, jambs kept
        assert len(lay.doors) >= len(lay.rooms) - 1
        for d in lay.doors:
            assert level.door_width[0] - 0.011 <= d.width <= level.door_width[1] + 0.011
            a, b = (lay.rooms[k] for k in d.rooms)
            for r in (a, b):
                lo, hi = (r.ymin, r.ymax) if d.axis == "x" else (r.xmin, r.xmax)
                assert lo + DOOR_JAMB - 1e-9 <= d.lo and d.hi <= hi - DOOR_JAMB + 1e-9
                assert d.at in ((r.xmin, r.xmax) if d.axis == "x" else (r.ymin, r.ymax))
            # no wall blocks the opening
            cx, cy = d.center
            for w in lay.walls:
                assert not (w.xmin < cx < w.xmax and w.ymin < cy < w.ymax), (d, w)
        assert _connected(lay)
        # every room but the root is entered by a tree door one level up
        for k, r in enumerate(lay.rooms):
            if r.entry >= 0:
                door = lay.doors[r.entry]
                parent = door.rooms[0]
                assert door.rooms[1] == k and lay.rooms[parent].depth == r.depth - 1
        # boxes
        assert level.boxes[0] <= lay.n_boxes <= level.boxes[1]
        n_big = sum(b.big for b in lay.boxes)
        assert level.big_boxes[0] <= n_big <= level.big_boxes[1]
        for b in lay.boxes:
            xs, ys = (level.big_x, level.big_y) if b.big else (level.small_x, level.small_y)
            assert xs[0] - 1e-3 <= b.size[0] <= xs[1] + 1e-3
            assert ys[0] - 1e-3 <= b.size[1] <= ys[1] + 1e-3
            assert level.height[0] - 1e-3 <= b.size[2] <= level.height[1] + 1e-3
            assert b.kind in BOX_KINDS and 0 <= b.variant < SHAPE_VARIANTS
        assert lay.loading_region == (x0, -0.5, y0, y1)
        assert lay.workspace == (x0, 1.5, y0, y1)


def test_boxes_and_crates_of_every_variant_are_drawn() -> None:
    boxes = [b for s in SEEDS for b in generate_storage_layout(s, "hard").boxes]
    crates = sum(b.kind == "crate" for b in boxes) / len(boxes)
    assert abs(crates - CRATE_SHARE) < 0.1
    assert {b.variant for b in boxes} == set(range(SHAPE_VARIANTS))


def test_the_entrance_stays_open() -> None:
    for difficulty in DIFFICULTIES:
        for seed in SEEDS:
            lay = generate_storage_layout(seed, difficulty)
            for w in lay.walls:
                # nothing stands in the entrance's gap of the east wall
                if w.xmin <= AREA_EAST + 0.05 <= w.xmax:
                    assert w.ymax <= ENTRANCE[0] + 1e-9 or w.ymin >= ENTRANCE[1] - 1e-9, w


def test_deterministic_and_independent_per_argument() -> None:
    a = generate_storage_layout(7, "medium")
    assert a == generate_storage_layout(7, "medium")
    others = [
        generate_storage_layout(8, "medium"),
        generate_storage_layout(7, "medium", attempt=1),
        generate_storage_layout(7, "hard"),
    ]
    for b in others:
        assert b != a and b.boxes != a.boxes and b.area != a.area
    layouts = {generate_storage_layout(s, "easy") for s in range(30)}
    assert len(layouts) == 30  # hashable, and all distinct


def test_the_same_layout_in_another_process() -> None:
    code = (
        "from voot.envs.conveyor.generated.layout import generate_storage_layout\n"
        "print(repr(generate_storage_layout(12, 'hard', 2)))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=60
    )
    assert out.stdout.strip() == repr(generate_storage_layout(12, "hard", 2))


def test_the_module_loads_no_mujoco() -> None:
    code = (
        "import json, sys\n"
        "import voot.envs.conveyor.generated.layout\n"
        "print(json.dumps(sorted(sys.modules)))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=60
    )
    modules = json.loads(out.stdout.strip().splitlines()[-1])
    assert not [m for m in modules if m == "mujoco" or m.startswith("mujoco.")]


def test_harder_levels_are_harder_on_average() -> None:
    stats = {}
    for difficulty in DIFFICULTIES:
        lays = [generate_storage_layout(s, difficulty) for s in SEEDS]
        stats[difficulty] = (
            np.mean([lay.n_boxes for lay in lays]),
            np.mean([np.mean([d.width for d in lay.doors]) for lay in lays]),
            np.mean([np.mean([r.area for r in lay.rooms]) for lay in lays]),
            np.mean([sum(b.size[0] * b.size[1] for b in lay.boxes) for lay in lays]),
        )
    easy, medium, hard = (stats[d] for d in ("easy", "medium", "hard"))
    assert easy[0] < medium[0] < hard[0]  # more boxes
    assert easy[1] > medium[1] > hard[1]  # narrower doors
    assert easy[2] > medium[2] > hard[2]  # smaller rooms
    assert easy[3] < medium[3] < hard[3]  # more floor to cover


def test_bad_arguments_name_the_valid_choices() -> None:
    with pytest.raises(ValueError, match="easy, medium, hard"):
        generate_storage_layout(0, "extreme")
    with pytest.raises(ValueError, match="easy, medium, hard"):
        difficulty_level(3)  # type: ignore[arg-type]
    for seed in (-1, 1.5, True, "3"):
        with pytest.raises(ValueError, match="layout_seed"):
            generate_storage_layout(seed, "easy")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="attempt"):
        generate_storage_layout(0, "easy", attempt=-1)
    level = DIFFICULTIES["easy"]
    with pytest.raises(ValueError, match="boxes"):
        replace(level, boxes=(5, 21))
    with pytest.raises(ValueError, match="door_width"):
        replace(level, door_width=(2.0, 1.0))
    with pytest.raises(ValueError, match="extra_door"):
        replace(level, extra_door=1.5)
    assert isinstance(level, StorageLevel)
