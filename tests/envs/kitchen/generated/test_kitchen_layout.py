"""Tests of the generated kitchens' floor plans (voot.envs.kitchen.generated.layout)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from voot.envs.kitchen.generated.layout import (
    CATALOGUE,
    DIFFICULTIES,
    GENERATOR_VERSION,
    SIZE_CLASSES,
    KitchenLayout,
    KitchenLevel,
    LayoutError,
    generate_kitchen_layout,
    layout_rng,
)
from voot.envs.motion.planner import Box2D
from voot.envs.motion.swept_volume import obstacles_on_path
from voot.envs.robot.model import ROBOT_RADIUS

LEVELS = tuple(DIFFICULTIES)


def first_layout(seed: int, difficulty: str) -> KitchenLayout:
    """The first attempt of ``seed`` that draws a layout (the family may reject it later)."""
    for attempt in range(40):
        try:
            return generate_kitchen_layout(seed, difficulty, attempt)
        except LayoutError:
            continue
    raise AssertionError(f"no layout for {seed}, {difficulty}")


def test_the_same_seed_gives_the_same_layout_and_seeds_differ() -> None:
    for level in LEVELS:
        a, b = first_layout(3, level), first_layout(3, level)
        assert a == b
        assert first_layout(4, level) != a
    # one seed is an independent stream per level and per attempt
    assert first_layout(5, "easy").start != first_layout(5, "medium").start
    r0 = layout_rng(5, "easy", 0).uniform(size=4)
    r1 = layout_rng(5, "easy", 1).uniform(size=4)
    assert not np.array_equal(r0, r1)
    assert np.array_equal(r0, layout_rng(5, "easy", 0).uniform(size=4))
    assert GENERATOR_VERSION >= 1


@pytest.mark.parametrize("level", LEVELS)
def test_each_level_draws_within_its_ranges(level: str) -> None:
    spec = DIFFICULTIES[level]
    for seed in range(8):
        layout = first_layout(seed, level)
        wk = layout.kitchen_width
        _, x1, y0, y1 = layout.house
        assert spec.kitchen_width[0] <= wk <= spec.kitchen_width[1]
        assert spec.depth[0] <= y1 - y0 <= spec.depth[1]
        assert layout.forbidden == (wk, x1, y0, y1)
        assert layout.shape == spec.shape
        names = {b.name for b in layout.blocks}
        assert ("island" in names) == (spec.shape == "island")
        assert ("peninsula" in names) == (spec.shape == "passage")
        if spec.shape == "passage":
            peninsula = next(b for b in layout.blocks if b.name == "peninsula")
            assert spec.passage[0] <= peninsula.rect[0] <= spec.passage[1]
            assert peninsula.rect[1] == wk
        on = [o for o in layout.objects if o.on_path]
        off = [o for o in layout.objects if not o.on_path]
        assert spec.on_path[0] <= len(on) <= spec.on_path[1]
        assert spec.clutter[0] <= len(off) <= spec.clutter[1]
        items = {(i.kind, i.size, i.variant) for i in spec.items()}
        for o in layout.objects:
            assert (o.kind, o.size, o.variant) in items
            assert o.kind in spec.kinds


@pytest.mark.parametrize("level", LEVELS)
def test_objects_stand_apart_in_the_kitchen_on_or_off_the_path(level: str) -> None:
    for seed in range(6):
        layout = first_layout(seed, level)
        path = np.array(layout.path)
        assert np.allclose(path[0], layout.start[:2]) and np.allclose(path[-1], layout.goal[:2])
        objs = layout.objects
        for i, a in enumerate(objs):
            x, y, _ = a.pose
            assert a.radius < x < layout.kitchen_width - a.radius
            assert a.radius < y < layout.house[3] - a.radius
            for b in objs[i + 1 :]:
                assert math.dist(a.pose[:2], b.pose[:2]) > a.radius + b.radius
        boxes = [
            Box2D(o.pose[0], o.pose[1], o.size[0] / 2, o.size[1] / 2, o.pose[2], o.name)
            for o in objs
        ]
        hit = set(obstacles_on_path(path, ROBOT_RADIUS, boxes))
        assert hit == {o.name for o in objs if o.on_path}


def test_the_catalogue_is_mesh_shapes_and_each_level_draws_from_part_of_it() -> None:
    from voot.envs.assets.meshes import SHAPE_KINDS

    assert all(i.kind in SHAPE_KINDS and i.size_class in SIZE_CLASSES for i in CATALOGUE)
    assert len({(i.kind, i.size, i.variant) for i in CATALOGUE}) == len(CATALOGUE)
    easy, medium, hard = (set(DIFFICULTIES[k].items()) for k in ("easy", "medium", "hard"))
    assert easy <= medium and len(hard) > len(easy)
    # the levels grow: the mean footprint of what they draw
    area = [np.mean([i.size[0] * i.size[1] for i in DIFFICULTIES[k].items()]) for k in DIFFICULTIES]
    assert area == sorted(area)
    # a seed's objects differ in kind across seeds (not one shape everywhere)
    kinds = {o.kind for s in range(6) for o in first_layout(s, "hard").objects}
    assert len(kinds) >= 4


def test_the_goal_faces_the_sink_on_the_north_counter() -> None:
    layout = first_layout(0, "easy")
    counter = next(b for b in layout.blocks if b.name == "counter_north")
    assert layout.goal[2] == pytest.approx(math.pi / 2)
    assert layout.goal[0] == layout.sink[0]
    assert counter.rect[2] - layout.goal[1] == pytest.approx(0.85)


def test_an_attempt_without_room_raises_layout_error() -> None:
    # hard, seed 0: the first attempts leave no room for every obstacle on the path
    with pytest.raises(LayoutError, match="no room"):
        generate_kitchen_layout(0, "hard", 0)


def test_bad_arguments_name_the_valid_choices() -> None:
    with pytest.raises(ValueError, match="valid levels are: easy, medium, hard"):
        generate_kitchen_layout(0, "brutal")
    with pytest.raises(ValueError, match="layout_seed must be"):
        generate_kitchen_layout(-1, "easy")
    with pytest.raises(ValueError, match="attempt must be"):
        generate_kitchen_layout(0, "easy", 1.5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="shape"):
        replace(DIFFICULTIES["easy"], shape="spiral")
    with pytest.raises(ValueError, match="kinds"):
        replace(DIFFICULTIES["easy"], kinds=("chair",))
    with pytest.raises(ValueError, match="no catalogue object"):
        replace(DIFFICULTIES["easy"], kinds=("jug",), sizes=("large",))
    with pytest.raises(ValueError, match="on_path"):
        KitchenLevel(**{**DIFFICULTIES["easy"].__dict__, "on_path": (0, 2)})
