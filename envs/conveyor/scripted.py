"""A hand-chosen solution of the paper's conveyor: proof that the task is solvable.

The parameters are in the paper's units (degrees for angles, for readability).
:data:`CONVEYOR_SOLUTION` packs all 20 boxes of ``voot/ConveyorPacking-v0`` (7 actions,
return 7.54): the two big boxes along the first room's west wall, the small ones in rows in
the west room. The env offers it as
:meth:`~voot.envs.conveyor.env.ConveyorPackingEnv.solution_actions`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from voot.envs.core.units import normalize

if TYPE_CHECKING:
    from voot.envs.conveyor.env import ConveyorPackingEnv

FloatArray = NDArray[np.float64]

_W = 180.0  # the robot faces west: box heading 180 deg
_N = 90.0  # the robot faces north
#: Conveyor: the box poses (x, y in m, theta in deg), three per action. With the fixed
#: grasp the robot faces the way the box points.
CONVEYOR_SOLUTION: tuple[tuple[float, float, float], ...] = (
    (-3.5, 2.1, _W),
    (-3.5, -0.05, _W),
    *(
        (x, y, _N)
        for y in (2.55, 1.95, 1.35, 0.75, 0.15, -0.45, -1.05, -1.65, -2.25)
        for x in (-6.55, -5.45)
    ),
)


def conveyor_actions(env: ConveyorPackingEnv) -> list[FloatArray]:
    """:data:`CONVEYOR_SOLUTION` as normalised 9-D actions for ``env``'s config."""
    cfg = env.config
    poses = CONVEYOR_SOLUTION[: env.n]
    per_action = env.action_dim // 3  # boxes per action, three parameters each
    out = []
    for k in range(0, len(poses), per_action):
        a = np.zeros(3 * per_action)
        for j, (x, y, th) in enumerate(poses[k : k + per_action]):
            a[3 * j : 3 * j + 3] = normalize([x, y, math.radians(th)], cfg.place_ranges)
        out.append(a)
    return out
