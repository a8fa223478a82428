"""The picture of the mesh objects in docs/meshes.md (``docs/figures/meshes.png``).

Every kind of :data:`~voot.envs.assets.meshes.SHAPE_KINDS` at its size of
:data:`voot.bench.measure.mesh_speed.SIZES`, variants 0, 1 and 2 one row each, rendered by MuJoCo
from the same XML and assets the scenes use (:func:`~voot.envs.assets.meshes.object_body_xml`,
:func:`~voot.envs.assets.meshes.shape_assets_xml`, :func:`~voot.envs.assets.meshes.mesh_assets`)::

    python -m voot.bench.demos.mesh_gallery docs/figures/meshes.png
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

import mujoco
import numpy as np

from voot.bench.measure.mesh_speed import SIZES
from voot.envs.assets import meshes as M
from voot.envs.assets.meshes import ShapeSpec

#: Materials the kinds cycle through.
COLORS = ("0.80 0.52 0.30 1", "0.35 0.55 0.75 1", "0.85 0.85 0.80 1", "0.45 0.65 0.45 1")


def gallery(variants: Sequence[int] = (0, 1, 2)) -> tuple[str, list[ShapeSpec]]:
    """The gallery scene's XML (no robot) and its specs: one row per variant."""
    specs, bodies = [], []
    for row, variant in enumerate(variants):
        x = 0.0
        for i, kind in enumerate(SIZES):
            spec = ShapeSpec(kind, SIZES[kind], variant)
            specs.append(spec)
            pose = (x + spec.size[0] / 2, -0.45 * row, 0.0, 0.0)
            bodies.append(M.object_body_xml(f"obj_{kind}_{variant}", spec, pose, f"m{i % 4}"))
            x += spec.size[0] + 0.08
    materials = "".join(
        f'    <material name="m{i}" rgba="{c}" specular="0.3"/>\n' for i, c in enumerate(COLORS)
    )
    xml = f"""<mujoco model="mesh_gallery">
  <compiler angle="radian" autolimits="true"/>
  <visual>
    <global offwidth="1600" offheight="700"/>
    <quality shadowsize="4096"/>
    <headlight ambient="0.35 0.35 0.35" diffuse="0.4 0.4 0.4"/>
  </visual>
  <asset>
{materials}{M.shape_assets_xml(specs)}  </asset>
  <default>
    <default class="object"><geom contype="4" conaffinity="7" group="0"/></default>
    <default class="decor"><geom contype="0" conaffinity="0" group="1"/></default>
  </default>
  <worldbody>
    <light pos="1.5 -1 3" dir="-0.2 0.4 -1" directional="true" castshadow="true" diffuse="0.5 0.5 0.5"/>
    <geom type="plane" size="10 10 0.1" rgba="0.93 0.93 0.92 1"/>
    <camera name="gallery" pos="1.35 -2.6 1.9" xyaxes="1 0 0 0 0.64 0.77" fovy="40"/>
{"".join(bodies)}  </worldbody>
</mujoco>
"""
    return xml, specs


def render(path: str) -> None:
    """Render the gallery to the PNG ``path`` (cropped to the objects)."""
    import imageio.v2 as imageio

    from voot.envs.core.rendering import new_renderer

    xml, specs = gallery()
    model = mujoco.MjModel.from_xml_string(xml, assets=M.mesh_assets(specs))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    with new_renderer(model, 700, 1600) as renderer:
        renderer.update_scene(data, camera="gallery")
        image: np.ndarray = renderer.render()
    imageio.imwrite(path, image[175:545, 220:1460])


if __name__ == "__main__":  # pragma: no cover - a docs figure
    if len(sys.argv) != 2:
        sys.exit("usage: python -m voot.bench.demos.mesh_gallery OUT.png")
    render(sys.argv[1])
