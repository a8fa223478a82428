r"""The planner interface: what any planner implements, how voot runs and measures it, and
where planners are found by name.

**The contract** (one function, in one file of your own package)::

    def my_planner(problem, budget, seed, **settings):
        ...                      # set up, e.g. rng = np.random.default_rng(seed)
        for _ in range(budget):  # one simulation per pass
            ...                  # snapshot / restore / step / is_feasible on ``problem``
            yield best_return    # the best return found so far
        return best_actions      # the plan that earns it

* ``problem`` is a :class:`MeteredProblem`: the planning protocol of
  :mod:`voot.tree.problem` (``snapshot()``, ``restore(snapshot)``, ``step(action) ->
  StepResult``, ``action_bounds()`` of the *current* state, the optional pre-check
  ``is_feasible(action)`` and ``action_metric()``), plus ``discount``, the problem's
  :math:`\gamma`. The step info (``StepResult.info``, read through
  :class:`voot.tree.step_info.StepInfo`) names the operator of the next action
  (``next_operator``, e.g. ``"pick"`` or ``"place"``), and ``action_bounds()`` is that
  operator's box, so a planner meets pick and place nodes through the same two calls.
* ``budget`` is the number of simulations: the planner yields exactly ``budget`` times.
* ``seed`` is a :class:`numpy.random.SeedSequence`: ``np.random.default_rng(seed)`` is
  the planner's generator (the same run gets the same seed in any process).
* ``settings`` are the planner's own keyword options; the values searched when tuning are
  its **grid**, a mapping ``{setting: values}`` set as the function's ``grid`` attribute
  (or per problem family, a function ``family -> {setting: values}``), every combination
  a candidate (``voot-bench plan --grid paper``).
* A yield is the best return :math:`\sum_t \gamma^t r_t` (goal bonus excluded) after that
  simulation, a finite number, or a :class:`Progress` carrying also the step info at the
  end of the best plan (its ``objects_left`` makes the objects-left curve).
* The return value is the best plan: a sequence of actions, or an object with an
  ``actions`` attribute (a :class:`voot.tree.PlanResult`, whose ``n_nodes`` and
  ``n_node_visits`` then go into the row too).

A class works as well: ``MyPlanner(problem, budget, seed, **settings)`` whose
``__iter__`` is such a generator (its ``grid`` a class attribute).

**What voot measures, not the planner** (:func:`run_planner`): the planner sees the
problem through a :class:`MeteredProblem`, which counts every executed ``step`` and every
pre-check; after each yield voot records the cumulative calls, the wall-clock and CPU
seconds (:func:`time.process_time`) since the run started. Every planner's cost is so
measured the same way. At the end voot replays the returned plan from the root and checks
that its discounted return is the last yielded one (a plan that does not replay is an
error). Every failure (an exception mid-run, a NaN or infinite return, the wrong number of
yields, a plan that does not replay) raises a :class:`PlannerError` naming the planner
and the simulation.

**Finding planners** (:class:`PlannerRegistry`): by a registered name (voot's own
planners, registered by :mod:`voot.bench.sweep.planners` through this same interface:
:func:`builtin_planner`), by an entry point of the group ``voot.planners`` that an
installed package declares (``greedy = "mypkg.planner:greedy"``), or as
``module:attribute`` (``mypkg.planner:greedy``), importable from where voot runs.

This module needs no MuJoCo: it sits beside :mod:`voot.tree` (whose planners it wraps)
and below :mod:`voot.bench` (which runs any planner through it).
"""

from __future__ import annotations

import importlib
import inspect
import itertools
import math
import time
from collections.abc import Callable, Generator, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from importlib import metadata
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from voot.optim.base import Bounds
from voot.tree.problem import FeasibilityCheck, PlanningProblem, StepResult

#: The entry-point group an outside package declares its planners in.
ENTRY_POINT_GROUP = "voot.planners"
#: The discount of a problem that declares none (the tree search's default).
DEFAULT_DISCOUNT = 0.9
#: How far a replayed plan's return may be from the planner's last yield.
REPLAY_TOLERANCE = 1e-9

#: A grid: each setting's candidate values (every combination is a candidate setting).
Axes = Mapping[str, Sequence[Any]]
#: A grid, or a grid per problem family (``"chain"``, ``"robot"``).
Grid = Axes | Callable[[str], Axes]


class PlannerError(RuntimeError):
    """A planner broke the contract or failed; the message names it (and the simulation)."""


@dataclass(frozen=True)
class Progress:
    """What a planner yields after a simulation when it has more than a number to say.

    Attributes:
        best_return: the best return so far (goal bonus excluded).
        info: the step info at the end of the best plan (e.g. ``objects_left``).
        search: the planner's own state, for observers such as a recorder of the search
            tree (None for a planner that offers none).
    """

    best_return: float
    info: Mapping[str, Any] = field(default_factory=dict)
    search: Any = None


class PlannerFunction(Protocol):
    """``planner(problem, budget, seed, **settings)``: an iterator of one best return (or
    :class:`Progress`) per simulation, whose return value is the plan (see the module)."""

    def __call__(
        self, problem: MeteredProblem, budget: int, seed: np.random.SeedSequence, **settings: Any
    ) -> Iterator[float | Progress]: ...


# ----- the problem a planner sees ---------------------------------------------------------
class MeteredProblem:
    """A planning problem as a planner receives it: the same protocol, every executed step
    and pre-check counted by voot.

    Attributes:
        problem: the problem wrapped.
        discount: the problem's discount :math:`\\gamma` (returns are
            :math:`\\sum_t \\gamma^t r_t`).
        n_steps: executed ``step`` calls so far.
        n_feasibility_checks: ``is_feasible`` calls so far.

    Anything else (``action_metric``, ``n_simulator_calls``, an env's ``unwrapped`` ...) is
    read from the wrapped problem. :func:`metered` gives a problem without a pre-check a
    wrapper without one, so ``isinstance(p, FeasibilityCheck)`` stays true to it.
    """

    def __init__(self, problem: PlanningProblem, discount: float = DEFAULT_DISCOUNT) -> None:
        self.problem = problem
        self.discount = float(discount)
        self.n_steps = 0
        self.n_feasibility_checks = 0

    @property
    def calls(self) -> int:
        """Simulator calls so far: executed steps plus pre-checks."""
        return self.n_steps + self.n_feasibility_checks

    def snapshot(self) -> Any:
        """The current state (see :class:`voot.tree.problem.PlanningProblem`)."""
        return self.problem.snapshot()

    def restore(self, snapshot: Any) -> None:
        """Go back to ``snapshot`` exactly."""
        self.problem.restore(snapshot)

    def step(self, action: NDArray[np.float64]) -> StepResult:
        """Execute ``action`` in the current state (counted)."""
        self.n_steps += 1
        return self.problem.step(action)

    def action_bounds(self) -> Bounds:
        """The action box of the current state (its operator's)."""
        return self.problem.action_bounds()

    def __getattr__(self, name: str) -> Any:
        if name == "problem":  # not set yet (e.g. while unpickling)
            raise AttributeError(name)
        return getattr(self.problem, name)


class MeteredCheckedProblem(MeteredProblem):
    """A :class:`MeteredProblem` of a problem with the pre-check (counted too)."""

    def is_feasible(self, action: NDArray[np.float64]) -> bool:
        """Pre-check ``action`` without changing the state (counted)."""
        self.n_feasibility_checks += 1
        return bool(self.problem.is_feasible(action))  # type: ignore[attr-defined]


def metered(problem: PlanningProblem, discount: float = DEFAULT_DISCOUNT) -> MeteredProblem:
    """``problem`` counted: a :class:`MeteredCheckedProblem` if it has the pre-check."""
    if isinstance(problem, FeasibilityCheck):
        return MeteredCheckedProblem(problem, discount)
    return MeteredProblem(problem, discount)


# ----- a planner and its registry ---------------------------------------------------------
@dataclass(frozen=True)
class Planner:
    """A planner by name: its function (the contract above), its grid and its version.

    Attributes:
        name: the name runs and rows carry (``"voot"``, ``"greedy"``,
            ``"mypkg.planner:greedy"``).
        function: ``function(problem, budget, seed, **settings)`` (see the module).
        grid: the settings searched when tuning: ``{setting: values}`` or a function of
            the problem family giving one (empty: the defaults only).
        version: the planner's version, kept in every row's planner config.
        builtin: whether voot ships it (its settings then are voot's own configs).
    """

    name: str
    function: Callable[..., Any]
    grid: Grid = field(default_factory=dict)
    version: str = ""
    builtin: bool = False

    def axes(self, family: str) -> Axes:
        """The grid's axes on a problem ``family``."""
        axes = self.grid(family) if callable(self.grid) else self.grid
        if not isinstance(axes, Mapping):
            raise PlannerError(
                f"planner {self.name!r}: its grid must be a mapping {{setting: values}},"
                f" got {type(axes).__name__}"
            )
        return axes

    def settings_grid(self, family: str) -> list[dict[str, Any]]:
        """Every combination of the grid's axes on ``family``, sorted by setting name."""
        axes = self.axes(family)
        names = sorted(axes)
        return [
            dict(zip(names, values, strict=True))
            for values in itertools.product(*(tuple(axes[n]) for n in names))
        ]

    def check_settings(self, settings: Mapping[str, Any]) -> None:
        """A ValueError naming the planner unless its function accepts ``settings``."""
        try:
            signature = inspect.signature(self.function)
        except (TypeError, ValueError):  # a builtin without a signature: trust it
            return
        try:
            signature.bind(None, 1, None, **settings)
        except TypeError as exc:
            params = [
                p.name
                for p in list(signature.parameters.values())[3:]
                if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)
            ]
            valid = ", ".join(params) or "none"
            raise ValueError(
                f"planner {self.name!r} does not take these settings"
                f" {sorted(settings)} ({exc}); it must be called as"
                f" {self.name}(problem, budget, seed, **settings) and its settings are: {valid}"
            ) from None


def as_planner(name: str, obj: object, version: str = "") -> Planner:
    """``obj`` (a :class:`Planner`, a planner function or a planner class) as a
    :class:`Planner` called ``name``; a :class:`PlannerError` if it cannot be one."""
    if isinstance(obj, Planner):
        return obj if obj.name == name else Planner(name, obj.function, obj.grid, obj.version)
    if not callable(obj):
        raise PlannerError(
            f"planner {name!r} is a {type(obj).__name__}, not a planner: expected a function"
            " or class called as planner(problem, budget, seed, **settings), or a"
            " voot.planners.Planner"
        )
    try:
        inspect.signature(obj).bind(None, 1, None)
    except TypeError:
        raise PlannerError(
            f"planner {name!r} ({getattr(obj, '__qualname__', obj)!r}) has the wrong"
            f" signature {inspect.signature(obj)}: a planner is called as"
            f" planner(problem, budget, seed, **settings)"
        ) from None
    except ValueError:  # no signature to read (a builtin): trust it
        pass
    grid = getattr(obj, "grid", None) or {}
    return Planner(name, obj, grid, str(getattr(obj, "version", "") or version))


def import_planner(target: str) -> Planner:
    """The planner ``module:attribute`` (``mypkg.planner:greedy``; ``a.b`` attributes
    allowed), or a :class:`PlannerError` saying what failed."""
    module_name, _, attr = target.partition(":")
    if not module_name or not attr:
        raise PlannerError(f"planner {target!r}: expected module:attribute")
    try:
        obj: Any = importlib.import_module(module_name)
    except Exception as exc:
        raise PlannerError(
            f"planner {target!r}: importing {module_name} failed: {type(exc).__name__}: {exc}"
        ) from exc
    for part in attr.split("."):
        try:
            obj = getattr(obj, part)
        except AttributeError:
            raise PlannerError(
                f"planner {target!r}: module {module_name} has no attribute {attr}"
            ) from None
    return as_planner(target, obj, _distribution_version(module_name))


def _distribution_version(module_name: str) -> str:
    """The version of the installed distribution holding ``module_name`` ("" if none)."""
    top = module_name.split(".")[0]
    for dist in metadata.packages_distributions().get(top, []):
        try:
            return metadata.version(dist)
        except metadata.PackageNotFoundError:
            continue
    return ""


def is_import_target(name: str) -> bool:
    """Whether ``name`` names a planner as ``module:attribute``."""
    return ":" in name


class PlannerRegistry:
    """Planners by name: the ones registered here, the entry points of the group
    :data:`ENTRY_POINT_GROUP` (listed once, loaded when first used), and any
    ``module:attribute``.

    Args:
        planners: planners registered at once (e.g. voot's own).
        group: the entry-point group read (None: none).
    """

    def __init__(
        self, planners: Sequence[Planner] = (), group: str | None = ENTRY_POINT_GROUP
    ) -> None:
        self._planners: dict[str, Planner] = {}
        self._group = group
        self._entry_points: dict[str, metadata.EntryPoint] | None = None
        for p in planners:
            self.register(p)

    def register(self, planner: Planner) -> Planner:
        """Add ``planner`` under its name (replacing one of that name)."""
        self._planners[planner.name] = planner
        return planner

    def entry_points(self) -> dict[str, metadata.EntryPoint]:
        """The installed entry points of the group by name (read on first use)."""
        if self._entry_points is None:
            found = metadata.entry_points(group=self._group) if self._group else ()
            self._entry_points = {ep.name: ep for ep in found if ep.name not in self._planners}
        return self._entry_points

    def names(self) -> list[str]:
        """Registered names, then the entry points' (installed plug-ins)."""
        return [*self._planners, *(n for n in self.entry_points() if n not in self._planners)]

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and (
            name in self._planners or name in self.entry_points() or is_import_target(name)
        )

    def get(self, name: str) -> Planner:
        """The planner called ``name`` (loading its entry point or module on first use).

        Raises:
            PlannerError: the plug-in failed to load or is no planner (the message names
                it and the entry point).
            KeyError: no planner has that name (the message lists the valid ones).
        """
        found = self._planners.get(name)
        if found is not None:
            return found
        ep = self.entry_points().get(name)
        if ep is not None:
            try:
                obj = ep.load()
            except Exception as exc:
                raise PlannerError(
                    f"planner {name!r} (entry point {ep.value} of"
                    f" {_dist_name(ep)}) failed to load: {type(exc).__name__}: {exc}"
                ) from exc
            version = getattr(getattr(ep, "dist", None), "version", "") or ""
            return self.register(as_planner(name, obj, version))
        if is_import_target(name):
            return self.register(import_planner(name))
        raise KeyError(
            f"unknown planner {name!r}; valid planners are: {', '.join(sorted(self.names()))},"
            f" or module:attribute (an installed package's planner, e.g. mypkg.planner:greedy)"
        )


def _dist_name(ep: metadata.EntryPoint) -> str:
    dist = getattr(ep, "dist", None)
    return f"the package {dist.name}" if dist is not None else "an installed package"


# ----- running a planner ------------------------------------------------------------------
@dataclass(frozen=True)
class Outcome:
    """One run of a planner, as voot measured it (:func:`run_planner`).

    Attributes:
        best_so_far: the yielded best return after every simulation.
        elapsed: wall-clock seconds since the run started, after every simulation.
        cpu_elapsed: CPU seconds of this process since the run started, likewise.
        calls_curve: cumulative simulator calls (steps plus pre-checks), likewise.
        info_curve: ``info[record_info]`` of every yield (None where it had none).
        actions: the plan returned.
        rewards: the plan's rewards, replayed from the root.
        n_steps: executed steps of the run.
        n_feasibility_checks: pre-checks of the run.
        simulator_calls: the problem's own count of simulator runs if it keeps one
            (``n_simulator_calls``), else steps plus pre-checks.
        wall_time: seconds of the whole run (the replay excluded).
        returned: what the planner returned (e.g. a :class:`voot.tree.PlanResult`).
    """

    best_so_far: list[float]
    elapsed: list[float]
    cpu_elapsed: list[float]
    calls_curve: list[int]
    info_curve: list[Any]
    actions: list[NDArray[np.float64]]
    rewards: list[float]
    n_steps: int
    n_feasibility_checks: int
    simulator_calls: int
    wall_time: float
    returned: Any = field(default=None, repr=False)


def run_planner(
    planner: Planner,
    problem: PlanningProblem,
    budget: int,
    seed: np.random.SeedSequence,
    settings: Mapping[str, Any] | None = None,
    *,
    discount: float = DEFAULT_DISCOUNT,
    record_info: str | None = None,
    on_simulation: Callable[[int, Progress], Any] | None = None,
) -> Outcome:
    """Run ``planner`` on ``problem`` (from its current state) for ``budget`` simulations
    and measure it; see the module docstring.

    Args:
        planner: the planner.
        problem: the problem; its current state is the root.
        budget: simulations (the planner yields exactly this many times).
        seed: the run's seed.
        settings: the planner's keyword settings.
        discount: the problem's discount, given to the planner and used by the replay.
        record_info: a step-info key to read from every :class:`Progress` (the
            ``info_curve``).
        on_simulation: called as ``on_simulation(i, progress)`` after simulation ``i``.

    Raises:
        PlannerError: the planner raised, yielded a non-finite return or the wrong number
            of times, or returned a plan that does not replay; the message names it and
            the simulation (the cause is chained).
    """
    name = planner.name
    meter = metered(problem, discount)
    root = problem.snapshot()
    own_calls = getattr(problem, "n_simulator_calls", None)
    best: list[float] = []
    elapsed: list[float] = []
    cpu: list[float] = []
    calls: list[int] = []
    infos: list[Any] = []
    clock, cpu_clock = time.perf_counter, time.process_time
    t0, c0 = clock(), cpu_clock()
    try:
        iterator = iter(planner.function(meter, budget, seed, **dict(settings or {})))
    except Exception as exc:
        raise PlannerError(
            f"planner {name!r} failed to start: {type(exc).__name__}: {exc}"
        ) from exc
    returned: Any = None
    while True:
        i = len(best)
        try:
            value = next(iterator)
        except StopIteration as stop:
            returned = stop.value
            break
        except Exception as exc:
            raise PlannerError(
                f"planner {name!r} raised {type(exc).__name__} in simulation {i + 1} of"
                f" {budget}: {exc}"
            ) from exc
        elapsed.append(clock() - t0)
        cpu.append(cpu_clock() - c0)
        calls.append(meter.calls)
        if i >= budget:
            _close(iterator)
            raise PlannerError(
                f"planner {name!r} yielded more than its budget of {budget} simulations"
            )
        progress = value if isinstance(value, Progress) else Progress(_real(value))
        ret = _real(progress.best_return)
        if not math.isfinite(ret):
            _close(iterator)
            raise PlannerError(
                f"planner {name!r} yielded the best return {progress.best_return!r} after"
                f" simulation {i + 1} of {budget}; a best return must be a finite number"
            )
        best.append(ret)
        if record_info is not None:
            infos.append(progress.info.get(record_info))
        if on_simulation is not None:
            on_simulation(i, progress)
    wall = clock() - t0
    if len(best) != budget:
        raise PlannerError(
            f"planner {name!r} yielded {len(best)} best returns for a budget of {budget}"
            " simulations (one per simulation)"
        )
    sim_calls = (
        int(problem.n_simulator_calls) - int(own_calls)  # type: ignore[attr-defined]
        if own_calls is not None
        else meter.calls
    )
    actions = _plan_actions(name, returned)
    rewards = replay(name, problem, root, actions, discount, best[-1])
    return Outcome(
        best_so_far=best,
        elapsed=elapsed,
        cpu_elapsed=cpu,
        calls_curve=calls,
        info_curve=infos,
        actions=actions,
        rewards=rewards,
        n_steps=meter.n_steps,
        n_feasibility_checks=meter.n_feasibility_checks,
        simulator_calls=sim_calls,
        wall_time=wall,
        returned=returned,
    )


def _close(iterator: Iterator[Any]) -> None:
    close = getattr(iterator, "close", None)
    if close is not None:
        close()


def _real(value: object) -> float:
    """``value`` as a float (NaN if it is no real number, for the caller's error)."""
    if isinstance(value, bool | np.bool_):
        return math.nan
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return math.nan


def _plan_actions(name: str, returned: object) -> list[NDArray[np.float64]]:
    """The actions of what planner ``name`` returned (a sequence, or ``.actions``)."""
    plan = getattr(returned, "actions", returned)
    if plan is None or isinstance(plan, str | bytes) or not isinstance(plan, Sequence | np.ndarray):
        raise PlannerError(
            f"planner {name!r} returned {type(returned).__name__}, not a plan: return the"
            " best plan's actions (a list of arrays) after the last yield"
        )
    try:
        return [np.asarray(a, dtype=np.float64).reshape(-1) for a in plan]
    except (TypeError, ValueError) as exc:
        raise PlannerError(
            f"planner {name!r} returned a plan of non-numeric actions: {exc}"
        ) from None


def replay(
    name: str,
    problem: PlanningProblem,
    root: Any,
    actions: Sequence[NDArray[np.float64]],
    discount: float,
    expected: float,
) -> list[float]:
    """Step ``actions`` from ``root`` (not counted) and return their rewards; a
    :class:`PlannerError` unless their discounted return is ``expected``. The problem is
    left at ``root``."""
    rewards: list[float] = []
    ret, weight = 0.0, 1.0
    problem.restore(root)
    try:
        for t, action in enumerate(actions):
            try:
                res = problem.step(action)
            except Exception as exc:
                raise PlannerError(
                    f"planner {name!r} returned a plan that does not replay: action {t + 1}"
                    f" of {len(actions)} raised {type(exc).__name__}: {exc}"
                ) from exc
            rewards.append(float(res.reward))
            ret += weight * float(res.reward)
            weight *= discount
            if not res.feasible or res.terminal:
                if t + 1 < len(actions):
                    raise PlannerError(
                        f"planner {name!r} returned a plan that does not replay: the episode"
                        f" ends after action {t + 1} of {len(actions)}"
                    )
    finally:
        problem.restore(root)
    if not math.isclose(ret, expected, rel_tol=REPLAY_TOLERANCE, abs_tol=REPLAY_TOLERANCE):
        raise PlannerError(
            f"planner {name!r} returned a plan that does not replay: its {len(actions)}"
            f" actions return {ret!r} from the root, the planner's best return is {expected!r}"
        )
    return rewards


# ----- voot's own planners through the same interface --------------------------------------
def builtin_planner(name: str, grid: Grid | None = None) -> Planner:
    """voot's planner ``name`` (a tree planner of :data:`voot.tree.PLANNERS` or a
    sampling-based one of :data:`voot.tree.SHOOTING_PLANNERS`) as a :class:`Planner`: its
    settings are its config's fields (:func:`voot.tree.planner_config`,
    :func:`voot.tree.shooting_config`)."""
    from voot.tree.shooting import is_shooting_planner

    function = _shooting_function(name) if is_shooting_planner(name) else _tree_function(name)
    return Planner(name, function, grid if grid is not None else {}, builtin=True)


def _tree_function(name: str) -> Callable[..., Generator[Progress, None, Any]]:
    from voot.tree.config import planner_config
    from voot.tree.mcts import MCTS

    def tree_planner(
        problem: MeteredProblem, budget: int, seed: np.random.SeedSequence, **settings: Any
    ) -> Generator[Progress, None, Any]:
        mcts = MCTS(problem, planner_config(name, **settings), seed=seed)
        for _ in mcts.iterate(budget):
            yield Progress(mcts.best_return, mcts.best_info(), mcts)
        return mcts.result()

    tree_planner.__qualname__ = tree_planner.__name__ = f"{name}_planner"
    return tree_planner


def _shooting_function(name: str) -> Callable[..., Generator[Progress, None, Any]]:
    from voot.tree.shooting import ShootingPlanner, shooting_config

    def shooting_planner(
        problem: MeteredProblem, budget: int, seed: np.random.SeedSequence, **settings: Any
    ) -> Generator[Progress, None, Any]:
        planner = ShootingPlanner(problem, shooting_config(name, **settings), seed)
        for _ in planner.iterate(budget):
            yield Progress(planner.best_return, planner.best_info(), planner)
        return planner.result()

    shooting_planner.__qualname__ = shooting_planner.__name__ = f"{name}_planner"
    return shooting_planner
