"""The benchmark environments as :mod:`voot.tree` planning problems.

:class:`EnvProblem` adapts any robot env (:class:`~voot.envs.core.env.ManipulationEnv`:
the kitchen, the conveyor, their generated families, or a ``gym.make`` of them) to the
:class:`~voot.tree.problem.PlanningProblem` protocol, asking the env for what differs
between tasks (the current operator, its parameter ranges and distance) instead of
knowing the tasks:

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
  (:mod:`voot.envs.core.metrics`), for ``MCTSConfig.use_problem_metric``.

It steps ``env.unwrapped`` directly (gymnasium's wrappers add nothing a planner needs;
the envs truncate at their own horizon), through
:meth:`~voot.envs.core.env.ManipulationEnv.transition`: the same reward, info and next
state as ``step``, without the observation that no planner reads.

The check path is lean but exact: the problem remembers the snapshot the env is at
(after ``restore``, a cached ``step`` or ``snapshot``), so a check does not take a new
one first; an infeasible action changes nothing but the task record (the envs'
:attr:`~voot.envs.core.env.ManipulationEnv.INFEASIBLE_CHANGES_TASK_ONLY` contract: it
only counts the step), so it is undone by putting the task record back instead of a
snapshot and a full ``set_state`` (a feasible action that happened to change nothing
is detected and treated alike); the action boxes are built once per operator. Every
result, snapshot and random number is the same as with the plain step-record-restore.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V
from voot.envs.core.metrics import to_action_units
from voot.envs.core.names import Operator, Precheck, Units, choices
from voot.envs.core.state import EnvState
from voot.envs.core.units import normalize
from voot.optim.base import Bounds
from voot.tree.problem import ActionDistance, StepResult

if TYPE_CHECKING:  # the env base offers planning_problem(): no import back at run time
    from voot.envs.core.env import ManipulationEnv

FloatArray = NDArray[np.float64]
_F64 = np.dtype(np.float64)

#: Action units an :class:`EnvProblem` can expose (:class:`~voot.envs.core.names.Units`).
UNITS: tuple[Units, ...] = tuple(Units)
#: What :class:`EnvProblem` asks of the env, beyond gymnasium's API (the env base's).
_ENV_METHODS = ("transition", "precheck", "current_operator", "operator_ranges", "get_state")


class EnvProblem:
    """A voot benchmark environment as a planning problem (see the module docstring).

    Args:
        env: A robot env (a :class:`~voot.envs.core.env.ManipulationEnv`: the kitchen,
            the conveyor, their generated families), possibly wrapped
            (``gym.make("voot/KitchenClearing-v0")``). The problem asks it for the current
            operator, its parameter ranges and distance; it knows no concrete task.
        seed: If not None, ``env.reset(seed=seed)`` first (through its wrappers, so that
            the plan can be executed with ``env.step`` afterwards); otherwise the problem
            starts from the env's current state.
        units: ``"normalized"`` (``[-1, 1]`` boxes) or ``"paper"`` (the parameters'
            own ranges).
        prescreen: With the ``"full_step"`` pre-check (v0), ask the env's exact
            pre-screen (:meth:`~voot.envs.core.env.ManipulationEnv.certainly_infeasible`)
            before stepping: an action it settles as infeasible is rejected without the
            step, whose result (:attr:`last_check`, or the step of that action that
            follows) is computed only when asked for. Every answer, result, count and
            state is the one without it (False: step every check, as before); only
            the time differs.
    """

    def __init__(
        self,
        env: Any,
        seed: int | None = None,
        units: str = Units.NORMALIZED,
        prescreen: bool = True,
    ) -> None:
        u = getattr(env, "unwrapped", env)
        if not all(callable(getattr(u, name, None)) for name in _ENV_METHODS):
            raise ValueError(
                "EnvProblem needs a voot robot env (a ManipulationEnv such as the kitchen or"
                f" the conveyor, or a gym.make of one); got {type(u).__name__}"
            )
        if units not in UNITS:
            raise ValueError(f"units must be one of {choices(Units)}; got {units!r}")
        self.env = env
        self.unwrapped: ManipulationEnv[Any] = u
        self.units = Units(units)
        self._dim = u.action_dim
        self._version = 0
        self._cache: tuple[int, bytes, StepResult, EnvState[Any], EnvState[Any]] | None = None
        # a snapshot equal to the env's current state, or None if unknown
        self._here: EnvState[Any] | None = None
        self._bounds: dict[Operator, Bounds] = {}
        self._last_check: StepResult | None = None
        # the last check the env's pre-screen settled: (version, action bytes, the
        # snapshot it was made in); its result is computed only if asked for
        self._screened: tuple[int, bytes, EnvState[Any]] | None = None
        self._pending = False  # is last_check the result of _screened (not computed)?
        self._kinematic = u.config.precheck == Precheck.KINEMATIC
        if not isinstance(prescreen, bool):
            raise ValueError(f"prescreen must be True or False, got {prescreen!r}")
        #: Whether full-step checks ask the env's exact pre-screen first (see the class).
        self.prescreen = prescreen
        #: Runs of the env's simulator (``transition``), pre-checks that step included.
        self.n_simulator_calls = 0
        self._metrics: dict[Operator, ActionDistance] = {}
        if seed is not None:
            env.reset(seed=seed)  # through the wrappers, which then allow env.step

    # ----- units ---------------------------------------------------------------------------
    def _ranges(self) -> Sequence[tuple[float, float]]:
        return self.unwrapped.operator_ranges(self._operator())

    def _operator(self) -> Operator:
        return self.unwrapped.current_operator()

    def action_bounds(self) -> Bounds:
        """The current operator's action box (built once per operator and shared)."""
        key = self._operator()
        box = self._bounds.get(key)
        if box is None:
            if self.units == Units.PAPER:
                r = self._ranges()
                box = Bounds([lo for lo, _ in r], [hi for _, hi in r])
            else:
                box = self.unwrapped.action_bounds()
            self._bounds[key] = box
        return box

    def to_env_action(self, action: ArrayLike) -> FloatArray:
        """The env's (normalised, full-length) action for a planner's action.

        ``action`` must be a vector of the current operator's length of finite real
        numbers (see :func:`voot.validation.real_array`), else a ValueError that names the
        length: the problem's :meth:`step` and :meth:`is_feasible` ask this before they
        change anything (counts, caches, the env).
        """
        a = V.real_array(action, "action")
        dim = self.action_bounds().dim
        if a.shape != (dim,):
            raise ValueError(
                f"action must have {dim} entries at this state (a vector: the"
                f" {self._operator()} operator's, {self.units} units), got shape {a.shape}"
            )
        if not np.isfinite(a).all():
            bad = np.flatnonzero(~np.isfinite(a)).tolist()
            raise ValueError(f"action has NaN or infinite entries at indices {bad}: {a.tolist()}")
        if self.units == Units.PAPER:
            a = normalize(a, self._ranges())
        if dim < self._dim:
            padded = np.zeros(self._dim)
            padded[:dim] = a
            return padded
        return a

    # ----- protocol ------------------------------------------------------------------------
    def snapshot(self) -> EnvState[Any]:
        here = self._here
        # every step, reset or set_state gives the env a new task record, so an env moved
        # behind the problem's back is noticed (and snapshotted afresh)
        if here is None or here.task is not self.unwrapped.task:
            here = self._here = self.unwrapped.get_state()
        return here

    def restore(self, snapshot: EnvState[Any]) -> None:
        self.unwrapped.set_state(snapshot)
        self._here = snapshot
        self._version += 1

    @property
    def last_check(self) -> StepResult | None:
        """The result of the last :meth:`is_feasible` call (None before the first).

        Its info says where a rejected proposal would have put the robot and the object.
        A check the pre-screen settled gets its result computed here, on first access
        (the same step, from the state the check was made in; the env is left where it
        is).
        """
        if self._pending:
            self._pending = False
            screened = self._screened
            assert screened is not None
            self._last_check = self._replay(screened[2], screened[1])
        return self._last_check

    def _replay(self, before: EnvState[Any], key: bytes) -> StepResult:
        """The step of the action ``key`` (its bytes) from snapshot ``before``.

        The env is put back where it was (the problem's snapshot of it, exactly).
        """
        u = self.unwrapped
        here = self.snapshot()
        u.set_state(before)
        action = self.to_env_action(np.frombuffer(key, dtype=np.float64))
        res = self._result(*u.transition(action))
        u.set_state(here)
        self._here = here
        return res

    @staticmethod
    def _result(
        reward: float, terminated: bool, truncated: bool, info: dict[str, Any]
    ) -> StepResult:
        return StepResult(
            float(reward),
            bool(info["feasible"]),
            bool(terminated or truncated),
            float(info["goal_bonus"]),
            info,
        )

    def _transition(self, env_action: FloatArray) -> StepResult:
        """One counted run of the env's simulator on an env action."""
        self.n_simulator_calls += 1
        return self._result(*self.unwrapped.transition(env_action))

    def step(self, action: ArrayLike) -> StepResult:
        env_action = self.to_env_action(action)  # a bad action is refused before any change
        key = np.asarray(action, dtype=np.float64).tobytes()
        cache, self._cache = self._cache, None
        screened = self._screened
        self._version += 1
        if (
            screened is not None
            and screened[0] == self._version - 1
            and screened[1] == key
            and screened[2].task is self.unwrapped.task
        ):
            # the step of a check the pre-screen settled (its simulator run was counted):
            # run now, it is also the check's result
            self._screened = None
            self._here = None
            res = self._result(*self.unwrapped.transition(env_action))
            if self._pending:
                self._pending = False
                self._last_check = res
            return res
        if (
            cache is not None
            and cache[0] == self._version - 1
            and cache[1] == key
            and cache[3].task is self.unwrapped.task
        ):
            self._jump(cache[3], cache[4])
            return cache[2]
        self._here = None
        return self._transition(env_action)

    def _jump(self, before: EnvState[Any], after: EnvState[Any]) -> None:
        """Go from snapshot ``before`` (the current state) to ``after``.

        When both share the physics and generator state (``is_feasible`` makes them share
        when the step changed neither), only the task progress differs.
        """
        u = self.unwrapped
        if after.physics is before.physics and after.rng_state is before.rng_state:
            u.task = after.task
        else:
            u.set_state(after)
        self._here = after

    def is_feasible(self, action: ArrayLike) -> bool:
        """Does ``action`` pass the env's pre-check now? (The state is left unchanged.)"""
        u = self.unwrapped
        # the plain actions' entries, or the env action (a bad action is refused here,
        # before any count, cache or state changes)
        values = self._plain_values(action) if self.prescreen and not self._kinematic else None
        env_action = self.to_env_action(action) if values is None else None
        self._pending = False
        if self._kinematic:
            assert env_action is not None
            ok, info = u.precheck(env_action)
            reward = 0.0 if ok else float(u.config.infeasible_reward)
            self._last_check = StepResult(reward=reward, feasible=ok, info=info)
            return ok
        before = self._here
        if before is None or before.task is not u.task:
            before = self.snapshot()
        self._screened = None
        if values is not None:
            # the env action's entries in [-1, 1]: the pre-screen of the env action
            # (zeros after the operator's parameters), without building it
            screened = u.certainly_infeasible_values(values)
        elif self.prescreen:
            assert env_action is not None
            screened = u.certainly_infeasible(env_action)
        else:
            screened = False
        if screened:
            # counted as the step it stands for; that step runs only if asked for
            self.n_simulator_calls += 1
            key = np.asarray(action, dtype=np.float64).tobytes()
            self._cache = None
            self._screened = (self._version, key, before)
            self._pending = True
            return False
        if env_action is None:
            env_action = self.to_env_action(action)
        res = self._transition(env_action)
        if not res.feasible and u.INFEASIBLE_CHANGES_TASK_ONLY:
            # only the task record moved on (the step count): share the rest, and put
            # the task record back (what _jump does for such a pair)
            after = before.with_task(u.task)
            u.task = before.task
            self._here = before
        else:
            after = u.get_state()
            if (
                after.rng_state is before.rng_state
                and after.physics.tobytes() == before.physics.tobytes()
            ):
                after = before.with_task(after.task)
            self._jump(after, before)
        key = np.asarray(action, dtype=np.float64).tobytes()
        self._cache = (self._version, key, res, before, after)
        self._last_check = res
        return res.feasible

    def _plain_values(self, action: ArrayLike) -> list[float] | None:
        """The entries of the env action of ``action`` when it is a plain one, else None.

        Plain: normalised units, a float64 vector of the current operator's length, every
        entry in ``[-1, 1]`` (so no clipping), followed by zeros up to the env's action
        length (as :meth:`to_env_action` pads it). Anything else (paper units, another
        shape, NaN) is None, and goes the general way.
        """
        # the native float64 descriptor is a singleton: another one goes the general way
        if type(action) is not np.ndarray or action.dtype is not _F64 or action.ndim != 1:
            return None
        if self.units != Units.NORMALIZED:
            return None
        values: list[float] = action.tolist()
        box = self._bounds.get(self._operator())
        if len(values) != (box if box is not None else self.action_bounds()).dim:
            return None
        if not (min(values) >= -1.0 and max(values) <= 1.0 and math.isfinite(sum(values))):
            return None
        if len(values) < self._dim:
            values.extend([0.0] * (self._dim - len(values)))
        return values

    def action_metric(self) -> ActionDistance:
        """The authors' distance between actions of the current operator (planner units)."""
        key = self._operator()
        metric = self._metrics.get(key)
        if metric is None:
            ranges = self._ranges()
            lo = np.array([r[0] for r in ranges])
            hi = np.array([r[1] for r in ranges])
            if self.units == Units.PAPER:
                scale, offset = np.ones_like(lo), np.zeros_like(lo)
            else:  # paper = lo + (a + 1) (hi - lo) / 2
                scale, offset = 0.5 * (hi - lo), lo + 0.5 * (hi - lo)
            base = self.unwrapped.operator_distance(key)
            metric = to_action_units(base, scale, offset)
            self._metrics[key] = metric
        return metric
