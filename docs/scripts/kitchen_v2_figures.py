"""Render generated kitchens (``voot/KitchenClearing-v2``) top-down for docs/environments.md.

Writes ``docs/figures/kitchen_v2_layouts.png``: two layout seeds of each difficulty level
(rows: seeds 0 and 1; columns: easy, medium, hard), each the env's ``top_down`` camera at
``reset()`` with its overlays (the fixed path's swept corridor in blue, the forbidden
rooms in red). Run from the repository root (a few seconds)::

    python docs/scripts/kitchen_v2_figures.py [--out docs/figures/kitchen_v2_layouts.png]
"""

from __future__ import annotations

import argparse
from pathlib import Path

from PIL import Image, ImageDraw

from voot.envs.kitchen_family import GeneratedKitchenEnv
from voot.envs.kitchen_layout import DIFFICULTIES

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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs/figures/kitchen_v2_layouts.png")
    args = parser.parse_args()
    levels = list(DIFFICULTIES)
    sheet = Image.new("RGB", (TILE[0] * len(levels), TILE[1] * len(SEEDS)), "white")
    for row, seed in enumerate(SEEDS):
        for col, level in enumerate(levels):
            sheet.paste(render(seed, level), (col * TILE[0], row * TILE[1]))
    out = Path(args.out)
    sheet.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(out, optimize=True)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
