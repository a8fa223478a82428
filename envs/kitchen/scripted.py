"""A hand-chosen solution of the paper's kitchen: proof that the task is solvable.

The parameters are in the paper's units (degrees for angles, for readability).
:data:`KITCHEN_SOLUTION` clears all seven obstacles of ``voot/KitchenClearing-v0``
(14 actions, return 7.67 with the default config). It was chosen by laying out target
slots by hand and keeping grasps that a quick search found feasible. The env offers it as
:meth:`~voot.envs.kitchen.env.KitchenClearingEnv.solution_actions`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from voot.envs.core.names import Operator
from voot.envs.core.units import normalize

if TYPE_CHECKING:
    from voot.envs.kitchen.env import KitchenClearingEnv

FloatArray = NDArray[np.float64]

#: Kitchen: (operator, parameters). Pick: grasp angle (deg), height fraction, depth
#: fraction, base distance fraction, base angle (deg), facing offset (deg).
#: Place: x, y (m), theta (deg).
KITCHEN_SOLUTION: tuple[tuple[Operator, tuple[float, ...]], ...] = (
    (Operator.PICK, (127, 0.86, 0.53, 0.87, 294, -30)),
    (Operator.PLACE, (-0.6, -3.5, 156)),
    (Operator.PICK, (153, 0.96, 0.31, 0.67, 159, 26)),
    (Operator.PLACE, (2.3, -1.7, 38)),
    (Operator.PICK, (174, 0.68, 0.54, 0.70, 305, -21)),
    (Operator.PLACE, (-0.6, -2.6, 145)),
    (Operator.PICK, (98, 0.96, 0.55, 0.69, 70, 2)),
    (Operator.PLACE, (1.1, 1.3, 307)),
    (Operator.PICK, (159, 0.71, 0.88, 0.89, 181, 15)),
    (Operator.PLACE, (0.2, -3.5, 251)),
    (Operator.PICK, (102, 0.79, 0.20, 0.87, 246, 19)),
    (Operator.PLACE, (0.2, -2.6, 187)),
    (Operator.PICK, (139, 0.66, 0.24, 0.74, 131, -10)),
    (Operator.PLACE, (1.1, 2.9, 139)),
)


def kitchen_actions(env: KitchenClearingEnv) -> list[FloatArray]:
    """:data:`KITCHEN_SOLUTION` as normalised 6-D actions for ``env``'s config."""
    cfg = env.config
    out = []
    for op, p in KITCHEN_SOLUTION:
        if op == Operator.PICK:
            q = [math.radians(p[0]), p[1], p[2], p[3], math.radians(p[4]), math.radians(p[5])]
            out.append(normalize(q, cfg.pick_ranges))
        else:
            a = np.zeros(6)
            a[:3] = normalize([p[0], p[1], math.radians(p[2])], cfg.place_ranges)
            out.append(a)
    return out
