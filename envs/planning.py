"""The benchmark environments as :mod:`voot.tree` planning problems.

:class:`EnvProblem` adapts :class:`~voot.envs.kitchen.KitchenClearingEnv` or
:class:`~voot.envs.conveyor.ConveyorPackingEnv` (or a ``gym.make`` of them) to the
:class:`~voot.tree.problem.PlanningProblem` protocol:

* ``snapshot()`` / ``restore()`` are the env's ``get_state()`` / ``set_state()``;
* ``action_bounds()`` is the *current* operator's box: 6-D at a kitchen pick, 3-D at a
  kitchen place, 9-D on the conveyor, in normalised units ``[-1, 1]`` (default) or in the
  paper's units (``units="paper"``: radians, fractions, metres), which changes the
  metric a Voronoi sampler sees;
* ``step(action)`` pads a 3-D place action to the env's 6-D space, steps the unwrapped
  env and returns a :class:`~voot.tree.problem.StepResult` whose ``reward`` excludes the
  goal bonus, ``bonus`` is ``info["goal_bonus"]``, ``feasible`` is ``info["feasible"]``
  and ``terminal`` is terminated or truncated;
* ``is_feasible(action)`` is the pre-check (stage 1 of :mod:`voot.tree.problem`) that
  the env's ``config.precheck`` names:

  - ``"full_step"`` (v0): it steps, records the result and restores; the following
    ``step`` with the same action from the same state reuses the recorded result, so a
    check followed by its execution costs one simulation (the envs are deterministic,
    so the reuse is exact);
  - ``"kinematic"`` (v1, the authors' protocol): the env's ``precheck(action)``, which
    copies no state and steps nothing; the forbidden rooms and the base paths are
    found by ``step``.

  :attr:`EnvProblem.last_check` keeps a :class:`~voot.tree.problem.StepResult` of the
  last check (its info says where a rejected proposal would have put the robot and the
  object);
* ``action_metric()`` is the authors' per-operator distance in the planner's units
  (:mod:`voot.envs.metrics`), for ``MCTSConfig.use_problem_metric``.

It steps ``env.unwrapped`` directly (gymnasium's wrappers add nothing a planner needs;
the envs truncate at their own horizon).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.conveyor import OBJECTS_PER_ACTION, ConveyorPackingEnv
from voot.envs.kitchen import KitchenClearingEnv
from voot.envs.metrics import pick_distance, place_distance, to_action_units
from voot.envs.task_env import EnvState, ManipulationEnv, normalize
from voot.optim.base import Bounds
from voot.tree.problem import ActionDistance, StepResult

FloatArray = NDArray[np.float64]

#: Action units an :class:`EnvProblem` can expose.
UNITS = ("normalized", "paper")


class EnvProblem:
    """A voot benchmark environment as a planning problem (see the module docstring).

    Args:
        env: A :class:`KitchenClearingEnv` or :class:`ConveyorPackingEnv`, possibly
            wrapped (``gym.make("voot/KitchenClearing-v0")``).
        seed: If not None, ``env.reset(seed=seed)`` first; otherwise the problem starts
            from the env's current state.
        units: ``"normalized"`` (``[-1, 1]`` boxes) or ``"paper"`` (the parameters'
            own ranges).
    """

    def __init__(self, env: Any, seed: int | None = None, units: str = "normalized") -> None:
        u = getattr(env, "unwrapped", env)
        if not isinstance(u, KitchenClearingEnv | ConveyorPackingEnv):
            raise ValueError(
                "EnvProblem needs a KitchenClearingEnv or ConveyorPackingEnv (or a gym.make of"
                f" one); got {type(u).__name__}"
            )
        if units not in UNITS:
            raise ValueError(f"units must be one of {', '.join(UNITS)}; got {units!r}")
        self.env = env
        self.unwrapped: ManipulationEnv[Any] = u
        self.units = units
        self._dim = u.action_dim
        self._version = 0
        self._cache: tuple[int, bytes, StepResult, EnvState[Any]] | None = None
        #: The result of the last :meth:`is_feasible` call (None before the first).
        self.last_check: StepResult | None = None
        self._kinematic = u.config.precheck == "kinematic"
        self._metrics: dict[str, ActionDistance] = {}
        if seed is not None:
            u.reset(seed=seed)

    # ----- units ---------------------------------------------------------------------------
    def _ranges(self) -> Sequence[tuple[float, float]]:
        u = self.unwrapped
        if isinstance(u, KitchenClearingEnv):
            cfg = u.config
            return cfg.pick_ranges if u.task.operator == "pick" else cfg.place_ranges
        assert isinstance(u, ConveyorPackingEnv)
        return tuple(u.config.place_ranges) * OBJECTS_PER_ACTION

    def action_bounds(self) -> Bounds:
        """The current operator's action box."""
        if self.units == "paper":
            r = self._ranges()
            return Bounds([lo for lo, _ in r], [hi for _, hi in r])
        return self.unwrapped.action_bounds()

    def to_env_action(self, action: ArrayLike) -> FloatArray:
        """The env's (normalised, full-length) action for a planner's action."""
        a = np.asarray(action, dtype=np.float64).reshape(-1)
        dim = self.action_bounds().dim
        if a.shape != (dim,):
            raise ValueError(f"action must have {dim} entries at this state, got shape {a.shape}")
        if self.units == "paper":
            a = normalize(a, self._ranges())
        if dim < self._dim:
            a = np.concatenate([a, np.zeros(self._dim - dim)])
        return a

    # ----- protocol ------------------------------------------------------------------------
    def snapshot(self) -> EnvState[Any]:
        return self.unwrapped.get_state()

    def restore(self, snapshot: EnvState[Any]) -> None:
        self.unwrapped.set_state(snapshot)
        self._version += 1

    def _run(self, action: ArrayLike) -> StepResult:
        _, reward, terminated, truncated, info = self.unwrapped.step(self.to_env_action(action))
        return StepResult(
            reward=float(reward),
            feasible=bool(info["feasible"]),
            terminal=bool(terminated or truncated),
            bonus=float(info["goal_bonus"]),
            info=info,
        )

    def step(self, action: ArrayLike) -> StepResult:
        key = np.asarray(action, dtype=np.float64).tobytes()
        cache, self._cache = self._cache, None
        self._version += 1
        if cache is not None and cache[0] == self._version - 1 and cache[1] == key:
            self.unwrapped.set_state(cache[3])
            return cache[2]
        return self._run(action)

    def is_feasible(self, action: ArrayLike) -> bool:
        """Does ``action`` pass the env's pre-check now? (The state is left unchanged.)"""
        if self._kinematic:
            ok, info = self.unwrapped.precheck(self.to_env_action(action))
            reward = 0.0 if ok else float(self.unwrapped.config.infeasible_reward)
            self.last_check = StepResult(reward=reward, feasible=ok, info=info)
            return ok
        before = self.unwrapped.get_state()
        res = self._run(action)
        after = self.unwrapped.get_state()
        self.unwrapped.set_state(before)
        self._cache = (self._version, np.asarray(action, dtype=np.float64).tobytes(), res, after)
        self.last_check = res
        return res.feasible

    def action_metric(self) -> ActionDistance:
        """The authors' distance between actions of the current operator (planner units)."""
        u = self.unwrapped
        key = u.task.operator if isinstance(u, KitchenClearingEnv) else "place"
        metric = self._metrics.get(key)
        if metric is None:
            ranges = self._ranges()
            lo = np.array([r[0] for r in ranges])
            hi = np.array([r[1] for r in ranges])
            if self.units == "paper":
                scale, offset = np.ones_like(lo), np.zeros_like(lo)
            else:  # paper = lo + (a + 1) (hi - lo) / 2
                scale, offset = 0.5 * (hi - lo), lo + 0.5 * (hi - lo)
            if isinstance(u, KitchenClearingEnv):
                base = (
                    pick_distance(u.config.planner.rotation_weight)
                    if key == "pick"
                    else place_distance()
                )
            else:
                base = place_distance(OBJECTS_PER_ACTION)
            metric = to_action_units(base, scale, offset)
            self._metrics[key] = metric
        return metric
