"""The synthetic planning chains as gymnasium environments (``voot/ShekelChain-v0`` ...).

``gymnasium.make("voot/ShekelChain-v0", dim=10)`` gives a :class:`SyntheticChainEnv`
over :func:`voot.tree.chains.make_chain`: the action is a point of the function's box,
the reward :math:`f(a)` plus the bonus if feasible (``info["bonus"]`` says how much of it
is bonus), else :math:`f(a) - 2`, and an infeasible action terminates the episode. The
observation is the number of feasible actions so far. The reset's info has the step's keys
(``feasible``, ``bonus``, ``value``; the value NaN: no action yet), as gymnasium's vector
envs want. The env offers
``get_state``/``set_state``, so :class:`voot.tree.GymProblem` plans in it.
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from voot.tree.chains import SyntheticChain, make_chain


class SyntheticChainEnv(gym.Env[np.ndarray, np.ndarray]):
    """A synthetic chain (see :mod:`voot.tree.chains`) as a gymnasium environment.

    Args:
        function: ``"shekel"``, ``"rastrigin"`` or ``"griewank"``.
        dim: action dimension (3, 10 and 20 have reference thresholds).
        threshold: feasibility threshold (default: the reference value).
        bonus: bonus per feasible action (default: the reference value).
        horizon: truncate after this many feasible actions (None: no limit; or use
            ``max_episode_steps`` of ``gymnasium.make``).
    """

    metadata: dict[str, Any] = {"render_modes": []}  # noqa: RUF012 - gymnasium's convention

    def __init__(
        self,
        function: str = "shekel",
        dim: int = 10,
        threshold: float | None = None,
        bonus: float | None = None,
        horizon: int | None = None,
    ) -> None:
        super().__init__()
        self.chain: SyntheticChain = make_chain(function, dim, threshold=threshold, bonus=bonus)
        self.function_name = function
        self.horizon = horizon
        b = self.chain.bounds
        self.action_space = spaces.Box(b.lower.copy(), b.upper.copy(), dtype=np.float64)
        self.observation_space = spaces.Box(0.0, np.inf, shape=(1,), dtype=np.float64)

    def _obs(self) -> np.ndarray:
        return np.array([float(self.chain.t)])

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        self.chain.t = 0
        return self._obs(), {"feasible": True, "bonus": 0.0, "value": math.nan}

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        res = self.chain.step(np.asarray(action, dtype=np.float64))
        truncated = self.horizon is not None and self.chain.t >= self.horizon
        info = {
            "feasible": bool(res.feasible),
            "bonus": float(res.bonus),
            "value": float(res.info["value"]),
        }
        return (
            self._obs(),
            float(res.reward + res.bonus),
            not res.feasible,
            bool(truncated),
            info,
        )

    def get_state(self) -> int:
        """The state: the number of feasible actions so far."""
        return self.chain.t

    def set_state(self, state: int) -> None:
        self.chain.t = int(state)


class ShekelChainEnv(SyntheticChainEnv):
    """``voot/ShekelChain-v0``: the Shekel chain (threshold 3 / 2 / 1, bonus 1)."""

    def __init__(self, dim: int = 10, **kwargs: Any) -> None:
        super().__init__("shekel", dim, **kwargs)


class GriewankChainEnv(SyntheticChainEnv):
    """``voot/GriewankChain-v0``: the Griewank chain (threshold -2 / -50 / -50, bonus 100)."""

    def __init__(self, dim: int = 10, **kwargs: Any) -> None:
        super().__init__("griewank", dim, **kwargs)


class RastriginChainEnv(SyntheticChainEnv):
    """``voot/RastriginChain-v0``: the Rastrigin chain (threshold -10 / -50 / -100, bonus 100)."""

    def __init__(self, dim: int = 10, **kwargs: Any) -> None:
        super().__init__("rastrigin", dim, **kwargs)
