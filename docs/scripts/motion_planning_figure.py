"""Draw docs/figures/motion_planning.png: the base planner and the swept volume at work.

* left: a kitchen-sized house (walls and furniture grey, movable objects orange), the
  reduced visibility graph for a robot disc of radius 0.4 (blue) and the shortest path
  from the hallway through the kitchen's 1.0 m door (red, with the disc drawn along it);
* right: the fixed path from the start to the sink, the area the disc sweeps along it
  and the objects whose footprint meets it (red) or not (orange).

Run from the repository root (needs the ``envs`` and ``bench`` extras)::

    python docs/scripts/motion_planning_figure.py
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.patches import Circle
from matplotlib.patches import Polygon as PolygonPatch

from voot.envs.motion.planar import Box2D, Pose2D
from voot.envs.motion.planner import BasePlanner
from voot.envs.motion.swept_volume import obstacles_on_path, swept_footprint

# the house is the tests' (tests/floor_plans.py)
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from floor_plans import WORKSPACE, house_movable, house_static

#: The house of the base-planning tests, with a thinner west wall (room for the start
#: pose of the path to the sink).
STATIC = house_static(west_wall=-1.98)
MOVABLE = house_movable()


def draw_boxes(ax: plt.Axes, boxes: list[Box2D], color: str) -> None:
    for b in boxes:
        ax.add_patch(PolygonPatch(b.corners(), closed=True, color=color, lw=0))


def main() -> None:
    planner = BasePlanner(WORKSPACE, STATIC)
    fig, axes = plt.subplots(1, 2, figsize=(12, 6.2), constrained_layout=True)

    # left: graph and a path through the kitchen door
    ax = axes[0]
    radius = 0.4
    movable = MOVABLE[6:]  # some objects cleared away, so that a path exists
    start, goal = Pose2D(-0.6, -1.6, 0.3), Pose2D(3.4, 1.2, -2.0)
    path = planner.plan(start, goal, radius, movable)
    assert path is not None
    scene = planner._scene(radius, tuple(movable))  # the cached graph, for the picture
    graph = scene.graph
    assert graph is not None
    pos = graph.nodes.pos
    for i, j in zip(graph.i.tolist(), graph.j.tolist(), strict=True):
        ax.plot(pos[[i, j], 0], pos[[i, j], 1], color="tab:blue", lw=0.4, alpha=0.6)
    ax.plot(pos[:, 0], pos[:, 1], ".", color="tab:blue", ms=3)
    draw_boxes(ax, STATIC, "0.55")
    draw_boxes(ax, movable, "tab:orange")
    for p in path.interpolate(0.35):
        ax.add_patch(Circle((p[0], p[1]), radius, fill=False, color="tab:red", lw=0.5))
    w = path.waypoints
    ax.plot(w[:, 0], w[:, 1], "-", color="tab:red", lw=2)
    ax.set_title(
        f"visibility graph (r = {radius} m): {len(graph.nodes)} nodes, {graph.i.size} edges;"
        f"\nshortest path {path.translation_length:.2f} m, SE(2) length {path.length:.2f}"
    )

    # right: the swept volume of the fixed path to the sink
    ax = axes[1]
    radius = 0.45
    fixed = planner.plan(Pose2D(-1.5, -1.5, math.pi / 2), Pose2D(0.0, 2.5, math.pi / 2), radius)
    assert fixed is not None
    area = swept_footprint(fixed.waypoints, radius)
    ax.add_patch(PolygonPatch(list(area.exterior.coords), color="tab:blue", alpha=0.25, lw=0))
    on_path = set(obstacles_on_path(fixed.waypoints, radius, MOVABLE))
    draw_boxes(ax, STATIC, "0.55")
    draw_boxes(ax, [b for b in MOVABLE if b.name not in on_path], "tab:orange")
    draw_boxes(ax, [b for b in MOVABLE if b.name in on_path], "tab:red")
    ax.plot(fixed.waypoints[:, 0], fixed.waypoints[:, 1], "-", color="tab:blue", lw=2)
    ax.set_title(
        f"swept area of the path to the sink (r = {radius} m):\n"
        f"{len(on_path)} of {len(MOVABLE)} objects on it (red)"
    )
    for ax in axes:
        ax.set_xlim(WORKSPACE[0], WORKSPACE[1])
        ax.set_ylim(WORKSPACE[2], WORKSPACE[3])
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
    out = Path(__file__).resolve().parents[1] / "figures" / "motion_planning.png"
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
