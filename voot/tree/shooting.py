r"""Sampling-based MPC over the planning protocol: CEM, MPPI, predictive sampling, shooting.

These planners search *open-loop action sequences* of a fixed horizon :math:`H` instead
of a tree. One **simulation** is one rollout from the root: restore the root snapshot,
then ``step`` the sequence's actions one by one until an action is infeasible, the state
is terminal, or :math:`H` actions were taken. Its *objective* is
:math:`J = \sum_t \gamma^t (r_t + b_t)` (the value the tree backs up, goal bonus
:math:`b_t` included); its *return* :math:`R = \sum_t \gamma^t r_t` (bonus excluded) is
what the best-return curve reports, exactly as for the tree search.

**Actions per state.** The action box can change with the state (a kitchen pick is 6-D,
a place 3-D), so a sequence is stored in normalised coordinates
:math:`z_t \in [-1, 1]^W` per step and mapped to the box of the state *when the rollout
gets there*: :math:`a_t = l + (z_t[:d] + 1)(h - l)/2` for the box :math:`[l, h]` of
dimension :math:`d` returned by ``action_bounds()`` at that state. :math:`[-1, 1]` (not
:math:`[0, 1]`) because the noise defaults of MuJoCo MPC are given for its usual control
range :math:`[-1, 1]`, so they carry over unchanged (and the robot domains' boxes already
are :math:`[-1, 1]`). :math:`W` is the largest box dimension met so far; when a wider box
appears, the distribution gains columns at its initial values and the samples of the
current iteration gain draws for them (those samples never used them). Coordinates a
rollout did not use (steps after its end, entries beyond a step's :math:`d`) are still
draws of the distribution, so a refit treats them as uninformative noise.

**Rewards and goal bonuses must be finite**: a step returning NaN or an infinity raises
the tree search's ValueError (:func:`voot.tree.problem.non_finite_step_error`, naming the
step's action and value); the rollout it cut short is discarded, and a later ``search``
starts again from the root.

**Infeasible actions** are executed, earn their reward (-2 on the robot domains and the
chains) and end the rollout, as in the tree search. CEM, MPPI and predictive sampling
never use the problem's optional pre-check (``is_feasible``): a Gaussian over whole
sequences has no notion of re-drawing one step until it passes, and re-drawing would
change the distribution the update assumes (their ``n_feasibility_checks`` is 0).
Random shooting keeps no distribution, so it can: with
``RandomShootingConfig.feasibility_retries`` :math:`= k > 0` each step's action is
re-drawn uniformly until it passes the pre-check, at most :math:`k` draws in all, and
the last draw is executed feasible or not: the tree search's two stages
(:meth:`voot.tree.mcts.MCTS.add_action`, the authors' 50 tries) applied to every step
of a rollout. The default :math:`k = 0` never pre-checks.

**Methods** (:data:`SHOOTING_PLANNERS`), every constant a named option:

``random_shooting`` (:class:`RandomShootingConfig`)
    Every sequence uniform in :math:`[-1, 1]^{H \times W}`; the reference (optionally
    with the pre-check, ``feasibility_retries``).
``cem`` (:class:`CEMConfig`)
    Cross-entropy method (Rubinstein and Kroese, *The Cross-Entropy Method*, 2004), as
    used for MPC by PETS (Chua et al., 2018): a diagonal Gaussian over the sequence;
    each iteration draws ``population`` sequences (clipped to the box), keeps the
    ``elites`` best by :math:`J`, and moves mean and variance towards theirs with
    ``smoothing`` :math:`\alpha`: :math:`\mu \leftarrow \alpha\mu + (1-\alpha)\mu_e`,
    :math:`\sigma^2 \leftarrow \alpha\sigma^2 + (1-\alpha)\sigma_e^2`, with
    :math:`\sigma \ge` ``min_std``.
``mppi`` (:class:`MPPIConfig`)
    Model predictive path integral control (Williams et al., "Information theoretic MPC
    for model-based reinforcement learning", ICRA 2017): each iteration draws
    ``population`` sequences :math:`\mu + \epsilon`, :math:`\epsilon \sim
    \mathcal{N}(0, \sigma^2)` (``noise``, clipped to the box) and sets
    :math:`\mu \leftarrow \sum_k w_k z_k` with
    :math:`w_k \propto \exp((J_k - \max_j J_j)/\lambda)` (``temperature``); the noise
    stays fixed.
``predictive_sampling`` (:class:`PredictiveSamplingConfig`)
    Predictive sampling (Howell et al., "Predictive Sampling: Real-time Behaviour
    Synthesis with MuJoCo", 2022): a nominal sequence (initially the box centre) and,
    each iteration, ``population - 1`` noisy copies :math:`z_0 + \epsilon`; the best of
    the nominal and the copies becomes the nominal. The problems are deterministic, so
    the nominal's return is known from the rollout that made it nominal and it is rolled
    out only once (MuJoCo MPC re-rolls it because its state moves between iterations).
    MuJoCo MPC's policy is a spline over time; here one knot per step (zero order),
    since a step is one high-level action.

A budget that is not a multiple of the population ends with a partial iteration (its
rollouts count; no update follows). :class:`ShootingPlanner` returns the
:class:`~voot.tree.search.PlanResult` of the tree search, so sweeps, the result store and
the plots treat both alike; ``n_nodes`` is 0 (no tree is kept), ``n_node_visits`` equals
``n_steps`` (every action taken in a rollout is a ``step`` call), ``mcts`` is None.

Deterministic given the seed: one :class:`numpy.random.Generator` per planner.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, replace
from functools import partial
from types import MappingProxyType
from typing import Any, ClassVar

import numpy as np

from voot import validation as V
from voot.optim.base import Bounds, FloatArray
from voot.tree.problem import PlanningProblem, check_problem, problem_bounds, step_values
from voot.tree.search import PlanResult, Search, check_n_simulations

#: ``callback(planner, simulation_index)`` after every simulation; True stops early.
ShootingCallback = Callable[["ShootingPlanner", int], Any]


@dataclass(frozen=True)
class ShootingConfig:
    """Options every sampling-based planner shares.

    Attributes:
        horizon: :math:`H`, actions per sequence (a rollout stops earlier at an
            infeasible action or a terminal state). 20: the conveyor's episode length and
            more than the 14 steps (7 obstacles, pick and place) that clear the kitchen;
            the robot envs truncate their episodes themselves (kitchen 50, conveyor 20).
        gamma: discount :math:`\\gamma \\in [0, 1]` of returns and objectives (0.9 as the
            tree search's default; the benchmark sets the problem's, e.g. 0.99 conveyor).
    """

    horizon: int = 20
    gamma: float = 0.9

    #: The planner's registry name.
    name: ClassVar[str] = ""
    #: Field -> check, run in this order by ``__post_init__`` (a subclass extends it).
    _checks: ClassVar[Mapping[str, V.Check]] = {
        "horizon": partial(V.integer, low=1),
        "gamma": V.probability,
    }

    def __post_init__(self) -> None:
        V.check_fields(self, self._checks)

    def replace(self, **changes: Any) -> ShootingConfig:
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        """Plain values, with the planner's name (e.g. for a results row)."""
        return {"planner": self.name, **asdict(self)}


@dataclass(frozen=True)
class RandomShootingConfig(ShootingConfig):
    """Uniform random shooting: independent uniform sequences (the reference).

    Attributes:
        feasibility_retries: :math:`k`, uniform draws per step until one passes the
            problem's pre-check (``is_feasible``), the last executed in any case; 0 (the
            default) never pre-checks, 50 is the authors' number of tries for a new
            action of every tree planner. Ignored by a problem without a pre-check.
    """

    feasibility_retries: int = 0

    name: ClassVar[str] = "random_shooting"
    _checks: ClassVar[Mapping[str, V.Check]] = {
        **ShootingConfig._checks,
        "feasibility_retries": partial(V.integer, low=0),
    }


@dataclass(frozen=True)
class CEMConfig(ShootingConfig):
    """The cross-entropy method over action sequences (module docstring).

    Attributes:
        population: sequences per iteration. PETS (Chua et al., 2018) used 400-500 with
            5 iterations per action; 50 here, a tenth, gives about 40 iterations in the
            paper's 2,000-simulation kitchen budget.
        elites: best sequences the Gaussian is refitted to: 5, PETS's 10% of the
            population (Rubinstein and Kroese's rarity parameter :math:`\\rho = 0.1`).
        init_std: initial standard deviation in normalised units: 0.5, PETS's initial
            variance :math:`(h - l)^2/16` in the box :math:`[-1, 1]`.
        min_std: floor of the standard deviation: :math:`\\sqrt{0.001} \\approx 0.032`,
            PETS's variance threshold :math:`\\epsilon = 0.001` (where PETS stops
            refining, this planner keeps sampling until its budget is spent).
        smoothing: :math:`\\alpha`, the weight of the old mean and variance in each
            update: 0.1, PETS's ``alpha`` (Rubinstein and Kroese suggest 0.1-0.3 as
            :math:`1 - \\alpha`-type smoothing; PETS weights the old values).
    """

    population: int = 50
    elites: int = 5
    init_std: float = 0.5
    min_std: float = math.sqrt(0.001)
    smoothing: float = 0.1

    name: ClassVar[str] = "cem"
    _checks: ClassVar[Mapping[str, V.Check]] = {
        **ShootingConfig._checks,
        "population": partial(V.integer, low=2),
        "elites": partial(V.integer, low=1),
        "init_std": V.positive,
        "min_std": partial(V.positive, allow_zero=True),
        "smoothing": partial(V.number, low=0.0, high=1.0, open_high=True),
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        V.at_most(self.elites, "elites", self.population, "population")
        # the floor above the start: the first update would jump the spread up to it
        why = "it is the standard deviation's floor"
        V.at_most(self.min_std, "min_std", self.init_std, "init_std", why)


@dataclass(frozen=True)
class MPPIConfig(ShootingConfig):
    """Model predictive path integral control over action sequences (module docstring).

    Attributes:
        population: sequences per iteration: 10, MuJoCo MPC's ``sampling_trajectories``
            (Williams et al. ran thousands in parallel on a GPU; on a CPU budget of
            simulations more iterations of fewer samples go further).
        noise: :math:`\\sigma`, standard deviation of the perturbations in normalised
            units: 0.1, MuJoCo MPC's ``sampling_exploration`` for its control range
            :math:`[-1, 1]`.
        temperature: :math:`\\lambda > 0`, in the units of the objective: 0.01, MuJoCo
            MPC's ``lambda``. Small against return differences of order 1 (the robot
            domains), it makes the update nearly the best sample of the iteration; raise
            it for a softer average.
    """

    population: int = 10
    noise: float = 0.1
    temperature: float = 0.01

    name: ClassVar[str] = "mppi"
    _checks: ClassVar[Mapping[str, V.Check]] = {
        **ShootingConfig._checks,
        "population": partial(V.integer, low=1),
        "noise": V.positive,
        "temperature": V.positive,
    }


@dataclass(frozen=True)
class PredictiveSamplingConfig(ShootingConfig):
    """Predictive sampling: perturb a nominal sequence, keep the best (module docstring).

    Attributes:
        population: candidates per iteration, the nominal included: 10, MuJoCo MPC's
            ``sampling_trajectories`` (Howell et al., 2022). After the first iteration
            the nominal's return is known, so an iteration rolls out ``population - 1``
            noisy candidates.
        noise: standard deviation of the perturbations in normalised units: 0.1, MuJoCo
            MPC's ``sampling_exploration`` for its control range :math:`[-1, 1]`.
    """

    population: int = 10
    noise: float = 0.1

    name: ClassVar[str] = "predictive_sampling"
    _checks: ClassVar[Mapping[str, V.Check]] = {
        **ShootingConfig._checks,
        "population": partial(V.integer, low=2),
        "noise": V.positive,
    }


#: The sampling-based planners by name.
SHOOTING_PLANNERS: Mapping[str, type[ShootingConfig]] = MappingProxyType(
    {c.name: c for c in (CEMConfig, MPPIConfig, PredictiveSamplingConfig, RandomShootingConfig)}
)


def available_shooting_planners() -> list[str]:
    """Names accepted by :func:`shooting_config` (and by :func:`voot.tree.plan`)."""
    return sorted(SHOOTING_PLANNERS)


def is_shooting_planner(name: object) -> bool:
    """Whether ``name`` is a sampling-based planner (``"CEM"``, ``"predictive-sampling"``)."""
    return isinstance(name, str) and V.name_key(name) in SHOOTING_PLANNERS


def shooting_config(name: str = "cem", **overrides: Any) -> ShootingConfig:
    """The config of a named sampling-based planner, with some options overridden.

    >>> shooting_config("mppi", temperature=0.1).population
    10
    """
    key = V.registered_name(name, SHOOTING_PLANNERS, "sampling-based planner", "planners")
    cls = SHOOTING_PLANNERS[key]
    V.config_options(cls, overrides, f"planner {key!r}")
    return cls(**overrides)


@dataclass
class _Rollout:
    """One simulated sequence: its objective, return and what it executed."""

    objective: float
    ret: float
    actions: list[FloatArray]
    rewards: list[float]
    bonuses: list[float]
    feasible: list[bool]
    info: Mapping[str, Any]


class ShootingPlanner(Search):
    """A sampling-based planner over a :class:`~voot.tree.problem.PlanningProblem`.

    Args:
        problem: the world; its current state is the root of every rollout.
        config: a :class:`ShootingConfig` subclass instance, or a planner name.
        seed: seed of the one generator every draw comes from.

    ``search(n)`` runs ``n`` more simulations and returns a
    :class:`~voot.tree.search.PlanResult`; call it again to continue.
    """

    def __init__(
        self,
        problem: PlanningProblem,
        config: ShootingConfig | str = "cem",
        seed: int | np.random.SeedSequence | None = None,
    ) -> None:
        cfg = shooting_config(config) if isinstance(config, str) else config
        if not isinstance(cfg, ShootingConfig) or type(cfg) is ShootingConfig:
            raise TypeError(
                "config must be a CEMConfig, MPPIConfig, PredictiveSamplingConfig,"
                f" RandomShootingConfig or a planner name, got {type(cfg).__name__}"
            )
        check_problem(problem)
        seed = V.seed(seed)
        self.problem = problem
        self.config = cfg
        self.rng = np.random.default_rng(seed)
        self._root = problem.snapshot()
        check = getattr(problem, "is_feasible", None)
        retries = cfg.feasibility_retries if isinstance(cfg, RandomShootingConfig) else 0
        #: The problem's pre-check when the planner uses it (random shooting, k > 0).
        self._check: Callable[[FloatArray], bool] | None = (
            check if callable(check) and retries > 0 else None
        )
        self._retries = retries
        self.n_feasibility_checks = 0
        H = cfg.horizon
        self._width = problem_bounds(problem).dim
        #: Mean (CEM, MPPI) or nominal (predictive sampling) sequence, ``(H, W)``.
        self.mean = np.zeros((H, self._width))
        #: Standard deviation per entry (CEM), ``(H, W)``.
        self.std = np.full((H, self._width), self._initial_std())
        self._batch: list[FloatArray] = []
        self._objectives: list[float] = []
        self._nominal_objective: float | None = None
        self._best: _Rollout | None = None
        self.n_steps = 0
        self._start_curve()

    # ----- the distribution ------------------------------------------------------------------
    def _initial_std(self) -> float:
        cfg = self.config
        if isinstance(cfg, CEMConfig):
            return cfg.init_std
        if isinstance(cfg, MPPIConfig | PredictiveSamplingConfig):
            return cfg.noise
        return 0.0

    def _draw(self, mean: FloatArray, std: FloatArray) -> FloatArray:
        """A sequence from the planner's distribution (box-clipped)."""
        if isinstance(self.config, RandomShootingConfig):
            return self.rng.uniform(-1.0, 1.0, size=mean.shape)
        z = mean + std * self.rng.standard_normal(mean.shape)
        return np.clip(z, -1.0, 1.0, out=z)

    def _propose(self) -> FloatArray:
        if isinstance(self.config, PredictiveSamplingConfig) and self._nominal_objective is None:
            return self.mean.copy()  # the nominal itself, once
        return self._draw(self.mean, self.std)

    def _widen(self, dim: int, z: FloatArray) -> FloatArray:
        """Grow the sequences to ``dim`` columns: the distribution at its initial values,
        the iteration's samples and ``z`` with draws for the new columns."""
        H, extra = self.config.horizon, dim - self._width
        self.mean = np.hstack([self.mean, np.zeros((H, extra))])
        self.std = np.hstack([self.std, np.full((H, extra), self._initial_std())])
        mean, std = self.mean[:, self._width :], self.std[:, self._width :]
        self._batch = [np.hstack([b, self._draw(mean, std)]) for b in self._batch]
        self._width = dim
        return np.hstack([z, self._draw(mean, std)])

    def _update(self) -> None:
        """Refit the distribution to a full iteration (its samples and objectives)."""
        cfg = self.config
        Z = np.stack(self._batch)
        J = np.asarray(self._objectives)
        if isinstance(cfg, CEMConfig):
            elite = Z[np.argsort(-J, kind="stable")[: cfg.elites]]
            a = cfg.smoothing
            self.mean = a * self.mean + (1.0 - a) * elite.mean(axis=0)
            var = a * self.std**2 + (1.0 - a) * elite.var(axis=0)
            self.std = np.maximum(np.sqrt(var), cfg.min_std)
        elif isinstance(cfg, MPPIConfig):
            w = np.exp((J - J.max()) / cfg.temperature)
            self.mean = np.tensordot(w / w.sum(), Z, axes=1)
        elif isinstance(cfg, PredictiveSamplingConfig):
            i = int(np.argmax(J))
            assert self._nominal_objective is not None
            if J[i] > self._nominal_objective:
                self.mean, self._nominal_objective = Z[i].copy(), float(J[i])
        self._batch.clear()
        self._objectives.clear()

    def _iteration_size(self) -> int:
        cfg = self.config
        if isinstance(cfg, PredictiveSamplingConfig):
            return cfg.population - 1
        if isinstance(cfg, CEMConfig | MPPIConfig):
            return cfg.population
        return 0  # random shooting keeps no distribution

    # ----- one simulation ---------------------------------------------------------------------
    def _rollout(self, z: FloatArray) -> tuple[_Rollout, FloatArray]:
        """Roll ``z`` out from the root; the rollout and ``z`` (widened if needed)."""
        problem = self.problem
        gamma = self.config.gamma
        problem.restore(self._root)
        out = _Rollout(0.0, 0.0, [], [], [], [], {})
        discount = 1.0
        for t in range(self.config.horizon):
            bounds = problem_bounds(problem)
            d = bounds.dim
            if d > self._width:
                z = self._widen(d, z)
            action = bounds.lower + (z[t, :d] + 1.0) * (0.5 * bounds.width)
            if self._check is not None:
                action = self._prechecked(action, bounds, z[t, :d])
            res = problem.step(action)
            self.n_steps += 1
            # the tree search's errors: a NaN objective has no order (the elites, the
            # weights and the best rollout would be arbitrary) and an infinite one makes
            # every MPPI weight NaN; the rollout is discarded
            reward, bonus = step_values(problem, action, res)
            out.ret += discount * reward
            out.objective += discount * (reward + bonus)
            out.actions.append(action)
            out.rewards.append(reward)
            out.bonuses.append(bonus)
            out.feasible.append(bool(res.feasible))
            out.info = res.info
            if not res.feasible or res.terminal:
                break
            discount *= gamma
        return out, z

    def _prechecked(self, action: FloatArray, bounds: Bounds, row: FloatArray) -> FloatArray:
        """Stage 1 of the two stages: re-draw ``row`` (a step of the sequence, in place)
        until its action passes the pre-check, at most ``feasibility_retries`` draws in
        all; the action to execute."""
        check = self._check
        assert check is not None
        for t in range(self._retries):
            self.n_feasibility_checks += 1
            if check(action) or t == self._retries - 1:
                break
            row[:] = self.rng.uniform(-1.0, 1.0, size=row.shape)
            action = bounds.lower + (row + 1.0) * (0.5 * bounds.width)
        return action

    def _simulate(self) -> None:
        rollout, z = self._rollout(self._propose())
        if self._best is None or rollout.ret > self._best.ret:
            self._best = rollout
        if isinstance(self.config, PredictiveSamplingConfig) and self._nominal_objective is None:
            self.mean, self._nominal_objective = z, rollout.objective
            return
        size = self._iteration_size()
        if size:
            self._batch.append(z)
            self._objectives.append(rollout.objective)
            if len(self._batch) == size:
                self._update()

    def _root_snapshot(self) -> Any:
        return self._root

    # ----- public -----------------------------------------------------------------------------
    def _best_info(self) -> Mapping[str, Any]:
        assert self._best is not None
        return self._best.info

    @property
    def best_return(self) -> float:
        """Best return (goal bonus excluded) of a rollout so far; -inf before the first."""
        return -math.inf if self._best is None else self._best.ret

    def result(self, with_info_curve: bool = False) -> PlanResult:
        """The :class:`~voot.tree.search.PlanResult` of the rollouts so far."""
        best = self._best
        actions = tuple(a.copy() for a in best.actions) if best is not None else ()
        return PlanResult(
            actions=actions,
            rewards=np.array(best.rewards if best else [], dtype=np.float64),
            bonuses=np.array(best.bonuses if best else [], dtype=np.float64),
            feasible=tuple(best.feasible) if best else (),
            best_return=self.best_return,
            best_return_curve=np.array(self.best_return_curve, dtype=np.float64),
            info_curve=tuple(self.info_curve) if with_info_curve else None,
            best_action=actions[0].copy() if actions else None,
            best_leaf_info=best.info if best else {},
            n_simulations=self.n_simulations,
            n_nodes=0,
            n_steps=self.n_steps,
            n_feasibility_checks=self.n_feasibility_checks,
            n_node_visits=self.n_steps,
            wall_time=self.wall_time,
            mcts=None,
        )


def plan_shooting(
    problem: PlanningProblem,
    planner: str | ShootingConfig = "cem",
    n_simulations: int = 1000,
    seed: int | np.random.SeedSequence | None = 0,
    *,
    callback: ShootingCallback | None = None,
    record_info: str | None = None,
    **options: Any,
) -> PlanResult:
    """Run one sampling-based planner on one problem with one seed.

    ``options`` override fields of the planner's config.

    >>> from voot.tree.null_problem import NullProblem
    >>> res = plan_shooting(NullProblem(dim=2), "cem", n_simulations=60, horizon=3)
    >>> res.best_return_curve.shape
    (60,)
    """
    check_n_simulations(n_simulations)
    if isinstance(planner, ShootingConfig):
        V.config_options(type(planner), options)  # a ValueError naming the valid options
        config = planner.replace(**options) if options else planner
    else:
        config = shooting_config(planner, **options)
    return ShootingPlanner(problem, config, seed).search(
        n_simulations, callback=callback, record_info=record_info
    )
