"""The authors' storage rooms: ``models/conveyor.xml`` with the original's walls.

``ConveyorConfig(rooms="authors")`` loads this scene instead of voot's. It is voot's
conveyor scene (belt, boxes, robot, cameras) with its walls and shelves replaced by the
walls of the authors' ``problem_environments/convbelt_env_diffcult_shapes_two_rooms.xml``
(beomjoonkim/voot, OpenRAVE box extents are half sizes), at their positions and
thicknesses:

* the east wall at x = -0.7 (8 cm thick) with the **1.5 m entrance** y in [0.1, 1.6];
* the first room x in [-4, -0.7], y in [-0.5, 2.5] (**3.3 x 3.0 m**), its south wall
  x in [-2.295, -0.645] leaving a **1.7 m door** (1.695 m between the faces) against
  its west wall (x = -4);
* the wall x = -4 between the rooms, y in [-5.5, 2.5], leaving the **2.0 m south-west
  opening** y in [-7.5, -5.5];
* the outer walls y = 2.5 (north), y = -7.5 (south), x = -7.4 (west).

Every wall is :data:`~voot.envs.assets.mjcf.CONVEYOR_WALL_HEIGHT` tall (the authors'
north and south walls were 0.4 m: lower than the arm, but the base planner's footprints
ignore heights, so they are full walls there too). The belt (a floor-level plate in the
original) and the boxes are voot's.
"""

from __future__ import annotations

import mujoco

from voot.envs.assets.fixed_scenes import conveyor_xml
from voot.envs.assets.meshes import compile_scene
from voot.envs.assets.mjcf import CONVEYOR_WALL_HEIGHT, wall

__all__ = ["AUTHORS_WALLS", "authors_rooms_model", "authors_rooms_xml"]

#: The authors' walls: name, x0, x1, y0, y1 (metres).
AUTHORS_WALLS: tuple[tuple[str, float, float, float, float], ...] = (
    ("wall_room1_s", -2.295, -0.645, -0.51, -0.49),
    ("wall_north", -7.405, -0.155, 2.49, 2.51),
    ("wall_south", -7.405, -0.155, -7.51, -7.49),
    ("wall_west", -7.41, -7.39, -7.5, 2.5),
    ("wall_rooms_mid", -4.01, -3.99, -5.5, 2.5),
    ("wall_east_n", -0.74, -0.66, 1.6, 2.4),
    ("wall_east_s", -0.74, -0.66, -7.3, 0.1),
)


def authors_rooms_xml() -> str:
    """The scene's MJCF text: voot's conveyor scene, its walls and shelves replaced."""
    lines = conveyor_xml().splitlines(keepends=True)
    kept = [ln for ln in lines if 'name="wall_' not in ln and 'name="shelf_' not in ln]
    at = next(k for k, ln in enumerate(kept) if 'name="belt_frame"' in ln)
    walls = [
        wall(name, x0, x1, y0, y1, CONVEYOR_WALL_HEIGHT) for name, x0, x1, y0, y1 in AUTHORS_WALLS
    ]
    return "".join(kept[:at] + walls + kept[at:])


def authors_rooms_model() -> mujoco.MjModel:
    """The compiled scene (with ``robot.xml``)."""
    return compile_scene(authors_rooms_xml(), ())
