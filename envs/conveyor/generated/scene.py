"""A generated storage layout as a MuJoCo scene: the MJCF text and the compiled model.

:func:`storage_xml` writes the scene of a :class:`~voot.envs.conveyor.generated.layout.StorageLayout`
with the same building blocks as the fixed ``conveyor.xml`` (:mod:`voot.envs.assets.mjcf`:
the header with its materials and collision classes,
walls, the belt, cameras), so a generated scene follows every convention the
environments read back (:mod:`voot.envs.core.scene`): static walls of class ``scene``, boxes
as bodies ``obj_NN`` with a free joint, queued on the belt in belt order. The boxes are
trimesh meshes (:mod:`voot.envs.assets.meshes`: closed boxes and open-top crates of the
layout's sizes and variants, convex collision parts, mass and inertia from the mesh);
their geoms' bounding boxes span exactly the box size, so their footprint rectangles
(what the checks read) are the sizes'. :func:`compile_storage_scene` compiles the scene
with ``robot.xml`` and the mesh files handed to MuJoCo in memory (no scene file is
written; the meshes are cached by :mod:`voot.envs.assets.meshes`).

Decoration (class ``decor``, never collides) marks the doors and the rooms' floors, so a
top-down image shows the layout.
"""

from __future__ import annotations

import mujoco

from voot.envs.assets.meshes import ShapeSpec, compile_scene, object_body_xml, shape_assets_xml
from voot.envs.assets.mjcf import (
    CONVEYOR_START,
    CONVEYOR_WALL_HEIGHT,
    START_RGBA,
    belt_pose,
    belt_xml,
    cameras,
    floor_plane,
    header,
    marker,
    sun_light,
    vec,
    wall,
)
from voot.envs.conveyor.generated.layout import StorageLayout

#: East edge of the top-down camera's view (past the start, over the belt's head).
_VIEW_EAST = 2.6
#: Aspect ratio (width / height) the top-down view is framed for (the default 640 x 480).
_ASPECT = 4.0 / 3.0
#: Floor tints of the rooms (decoration), cycled.
_ROOM_TINTS = (
    "0.86 0.80 0.70 1",
    "0.74 0.82 0.86 1",
    "0.80 0.86 0.74 1",
    "0.88 0.76 0.80 1",
    "0.82 0.80 0.88 1",
)


def box_shapes(layout: StorageLayout) -> list[ShapeSpec]:
    """The mesh spec of every box, in belt order."""
    return [ShapeSpec(b.kind, b.size, b.variant) for b in layout.boxes]


def box_material(big: bool, kind: str) -> str:
    """The material of a box: big ones red, crates blue-grey, the others cardboard."""
    return "big_box" if big else ("clutter" if kind == "crate" else "cardboard")


def storage_xml(layout: StorageLayout) -> str:
    """The MJCF text of ``layout``'s scene (robot included by ``robot.xml``; the boxes'
    mesh files are named in an ``<asset>`` section, see :func:`compile_storage_scene`)."""
    x0, _x1, y0, y1 = layout.area
    view = (x0 - 0.4, _VIEW_EAST, y0 - 0.4, y1 + 0.4)
    cx, cy = 0.5 * (view[0] + view[1]), 0.5 * (view[2] + view[3])
    fovy = max(view[3] - view[2], (view[1] - view[0]) / _ASPECT)
    name = f"voot_storage_{layout.difficulty}_{layout.layout_seed}_{layout.attempt}"
    shapes = box_shapes(layout)
    out = [header(name, max(fovy, 12.0) + 4.0, (cx, cy, 0.5))]
    out.append(f"  <asset>\n{shape_assets_xml(shapes)}  </asset>\n")
    out.append("  <worldbody>\n")
    out.append(sun_light(cx, cy, 10))
    # the floor reaches the belt's far end like conveyor.xml's (x up to 25)
    fx0, fx1 = x0 - 1.0, 25.0
    fy0, fy1 = y0 - 1.0, y1 + 1.5
    out.append(
        floor_plane(0.5 * (fx0 + fx1), 0.5 * (fy0 + fy1), 0.5 * (fx1 - fx0), 0.5 * (fy1 - fy0))
    )
    target = (cx - 0.6, cy, 0.0)
    out.append(
        cameras(
            top_center=(cx, cy),
            top_height=15.0,
            top_extent=fovy,
            persp_pos=(target[0] + 7.5, target[1] - 9.6, 10.5),
            persp_target=target,
            persp_fovy=48.0,
        )
    )
    for k, room in enumerate(layout.rooms):
        rx0, rx1, ry0, ry1 = room.interior()
        out.append(
            f'    <geom name="room_{k}_floor" class="decor" type="box" size="{vec(0.5 * (rx1 - rx0), 0.5 * (ry1 - ry0), 0.002)}" pos="{vec(0.5 * (rx0 + rx1), 0.5 * (ry0 + ry1), 0.004)}" rgba="{_ROOM_TINTS[k % len(_ROOM_TINTS)]}"/>\n'
        )
    for w in layout.walls:
        out.append(wall(w.name, w.xmin, w.xmax, w.ymin, w.ymax, CONVEYOR_WALL_HEIGHT))
    for k, door in enumerate(layout.doors):
        dx, dy = door.center
        hx, hy = (0.06, 0.5 * door.width) if door.axis == "x" else (0.5 * door.width, 0.06)
        out.append(
            f'    <geom name="door_{k}" class="decor" type="box" size="{vec(hx, hy, 0.002)}" pos="{vec(dx, dy, 0.003)}" rgba="0.2 0.7 0.3 1"/>\n'
        )
    out.append(belt_xml())
    out.append(marker("start_marker", CONVEYOR_START[0], CONVEYOR_START[1], START_RGBA))
    for i, (box, shape) in enumerate(zip(layout.boxes, shapes, strict=True)):
        out.append(
            object_body_xml(f"obj_{i:02d}", shape, belt_pose(i), box_material(box.big, box.kind))
        )
    out.append("  </worldbody>\n</mujoco>\n")
    return "".join(out)


def compile_storage_scene(layout: StorageLayout, xml: str | None = None) -> mujoco.MjModel:
    """Compile ``layout``'s scene (``xml``, default :func:`storage_xml`) into a MuJoCo
    model, with ``robot.xml`` and the boxes' mesh files as in-memory assets."""
    text = storage_xml(layout) if xml is None else xml
    return compile_scene(text, box_shapes(layout))
