"""Make Figure 5 on KitchenClearing-v1 for docs/results-planning.md and docs/recordings.md.

* ``docs/figures/figure5_v1.png``: the placements sampled at the first object's place
  node after 50 visits for PW-UCT, RAND-DOOT and VOOT (seed 0), drawn from the
  recordings, with each panel's counts (:func:`voot.bench.demos.figure5.figure5`);
* ``docs/figures/figure5_v1.json``: those counts;
* ``docs/figures/figure5_v1_viewer_{pw_uct,rand_doot,voot}.png``: rerun's viewer on each
  recording's Figure-5 view, and ``figure5_v1_viewer.png`` its whole window for VOOT
  (with the "Samples at the node" text panel).

The screenshots need a graphics driver; without a GPU, Mesa's lavapipe
(``apt-get install mesa-vulkan-drivers``). ``--no-viewer`` skips them.

Run from the repository root (about 15 s)::

    python docs/scripts/figure5_v1.py [--work /tmp/figure5_v1] [--no-viewer]
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

from voot.bench.demos.figure5 import figure5
from voot.record.screenshot import viewer_screenshots

sys.path.insert(0, str(Path(__file__).resolve().parent))
from figure_scripts import FIGURES, figure_options, shrink

PLANNERS = ("pw_uct", "rand_doot", "voot")


def main() -> None:
    work, viewer = figure_options(__doc__, "/tmp/figure5_v1")
    runs = figure5(
        work, 0, planners=PLANNERS, env_id="voot/KitchenClearing-v1", image="figure5_v1.png"
    )
    for name in ("figure5_v1.png", "figure5_v1.json"):
        shutil.copy(work / name, FIGURES / name)
    if not viewer:
        return
    for r in runs.values():
        outputs: dict[str | None, Path] = {r.view: FIGURES / f"figure5_v1_viewer_{r.planner}.png"}
        if r.planner == "voot":
            outputs[None] = FIGURES / "figure5_v1_viewer.png"
        taken = viewer_screenshots(
            r.recording, outputs, timeline="search", sequence=r.n_simulations - 1
        )
        for name, path in taken.items():
            shrink(path, 1400 if name is None else 800)
            print(f"screenshot -> {path} ({path.stat().st_size // 1024} kB)")


if __name__ == "__main__":
    main()
