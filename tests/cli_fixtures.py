"""Tiny ``voot-bench`` command lines shared by the tests of the command line (a helper,
not a test module): each runs in a second or two."""

from __future__ import annotations

#: ``voot-bench plan`` options: two planners, two seeds, 12 simulations on the 3-D chain.
PLAN_TINY = (
    "--problems shekel_chain --dims 3 --planners voot pw_uct --seeds 2 --simulations 12"
    " --grid default --workers 1 --no-progress"
).split()
