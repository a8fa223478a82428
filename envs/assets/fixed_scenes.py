"""The paper's two scenes, ``kitchen.xml`` and ``conveyor.xml``, as MJCF text.

``models/generate_scenes.py`` writes them into ``voot.models`` (run once; the output is
committed). Every number of the two floor plans lives here; the environments read the
geometry back from the compiled MuJoCo model (geom positions, sizes and orientations), so
there is a single source of truth for the scenes. Nothing is downloaded: the robot is
``robot.xml`` (hand written, included by both scenes) and every other body is built from
primitives with the writers of :mod:`.mjcf` (collision classes, materials and the other
shared conventions are there).

Geometry (metres), after the original problems (see the reference page):

* Kitchen house: the house interior is x in [-2, 6], y in [-4, 4]. The kitchen
  (x in [-2, 2.8], y in [-1, 3]) has counters along the north and west walls with the
  sink at (0, 3.65), a fridge and a side table; south of it is a hall. A wall at
  x = 2.8 with a 0.9 m door at y = 2 (the original's 1.0 m door was sized for a PR2 with
  its arms out; ours is sized for the base-motion disc, see ``voot.envs.robot.model``) leads to
  two large rooms (x in [2.8, 6]) split by a wall at y = 0. Seven obstacles (boxes and
  chairs) stand on the straight path from the start (-1.5, -1.5) to the sink pose
  (0, 2.5), as in the original problem; two more chairs stand by the east wall.
* Storage rooms: the robot starts at (0, 1.05) facing the belt (x >= 1.5, y in
  [0.55, 1.55]) that carries 20 boxes. West of the start, a 2.6 m wide entrance at
  x = -0.7 opens into the small first room (x in [-4, -0.7], y in [-1, 3]); a 1.62 m
  door in its south wall leads to the larger rooms (x in [-4, -0.7], y in [-7.5, -1]
  and x in [-7.4, -4], y in [-7.5, 3], joined by a 3.5 m opening). Box sizes follow the
  original's generator: the first two are big (x size U[0.6, 0.7], y size 0.7), the
  others small (x size U[0.4, 0.5], y size U[0.5, 0.6]); heights U[0.7, 1.0].
"""

from __future__ import annotations

import math

import numpy as np

from voot.envs.assets.mjcf import (
    CONVEYOR_START,
    CONVEYOR_WALL_HEIGHT,
    GOAL_RGBA,
    KITCHEN_GOAL,
    KITCHEN_START,
    KITCHEN_WALL_HEIGHT,
    START_RGBA,
    WALL_THICKNESS,
    Rect,
    belt_pose,
    belt_xml,
    box_object,
    cameras,
    chair_object,
    floor_plane,
    header,
    marker,
    sink,
    sun_light,
    table,
    wall,
)

__all__ = [
    "CONVEYOR_N_BOXES",
    "CONVEYOR_SIZE_SEED",
    "FIXED_SCENES",
    "conveyor_box_sizes",
    "conveyor_xml",
    "kitchen_xml",
]

#: Seed of the box sizes of the conveyor scene (fixed: the XML is committed).
CONVEYOR_SIZE_SEED = 2020
#: Number of boxes on the belt.
CONVEYOR_N_BOXES = 20


# ----- kitchen house -----------------------------------------------------------------------
def _along_path(s: float, d: float) -> tuple[float, float]:
    """Point ``s`` metres along the start->goal segment, ``d`` metres to its left."""
    sx, sy = KITCHEN_START[0], KITCHEN_START[1]
    gx, gy = KITCHEN_GOAL[0], KITCHEN_GOAL[1]
    length = math.hypot(gx - sx, gy - sy)
    ux, uy = (gx - sx) / length, (gy - sy) / length
    return sx + s * ux - d * uy, sy + s * uy + d * ux


def kitchen_xml() -> str:
    """The kitchen house scene as an MJCF string."""
    t = WALL_THICKNESS  # outside the interior bounds
    out = [header("voot_kitchen", 12.0, (2.0, 0.0, 0.5))]
    out.append("  <worldbody>\n")
    out.append(sun_light(2, 0, 9))
    out.append(floor_plane(2, 0, 4.6, 4.6))
    out.append(
        '    <geom name="kitchen_floor" class="decor" type="box" size="2.4 2.0 0.001" pos="0.4 1 0.001" material="tile"/>\n'
    )
    out.append(
        cameras(
            top_center=(2.0, 0.0),
            top_height=12.0,
            top_extent=8.6,
            persp_pos=(-3.9, -7.0, 6.2),
            persp_target=(1.6, 0.3, 0.0),
            persp_fovy=47.0,
        )
    )
    # outer walls: interior x in [-2, 6], y in [-4, 4]
    walls = [
        ("wall_west", -2 - t, -2, -4 - t, 4 + t),
        ("wall_east", 6, 6 + t, -4 - t, 4 + t),
        ("wall_south", -2, 6, -4 - t, -4),
        ("wall_north", -2, 6, 4, 4 + t),
        # the wall between the kitchen and the two large rooms, door y in [1.55, 2.45]
        ("wall_rooms_s", 2.8, 2.8 + t, -4, 1.55),
        ("wall_rooms_n", 2.8, 2.8 + t, 2.45, 4),
        # the wall between the two large rooms, door x in [4.0, 4.9]
        ("wall_between_w", 2.8 + t, 4.0, -0.05, 0.05),
        ("wall_between_e", 4.9, 6, -0.05, 0.05),
        # a partial wall between the hall and the kitchen's east part
        ("wall_hall", 1.2, 2.8, -1.05, -0.95),
    ]
    for name, x0, x1, y0, y1 in walls:
        out.append(wall(name, x0, x1, y0, y1, KITCHEN_WALL_HEIGHT))
    # kitchen furniture
    out.append(Rect(-2, 2.0, 3.35, 4.0, 0.86).line("counter_north", "counter"))
    out.append(Rect(-2, -1.35, 1.0, 3.35, 0.86).line("counter_west", "counter"))
    out.append(Rect(2.0, 2.8, 3.3, 4.0, 1.8).line("fridge", "steel"))
    out.append(
        '    <geom name="counter_north_top" class="decor" type="box" size="2.0 0.34 0.02" pos="0 3.67 0.88" material="counter_top"/>\n'
    )
    out.append(
        '    <geom name="counter_west_top" class="decor" type="box" size="0.34 1.19 0.02" pos="-1.67 2.16 0.88" material="counter_top"/>\n'
    )
    out.append(sink(0, 3.66, 0.9))
    out.append(
        '    <geom name="sink_spout" class="decor" type="capsule" fromto="0 3.92 1.14 0 3.78 1.14" size="0.018" material="steel"/>\n'
    )
    out.append(
        '    <geom name="stove" class="decor" type="box" size="0.28 0.3 0.005" pos="-1.67 2.6 0.902" material="belt"/>\n'
    )
    out.append(
        '    <geom name="fridge_handle" class="decor" type="box" size="0.01 0.01 0.3" pos="2.1 3.28 1.1" material="rail"/>\n'
    )
    out.append(table("side_table", Rect(2.15, 2.8, 1.2, 2.4, 0.75)))
    # hall and rooms furniture
    out.append(Rect(1.3, 2.8, -4.0, -3.25, 0.75).line("sofa", "fabric"))
    out.append(Rect(4.2, 6.0, 2.2, 4.0, 0.5).line("bed", "bed"))
    out.append(Rect(2.95, 3.35, 2.8, 3.9, 1.6).line("shelf_n", "dark_wood"))
    out.append(table("desk", Rect(4.8, 6.0, -4.0, -3.2, 0.75)))
    out.append(Rect(2.95, 3.35, -3.8, -1.5, 1.8).line("bookcase", "dark_wood"))
    out.append(Rect(5.3, 5.9, -1.0, -0.1, 0.45).line("armchair", "fabric"))
    # start and goal markers (decoration)
    out.append(marker("start_marker", KITCHEN_START[0], KITCHEN_START[1], START_RGBA))
    out.append(marker("goal_marker", KITCHEN_GOAL[0], KITCHEN_GOAL[1], GOAL_RGBA))
    # obstacles on the path (s along the path from the start, d to its left)
    on_path = [
        ("obj_box1", "box", 0.70, -0.40, 0.3, (0.40, 0.40, 0.60)),
        ("obj_chair1", "chair", 1.30, 0.05, 2.2, None),
        ("obj_box2", "box", 1.90, -0.50, -0.4, (0.50, 0.36, 0.45)),
        ("obj_chair2", "chair", 2.50, 0.00, -2.6, None),
        ("obj_box3", "box", 3.10, -0.50, 0.9, (0.32, 0.32, 0.85)),
        ("obj_box4", "box", 3.65, 0.05, 0.2, (0.40, 0.40, 0.50)),
        ("obj_chair3", "chair", 4.25, -0.40, 1.3, None),
    ]
    for name, kind, s, d, yaw, size in on_path:
        x, y = _along_path(s, d)
        if kind == "box":
            assert size is not None
            out.append(box_object(name, x, y, yaw, size, "cardboard"))
        else:
            out.append(chair_object(name, x, y, yaw))
    # other movable objects, off the path
    out.append(chair_object("obj_chair4", 2.5, -0.45, math.pi))
    out.append(chair_object("obj_chair5", 2.5, 0.25, math.pi))
    out.append("  </worldbody>\n</mujoco>\n")
    return "".join(out)


# ----- storage rooms and conveyor belt -------------------------------------------------------
def conveyor_box_sizes(
    n: int = CONVEYOR_N_BOXES, seed: int = CONVEYOR_SIZE_SEED
) -> list[tuple[float, float, float]]:
    """Box sizes (x, y, z) in metres, after the original's ``create_objects``.

    The first two are big: x ~ U[0.6, 0.7], y = 0.7; the others small: x ~ U[0.4, 0.5],
    y ~ U[0.5, 0.6]; heights ~ U[0.7, 1.0]. Rounded to millimetres.
    """
    rng = np.random.default_rng(seed)
    sizes = []
    for i in range(n):
        if i < 2:
            sx, sy = rng.uniform(0.6, 0.7), 0.7
        else:
            sx, sy = rng.uniform(0.4, 0.5), rng.uniform(0.5, 0.6)
        sz = rng.uniform(0.7, 1.0)
        sizes.append((round(sx, 3), round(sy, 3), round(sz, 3)))
    return sizes


def conveyor_xml() -> str:
    """The storage rooms and conveyor belt scene as an MJCF string."""
    t = WALL_THICKNESS
    out = [header("voot_conveyor", 16.0, (-1.5, -2.2, 0.5))]
    out.append("  <worldbody>\n")
    out.append(sun_light(-2, -2, 10))
    out.append(floor_plane(8.5, -2.2, 16.5, 5.6))
    out.append(
        cameras(
            top_center=(-2.0, -2.25),
            top_height=15.0,
            top_extent=11.0,
            persp_pos=(5.5, -11.5, 10.5),
            persp_target=(-2.2, -1.9, 0.0),
            persp_fovy=46.0,
        )
    )
    walls = [
        # rooms: x in [-7.4, -0.7], y in [-7.5, 3]
        ("wall_west", -7.4 - t, -7.4, -7.5 - t, 3 + t),
        ("wall_south", -7.4, -0.7 + t, -7.5 - t, -7.5),
        ("wall_north", -7.4, 1.5, 3.0, 3.0 + t),
        # east wall of the rooms with the 2.6 m entrance y in [0, 2.6] into the first room
        ("wall_east_s", -0.7, -0.7 + t, -7.5, 0.0),
        ("wall_east_n", -0.7, -0.7 + t, 2.6, 3.0),
        # first room's south wall, door x in [-2.98, -1.36] (1.62 m)
        ("wall_room1_s_w", -4.0, -2.98, -1.05, -0.95),
        ("wall_room1_s_e", -1.36, -0.7, -1.05, -0.95),
        # first room's west wall (no door) and the wall between the larger rooms with a
        # 3.5 m opening y in [-4.5, -1.05]
        ("wall_room1_w", -4.05, -3.95, -1.05, 3.0),
        ("wall_rooms_mid", -4.05, -3.95, -7.5, -4.5),
        # the hall between the rooms and the belt: south wall
        ("wall_hall_s", -0.6, 1.5, -1.1, -1.0),
    ]
    for name, x0, x1, y0, y1 in walls:
        out.append(wall(name, x0, x1, y0, y1, CONVEYOR_WALL_HEIGHT))
    out.append(belt_xml())
    # a few static shelves along the walls of the larger rooms
    out.append(Rect(-7.4, -6.9, -7.5, -5.0, 1.8).line("shelf_sw", "dark_wood"))
    out.append(Rect(-2.5, -0.7, -7.5, -7.0, 1.8).line("shelf_s", "dark_wood"))
    out.append(marker("start_marker", CONVEYOR_START[0], CONVEYOR_START[1], START_RGBA))
    for i, size in enumerate(conveyor_box_sizes()):
        material = "big_box" if i < 2 else "cardboard"
        x, y, z, yaw = belt_pose(i)
        out.append(box_object(f"obj_{i:02d}", x, y, yaw, size, material, z=z))
    out.append("  </worldbody>\n</mujoco>\n")
    return "".join(out)


#: The committed scenes: file name (in ``voot.models``) -> its writer.
FIXED_SCENES = {"kitchen.xml": kitchen_xml, "conveyor.xml": conveyor_xml}
