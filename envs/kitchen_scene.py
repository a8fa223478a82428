"""A generated kitchen as a MuJoCo scene: :class:`~voot.envs.kitchen_layout.KitchenLayout`
to MJCF, and the MJCF compiled.

:func:`kitchen_layout_xml` writes the layout with the v1 scene's building blocks
(:mod:`voot.models.generate_scenes`: its header with materials and collision classes,
walls, blocks, movable boxes and chairs, cameras), so a generated kitchen looks and
collides like the paper's one: static blocks are class ``scene``, the movable objects
bodies ``obj_*`` with a free joint of class ``object``, the sink, stove and markers
decoration. :func:`compile_kitchen` compiles the string with ``robot.xml`` (which the
header includes) from ``voot.models`` in MuJoCo's in-memory assets: no file is written.

The MJCF is a pure function of the layout (numbers written with 4 decimals), so the same
layout gives the same bytes in every process: :func:`scene_digest` is its SHA-256.
"""

from __future__ import annotations

import hashlib
from functools import cache
from importlib import resources

import mujoco

from voot.envs.kitchen_layout import Block, KitchenLayout, ObjectSpec
from voot.models.generate_scenes import (
    Rect,
    _box_object,
    _cameras,
    _chair_object,
    _header,
    _v,
)

__all__ = ["compile_kitchen", "kitchen_layout_xml", "robot_xml", "scene_digest"]

#: The scene material of each block kind.
BLOCK_MATERIALS = {
    "wall": "wall",
    "counter": "counter",
    "fridge": "steel",
    "island": "wood",
    "furniture": "bed",
}


def _block_geom(block: Block) -> str:
    x0, x1, y0, y1 = block.rect
    rect = Rect(x0, x1, y0, y1, block.height)
    return "    " + rect.geom(block.name, "scene", BLOCK_MATERIALS[block.kind]) + "\n"


def _object_body(obj: ObjectSpec) -> str:
    x, y, yaw = obj.pose
    if obj.kind == "chair":
        return _chair_object(obj.name, x, y, yaw)
    material = "cardboard" if obj.on_path else "clutter"
    return _box_object(obj.name, x, y, yaw, obj.size, material)


def kitchen_layout_xml(layout: KitchenLayout) -> str:
    """The layout as an MJCF string (includes ``robot.xml``)."""
    x0, x1, y0, y1 = layout.house
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    extent = max(x1 - x0, y1 - y0)
    out = [
        _header(
            f"voot_kitchen_{layout.difficulty}_{layout.layout_seed}", extent + 4.0, (cx, cy, 0.5)
        )
    ]
    out.append("  <worldbody>\n")
    out.append(
        f'    <light name="sun" pos="{_v(cx, cy, 9)}" dir="0.3 0.4 -1" directional="true"'
        ' castshadow="true" diffuse="0.45 0.45 0.45"/>\n'
    )
    out.append(
        f'    <geom name="floor" class="decor" type="plane" size="{_v(0.5 * (x1 - x0) + 0.6, 0.5 * (y1 - y0) + 0.6, 0.1)}"'
        f' pos="{_v(cx, cy, 0)}" material="floor"/>\n'
    )
    wk = layout.kitchen_width
    out.append(
        f'    <geom name="kitchen_floor" class="decor" type="box" size="{_v(0.5 * wk, 0.5 * (y1 - y0), 0.001)}"'
        f' pos="{_v(0.5 * wk, cy, 0.001)}" material="tile"/>\n'
    )
    out.append(
        _cameras(
            top_center=(cx, cy),
            top_height=12.0,
            top_extent=extent + 0.6,
            persp_pos=(cx - 5.0, cy - 8.0, 7.0),
            persp_target=(cx, cy, 0.0),
            persp_fovy=47.0,
        )
    )
    for block in layout.blocks:
        out.append(_block_geom(block))
    sx, sy = layout.sink
    out.append(
        f'    <geom name="sink_basin" class="decor" type="box" size="0.32 0.22 0.005"'
        f' pos="{_v(sx, sy, 0.862)}" material="steel"/>\n'
    )
    out.append(
        f'    <geom name="sink_faucet" class="decor" type="cylinder" size="0.02 0.12"'
        f' pos="{_v(sx, sy + 0.26, 0.98)}" material="steel"/>\n'
    )
    for name, pose, rgba in (
        ("start_marker", layout.start, "0.1 0.6 1 1"),
        ("goal_marker", layout.goal, "1 0.8 0.1 1"),
    ):
        out.append(
            f'    <geom name="{name}" class="decor" type="cylinder" size="0.12 0.002"'
            f' pos="{_v(pose[0], pose[1], 0.003)}" rgba="{rgba}"/>\n'
        )
    for obj in layout.objects:
        out.append(_object_body(obj))
    out.append("  </worldbody>\n</mujoco>\n")
    return "".join(out)


@cache
def robot_xml() -> bytes:
    """The robot's MJCF (``voot.models/robot.xml``), which every scene includes."""
    return resources.files("voot.models").joinpath("robot.xml").read_bytes()


def compile_kitchen(xml: str) -> mujoco.MjModel:
    """Compile a generated kitchen's MJCF (``robot.xml`` given as an in-memory asset)."""
    return mujoco.MjModel.from_xml_string(xml, assets={"robot.xml": robot_xml()})


def scene_digest(xml: str) -> str:
    """SHA-256 of the MJCF text (the same layout gives the same digest in every process)."""
    return hashlib.sha256(xml.encode()).hexdigest()
