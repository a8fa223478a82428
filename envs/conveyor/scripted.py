"""Hand-chosen and searched solutions of the paper's conveyor: proof that the task is solvable.

The parameters are in the paper's units (degrees for angles, for readability).

* :data:`CONVEYOR_SOLUTION` packs all 20 boxes of ``voot/ConveyorPacking-v0`` in voot's
  rooms (7 actions, return 7.54): the two big boxes along the first room's west wall, the
  small ones in rows in the west room.
* :data:`AUTHORS_SOLUTION` packs them in the authors' rooms (``rooms="authors"``,
  :mod:`voot.envs.conveyor.authors_rooms`), whose north wall (y = 2.5) cuts voot's top row
  (y = 2.55). It was found by :func:`search_solution` over :data:`AUTHORS_BIG_SLOTS` and
  :data:`AUTHORS_SMALL_SLOTS` with the exact footprint (``base_model="footprint"``) and the
  big-box ban: the big boxes along the first room's north wall, the small ones in rows of
  three in the west room, reached through the entrance, the door and the south-west
  opening. With the disc no big box passes the authors' 1.5 m entrance, so no plan exists
  there.

The env offers the one of its rooms as
:meth:`~voot.envs.conveyor.env.ConveyorPackingEnv.solution_actions`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, cast

import numpy as np
from numpy.typing import NDArray

from voot.envs.core.units import normalize

if TYPE_CHECKING:
    from voot.envs.conveyor.env import ConveyorPackingEnv

FloatArray = NDArray[np.float64]
#: A box pose in the paper's units: x, y (m), theta (deg).
Pose = tuple[float, float, float]

_W = 180.0  # the robot faces west: box heading 180 deg
_N = 90.0  # the robot faces north
#: Conveyor: the box poses (x, y in m, theta in deg), three per action. With the fixed
#: grasp the robot faces the way the box points.
CONVEYOR_SOLUTION: tuple[Pose, ...] = (
    (-3.5, 2.1, _W),
    (-3.5, -0.05, _W),
    *(
        (x, y, _N)
        for y in (2.55, 1.95, 1.35, 0.75, 0.15, -0.45, -1.05, -1.65, -2.25)
        for x in (-6.55, -5.45)
    ),
)

#: The authors' rooms: candidate poses of the big boxes in the first room (x in [-4, -0.7],
#: y in [-0.5, 2.5]), north first, then west first, facing west then north.
AUTHORS_BIG_SLOTS: tuple[Pose, ...] = tuple(
    (round(-3.6 + 0.2 * i, 2), round(2.1 - 0.2 * j, 2), th)
    for j in range(12)
    for i in range(14)
    for th in (_W, _N)
)
#: The authors' rooms: candidate poses of the small boxes in the west room (x in
#: [-7.4, -4]): rows 0.6 m apart from the north wall down, three columns, facing north.
AUTHORS_SMALL_SLOTS: tuple[Pose, ...] = tuple(
    (x, round(2.2 - 0.6 * j, 2), _N) for j in range(9) for x in (-6.95, -5.7, -4.45)
)
#: The authors' rooms: the first feasible slot of every box, in order
#: (:func:`search_solution`; ``python -m voot.envs.conveyor.scripted`` re-derives it).
AUTHORS_SOLUTION: tuple[Pose, ...] = (
    (-3.6, 2.1, _W),
    (-2.8, 2.1, _W),
    *((x, y, _N) for y in (2.2, 1.6, 1.0, 0.4, -0.2, -0.8) for x in (-6.95, -5.7, -4.45)),
)


def solution_poses(env: ConveyorPackingEnv) -> tuple[Pose, ...]:
    """The solution table of ``env``'s rooms (module docstring)."""
    return AUTHORS_SOLUTION if env.config.rooms == "authors" else CONVEYOR_SOLUTION


def pose_actions(env: ConveyorPackingEnv, poses: Sequence[Pose]) -> list[FloatArray]:
    """``poses`` (one per box, in order) as normalised 9-D actions for ``env``'s config."""
    cfg = env.config
    poses = poses[: env.n]
    per_action = env.action_dim // 3  # boxes per action, three parameters each
    out = []
    for k in range(0, len(poses), per_action):
        a = np.zeros(3 * per_action)
        for j, (x, y, th) in enumerate(poses[k : k + per_action]):
            a[3 * j : 3 * j + 3] = normalize([x, y, math.radians(th)], cfg.place_ranges)
        out.append(a)
    return out


def conveyor_actions(env: ConveyorPackingEnv) -> list[FloatArray]:
    """The solution of ``env``'s rooms (:func:`solution_poses`) as normalised 9-D actions."""
    return pose_actions(env, solution_poses(env))


def search_solution(
    env: ConveyorPackingEnv,
    big_slots: Sequence[Pose] = AUTHORS_BIG_SLOTS,
    small_slots: Sequence[Pose] = AUTHORS_SMALL_SLOTS,
    big_boxes: int = 2,
) -> tuple[Pose, ...]:
    """A packing of ``env`` by a greedy, deterministic search over candidate slots.

    From a reset, each box in turn takes the first slot of its list (``big_slots`` for the
    first ``big_boxes`` boxes, else ``small_slots``) not taken yet whose placement
    executes in ``env``'s domain after the boxes before it (the env's own region,
    collision, ban and base-path checks); every three boxes the action is executed.

    Raises:
        ValueError: If some box has no feasible slot (no packing from these slots).
    """
    env.reset(seed=0)
    taken: set[Pose] = set()
    poses: list[Pose] = []
    while env.task.placed < env.n:
        moved: dict[int, tuple[float, float, float, float]] = {}
        lengths: list[float] = []
        paths: list[FloatArray] = []
        chosen: list[Pose] = []
        for i in range(env.task.placed, min(env.task.placed + 3, env.n)):
            for slot in big_slots if i < big_boxes else small_slots:
                if slot in taken:
                    continue
                xyt = np.array([slot[0], slot[1], math.radians(slot[2])])
                if not env._check_place(i, xyt, moved, lengths, paths)[0]:
                    taken.add(slot)
                    chosen.append(slot)
                    break
            else:
                raise ValueError(f"no slot of the list fits {env.objects[i].name}")
        _, _, _, info = env.transition(pose_actions(env, chosen)[0])
        if not info["feasible"]:  # pragma: no cover - the checks above are the step's own
            raise RuntimeError(f"a searched action failed when executed: {info['reason']}")
        poses += chosen
    return tuple(poses)


if __name__ == "__main__":  # pragma: no cover - re-derives AUTHORS_SOLUTION (about 4 CPU min)
    import gymnasium as gym

    import voot  # noqa: F401  (registers the ids; by id, so this module imports no env)

    _env = gym.make(
        "voot/ConveyorPacking-v1", rooms="authors", base_model="footprint", big_box_ban=True
    ).unwrapped
    _found = search_solution(cast("ConveyorPackingEnv", _env))
    print(_found)
    print("matches AUTHORS_SOLUTION:", _found == AUTHORS_SOLUTION)
