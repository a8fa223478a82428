"""The exact-footprint base planner: the robot's oriented footprint searched on an
(x, y, theta) lattice, the option that runs when the disc finds no path.

* :mod:`.shape`: :class:`Footprint`, :class:`FootprintConfig` and the lattice's
  occupancy (:class:`FootprintLattice`), the surface re-exported here;
* :mod:`.search`: :class:`~.search.FootprintSearch`, the query (disc first, coarse
  lattice, exact lattice, path tightening);
* :mod:`.scene`: the lazy scene, poses tested where the search looks;
* :mod:`.astar`: the A* driver and its engines; :mod:`.kernels` and
  :mod:`.pose_kernels`: its compiled loops and pose tests (numba);
* :mod:`.geodesic`: the geodesic heuristic; :mod:`.moves`: joins between lattice poses.
"""

from voot.envs.motion.footprint.shape import (
    ENGINES,
    HEURISTICS,
    Footprint,
    FootprintConfig,
    FootprintLattice,
    footprint_hits,
)

__all__ = [
    "ENGINES",
    "HEURISTICS",
    "Footprint",
    "FootprintConfig",
    "FootprintLattice",
    "footprint_hits",
]
