"""The default viewer layout of a search recording (a :mod:`rerun.blueprint`).

Left, large: the 3-D scene (geometry, the robot along the best plan on the ``plan``
timeline, the watched nodes' sampled base poses and placements on the ``search``
timeline) or, for problems without a scene, the 2-D plot of sampled actions. Right, top
to bottom: the best return over simulations, the tree size, the search tree as a graph,
the plan's rewards (a static bar chart, one bar per action, so that it shows on any
timeline) and its return on the ``plan`` timeline, and the 2-D sample plot when it is not
already the main view. The time panel opens on the ``search`` timeline.

The 3-D view opens with an :class:`Eye3D` when one is given (the recorder takes it from
the scene's ``perspective`` camera, :func:`voot.record.mujoco_scene.model_camera_eye`):
rerun's own first view frames the bounding box of everything logged from a fixed side,
which on the kitchen and conveyor scenes cuts off the robot.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

#: Entity paths written by :class:`voot.record.SearchRecorder` (and read by the tests).
SCENE = "scene"
SAMPLES_2D = "samples"
BEST_RETURN = "search/best_return"
N_NODES = "search/n_nodes"
TREE = "tree"
PLAN = "plan"
SEARCH_TIMELINE = "search"
PLAN_TIMELINE = "plan"


@dataclass(frozen=True)
class Eye3D:
    """Where the 3-D view's orbiting eye starts: world coordinates (metres), z up.

    Attributes:
        position: the eye.
        look_target: the point it looks at and orbits around.
        up: the world's up direction the eye keeps (MuJoCo's +z).
    """

    position: tuple[float, float, float]
    look_target: tuple[float, float, float]
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)

    def __post_init__(self) -> None:
        for name in ("position", "look_target", "up"):
            value = np.asarray(getattr(self, name), dtype=np.float64)
            if value.shape != (3,) or not np.all(np.isfinite(value)):
                raise ValueError(f"{name} must be 3 finite numbers, got {getattr(self, name)!r}")
            object.__setattr__(self, name, tuple(float(v) for v in value))
        if self.position == self.look_target:
            raise ValueError("position and look_target must differ")
        if not any(self.up):
            raise ValueError("up must not be the zero vector")

    def controls(self) -> Any:
        """The rerun ``EyeControls3D`` (orbital) of this eye."""
        import rerun.blueprint as rrb

        return rrb.archetypes.EyeControls3D(
            kind=rrb.components.Eye3DKind.Orbital,
            position=self.position,
            look_target=self.look_target,
            eye_up=self.up,
        )


def default_blueprint(
    *, has_scene: bool, has_plot: bool, has_plan: bool = True, eye: Eye3D | None = None
) -> Any:
    """The blueprint for a recording with (or without) a 3-D scene and a 2-D sample plot.

    ``eye``: where the 3-D view's eye starts (None: rerun's automatic view).
    """
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
        main: Any = rrb.Spatial3DView(
            origin=f"/{SCENE}",
            name="Scene and sampled actions",
            eye_controls=None if eye is None else eye.controls(),
        )
        if has_plot:
            side.append(rrb.Spatial2DView(origin=f"/{SAMPLES_2D}", name="Sampled actions (2-D)"))
    else:
        main = rrb.Spatial2DView(origin=f"/{SAMPLES_2D}", name="Sampled actions")
    return rrb.Blueprint(
        rrb.Horizontal(main, rrb.Vertical(*side), column_shares=[3, 2]),
        rrb.TimePanel(timeline=SEARCH_TIMELINE),
        collapse_panels=False,
    )
