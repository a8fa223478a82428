"""Shared floor plans of the base-planning tests (a helper module, not a test module).

A kitchen-sized house (outer walls, a kitchen with a 1.0 m door, furniture and ten
movable objects), a wall with a door, random free poses, an independent (shapely) check
that a path keeps its distance from every obstacle and the array expression of a path's
length. Used by ``tests/envs/motion/test_base_planner.py`` and the tests of the modules it
is built from, and by ``docs/scripts/motion_planning_figure.py`` (the house it draws).
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from voot.envs.motion.planar import BasePath, Box2D, Pose2D, wrap_angle
from voot.envs.motion.planner import BasePlanner

WORKSPACE = (-2.0, 6.0, -4.0, 4.0)


def wall(x0: float, x1: float, y0: float, y1: float, name: str) -> Box2D:
    return Box2D.from_bounds(x0, x1, y0, y1, name)


def house_static(west_wall: float = -1.9) -> list[Box2D]:
    """A kitchen-sized floor plan: outer walls, a kitchen with a 1.0 m door, furniture.

    ``west_wall``: x of the west wall's inner face (the figure's thinner wall leaves room
    for its start pose).
    """
    return [
        wall(-2.0, west_wall, -4.0, 4.0, "wall_w"),
        wall(5.9, 6.0, -4.0, 4.0, "wall_e"),
        wall(-2.0, 6.0, 3.9, 4.0, "wall_n"),
        wall(-0.5, 6.0, -4.0, -3.9, "wall_s"),
        wall(2.75, 2.85, -1.0, 1.5, "kitchen_e_low"),  # door y in [1.5, 2.5]
        wall(2.75, 2.85, 2.5, 3.65, "kitchen_e_high"),
        wall(-2.0, 2.85, 3.55, 3.65, "kitchen_n"),
        wall(0.6, 2.85, -1.05, -0.95, "kitchen_s"),
        wall(2.85, 6.0, 0.45, 0.55, "rooms_divider"),
        wall(-1.5, 1.5, 2.97, 3.55, "counter_sink"),
        wall(2.2, 2.75, -0.5, 1.4, "counter_e"),
        wall(-1.9, -1.35, 2.4, 3.55, "fridge"),
        Box2D(1.3, 0.3, 0.5, 0.35, 0.0, "table"),
        wall(3.5, 5.0, 2.3, 3.9, "bed"),
        wall(4.8, 5.9, -2.2, -0.8, "sofa"),
        wall(3.0, 3.6, -3.9, -3.3, "shelf"),
        wall(1.0, 2.2, -3.9, -3.4, "cabinet"),
        Box2D(4.6, 1.5, 0.4, 0.4, 0.6, "armchair"),
        wall(-1.9, -1.4, -3.9, -3.5, "coat_rack"),
    ]


def house_movable() -> list[Box2D]:
    """The house's ten movable objects (chairs and boxes)."""
    return [
        Box2D(-1.2, -0.5, 0.22, 0.22, 0.1, "chair_a"),
        Box2D(-0.7, 0.4, 0.15, 0.15, 0.0, "box_a"),
        Box2D(-0.1, 1.3, 0.22, 0.22, 0.4, "chair_b"),
        Box2D(0.6, 2.0, 0.15, 0.15, 0.0, "box_b"),
        Box2D(-0.8, 2.0, 0.12, 0.12, 0.3, "box_c"),
        Box2D(0.9, 1.1, 0.22, 0.22, 0.0, "chair_c"),
        Box2D(1.8, -0.3, 0.22, 0.22, 0.2, "chair_d"),
        Box2D(0.2, -2.0, 0.15, 0.15, 0.0, "box_d"),
        Box2D(1.5, 1.9, 0.12, 0.12, 0.0, "box_e"),
        Box2D(-0.9, -2.6, 0.15, 0.15, 0.5, "box_f"),
    ]


def random_free_poses(
    planner: BasePlanner, radius: float, movable: list[Box2D], n: int, seed: int
) -> list[Pose2D]:
    rng = np.random.default_rng(seed)
    out: list[Pose2D] = []
    while len(out) < n:
        p = Pose2D(rng.uniform(-2, 6), rng.uniform(-4, 4), rng.uniform(-math.pi, math.pi))
        if planner.is_free(p, radius, movable):
            out.append(p)
    return out


def assert_path_clear(
    path: BasePath, radius: float, obstacles: list[Box2D], workspace=WORKSPACE
) -> None:
    """Independent check with shapely: every obstacle at least ``radius`` from the path."""
    xy = path.waypoints[:, :2]
    line = shapely.LineString(xy) if len(np.unique(xy, axis=0)) > 1 else shapely.Point(xy[0])
    for box in obstacles:
        d = line.distance(shapely.Polygon(box.corners()))
        assert d >= radius - 1e-7, f"path passes {d:.6f} from {box.name}, radius {radius}"
    xmin, xmax, ymin, ymax = workspace
    assert np.all(xy[:, 0] >= xmin + radius - 1e-9) and np.all(xy[:, 0] <= xmax - radius + 1e-9)
    assert np.all(xy[:, 1] >= ymin + radius - 1e-9) and np.all(xy[:, 1] <= ymax - radius + 1e-9)
    # dense samples against the inflated boxes too
    dense = path.interpolate(0.01)[:, :2]
    for box in obstacles:
        poly = shapely.Polygon(box.corners())
        dists = shapely.distance(shapely.points(dense), poly)
        assert np.all(dists >= radius - 1e-7), box.name


def door_scene(width: float) -> list[Box2D]:
    """A wall along x = 0 across the workspace with a door of ``width`` centred at y = 0."""
    return [
        wall(-0.1, 0.1, -5.0, -width / 2, "wall_low"),
        wall(-0.1, 0.1, width / 2, 5.0, "wall_high"),
    ]


def path_length_arrays(w: np.ndarray, rw: float) -> float:
    """:func:`~voot.envs.motion.planar.path_length`'s array expression (the float version
    must equal it bit for bit)."""
    diff = np.diff(w, axis=0)
    trans = np.hypot(diff[:, 0], diff[:, 1])
    rot = np.abs(wrap_angle(diff[:, 2]))
    return float(np.sum(trans) + rw * np.sum(rot))
