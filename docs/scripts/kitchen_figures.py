"""Make the kitchen figures of the README and docs/recordings.md from recordings.

* ``docs/figures/voot_kitchen.gif``: VOOT's best plan clearing the kitchen
  (:func:`voot.bench.demos.kitchen_demo.run`, its default simulations and seed);
* ``docs/figures/recordings_kitchen_viewer.png``: rerun's viewer on that recording, at
  the end of the best plan;
* ``docs/figures/recordings_kitchen_figure5_{voot,pw_uct}.png``: rerun's viewer showing
  the Figure-5 recordings (:func:`voot.bench.demos.figure5.figure5`, same seed): the
  placements sampled at the first object's place node after 50 visits; and the
  viewer's whole window for VOOT (``..._figure5_viewer.png``);
* ``docs/figures/recordings_kitchen_figure5_drawn.png``: the same data drawn with
  matplotlib from the ``.rrd`` files (:mod:`voot.record.figure5`).

The screenshots are taken by the native viewer of ``rerun-sdk`` running headless
(:mod:`voot.record.screenshot`); without a GPU it needs Mesa's lavapipe
(``apt-get install mesa-vulkan-drivers``). ``--no-viewer`` skips them.

Run from the repository root (about 3 minutes of CPU)::

    python docs/scripts/kitchen_figures.py [--work /tmp/kitchen] [--no-viewer]
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

from voot.bench.demos.figure5 import figure5
from voot.bench.demos.kitchen_demo import run
from voot.record.screenshot import viewer_screenshots

sys.path.insert(0, str(Path(__file__).resolve().parent))
from figure_scripts import FIGURES, figure_options, shrink


def main() -> None:
    work, viewer = figure_options(__doc__, "/tmp/voot_kitchen_figures")
    summary = run(work)
    assert summary.video is not None
    shutil.copy(summary.video, FIGURES / "voot_kitchen.gif")
    runs = figure5(work, summary.seed, image="kitchen_figure5.png")
    shutil.copy(work / "kitchen_figure5.png", FIGURES / "recordings_kitchen_figure5_drawn.png")
    if not viewer:
        return
    shots = viewer_screenshots(
        summary.recording,
        {None: FIGURES / "recordings_kitchen_viewer.png"},
        timeline="plan",
        sequence=summary.plan_length,
    )
    widths = {path: 1400 for path in shots.values()}  # whole windows
    for r in runs.values():
        outputs: dict[str | None, Path] = {
            r.view: FIGURES / f"recordings_kitchen_figure5_{r.planner}.png"
        }
        if r.planner == "voot":
            outputs[None] = FIGURES / "recordings_kitchen_figure5_viewer.png"
        taken = viewer_screenshots(
            r.recording, outputs, timeline="search", sequence=r.n_simulations - 1
        )
        widths.update({path: 1400 if name is None else 1000 for name, path in taken.items()})
    for path, width in widths.items():
        shrink(path, width)
        print(f"screenshot -> {path} ({path.stat().st_size // 1024} kB)")


if __name__ == "__main__":
    main()
