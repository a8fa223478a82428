"""A tiny generated family for the tests of the layout axis (a helper, not a test module).

``voot-test/LayoutChain-v0`` is the 3-D Shekel chain whose feasibility threshold is
drawn from its ``layout_seed`` (log-uniform in :math:`[10^{-4.5}, 10^{-3.5}]`, where a
uniform action's value lies): each layout is another instance of one family, cheap
enough for end-to-end sweeps in tests. It takes ``difficulty`` too (``easy`` lowers the
threshold ten times), as the generated v2 families do. It is
registered on import (idempotent), only in the test process: the tests run it on the
serial backend (``--workers 1``).
"""

from __future__ import annotations

import gymnasium
import numpy as np

from voot.envs.chain_env import SyntheticChainEnv

LAYOUT_ENV_ID = "voot-test/LayoutChain-v0"
DIFFICULTIES = ("easy", "medium")


class LayoutChainEnv(SyntheticChainEnv):
    """The 3-D Shekel chain with a layout-dependent threshold (see the module docstring)."""

    def __init__(self, layout_seed: int = 0, difficulty: str = "medium", dim: int = 3) -> None:
        if difficulty not in DIFFICULTIES:
            raise ValueError(f"difficulty must be one of {', '.join(DIFFICULTIES)}")
        exponent = float(np.random.default_rng(int(layout_seed)).uniform(-4.5, -3.5))
        if difficulty == "easy":
            exponent -= 1.0
        super().__init__("shekel", dim, threshold=10.0**exponent)
        self.layout_seed = int(layout_seed)


def register() -> str:
    """Register :data:`LAYOUT_ENV_ID` (once) and return it."""
    if LAYOUT_ENV_ID not in gymnasium.registry:
        gymnasium.register(LAYOUT_ENV_ID, entry_point=LayoutChainEnv)
    return LAYOUT_ENV_ID


register()
