"""Plan in gymnasium environments: adapters to the planning-problem protocol.

* :class:`GymProblem` works with any environment whose *unwrapped* env offers
  ``get_state()`` / ``set_state(state)`` (the voot environments do);
* :class:`MujocoGymProblem` works with gymnasium's own MuJoCo environments
  (``Reacher-v5``, ``InvertedPendulum-v5`` ...), saving the physics with
  ``mujoco.mj_getState`` / ``mj_setState`` under the ``mjSTATE_INTEGRATION`` signature
  (everything that changes the next step: time, qpos, qvel, act, warm start, controls,
  applied forces, mocap, equality activations, user data, plugin state).

Both also save the step counters of the wrappers that keep one (gymnasium's
``TimeLimit``), so a restored env truncates at the same step. A step's
:class:`~voot.tree.problem.StepResult` reads the env's ``info``: ``info["feasible"]``
(default True) and ``info["bonus"]`` (default 0), the part of the reward that is a goal
bonus (it is moved out of :attr:`StepResult.reward` into :attr:`StepResult.bonus`). The
step is terminal when the env terminates or truncates. If the unwrapped env has
``action_bounds()`` (a per-state box) or ``is_feasible(action)``, they are used.

An env that offers its own adapter (a ``planning_problem()`` method: voot's robot envs,
``voot/KitchenClearing-v1`` and the rest) is refused by both, with a message naming
:class:`~voot.envs.core.problem.EnvProblem`: its action length changes between operators
(6 values at a kitchen pick, 3 at a place, padded to the action space by the adapter),
its goal bonus is ``info["goal_bonus"]``, its pre-check and task record are its own, and
a gymnasium-level adapter would get each of them silently wrong. The chains' ids
(``voot/ShekelChain-v0`` ...) work with :class:`GymProblem`.

Neither this module nor :mod:`voot.tree` imports MuJoCo: :class:`MujocoGymProblem`
imports it when constructed.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from voot.optim.base import Bounds, FloatArray
from voot.tree.problem import StepResult
from voot.validation import real_number


def box_bounds(space: Any) -> Bounds:
    """The :class:`Bounds` of a 1-D, finite gymnasium ``Box`` action space."""
    low = getattr(space, "low", None)
    high = getattr(space, "high", None)
    if low is None or high is None:
        raise ValueError(
            f"the action space must be a gymnasium Box with finite bounds, got {space!r}"
        )
    low, high = np.asarray(low, dtype=np.float64), np.asarray(high, dtype=np.float64)
    if low.ndim != 1:
        raise ValueError(
            f"the action box must be 1-D (a vector of {low.size} numbers); got shape {low.shape}"
        )
    if not (np.all(np.isfinite(low)) and np.all(np.isfinite(high))):
        raise ValueError(
            f"the action box must be finite to be searched, got low={low.tolist()} high={high.tolist()}"
        )
    return Bounds(low, high)


def _counter_wrappers(env: Any) -> list[Any]:
    """Wrappers in ``env``'s chain that count steps (``TimeLimit._elapsed_steps``)."""
    out = []
    w = env
    while w is not None:
        if hasattr(w, "_elapsed_steps"):
            out.append(w)
        w = getattr(w, "env", None)
    return out


def _refuse_own_adapter(env: Any) -> None:
    """Raise ValueError if ``env`` offers its own planning adapter (``planning_problem()``),
    naming it (see the module docstring)."""
    u = env.unwrapped
    if callable(getattr(u, "planning_problem", None)):
        spec = getattr(env, "spec", None)
        name = spec.id if spec is not None else type(u).__name__
        raise ValueError(
            f"{name} has its own planning adapter, which a gymnasium-level one cannot stand"
            " in for (its action length changes between operators, its goal bonus is"
            " info['goal_bonus'], its pre-check and task record are its own): use"
            " EnvProblem(env) (from voot.envs.core.problem import EnvProblem), or"
            " env.unwrapped.planning_problem(env)"
        )


class GymProblem:
    """A gymnasium env with ``get_state``/``set_state`` as a planning problem.

    Args:
        env: the environment (wrappers allowed); not one with its own adapter (a
            ``planning_problem()`` method, as voot's robot envs have: a ValueError names
            :class:`~voot.envs.core.problem.EnvProblem`).
        seed: if not None, ``env.reset(seed=seed)`` first; otherwise the env must have
            been reset already (the adapter starts from its current state).
        bonus_key: info key of the goal-bonus part of the reward.
        feasible_key: info key of the feasibility flag.
    """

    def __init__(
        self,
        env: Any,
        seed: int | None = None,
        *,
        bonus_key: str = "bonus",
        feasible_key: str = "feasible",
    ) -> None:
        self.env = env
        self.unwrapped = env.unwrapped
        #: Calls of the env's ``step`` (the simulator) through this problem.
        self.n_simulator_calls = 0
        _refuse_own_adapter(env)
        self._check_state_api()
        self.bonus_key = bonus_key
        self.feasible_key = feasible_key
        self._bounds = box_bounds(env.action_space)
        self._counters = _counter_wrappers(env)
        self._state_bounds: Callable[[], Any] | None = getattr(
            self.unwrapped, "action_bounds", None
        )
        check = getattr(self.unwrapped, "is_feasible", None)
        if callable(check):
            #: Present only when the env offers it (the search then retries new actions).
            self.is_feasible: Callable[[FloatArray], bool] = check
        if seed is not None:
            env.reset(seed=seed)
        #: The observation after the last step (or reset).
        self.last_observation: Any = None

    def _check_state_api(self) -> None:
        for method in ("get_state", "set_state"):
            if not callable(getattr(self.unwrapped, method, None)):
                raise ValueError(
                    f"{type(self.unwrapped).__name__} has no {method}(); GymProblem needs an"
                    " unwrapped env with get_state()/set_state() (use MujocoGymProblem for"
                    " gymnasium's MuJoCo envs)"
                )

    # ----- protocol ------------------------------------------------------------------------
    def _get_physics(self) -> Any:
        return self.unwrapped.get_state()

    def _set_physics(self, state: Any) -> None:
        self.unwrapped.set_state(state)

    def snapshot(self) -> tuple[Any, tuple[int, ...]]:
        return self._get_physics(), tuple(int(w._elapsed_steps) for w in self._counters)

    def restore(self, snapshot: tuple[Any, tuple[int, ...]]) -> None:
        physics, counters = snapshot
        self._set_physics(physics)
        for w, n in zip(self._counters, counters, strict=True):
            w._elapsed_steps = n

    def action_bounds(self) -> Bounds:
        """The env's ``action_bounds()`` if it has one, else its action space's box.

        ``action_bounds()`` may return a :class:`Bounds` or a ``(lower, upper)`` tuple.
        """
        if self._state_bounds is None:
            return self._bounds
        raw = self._state_bounds()
        if isinstance(raw, Bounds):
            return raw
        if isinstance(raw, tuple) and len(raw) == 2:
            return Bounds(raw[0], raw[1])
        return Bounds.coerce(raw)

    def step(self, action: FloatArray) -> StepResult:
        obs, reward, terminated, truncated, info = self.env.step(action)
        self.n_simulator_calls += 1
        self.last_observation = obs
        bonus = info.get(self.bonus_key, 0.0)
        if type(reward) is not float or type(bonus) is not float:
            reward, bonus = (
                _step_value(action, "reward", reward),
                _step_value(action, f"info[{self.bonus_key!r}]", bonus),
            )
        return StepResult(
            reward - bonus,
            feasible=bool(info.get(self.feasible_key, True)),
            terminal=bool(terminated or truncated),
            bonus=bonus,
            info=info,
        )


class MujocoGymProblem(GymProblem):
    """A gymnasium MuJoCo env (``MujocoEnv``) as a planning problem.

    Snapshots hold the ``mjSTATE_INTEGRATION`` state vector (a read-only float64 array)
    and the wrappers' step counters. ``restore`` also runs ``mj_forward`` so that derived
    quantities (body positions) match the state, as after a step (set ``forward=False``
    to skip it; the next step recomputes them anyway).

    Args:
        env: the environment (wrappers allowed).
        seed: as for :class:`GymProblem`.
        forward: run ``mj_forward`` after each restore.
        **keys: ``bonus_key`` and ``feasible_key``, as for :class:`GymProblem`.
    """

    def __init__(
        self, env: Any, seed: int | None = None, *, forward: bool = True, **keys: str
    ) -> None:
        import mujoco

        self._mujoco = mujoco
        self.forward = forward
        super().__init__(env, seed, **keys)
        self._model = self.unwrapped.model
        self._sig = int(mujoco.mjtState.mjSTATE_INTEGRATION)
        self._size = int(mujoco.mj_stateSize(self._model, self._sig))

    def _check_state_api(self) -> None:
        u = self.unwrapped
        if not (hasattr(u, "model") and hasattr(u, "data")):
            raise ValueError(
                f"{type(u).__name__} is not a gymnasium MuJoCo env (no model/data);"
                " use GymProblem for envs with get_state()/set_state()"
            )

    def _get_physics(self) -> FloatArray:
        state = np.empty(self._size)
        self._mujoco.mj_getState(self._model, self.unwrapped.data, state, self._sig)
        state.setflags(write=False)
        return state

    def _set_physics(self, state: FloatArray) -> None:
        data = self.unwrapped.data
        self._mujoco.mj_setState(self._model, data, state, self._sig)
        if self.forward:
            self._mujoco.mj_forward(self._model, data)


def _step_value(action: FloatArray, what: str, value: object) -> float:
    """A reward (or goal bonus) of ``env.step(action)`` as a float, or a ValueError naming
    the step: None, a string, a bool or a complex number is not read as some number."""
    try:
        return real_number(value, what)
    except ValueError as exc:
        raise ValueError(
            f"env.step(action={np.asarray(action).tolist()}) returned {exc}; a gymnasium"
            " reward is a real number"
        ) from None
