"""The default viewer layout of a search recording (a :mod:`rerun.blueprint`).

Left, large: the 3-D scene (geometry, the robot along the best plan on the ``plan``
timeline, the watched nodes' sampled base poses and placements on the ``search``
timeline) or, for problems without a scene, the 2-D plot of sampled actions. Right, top
to bottom: the best return over simulations, the tree size, the search tree as a graph,
the plan's rewards (a static bar chart, one bar per action, so that it shows on any
timeline) and its return on the ``plan`` timeline, and the 2-D sample plot when it is not already the main view. The time panel
opens on the ``search`` timeline.
"""

from __future__ import annotations

from typing import Any

#: Entity paths written by :class:`voot.record.SearchRecorder` (and read by the tests).
SCENE = "scene"
SAMPLES_2D = "samples"
BEST_RETURN = "search/best_return"
N_NODES = "search/n_nodes"
TREE = "tree"
PLAN = "plan"
SEARCH_TIMELINE = "search"
PLAN_TIMELINE = "plan"


def default_blueprint(*, has_scene: bool, has_plot: bool, has_plan: bool = True) -> Any:
    """The blueprint for a recording with (or without) a 3-D scene and a 2-D sample plot."""
    import rerun.blueprint as rrb

    side: list[Any] = [
        rrb.TimeSeriesView(origin=f"/{BEST_RETURN}", name="Best return"),
        rrb.TimeSeriesView(origin=f"/{N_NODES}", name="Tree nodes"),
        rrb.GraphView(origin=f"/{TREE}", name="Search tree"),
    ]
    if has_plan:
        # a static bar chart, not empty on the search timeline the viewer opens on, and the
        # rewards and return step by step on the plan timeline
        side.append(rrb.BarChartView(origin=f"/{PLAN}/rewards", name="Plan rewards"))
        side.append(
            rrb.TimeSeriesView(
                origin=f"/{PLAN}",
                contents=[f"/{PLAN}/reward", f"/{PLAN}/return"],
                name="Plan return (plan timeline)",
            )
        )
    if has_scene:
        main: Any = rrb.Spatial3DView(origin=f"/{SCENE}", name="Scene and sampled actions")
        if has_plot:
            side.append(rrb.Spatial2DView(origin=f"/{SAMPLES_2D}", name="Sampled actions (2-D)"))
    else:
        main = rrb.Spatial2DView(origin=f"/{SAMPLES_2D}", name="Sampled actions")
    return rrb.Blueprint(
        rrb.Horizontal(main, rrb.Vertical(*side), column_shares=[3, 2]),
        rrb.TimePanel(timeline=SEARCH_TIMELINE),
        collapse_panels=False,
    )
