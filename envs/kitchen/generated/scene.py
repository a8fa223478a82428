"""A generated kitchen as a MuJoCo scene: :class:`~voot.envs.kitchen.generated.layout.KitchenLayout`
to MJCF, and the MJCF compiled.

:func:`kitchen_layout_xml` writes the layout with the v1 scene's building blocks
(:mod:`voot.envs.assets.mjcf`: its header with materials and collision classes,
walls and blocks, cameras), so a generated kitchen collides like the paper's one: static
blocks are class ``scene``, the sink and the markers decoration. The movable objects are
trimesh meshes (:mod:`voot.envs.assets.meshes`): :func:`shape_spec` names each object's shape,
:func:`~voot.envs.assets.meshes.object_body_xml` writes its body (a free joint, convex collision
parts of class ``object``, a visual mesh, the inertia from the mesh) and the mesh
``<asset>`` entries join the header's. :func:`compile_kitchen` compiles the string with
``robot.xml`` and the meshes' STL bytes as MuJoCo's in-memory assets
(:func:`~voot.envs.assets.meshes.compile_scene`; the meshes come from the mesh cache): no file
is written.

The MJCF is a pure function of the layout, so the same layout gives the same bytes in
every process: its SHA-256 (:func:`~voot.envs.assets.mjcf.mjcf_sha256`) keys the
kitchen's records.
"""

from __future__ import annotations

import mujoco

from voot.envs.assets.meshes import ShapeSpec, compile_scene, object_body_xml, shape_assets_xml
from voot.envs.assets.mjcf import (
    COUNTER_HEIGHT,
    GOAL_RGBA,
    START_RGBA,
    Rect,
    cameras,
    floor_plane,
    header,
    marker,
    sink,
    sun_light,
    vec,
)
from voot.envs.kitchen.generated.layout import Block, KitchenLayout, ObjectSpec

__all__ = ["compile_kitchen", "kitchen_layout_xml", "shape_spec"]

#: The scene material of each block kind.
BLOCK_MATERIALS = {
    "wall": "wall",
    "counter": "counter",
    "fridge": "steel",
    "island": "wood",
    "furniture": "bed",
}
#: Each mesh kind's material (the v1 header's ``cardboard`` or :data:`OBJECT_MATERIALS`).
KIND_MATERIALS = {
    "box": "cardboard",
    "crate": "crate",
    "tray": "crate",
    "bin": "bin",
    "bucket": "bucket",
    "jug": "jug",
    "bottle": "jug",
    "bowl": "ceramic",
    "plate": "ceramic",
    "mug": "ceramic",
}
#: The objects' materials beside the v1 header's.
OBJECT_MATERIALS = (
    '    <material name="crate" rgba="0.25 0.45 0.75 1"/>\n'
    '    <material name="bin" rgba="0.35 0.62 0.40 1"/>\n'
    '    <material name="bucket" rgba="0.85 0.55 0.15 1"/>\n'
    '    <material name="jug" rgba="0.75 0.85 0.92 1"/>\n'
    '    <material name="ceramic" rgba="0.92 0.90 0.85 1"/>\n'
)


def shape_spec(obj: ObjectSpec) -> ShapeSpec:
    """The mesh shape of a layout's object."""
    return ShapeSpec(obj.kind, obj.size, obj.variant)


def _block_geom(block: Block) -> str:
    x0, x1, y0, y1 = block.rect
    return Rect(x0, x1, y0, y1, block.height).line(block.name, BLOCK_MATERIALS[block.kind])


def _object_body(obj: ObjectSpec) -> str:
    x, y, yaw = obj.pose
    return object_body_xml(obj.name, shape_spec(obj), (x, y, 0.0, yaw), KIND_MATERIALS[obj.kind])


def kitchen_layout_xml(layout: KitchenLayout) -> str:
    """The layout as an MJCF string (includes ``robot.xml`` and the objects' meshes)."""
    x0, x1, y0, y1 = layout.house
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    extent = max(x1 - x0, y1 - y0)
    assets = OBJECT_MATERIALS + shape_assets_xml(shape_spec(o) for o in layout.objects)
    name = f"voot_kitchen_{layout.difficulty}_{layout.layout_seed}"
    out = [header(name, extent + 4.0, (cx, cy, 0.5), assets)]
    out.append("  <worldbody>\n")
    out.append(sun_light(cx, cy, 9))
    out.append(floor_plane(cx, cy, 0.5 * (x1 - x0) + 0.6, 0.5 * (y1 - y0) + 0.6))
    wk = layout.kitchen_width
    out.append(
        f'    <geom name="kitchen_floor" class="decor" type="box" size="{vec(0.5 * wk, 0.5 * (y1 - y0), 0.001)}"'
        f' pos="{vec(0.5 * wk, cy, 0.001)}" material="tile"/>\n'
    )
    out.append(
        cameras(
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
    out.append(sink(*layout.sink, COUNTER_HEIGHT))
    out.append(marker("start_marker", layout.start[0], layout.start[1], START_RGBA))
    out.append(marker("goal_marker", layout.goal[0], layout.goal[1], GOAL_RGBA))
    for obj in layout.objects:
        out.append(_object_body(obj))
    out.append("  </worldbody>\n</mujoco>\n")
    return "".join(out)


def compile_kitchen(xml: str, layout: KitchenLayout) -> mujoco.MjModel:
    """Compile ``layout``'s MJCF ``xml`` (``robot.xml`` and the meshes as in-memory assets)."""
    return compile_scene(xml, [shape_spec(o) for o in layout.objects])
