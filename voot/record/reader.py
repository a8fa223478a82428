"""Read a rerun ``.rrd`` file back with rerun's own reader (:class:`rerun.chunk.RrdReader`).

:func:`read_recording` returns what a recording holds: its entities (with their
components, static rows and rows per timeline), its timelines (with their ranges) and
whether it carries a blueprint; :meth:`Recording.column` gives a component's values.
A file that is missing, truncated (every complete recording ends with rerun's footer,
which a cut file lacks), or not an RRD at all raises a ValueError saying so.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

#: Columns of a chunk's record batch that are not components.
_CONTROL_PREFIX = "rerun.controls."


@dataclass(frozen=True)
class EntityInfo:
    """What one entity holds.

    Attributes:
        path: entity path (with its leading ``/``).
        components: component column names (e.g. ``"Points2D:positions"``).
        static_rows: number of static rows.
        rows: rows per timeline name.
    """

    path: str
    components: tuple[str, ...]
    static_rows: int
    rows: Mapping[str, int]

    @property
    def is_static(self) -> bool:
        return self.static_rows > 0


@dataclass(frozen=True)
class TimelineInfo:
    """A timeline: its name, the number of rows on it, and its smallest and largest time."""

    name: str
    rows: int
    min: int
    max: int


@dataclass(frozen=True)
class Recording:
    """The contents of an ``.rrd`` file (its first recording store).

    Attributes:
        path: the file.
        application_id, recording_id: rerun's ids of the recording.
        entities: by entity path (``"/search/best_return"`` ...), properties excluded
            (rerun's ``/__properties``).
        timelines: by name.
        n_blueprints: blueprint stores in the file (1 for a recording with a default
            layout).
        n_chunks: chunks of the recording store.
    """

    path: Path
    application_id: str
    recording_id: str
    entities: Mapping[str, EntityInfo]
    timelines: Mapping[str, TimelineInfo]
    n_blueprints: int
    n_chunks: int
    _batches: Mapping[str, list[tuple[bool, Any]]] = field(repr=False, default_factory=dict)

    def entity(self, path: str) -> EntityInfo:
        """The entity at ``path`` (leading ``/`` optional); KeyError listing them if absent."""
        key = path if path.startswith("/") else "/" + path
        if key not in self.entities:
            raise KeyError(f"no entity {key!r} in {self.path}; entities: {sorted(self.entities)}")
        return self.entities[key]

    def column(
        self, path: str, component: str, timeline: str | None = None
    ) -> list[tuple[int | None, list[Any]]]:
        """The rows of one component: ``(time, values)`` pairs, sorted by time.

        ``timeline`` None gives the static rows (time None); otherwise the rows on that
        timeline. ``component`` is a column name such as ``"Scalars:scalars"``.
        """
        info = self.entity(path)
        if component not in info.components:
            raise KeyError(
                f"{info.path} has no component {component!r}; it has {list(info.components)}"
            )
        out: list[tuple[int | None, list[Any]]] = []
        for static, batch in self._batches[info.path]:
            names = batch.schema.names
            if component not in names:
                continue
            if timeline is None:
                if not static:
                    continue
                times: list[Any] = [None] * batch.num_rows
            else:
                if static or timeline not in names:
                    continue
                times = batch.column(timeline).cast("int64").to_pylist()
            values = batch.column(component).to_pylist()
            out.extend((t, v) for t, v in zip(times, values, strict=True) if v is not None)
        if timeline is not None:
            out.sort(key=lambda tv: tv[0] if tv[0] is not None else -1)
        return out

    def latest(self, path: str, component: str, timeline: str | None = None) -> list[Any]:
        """The values of the last row of a component (static rows if ``timeline`` is None)."""
        rows = self.column(path, component, timeline)
        if not rows:
            raise KeyError(f"{path} has no rows of {component!r} on {timeline or 'static'}")
        return rows[-1][1]


def _open(path: Path, strict: bool) -> tuple[Any, Any, int, Any]:
    """``(reader, store entry, n_blueprints, chunk iterable)``; rerun errors as ValueError."""
    from rerun.chunk import RrdReader

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the no-footer warning: we raise or say it below
            reader = RrdReader(path)
            recordings = reader.recordings()
            n_blueprints = len(reader.blueprints())
    except (RuntimeError, OSError, ValueError) as exc:
        raise ValueError(
            f"{path} is not a readable rerun recording (truncated or corrupt): {exc}"
        ) from None
    if not recordings:
        raise ValueError(f"{path} holds no recording store (only {n_blueprints} blueprint(s))")
    entry = recordings[0]
    try:
        if strict:
            chunks: Any = reader.store(store=entry).stream()
        else:
            chunks = reader.stream(store=entry)
    except (RuntimeError, ValueError) as exc:
        if "footer" in str(exc).lower():
            raise ValueError(
                f"{path} is truncated: it has no RRD footer (a recording that was not closed,"
                " or a cut file); read_recording(..., strict=False) reads what is there"
            ) from None
        raise ValueError(f"{path} is not a readable rerun recording: {exc}") from None
    return reader, entry, n_blueprints, chunks


def read_recording(path: str | os.PathLike[str], *, strict: bool = True) -> Recording:
    """Read ``path`` back: entities, timelines, row counts (see :class:`Recording`).

    Args:
        path: an ``.rrd`` file.
        strict: require rerun's footer (written when a recording is closed): a file
            without it is truncated. ``strict=False`` scans whatever complete messages
            the file holds (still an error if a message is cut).

    Raises:
        ValueError: the file is missing, truncated, corrupt, or holds no recording.
    """
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"no recording file at {str(p)!r}")
    _, entry, n_blueprints, chunks = _open(p, strict)
    components: dict[str, set[str]] = {}
    static_rows: dict[str, int] = {}
    rows: dict[str, dict[str, int]] = {}
    batches: dict[str, list[tuple[bool, Any]]] = {}
    tl_rows: dict[str, int] = {}
    tl_min: dict[str, int] = {}
    tl_max: dict[str, int] = {}
    n_chunks = 0
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for chunk in chunks:
                n_chunks += 1
                ent = chunk.entity_path
                if ent.startswith("/__"):
                    continue
                batch = chunk.to_record_batch()
                timelines = list(chunk.timeline_names)
                comps = {
                    n
                    for n in batch.schema.names
                    if not n.startswith(_CONTROL_PREFIX) and n not in timelines
                }
                components.setdefault(ent, set()).update(comps)
                batches.setdefault(ent, []).append((chunk.is_static, batch))
                static_rows.setdefault(ent, 0)
                rows.setdefault(ent, {})
                if chunk.is_static:
                    static_rows[ent] += chunk.num_rows
                    continue
                for tl in timelines:
                    rows[ent][tl] = rows[ent].get(tl, 0) + chunk.num_rows
                    col = batch.column(tl).cast("int64").to_numpy()
                    tl_rows[tl] = tl_rows.get(tl, 0) + chunk.num_rows
                    if len(col):
                        lo, hi = int(col.min()), int(col.max())
                        tl_min[tl] = min(tl_min.get(tl, lo), lo)
                        tl_max[tl] = max(tl_max.get(tl, hi), hi)
    except (RuntimeError, OSError) as exc:
        raise ValueError(f"{p} is truncated or corrupt: reading its chunks failed: {exc}") from None
    entities = {
        e: EntityInfo(e, tuple(sorted(components[e])), static_rows[e], dict(rows[e]))
        for e in sorted(components)
    }
    timelines_info = {
        tl: TimelineInfo(tl, tl_rows[tl], tl_min.get(tl, 0), tl_max.get(tl, 0))
        for tl in sorted(tl_rows)
    }
    return Recording(
        p,
        entry.application_id,
        entry.recording_id,
        entities,
        timelines_info,
        n_blueprints,
        n_chunks,
        batches,
    )
