"""Hand-chosen solutions of the two domains: proof that the tasks are solvable.

The parameters are in the paper's units (degrees for angles, for readability).
:data:`KITCHEN_SOLUTION` clears all seven obstacles of ``voot/KitchenClearing-v0``
(14 actions, return 7.67 with the default config); :data:`CONVEYOR_SOLUTION` packs all
20 boxes of ``voot/ConveyorPacking-v0`` (7 actions, return 7.54): the two big boxes along
the first room's west wall, the small ones in rows in the west room. They were chosen by
laying out target slots by hand and keeping grasps that a quick search found feasible.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from voot.envs.conveyor.env import OBJECTS_PER_ACTION, ConveyorPackingEnv
from voot.envs.core.units import normalize
from voot.envs.kitchen.env import KitchenClearingEnv

FloatArray = NDArray[np.float64]

#: Kitchen: (operator, parameters). Pick: grasp angle (deg), height fraction, depth
#: fraction, base distance fraction, base angle (deg), facing offset (deg).
#: Place: x, y (m), theta (deg).
KITCHEN_SOLUTION: tuple[tuple[str, tuple[float, ...]], ...] = (
    ("pick", (127, 0.86, 0.53, 0.87, 294, -30)),
    ("place", (-0.6, -3.5, 156)),
    ("pick", (153, 0.96, 0.31, 0.67, 159, 26)),
    ("place", (2.3, -1.7, 38)),
    ("pick", (174, 0.68, 0.54, 0.70, 305, -21)),
    ("place", (-0.6, -2.6, 145)),
    ("pick", (98, 0.96, 0.55, 0.69, 70, 2)),
    ("place", (1.1, 1.3, 307)),
    ("pick", (159, 0.71, 0.88, 0.89, 181, 15)),
    ("place", (0.2, -3.5, 251)),
    ("pick", (102, 0.79, 0.20, 0.87, 246, 19)),
    ("place", (0.2, -2.6, 187)),
    ("pick", (139, 0.66, 0.24, 0.74, 131, -10)),
    ("place", (1.1, 2.9, 139)),
)

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


def kitchen_actions(env: KitchenClearingEnv) -> list[FloatArray]:
    """:data:`KITCHEN_SOLUTION` as normalised 6-D actions for ``env``'s config."""
    cfg = env.config
    out = []
    for op, p in KITCHEN_SOLUTION:
        if op == "pick":
            q = [math.radians(p[0]), p[1], p[2], p[3], math.radians(p[4]), math.radians(p[5])]
            out.append(normalize(q, cfg.pick_ranges))
        else:
            a = np.zeros(6)
            a[:3] = normalize([p[0], p[1], math.radians(p[2])], cfg.place_ranges)
            out.append(a)
    return out


def conveyor_actions(env: ConveyorPackingEnv) -> list[FloatArray]:
    """:data:`CONVEYOR_SOLUTION` as normalised 9-D actions for ``env``'s config."""
    cfg = env.config
    poses = CONVEYOR_SOLUTION[: env.n]
    out = []
    for k in range(0, len(poses), OBJECTS_PER_ACTION):
        a = np.zeros(3 * OBJECTS_PER_ACTION)
        for j, (x, y, th) in enumerate(poses[k : k + OBJECTS_PER_ACTION]):
            a[3 * j : 3 * j + 3] = normalize([x, y, math.radians(th)], cfg.place_ranges)
        out.append(a)
    return out
