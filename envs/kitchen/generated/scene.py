"""A generated kitchen as a MuJoCo scene: :class:`~voot.envs.kitchen.generated.layout.KitchenLayout`
to MJCF, and the MJCF compiled.

:func:`kitchen_layout_xml` writes the layout with the v1 scene's building blocks
(:mod:`voot.models.generate_scenes`: its header with materials and collision classes,
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
every process: :func:`scene_digest` is its SHA-256.
"""

from __future__ import annotations

import hashlib

import mujoco

from voot.envs.assets.meshes import ShapeSpec, compile_scene, object_body_xml, shape_assets_xml
from voot.envs.kitchen.generated.layout import Block, KitchenLayout, ObjectSpec
from voot.models.generate_scenes import Rect, _cameras, _header, _v

__all__ = ["compile_kitchen", "kitchen_layout_xml", "scene_digest", "shape_spec"]

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
    rect = Rect(x0, x1, y0, y1, block.height)
    return "    " + rect.geom(block.name, "scene", BLOCK_MATERIALS[block.kind]) + "\n"


def _object_body(obj: ObjectSpec) -> str:
    x, y, yaw = obj.pose
    return object_body_xml(obj.name, shape_spec(obj), (x, y, 0.0, yaw), KIND_MATERIALS[obj.kind])


def kitchen_layout_xml(layout: KitchenLayout) -> str:
    """The layout as an MJCF string (includes ``robot.xml`` and the objects' meshes)."""
    x0, x1, y0, y1 = layout.house
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    extent = max(x1 - x0, y1 - y0)
    header = _header(
        f"voot_kitchen_{layout.difficulty}_{layout.layout_seed}", extent + 4.0, (cx, cy, 0.5)
    )
    assets = OBJECT_MATERIALS + shape_assets_xml(shape_spec(o) for o in layout.objects)
    out = [header.replace("  </asset>\n", assets + "  </asset>\n", 1)]
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


def compile_kitchen(xml: str, layout: KitchenLayout) -> mujoco.MjModel:
    """Compile ``layout``'s MJCF ``xml`` (``robot.xml`` and the meshes as in-memory assets)."""
    return compile_scene(xml, [shape_spec(o) for o in layout.objects])


def scene_digest(xml: str) -> str:
    """SHA-256 of the MJCF text (the same layout gives the same digest in every process)."""
    return hashlib.sha256(xml.encode()).hexdigest()
