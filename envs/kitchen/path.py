"""The kitchen's layout as the task sees it: the fixed path and which objects are on it.

The robot's way to the sink is one fixed base path, planned once among the static
obstacles (counters, walls) from the config's ``start`` to its ``goal``. An object is an
*obstacle* while its footprint meets the swept volume of the robot's disc along that path
(:mod:`voot.envs.motion.swept_volume`). The objects are handled in a fixed order: the initial
obstacles by their position along the path (the arc length of the path point nearest
their centre), then the others; the next pick is always the first obstacle left in that
order.

:class:`ClearingPath` holds the path, the order and a memory of the swept-volume answers.
Each footprint's answer is a function of the footprint alone (the path and the radius are
fixed), so it is remembered per footprint: after a place only the moved object is new.
Apart from the env because it is the scene's geometry, not the task's progress: it is
built once per env and never changes.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np

from voot.envs.motion.planner import BasePath, Box2D
from voot.envs.motion.swept_volume import PathProbe, obstacles_on_path


class ClearingPath:
    """The fixed base path, the handling order and the obstacles on the path.

    Args:
        path: The fixed base path (static obstacles only).
        radius: The robot's disc radius along it (the swept volume's half width).
        names: The objects' names, in object order.
        boxes: The objects' footprints at the start, in object order (they fix the
            handling order).

    Attributes:
        path: The fixed base path.
        radius: The swept volume's disc radius.
        names: The objects' names.
        probe: The swept-volume test of footprints (:class:`PathProbe`).
        memo: Each footprint's answer, once asked.
        order: The handling order (object indices): the initial obstacles by position
            along the path, then the other objects.
        rank: Each object's position in :attr:`order` (for checking task records).
    """

    def __init__(
        self, path: BasePath, radius: float, names: Sequence[str], boxes: Sequence[Box2D]
    ) -> None:
        self.path = path
        self.radius = radius
        self.names = tuple(names)
        self.probe = PathProbe(path.waypoints, radius)
        self.memo: dict[Box2D, bool] = {}
        self.order = self._handling_order(boxes)
        self.rank = {i: k for k, i in enumerate(self.order)}

    def position(self, box: Box2D) -> float:
        """Arc length along the fixed path of the point nearest the box centre."""
        w = self.path.waypoints[:, :2]
        best, best_s, s0 = math.inf, 0.0, 0.0
        p = np.array([box.cx, box.cy])
        for a, b in itertools.pairwise(w):
            d = b - a
            seg = float(np.hypot(*d))
            t = 0.0 if seg == 0 else float(np.clip((p - a) @ d / seg**2, 0.0, 1.0))
            dist = float(np.hypot(*(a + t * d - p)))
            if dist < best:
                best, best_s = dist, s0 + t * seg
            s0 += seg
        return best_s

    def _handling_order(self, boxes: Sequence[Box2D]) -> tuple[int, ...]:
        """Initial obstacles by position along the path, then the other objects."""
        on = set(obstacles_on_path(self.path.waypoints, self.radius, boxes))
        first = sorted(
            (i for i, name in enumerate(self.names) if name in on),
            key=lambda i: (self.position(boxes[i]), i),
        )
        rest = [i for i in range(len(self.names)) if i not in first]
        return tuple(first + rest)

    def on_path(self, boxes: Sequence[Box2D]) -> tuple[int, ...]:
        """The objects whose footprints ``boxes`` (all, in object order) meet the path,
        in handling order.

        The answers are :func:`obstacles_on_path`'s (its :class:`PathProbe`'s),
        remembered per footprint in :attr:`memo`.
        """
        memo = self.memo
        missing = [b for b in boxes if b not in memo]
        if missing:
            if len(memo) > 100_000:
                memo.clear()
            memo.update(zip(missing, self.probe.hits(missing), strict=True))
        on = {b.name for b in boxes if memo[b]}
        names = self.names
        return tuple(i for i in self.order if names[i] in on)
