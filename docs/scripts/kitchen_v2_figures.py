"""Render generated kitchens (``voot/KitchenClearing-v2``) top-down for docs/environments.md.

Writes ``docs/figures/kitchen_v2_layouts.png``: two layout seeds of each difficulty level
(rows: seeds 0 and 1; columns: easy, medium, hard), each the env's ``top_down`` camera at
``reset()`` with its overlays (the fixed path's swept corridor in blue, the forbidden
rooms in red); and ``docs/figures/kitchen_v2_objects.png``: a closer look at the mesh
objects of one hard kitchen (layout seed 1) from a free camera. Run from the repository
root (a few seconds)::

    python docs/scripts/kitchen_v2_figures.py [--out docs/figures]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import mujoco
import numpy as np
from PIL import Image, ImageDraw

from voot.envs.core.rendering import new_renderer
from voot.envs.kitchen.generated.env import GeneratedKitchenEnv
from voot.envs.kitchen.generated.layout import DIFFICULTIES

SEEDS = (0, 1)
TILE = (420, 360)


def render(seed: int, difficulty: str) -> Image.Image:
    """The top-down image of one generated kitchen at ``reset()``, captioned."""
    env = GeneratedKitchenEnv(
        layout_seed=seed,
        difficulty=difficulty,
        render_mode="rgb_array",
        render_camera="top_down",
        render_size=TILE,
    )
    env.reset(seed=0)
    img = Image.fromarray(env.render())
    layout = env.layout
    caption = (
        f"{difficulty}, layout_seed={seed}: {layout.n_on_path} on the path,"
        f" {len(layout.objects) - layout.n_on_path} clutter"
    )
    ImageDraw.Draw(img).text((8, 6), caption, fill=(0, 0, 0))
    env.close()
    return img


def objects_view(seed: int = 1, difficulty: str = "hard") -> Image.Image:
    """A free camera's view of a kitchen's objects (meshes), looking along the fixed path."""
    env = GeneratedKitchenEnv(layout_seed=seed, difficulty=difficulty)
    env.reset(seed=0)
    path = np.array(env.layout.path)
    mujoco.mj_forward(env.model, env.data)
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = (*path.mean(axis=0), 0.3)
    cam.distance, cam.azimuth, cam.elevation = 4.2, 60.0, -38.0
    with new_renderer(env.model, height=480, width=720) as renderer:
        renderer.update_scene(env.data, camera=cam)
        img = Image.fromarray(renderer.render())
    env.close()
    return img


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs/figures", help="folder of the figures")
    args = parser.parse_args()
    levels = list(DIFFICULTIES)
    sheet = Image.new("RGB", (TILE[0] * len(levels), TILE[1] * len(SEEDS)), "white")
    for row, seed in enumerate(SEEDS):
        for col, level in enumerate(levels):
            sheet.paste(render(seed, level), (col * TILE[0], row * TILE[1]))
    out = Path(args.out)
    for name, img in (
        ("kitchen_v2_layouts.png", sheet),
        ("kitchen_v2_objects.png", objects_view()),
    ):
        img.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(out / name, optimize=True)
        print(f"wrote {out / name}")


if __name__ == "__main__":
    main()
