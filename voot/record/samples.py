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
:math:`\hat Q` and the feasibility flags are re-read at each drawing. Drawings are
buffered and sent in columns (:class:`SampleLog`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.record.colors import value_colors
from voot.tree.node import Node
from voot.tree.step_info import StepInfo, pose

#: Step-info keys read for drawing (fields of :class:`voot.tree.step_info.StepInfo`, the
#: environments' contract with this module).
BASE_POSE_KEY = "base_pose"
PLACEMENT_KEY = "placement"


def pose_of(info: Mapping[str, Any], key: str) -> NDArray[np.float64] | None:
    """``info[key]`` as a finite ``(x, y, theta)`` array, or None if absent or malformed
    (the parsing of :class:`~voot.tree.step_info.StepInfo`'s poses)."""
    p = pose(info.get(key))
    return None if p is None else np.array(p, dtype=np.float64)


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
                step = StepInfo.of(info)
                if step.base_pose is not None:
                    base[j] = step.base_pose
                if step.placement is not None:
                    place[j] = step.placement
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
    return [
        f"Q={v:.4g}" if ok else f"Q={v:.4g} (infeasible)"
        for v, ok in zip(q.tolist(), feasible.tolist(), strict=True)
    ]


def _heading_arrows(
    poses: NDArray[np.float64], height: float, length: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    origins = np.column_stack([poses[:, 0], poses[:, 1], np.full(len(poses), height)])
    vectors = np.column_stack(
        [length * np.cos(poses[:, 2]), length * np.sin(poses[:, 2]), np.zeros(len(poses))]
    )
    return origins, vectors


class _Series:
    """The buffered drawings of one entity: rows (a time and a batch of instances)."""

    def __init__(self, kind: str) -> None:
        self.kind = kind  # "arrows", "placements" or "points2d"
        self.times: list[int] = []
        self.lengths: list[int] = []
        self.arrays: dict[str, list[Any]] = {}

    def add(self, i: int, **arrays: Any) -> None:
        self.times.append(i)
        self.lengths.append(len(arrays["colors"]))
        for k, v in arrays.items():
            self.arrays.setdefault(k, []).append(v)

    def clear(self) -> None:
        self.times.clear()
        self.lengths.clear()
        self.arrays.clear()


@dataclass(kw_only=True, eq=False)
class SampleLog:
    r"""Drawings of the watched nodes' sampled actions, buffered and sent as columns.

    :meth:`add` computes a node's drawing (positions, colours by :math:`\hat Q`) at
    simulation ``i`` and keeps it; :meth:`flush` sends everything kept with one
    ``send_columns`` per entity and archetype, which costs far less than one ``log``
    per drawing. Every drawn instance also carries its :math:`\hat Q` as the component
    ``q_hat`` (shown in the viewer's selection panel).

    Attributes:
        scene_root, plot_root: entity roots of the 3-D drawings and of the 2-D fallback.
        timeline: the timeline of the rows (simulation index).
        height, arrow_length, point_radius: drawing sizes (m).
        labels: also attach ``Q=...`` text labels (hidden; costly for big nodes).
        infeasible_color: RGB of infeasible actions.
        entities: entity paths drawn so far (flushed or not).
    """

    scene_root: str = "scene"
    plot_root: str = "samples"
    timeline: str = "search"
    height: float = 0.02
    arrow_length: float = 0.15
    point_radius: float = 0.03
    labels: bool = False
    infeasible_color: tuple[int, int, int] = (170, 170, 170)
    entities: set[str] = field(default_factory=set, init=False)
    _series: dict[str, _Series] = field(default_factory=dict, init=False, repr=False)

    def _get(self, entity: str, kind: str) -> _Series:
        series = self._series.get(entity)
        if series is None:
            series = self._series[entity] = _Series(kind)
            self.entities.add(entity)
        return series

    def add(self, i: int, samples: NodeSamples, name: str) -> str:
        """Keep the drawing of ``samples`` (as ``name``) at simulation ``i``.

        Returns ``"scene"`` (base poses and/or placements), ``"plot"`` (the 2-D
        fallback) or ``"none"`` (the node has no action yet).
        """
        samples.update()
        if samples.n == 0:
            return "none"
        q, feasible = samples.values()
        colors = value_colors(q, feasible, self.infeasible_color)
        text = _labels(q, feasible) if self.labels else None
        base, place = samples.base_poses, samples.placements
        has_base = ~np.isnan(base[:, 0])
        has_place = ~np.isnan(place[:, 0])
        if has_base.any() or has_place.any():
            for key, mask, poses, length in (
                ("base_poses", has_base, base, self.arrow_length),
                ("placements", has_place, place, 0.5 * self.arrow_length),
            ):
                if not mask.any():
                    continue
                o, v = _heading_arrows(poses[mask], self.height, length)
                kind = "arrows" if key == "base_poses" else "placements"
                self._get(f"{self.scene_root}/samples/{name}/{key}", kind).add(
                    i,
                    origins=o,
                    vectors=v,
                    colors=colors[mask],
                    q_hat=q[mask],
                    labels=None
                    if text is None
                    else [t for t, m in zip(text, mask, strict=True) if m],
                )
            return "scene"
        a = samples.actions
        xy = np.column_stack([a[:, 0], q]) if a.shape[1] == 1 else a[:, :2]
        self._get(f"{self.plot_root}/{name}", "points2d").add(
            i, positions=xy, colors=colors, q_hat=q, labels=text
        )
        return "plot"

    def flush(self, rec: Any) -> None:
        """Send every kept drawing to the recording ``rec`` and forget them."""
        import rerun as rr

        for entity, s in self._series.items():
            if not s.times:
                continue
            lengths = np.array(s.lengths, dtype=np.int64)
            n = int(lengths.sum())

            def cat(key: str, series: _Series = s) -> Any:
                return np.concatenate(series.arrays[key])

            text = None
            if s.arrays.get("labels") and s.arrays["labels"][0] is not None:
                text = [t for batch in s.arrays["labels"] for t in batch]
            columns: list[Any] = []
            if s.kind == "points2d":
                columns += rr.Points2D.columns(
                    positions=cat("positions"),
                    colors=cat("colors"),
                    radii=np.full(n, -4.0, dtype=np.float32),  # 4 UI points
                    labels=text,
                ).partition(lengths)
                if text is not None:
                    columns += rr.Points2D.columns(show_labels=[False] * len(lengths))
            else:
                origins = cat("origins")
                if s.kind == "placements":
                    columns += rr.Points3D.columns(
                        positions=origins,
                        colors=cat("colors"),
                        radii=np.full(n, self.point_radius, dtype=np.float32),
                        labels=text,
                    ).partition(lengths)
                    if text is not None:
                        columns += rr.Points3D.columns(show_labels=[False] * len(lengths))
                    text = None
                columns += rr.Arrows3D.columns(
                    origins=origins, vectors=cat("vectors"), colors=cat("colors"), labels=text
                ).partition(lengths)
                if text is not None:
                    columns += rr.Arrows3D.columns(show_labels=[False] * len(lengths))
            columns += rr.AnyValues.columns(q_hat=cat("q_hat")).partition(lengths)
            rec.send_columns(
                entity,
                indexes=[rr.TimeColumn(self.timeline, sequence=np.array(s.times, dtype=np.int64))],
                columns=columns,
            )
            s.clear()
