"""Rerun recordings of searches and plans, and videos of plans (needs the ``[record]`` extra).

* :class:`SearchRecorder`: a search callback writing a ``.rrd`` file (scalars over
  simulations, sampled actions coloured by :math:`\\hat Q`, the tree as a graph, the best
  plan, the MuJoCo scene), with a default viewer layout; :func:`record_plan` in one call;
* :func:`read_recording`: read a ``.rrd`` back (entities, timelines, counts);
* :mod:`voot.record.mujoco_scene`: any ``MjModel`` in rerun;
* :mod:`voot.record.video`: a GIF/MP4 of a plan, rendered headless by MuJoCo;
* :mod:`voot.bench.measure.overhead`: the cost of recording (a ``voot-bench`` command).

Names are imported lazily, so ``voot.record.video`` works without rerun installed.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from voot.record.config import RecorderConfig
    from voot.record.reader import Recording, read_recording
    from voot.record.recorder import SearchRecorder, combine_callbacks, record_plan
    from voot.record.video import plan_frames, write_plan_video, write_video

_EXPORTS = {
    "RecorderConfig": "voot.record.config",
    "Recording": "voot.record.reader",
    "read_recording": "voot.record.reader",
    "SearchRecorder": "voot.record.recorder",
    "combine_callbacks": "voot.record.recorder",
    "record_plan": "voot.record.recorder",
    "plan_frames": "voot.record.video",
    "write_plan_video": "voot.record.video",
    "write_video": "voot.record.video",
}

__all__ = [
    "RecorderConfig",
    "Recording",
    "SearchRecorder",
    "combine_callbacks",
    "plan_frames",
    "read_recording",
    "record_plan",
    "write_plan_video",
    "write_video",
]


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'voot.record' has no attribute {name!r}")
    return getattr(importlib.import_module(module), name)
