"""A tiny generated family for the tests of the layout axis (a helper, not a test module).

``voot-test/LayoutChain-v0`` is the 3-D Shekel chain whose feasibility threshold is
drawn from its ``layout_seed`` (log-uniform in :math:`[10^{-4.5}, 10^{-3.5}]`, where a
uniform action's value lies): each layout is another instance of one family, cheap
enough for end-to-end sweeps in tests. It takes ``difficulty`` too (``easy`` lowers the
threshold ten times), as the generated v2 families do; an episode ends after 5 feasible
actions (a rollout of a planner that keeps finding feasible actions ends too). It is
registered on import (idempotent), with ``voot-test/PlainChain-v0`` (a fixed chain that
takes no layout seed), only in the test process: the tests run it on the
serial backend (``--workers 1``).
"""

from __future__ import annotations

import gymnasium
import numpy as np

from voot.envs.chains.env import SyntheticChainEnv

LAYOUT_ENV_ID = "voot-test/LayoutChain-v0"
#: A chain env whose constructor takes no layout seed (nor ``**kwargs``).
PLAIN_ENV_ID = "voot-test/PlainChain-v0"
DIFFICULTIES = ("easy", "medium")


class LayoutChainEnv(SyntheticChainEnv):
    """The 3-D Shekel chain with a layout-dependent threshold (see the module docstring)."""

    def __init__(
        self, layout_seed: int = 0, difficulty: str = "medium", dim: int = 3, horizon: int = 5
    ) -> None:
        if difficulty not in DIFFICULTIES:
            raise ValueError(f"difficulty must be one of {', '.join(DIFFICULTIES)}")
        exponent = float(np.random.default_rng(int(layout_seed)).uniform(-4.5, -3.5))
        if difficulty == "easy":
            exponent -= 1.0
        super().__init__("shekel", dim, threshold=10.0**exponent, horizon=horizon)
        self.layout_seed = int(layout_seed)


def plain_chain(dim: int = 3) -> SyntheticChainEnv:
    """The 3-D Shekel chain, one fixed instance (:data:`PLAIN_ENV_ID`)."""
    return SyntheticChainEnv("shekel", dim)


def register() -> str:
    """Register :data:`LAYOUT_ENV_ID` and :data:`PLAIN_ENV_ID` (once); the first's id."""
    if LAYOUT_ENV_ID not in gymnasium.registry:
        gymnasium.register(LAYOUT_ENV_ID, entry_point=LayoutChainEnv)
    if PLAIN_ENV_ID not in gymnasium.registry:
        gymnasium.register(PLAIN_ENV_ID, entry_point=plain_chain)
    return LAYOUT_ENV_ID


register()
