"""Make the generated-kitchen demo's figures of docs/recordings.md from its recording.

* ``docs/figures/voot_kitchen_v2.gif``: VOOT's best plan in a generated kitchen
  (:func:`voot.bench.demos.kitchen_demo.run` on ``voot/KitchenClearing-v2``, medium, layout
  seed 3; the demo's default simulations and seed);
* ``docs/figures/recordings_kitchen_v2_viewer.png``: rerun's viewer on that recording's
  3-D view at the end of the best plan (the mesh objects where the plan left them).

The screenshot is taken by the native viewer of ``rerun-sdk`` running headless
(:mod:`voot.record.screenshot`); without a GPU it needs Mesa's lavapipe
(``apt-get install mesa-vulkan-drivers``). ``--no-viewer`` skips it.

Run from the repository root (about 15 s)::

    python docs/scripts/kitchen_v2_demo_figures.py [--work /tmp/kitchen_v2] [--no-viewer]
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

from voot.bench.demos.kitchen_demo import GENERATED_ID, run
from voot.record.screenshot import viewer_screenshots

sys.path.insert(0, str(Path(__file__).resolve().parent))
from figure_scripts import FIGURES, figure_options, shrink

#: The kitchen shown: a medium one whose search clears every obstacle.
LAYOUT_SEED, DIFFICULTY = 3, "medium"
#: The 3-D view of the recording's default layout.
SCENE_VIEW = "Scene and sampled actions"


def main() -> None:
    work, viewer = figure_options(__doc__, "/tmp/voot_kitchen_v2_figures", "screenshot")
    summary = run(work, env_id=GENERATED_ID, layout_seed=LAYOUT_SEED, difficulty=DIFFICULTY)
    assert summary.video is not None
    shutil.copy(summary.video, FIGURES / "voot_kitchen_v2.gif")
    if not viewer:
        return
    path = FIGURES / "recordings_kitchen_v2_viewer.png"
    viewer_screenshots(
        summary.recording, {SCENE_VIEW: path}, timeline="plan", sequence=summary.plan_length
    )
    shrink(path)
    print(f"screenshot -> {path} ({path.stat().st_size // 1024} kB)")


if __name__ == "__main__":
    main()
