r"""The actions sampled at one tree node, drawn coloured by :math:`\hat Q` (paper Figure 5).

What is drawn comes from the step info of each action (the info of the child it led to),
and only from two keys the environments fill in:

``base_pose``
    ``(x, y, theta)`` of the robot base for that action: an arrow on the floor
    (``<scene>/samples/<name>/base_poses``).
``placement``
    ``(x, y, theta)`` of the placed object: a point with a heading arrow on the floor
    (``<scene>/samples/<name>/placements``).

A node none of whose actions carries either key (a synthetic chain, a gymnasium
control task) is drawn in a 2-D view instead (``samples/<name>``): the first two action
coordinates, or :math:`(a, \hat Q)` for a 1-D action. Colours: viridis over the node's
feasible :math:`\hat Q` (see :mod:`voot.record.colors`), infeasible actions apart.

The node's edges only grow, so actions and poses are cached and extended; only
:math:`\hat Q` and the feasibility flags are re-read at each drawing.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.record.colors import value_colors
from voot.tree.node import Node

#: Step-info keys read for drawing (the environments' contract with this module).
BASE_POSE_KEY = "base_pose"
PLACEMENT_KEY = "placement"


def pose_of(info: Mapping[str, Any], key: str) -> NDArray[np.float64] | None:
    """``info[key]`` as a finite ``(x, y, theta)`` array, or None if absent or malformed."""
    v = info.get(key)
    if v is None:
        return None
    try:
        a = np.asarray(v, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        return None
    if a.size != 3 or not np.all(np.isfinite(a)):
        return None
    return a


class NodeSamples:
    """Cached arrays of one node's actions and the poses their infos carry.

    Attributes:
        node: the watched node.
        actions: ``(n, d)`` actions tried so far.
        base_poses, placements: ``(n, 3)``; rows of actions without the key are NaN.
    """

    def __init__(self, node: Node) -> None:
        self.node = node
        self.n = 0
        self._actions = np.empty((0, 0))
        self._base = np.empty((0, 3))
        self._place = np.empty((0, 3))

    def update(self) -> None:
        """Append the edges added since the last update."""
        node = self.node
        k = len(node.actions)
        if k == self.n:
            return
        new = range(self.n, k)
        acts = np.array([node.actions[i] for i in new], dtype=np.float64).reshape(len(new), -1)
        base = np.full((len(new), 3), np.nan)
        place = np.full((len(new), 3), np.nan)
        for j, i in enumerate(new):
            info = node.children[i].info
            if info:
                p = pose_of(info, BASE_POSE_KEY)
                if p is not None:
                    base[j] = p
                p = pose_of(info, PLACEMENT_KEY)
                if p is not None:
                    place[j] = p
        self._actions = acts if self.n == 0 else np.concatenate([self._actions, acts])
        self._base = np.concatenate([self._base, base])
        self._place = np.concatenate([self._place, place])
        self.n = k

    @property
    def actions(self) -> NDArray[np.float64]:
        return self._actions[: self.n]

    @property
    def base_poses(self) -> NDArray[np.float64]:
        return self._base[: self.n]

    @property
    def placements(self) -> NDArray[np.float64]:
        return self._place[: self.n]

    def values(self) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        r""":math:`\hat Q` and feasibility of the cached actions."""
        node = self.node
        n = self.n
        return (
            np.fromiter(node.q[:n], dtype=np.float64, count=n),
            np.fromiter(node.feasible[:n], dtype=bool, count=n),
        )


def _labels(q: NDArray[np.float64], feasible: NDArray[np.bool_]) -> list[str]:
    return [f"Q={v:.4g}" if ok else f"Q={v:.4g} (infeasible)" for v, ok in zip(q.tolist(), feasible.tolist(), strict=True)]


def _heading_arrows(
    poses: NDArray[np.float64], height: float, length: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    origins = np.column_stack([poses[:, 0], poses[:, 1], np.full(len(poses), height)])
    vectors = np.column_stack(
        [length * np.cos(poses[:, 2]), length * np.sin(poses[:, 2]), np.zeros(len(poses))]
    )
    return origins, vectors


def log_node_samples(
    rec: Any,
    samples: NodeSamples,
    name: str,
    *,
    scene_root: str = "scene",
    plot_root: str = "samples",
    height: float = 0.02,
    arrow_length: float = 0.15,
    point_radius: float = 0.03,
    labels: bool = True,
    infeasible_color: tuple[int, int, int] = (170, 170, 170),
) -> str:
    """Log the node's sampled actions at the recording's current time.

    Returns which drawing was used: ``"scene"`` (base poses and/or placements),
    ``"plot"`` (the 2-D fallback) or ``"none"`` (no action yet).
    """
    import rerun as rr

    samples.update()
    if samples.n == 0:
        return "none"
    q, feasible = samples.values()
    colors = value_colors(q, feasible, infeasible_color)
    text = _labels(q, feasible) if labels else None
    base, place = samples.base_poses, samples.placements
    has_base = ~np.isnan(base[:, 0])
    has_place = ~np.isnan(place[:, 0])
    if has_base.any() or has_place.any():
        if has_base.any():
            o, v = _heading_arrows(base[has_base], height, arrow_length)
            rec.log(
                f"{scene_root}/samples/{name}/base_poses",
                rr.Arrows3D(
                    origins=o,
                    vectors=v,
                    colors=colors[has_base],
                    labels=None if text is None else [t for t, h in zip(text, has_base, strict=True) if h],
                    show_labels=False,
                ),
            )
        if has_place.any():
            o, v = _heading_arrows(place[has_place], height, 0.5 * arrow_length)
            sub = colors[has_place]
            rec.log(
                f"{scene_root}/samples/{name}/placements",
                rr.Points3D(
                    o,
                    colors=sub,
                    radii=point_radius,
                    labels=None if text is None else [t for t, h in zip(text, has_place, strict=True) if h],
                    show_labels=False,
                ),
                rr.Arrows3D(origins=o, vectors=v, colors=sub),
            )
        return "scene"
    a = samples.actions
    xy = np.column_stack([a[:, 0], q]) if a.shape[1] == 1 else a[:, :2]
    rec.log(
        f"{plot_root}/{name}",
        rr.Points2D(
            xy,
            colors=colors,
            radii=rr.Radius.ui_points(4.0),
            labels=text,
            show_labels=False,
        ),
    )
    return "plot"
