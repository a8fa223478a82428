"""Helpers shared by the kitchen's test modules (not a test module itself)."""

from __future__ import annotations

import numpy as np

from voot.envs.core.units import normalize
from voot.envs.kitchen.env import KitchenClearingEnv


def place_action(env: KitchenClearingEnv, x: float, y: float, theta: float) -> np.ndarray:
    """The normalised action placing the held object at ``(x, y, theta)``."""
    a = np.zeros(6)
    a[:3] = normalize([x, y, theta], env.config.place_ranges)
    return a
