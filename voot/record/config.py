"""Options of a search recording: which nodes to watch, how often to log what.

Logging costs time inside the search loop, so everything that grows with the tree
(sampled actions of the watched nodes, the tree graph) is logged every so many
simulations, and the per-simulation scalars are buffered and sent in columns. The
defaults keep a recording within 1.5x of the search time without one (see
:mod:`voot.bench.measure.overhead`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any

from voot import validation as V
from voot.record.colors import INFEASIBLE_COLOR, check_color

#: Watch entry meaning the tree's root.
ROOT = "root"

#: ``view_camera`` value: the scene's ``perspective`` camera if it has one.
AUTO_CAMERA = "auto"
#: The camera ``view_camera="auto"`` looks for (voot's scenes, models/generate_scenes.py).
PERSPECTIVE_CAMERA = "perspective"

#: Prefix of a watch entry meaning "the first node of the current best path whose
#: operator is ...", e.g. ``"best:place"``.
BEST_PREFIX = "best:"


@dataclass(frozen=True)
class RecorderConfig:
    """What a :class:`~voot.record.SearchRecorder` logs and how often.

    Attributes:
        application_id: rerun application id (the viewer groups recordings by it).
        watch: the nodes whose sampled actions are drawn: ``"root"`` (the tree's root),
            a node id (int), an operator name such as ``"place"``: the first node, in
            creation order, whose operator is that name (see ``operator_key``), or
            ``"best:<operator>"``: the first node with that operator on the best path
            *at the time of each drawing* (it may change as the search improves).
            Default: the root and the first place node, the paper's Figure 5.
        operator_key: step-info key naming the operator of the actions taken *from* the
            state an action leads to (the environments' "next operator").
        samples_every: log the watched nodes' sampled actions every this many
            simulations (and after the last one).
        tree_every: log the tree as a graph every this many simulations; None logs it
            only once, at the end (a tree of thousands of nodes costs milliseconds).
        tree_max_nodes: at most this many nodes in a logged graph: the shallowest ones
            (breadth first) plus the best path, so a huge tree stays viewable.
        flush_every: the per-simulation scalars (best return, tree size) are buffered and
            sent in one column every this many simulations.
        record_plan: replay the best plan at the end and log its states on the ``plan``
            timeline.
        scene: log the MuJoCo scene (geometry once, body poses along the plan) when the
            problem has a MuJoCo model.
        geom_groups: MuJoCo geom groups to draw (MuJoCo's viewer shows 0, 1, 2 by
            default; collision-only geoms usually sit in group 3); None draws all.
        view_camera: the MuJoCo camera whose pose the default layout's 3-D view opens
            with (:func:`voot.record.mujoco_scene.model_camera_eye`): a camera name of
            the model; ``"auto"``: its ``perspective`` camera if it has one (voot's
            kitchen and conveyor scenes: above and beside the rooms, looking at the
            robot's workspace), else rerun's automatic view; None: rerun's automatic
            view (it frames everything logged from a fixed side and can cut off the
            robot). A name the model has no camera for is an error listing its cameras.
        floor_height: height (m) at which sampled base poses and placements are drawn.
        arrow_length: length (m) of the heading arrows of sampled poses.
        point_radius: radius (m) of the placement points in 3-D (and, in action units,
            of the 2-D fallback points).
        sample_labels: also attach ``Q=...`` text labels to sampled actions (hidden,
            shown on hover; formatting them costs about 1 ms per 1,000 actions per
            drawing). Every drawn action carries its value as the ``q_hat`` component
            anyway.
        infeasible_color: RGB of infeasible sampled actions.
    """

    application_id: str = "voot"
    watch: tuple[str | int, ...] = (ROOT, "place")
    operator_key: str = "next_operator"
    samples_every: int = 10
    tree_every: int | None = None
    tree_max_nodes: int = 2000
    flush_every: int = 100
    record_plan: bool = True
    scene: bool = True
    geom_groups: tuple[int, ...] | None = (0, 1, 2)
    view_camera: str | None = AUTO_CAMERA
    floor_height: float = 0.02
    arrow_length: float = 0.15
    point_radius: float = 0.03
    sample_labels: bool = False
    infeasible_color: tuple[int, int, int] = INFEASIBLE_COLOR

    def __post_init__(self) -> None:
        if not isinstance(self.application_id, str) or not self.application_id.strip():
            raise ValueError(
                f"application_id must be a non-empty string, got {self.application_id!r}"
            )
        watch = (self.watch,) if isinstance(self.watch, str | int) else self.watch
        try:
            watch = tuple(watch)
        except TypeError:
            raise ValueError(
                f"watch must be a tuple of 'root', node ids (int >= 0) or operator names, got {self.watch!r}"
            ) from None
        for w in watch:
            ok = (isinstance(w, str) and w.strip() not in ("", BEST_PREFIX)) or (
                isinstance(w, int) and not isinstance(w, bool) and w >= 0
            )
            if not ok:
                raise ValueError(
                    f"watch entries must be 'root', a node id (int >= 0) or an operator name,"
                    f" got {w!r}"
                )
        if len(set(watch)) != len(watch):
            raise ValueError(f"watch has duplicate entries: {list(watch)}")
        object.__setattr__(self, "watch", watch)
        if not isinstance(self.operator_key, str) or not self.operator_key:
            raise ValueError(f"operator_key must be a non-empty string, got {self.operator_key!r}")
        V.integer(self.samples_every, "samples_every", 1)
        V.optional_integer(self.tree_every, "tree_every", 1)
        V.integer(self.tree_max_nodes, "tree_max_nodes", 1)
        V.integer(self.flush_every, "flush_every", 1)
        for name in ("record_plan", "scene", "sample_labels"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{name} must be True or False, got {getattr(self, name)!r}")
        if self.geom_groups is not None:
            groups = self.geom_groups
            if isinstance(groups, str | int) or not all(
                isinstance(g, int) and not isinstance(g, bool) and 0 <= g <= 5 for g in groups
            ):
                raise ValueError(
                    f"geom_groups must be None or a tuple of MuJoCo groups 0-5, got {groups!r}"
                )
            object.__setattr__(self, "geom_groups", tuple(groups))
        if self.view_camera is not None and (
            not isinstance(self.view_camera, str) or not self.view_camera.strip()
        ):
            raise ValueError(
                f"view_camera must be None, {AUTO_CAMERA!r} or a camera name of the model,"
                f" got {self.view_camera!r}"
            )
        object.__setattr__(
            self, "floor_height", V.positive(self.floor_height, "floor_height", allow_zero=True)
        )
        object.__setattr__(self, "arrow_length", V.positive(self.arrow_length, "arrow_length"))
        object.__setattr__(self, "point_radius", V.positive(self.point_radius, "point_radius"))
        object.__setattr__(
            self, "infeasible_color", check_color(self.infeasible_color, "infeasible_color")
        )

    def replace(self, **changes: Any) -> RecorderConfig:
        """A copy with some fields changed (validated again)."""
        valid = {f.name for f in fields(self)}
        unknown = sorted(set(changes) - valid)
        if unknown:
            raise ValueError(f"unknown RecorderConfig option(s) {unknown}; valid: {sorted(valid)}")
        return replace(self, **changes)
