"""The paper's Figure 5 from recordings: one node's sampled actions, side by side per planner.

The viewer shows the same thing interactively; this draws it as a still image from the
``.rrd`` files themselves (read with :func:`voot.record.read_recording`), for documents
and for machines where the viewer cannot run. Each panel is the latest drawing of one
entity (by default the first place node's placements) in one recording: the points
with the colours the recorder gave them (viridis by :math:`\\hat Q`, infeasible grey).
Needs matplotlib (the ``[bench]`` extra), imported when called.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.record.reader import read_recording

#: Entity drawn by default: the first place node's placements (paper Figure 5).
DEFAULT_ENTITY = "scene/samples/first_place/placements"


def unpack_colors(packed: Any) -> NDArray[np.float64]:
    """rerun's packed ``0xRRGGBBAA`` colours as ``(n, 4)`` floats in [0, 1]."""
    c = np.asarray(packed, dtype=np.uint64).reshape(-1)
    shifts = np.array([24, 16, 8, 0], dtype=np.uint64)
    return ((c[:, None] >> shifts) & np.uint64(0xFF)).astype(np.float64) / 255.0


def node_samples(
    path: str | os.PathLike[str], entity: str = DEFAULT_ENTITY, timeline: str = "search"
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """The latest drawing of ``entity`` in a recording: ``(xy (n, 2), rgba (n, 4), time)``.

    Works for the 3-D drawings (``Points3D``/``Arrows3D``) and the 2-D fallback
    (``Points2D``). Raises ValueError if the recording has no such entity.
    """
    rec = read_recording(path)
    key = entity if entity.startswith("/") else "/" + entity
    if key not in rec.entities:
        drawn = sorted(e for e in rec.entities if "/samples/" in e or e.startswith("/samples"))
        raise ValueError(f"{path} has no entity {key!r}; sampled-action entities: {drawn}")
    comps = rec.entities[key].components
    for arch, field in (
        ("Points3D", "positions"),
        ("Points2D", "positions"),
        ("Arrows3D", "origins"),
    ):
        if f"{arch}:{field}" in comps:
            t, pos = rec.column(key, f"{arch}:{field}", timeline)[-1]
            colors = rec.latest(key, f"{arch}:colors", timeline)
            xy = np.asarray(pos, dtype=np.float64).reshape(len(pos), -1)[:, :2]
            return xy, unpack_colors(colors), int(t if t is not None else -1)
    raise ValueError(f"{key} in {path} holds no points or arrows (components: {list(comps)})")


def samples_figure(
    recordings: Mapping[str, str | os.PathLike[str]],
    out: str | os.PathLike[str],
    entity: str | Mapping[str, str | Sequence[str]] = DEFAULT_ENTITY,
    *,
    xlim: tuple[float, float] | None = None,
    ylim: tuple[float, float] | None = None,
    point_size: float = 14.0,
    background: Callable[[Any], None] | None = None,
    title: str | None = None,
    notes: Mapping[str, str] | None = None,
) -> Path:
    """Draw ``entity``'s latest samples of each recording (title: its key) into ``out``.

    Args:
        recordings: panel title -> ``.rrd`` path, e.g. ``{"VOOT": "voot.rrd",
            "PW-UCT": "pw.rrd"}`` (same problem and seed for a fair comparison).
        out: the image file (``.png``, ``.svg`` ...).
        entity: the entity to draw (default: the first place node's placements), or
            per panel title one entity or several (drawn in that order, the first
            underneath; e.g. when the watched node has a different id in each tree).
        xlim: common x limits (default: fitted to all panels).
        ylim: common y limits (default: fitted to all panels).
        point_size: marker area.
        background: called with each panel's matplotlib ``Axes`` before the samples
            are drawn (e.g. to draw the floor plan underneath).
        title: the figure's title (default: the entity and the colour legend).
        notes: per panel title, a text written under the panel (e.g. the counts of
            feasible and failed samples).
    """
    if not recordings:
        raise ValueError("recordings must name at least one .rrd file")
    entities: dict[str, list[str]]
    if isinstance(entity, str):
        entities = {name: [entity] for name in recordings}
    else:
        missing = sorted(set(recordings) - set(entity))
        if missing:
            raise ValueError(f"entity gives no entity for the panels {missing}")
        entities = {}
        for name in recordings:
            given = entity[name]
            entities[name] = [given] if isinstance(given, str) else list(given)
        empty = sorted(name for name, e in entities.items() if not e)
        if empty:
            raise ValueError(f"entity gives an empty list of entities for the panels {empty}")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = {
        name: [(e, *node_samples(p, e)) for e in entities[name]] for name, p in recordings.items()
    }
    fig, axes = plt.subplots(1, len(data), figsize=(4.2 * len(data), 4.2), squeeze=False)
    every = np.concatenate([xy for panel in data.values() for _, xy, _, _ in panel])
    pad = 0.05 * max(float(np.ptp(every[:, 0])), float(np.ptp(every[:, 1])), 1e-9)
    xl = xlim or (float(every[:, 0].min()) - pad, float(every[:, 0].max()) + pad)
    yl = ylim or (float(every[:, 1].min()) - pad, float(every[:, 1].max()) + pad)
    for ax, (name, panel) in zip(axes[0], data.items(), strict=True):
        if background is not None:
            background(ax)
        for k, (_, xy, rgba, _) in enumerate(panel):
            ax.scatter(xy[:, 0], xy[:, 1], c=rgba, s=point_size, edgecolors="none", zorder=3 + k)
        t = max(t for _, _, _, t in panel)
        if len(panel) == 1:
            counts = f"{len(panel[0][1])} samples"
        else:
            counts = ", ".join(f"{len(xy)} {e.rsplit('/', 1)[-1]}" for e, xy, _, _ in panel)
        if notes and name in notes:  # the counts are in the note: a short title
            ax.set_title(f"{name} (simulation {t + 1})", fontsize=9)
        else:
            ax.set_title(f"{name}: {counts} (simulation {t + 1})", fontsize=9)
        ax.set_xlim(*xl)
        ax.set_ylim(*yl)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        if notes and name in notes:
            ax.text(0.0, -0.14, notes[name], transform=ax.transAxes, va="top", fontsize=8)
    legend = "colour = Q-hat (viridis, low to high), grey = infeasible"
    shown = entity if isinstance(entity, str) else "the watched node's samples"
    fig.suptitle(title if title is not None else f"{shown}: {legend}", fontsize=9)
    fig.tight_layout()
    path = Path(out)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110, bbox_inches="tight" if notes else None)
    plt.close(fig)
    return path
