r"""The planning sweep of ``voot-bench plan``: planners x problems x seeds (paper Figure 4).

A sweep is a grid of problems (:mod:`voot.bench.protocol.problems`) x planners (each with its
hyperparameter grid, :func:`planner_grid`) x seeds, every run with a budget of
simulations. :func:`build_plan_specs` turns the grid into :class:`PlanSpec` values and
:func:`run_plan_spec` runs one with :class:`voot.tree.MCTS` (or, for the sampling-based
planners ``cem``, ``mppi``, ``predictive_sampling`` and ``random_shooting``, with
:class:`voot.tree.shooting.ShootingPlanner`: the same row; for the RL planners ``ppo`` and
``ddpg``, by :mod:`voot.bench.sweep.rl`, with a budget matched to a tree search), returning a result row of
kind ``"plan"`` for the same store, backends and resume logic as the black-box sweep
(:func:`voot.bench.sweep.bbfo.run_sweep`).

The protocol of one run (``PLAN_PROTOCOL = 1``):

* **Problem**: a chain is built fresh; an environment is made once per process
  (:func:`voot.bench.protocol.problems.cached_env`) and reset with the run's ``seed``, so every
  planner plans from the same initial state for a given seed.
* **Planner**: the named planner (:func:`voot.tree.planner_config`) with the problem's
  settings (:func:`voot.bench.protocol.problems.domain_options`) and the grid's ``params``.
  A parameter that is an :class:`~voot.tree.MCTSConfig` field (``reevaluations``,
  ``pw_k``, ``ucb_c`` ...) sets that field; any other one (``omega``, ``epsilon``,
  ``v1`` ...) is an option of the per-node sampler. A sampling-based planner takes the
  problem's discount and its own options (:func:`shooting_run_config`); its row has the
  same fields (``n_nodes`` 0, ``n_feasibility_checks`` 0).
* **Search seed**: ``SeedSequence([seed, key(problem), dim, key(env keywords),
  key(planner)])``; the hyperparameters are deliberately not in it (common random
  numbers across a planner's grid, as in :mod:`voot.bench.sweep.bbfo`).
* **Record** after every simulation: the best discounted return from the root, goal
  bonus excluded (``best_so_far``), the wall-clock seconds since the search started
  (``elapsed``), the CPU seconds of the process since the search started
  (``cpu_elapsed``, :func:`time.process_time`), the cumulative simulator calls
  (``calls_curve``: executed steps plus kinematic pre-checks, so ``calls_curve[-1] ==
  n_steps + n_feasibility_checks``) and, when the problem reports it in its step info,
  the objects still to handle at the best leaf (``objects_left``); at the end the
  simulator calls, tree size, best plan and the resolved planner configuration.

Two call counts, on purpose: ``simulator_calls`` is the problem's own count when it
keeps one (the v1 robot domains count executed steps only, their pre-checks are cheap
kinematic tests), else steps plus pre-checks; ``calls_curve`` always counts both, the
x axis "simulator calls" of :mod:`voot.bench.protocol.axes` (a sampling-based planner makes no
pre-checks, so its curve counts rollout steps).

Same spec -> bit-identical ``best_so_far``, ``objects_left`` and ``calls_curve``, in any
process, on any backend (only the timings differ: ``elapsed``, ``cpu_elapsed`` ...).
"""

from __future__ import annotations

import itertools
import json
import time
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from voot import validation as V
from voot.bench.protocol import problems as P
from voot.bench.protocol.layouts import (
    LAYOUT_KEY,
    check_layout_problem,
    family_kwargs,
    layout_of,
    with_layout,
)
from voot.bench.store.format import Row, make_row, make_run_id
from voot.bench.sweep.bbfo import GRIDS, exception_row, name_key, one_blas_thread, register_runner

#: Version of the plan-run protocol (problem set-up and seeding rules); in every run id.
PLAN_PROTOCOL = 1
#: Planners in plotting order (the paper's first).
PLAN_PLANNERS: tuple[str, ...] = (
    "voot",
    "doot",
    "rand_doot",
    "pw_uct",
    "voronoi_pw",
    "hoot",
    "uniform_t",
    "cem",
    "mppi",
    "predictive_sampling",
    "random_shooting",
    "ppo",
    "ddpg",
)
#: Re-evaluation counts ``w`` (the paper's :math:`N_r = 1 + w`) searched per family; the
#: authors used 100 on the chains and 5 on the robot domains.
REEVALUATIONS: Mapping[str, tuple[float, ...]] = {"chain": (10, 100), "robot": (2, 5)}
#: VOO's exploration probabilities searched (the original's grid, thinned; 0.001 is the
#: authors' value on the chains, 0.3 on the conveyor).
OMEGAS: tuple[float, ...] = (0.001, 0.1, 0.3)
#: DOO's exploration weights searched (a spread of the authors' DOO grid).
EPSILONS: tuple[float, ...] = (0.001, 0.1, 1.0)
#: Progressive-widening coefficients :math:`k` searched (:math:`\alpha = 0.5` fixed).
PW_KS: tuple[float, ...] = (1.0, 3.0)
#: UCB constants :math:`c` searched for PW-UCT.
UCB_CS: tuple[float, ...] = (0.1, 1.0, 10.0)
#: HOO smoothness scales :math:`\nu_1` searched for HOOT.
HOO_V1S: tuple[float, ...] = (0.1, 1.0, 10.0)
#: CEM's initial standard deviations searched (normalised units; 0.5 is PETS's).
CEM_INIT_STDS: tuple[float, ...] = (0.25, 0.5)
#: Perturbation scales searched for MPPI and predictive sampling (0.1 is MuJoCo MPC's).
SAMPLING_NOISES: tuple[float, ...] = (0.1, 0.3)
#: MPPI temperatures searched (0.01 is MuJoCo MPC's).
MPPI_TEMPERATURES: tuple[float, ...] = (0.01, 0.1)
#: Most runs one sweep may record (one ``.rrd`` file each).
MAX_RECORDINGS = 50
#: Row keys that hold timings (they differ between two runs of the same spec).
TIMING_KEYS = ("wall_time", "elapsed", "cpu_elapsed", "search_time", "finished_at")


def planner_grid(planner: str, family: str, grid: str = "paper") -> list[dict[str, Any]]:
    """Hyperparameter settings of ``planner`` on a problem ``family`` (``chain``/``robot``).

    ``grid="default"`` is one empty setting (the planner's and problem's defaults);
    ``grid="paper"`` every combination of the axes below, the paper's selection rule then
    keeps the best mean final return (:mod:`voot.bench.protocol.select`). The paper's appendix
    grids are not public; these span the values the reference page reports.

    ==========  ==================================================
    planner     axes
    ==========  ==================================================
    voot        omega x reevaluations
    doot        epsilon x reevaluations
    rand_doot   epsilon x reevaluations
    uniform_t   reevaluations
    pw_uct      pw_k x ucb_c
    voronoi_pw  omega x pw_k
    hoot        v1
    cem         init_std
    mppi        noise x temperature
    predictive_sampling  noise
    random_shooting      (none)
    ppo, ddpg   (none: the paper gives no RL grid; SB3's defaults)
    ==========  ==================================================
    """
    key = normalize_plan_planner(planner)
    if grid not in GRIDS:
        raise ValueError(f"unknown grid {grid!r}; valid grids are: {', '.join(GRIDS)}")
    if family not in REEVALUATIONS:
        raise ValueError(f"unknown family {family!r}; valid: {', '.join(REEVALUATIONS)}")
    if grid == "default":
        return [{}]
    w = REEVALUATIONS[family]
    axes: dict[str, Sequence[Any]] = {
        "voot": {"omega": OMEGAS, "reevaluations": w},
        "doot": {"epsilon": EPSILONS, "reevaluations": w},
        "rand_doot": {"epsilon": EPSILONS, "reevaluations": w},
        "uniform_t": {"reevaluations": w},
        "pw_uct": {"pw_k": PW_KS, "ucb_c": UCB_CS},
        "voronoi_pw": {"omega": OMEGAS, "pw_k": PW_KS},
        "hoot": {"v1": HOO_V1S},
        "cem": {"init_std": CEM_INIT_STDS},
        "mppi": {"noise": SAMPLING_NOISES, "temperature": MPPI_TEMPERATURES},
        "predictive_sampling": {"noise": SAMPLING_NOISES},
    }.get(key, {})  # type: ignore[assignment]
    names = sorted(axes)
    return [
        dict(zip(names, values, strict=True))
        for values in itertools.product(*(axes[n] for n in names))  # type: ignore[index]
    ]


def normalize_plan_planner(name: str) -> str:
    """The canonical name of any planner of ``voot-bench plan``: a tree planner, a
    sampling-based one or an RL one (``ppo``, ``ddpg``); a ValueError listing all."""
    from voot.bench.sweep.rl import RL_PLANNERS, is_rl_planner
    from voot.tree.config import available_planners
    from voot.tree.planners import normalize_any_planner
    from voot.tree.shooting import available_shooting_planners

    if is_rl_planner(name):
        return str(name).strip().lower()
    try:
        return normalize_any_planner(name)
    except ValueError:
        valid = sorted(available_planners() + available_shooting_planners() + list(RL_PLANNERS))
        raise ValueError(
            f"unknown planner {name!r}; valid planners are: {', '.join(valid)}"
        ) from None


def _config_fields() -> set[str]:
    from voot.tree.config import MCTSConfig

    return {f.name for f in fields(MCTSConfig)}


#: ``--set sampler.NAME=VALUE`` sets the per-node sampler's option NAME (e.g. VOO's own
#: ``sampler``, which the tree's ``sampler`` field would otherwise take).
SAMPLER_PREFIX = "sampler."


def mcts_config(
    problem: str,
    dim: int | None,
    planner: str,
    params: Mapping[str, Any],
    env_kwargs: Mapping[str, Any] | None = None,
) -> Any:
    """The :class:`~voot.tree.MCTSConfig` of a run: planner, problem settings, ``params``."""
    from voot.tree.config import available_samplers, planner_config

    options = P.domain_options(problem, dim, planner, env_kwargs)
    sampler_options = dict(options.pop("sampler_options", {}))
    config_fields = _config_fields()
    tree_samplers = set(available_samplers())
    for name, value in params.items():
        if name == "sampler_options":
            raise ValueError("set sampler options by name (e.g. omega=0.3), not sampler_options=")
        if name.startswith(SAMPLER_PREFIX):  # sampler.sampler=gaussian: VOO's own option
            sampler_options[name[len(SAMPLER_PREFIX) :]] = value
        elif name == "sampler" and value not in tree_samplers:
            # not a per-node sampler (voo, doo, uniform ...): the sampler's own option of
            # that name, e.g. VOO's best-cell sampler (gaussian, centered_uniform)
            sampler_options[name] = value
        elif name in config_fields:
            options[name] = value
        else:
            sampler_options[name] = value
    if sampler_options:
        options["sampler_options"] = sampler_options
    base = planner_config(planner)
    if base.sampler == "uniform" and "sampler_options" in options:
        unknown = sorted(options.pop("sampler_options"))
        valid = sorted(config_fields - {"sampler_options"})
        raise ValueError(
            f"planner {planner!r} samples uniformly and takes no sampler option {unknown};"
            f" valid parameters are: {', '.join(valid)}"
        )
    try:
        return planner_config(planner, **options)
    except ValueError as exc:
        if "unknown option" not in str(exc):
            raise
        names = ", ".join(sorted(config_fields - {"sampler_options"}))
        raise ValueError(f"{exc}; or a planner parameter (an MCTSConfig field): {names}") from None


def shooting_run_config(
    problem: str,
    dim: int | None,
    planner: str,
    params: Mapping[str, Any],
    env_kwargs: Mapping[str, Any] | None = None,
) -> Any:
    """The :class:`~voot.tree.shooting.ShootingConfig` of a sampling-based run: the
    planner's defaults, the problem's discount (the one the tree planners get), ``params``."""
    from voot.tree.shooting import shooting_config

    options: dict[str, Any] = {}
    domain = P.domain_options(problem, dim, planner, env_kwargs)
    if "gamma" in domain:
        options["gamma"] = domain["gamma"]
    options.update(params)
    return shooting_config(planner, **options)


def run_config(
    problem: str,
    dim: int | None,
    planner: str,
    params: Mapping[str, Any],
    env_kwargs: Mapping[str, Any] | None = None,
) -> Any:
    """The config of a run: :func:`shooting_run_config` for a sampling-based planner,
    :func:`voot.bench.sweep.rl.rl_run_config` for an RL one, else :func:`mcts_config`."""
    from voot.bench.sweep.rl import is_rl_planner, rl_run_config
    from voot.tree.shooting import is_shooting_planner

    if is_rl_planner(planner):
        return rl_run_config(problem, dim, planner, params, env_kwargs)
    if is_shooting_planner(planner):
        return shooting_run_config(problem, dim, planner, params, env_kwargs)
    return mcts_config(problem, dim, planner, params, env_kwargs)


@dataclass(frozen=True)
class PlanSpec:
    """One planning run: ``planner`` with ``params`` on ``problem`` (``dim`` for a chain,
    ``env_kwargs`` for an env), ``simulations`` simulations, ``seed``.

    ``record`` (a ``.rrd`` path, or None) asks for a rerun recording of the search; it is
    not part of the run's identity. ``variant`` names a set of planner options that is
    not tuned but compared (an ablation switch, :mod:`voot.bench.protocol.ablation`): the planner
    with a variant is a planner of its own in selections, figures and tables
    (``voot[variant]``); empty for a plain run, whose config and run id are as before.
    """

    problem: str
    dim: int | None
    env_kwargs: tuple[tuple[str, Any], ...]
    planner: str
    params: tuple[tuple[str, Any], ...]
    simulations: int
    seed: int
    record: str | None = field(default=None, compare=False)
    variant: str = ""

    kind: ClassVar[str] = "plan"

    @property
    def params_dict(self) -> dict[str, Any]:
        return dict(self.params)

    @property
    def env_kwargs_dict(self) -> dict[str, Any]:
        return dict(self.env_kwargs)

    @property
    def budget(self) -> int:
        return self.simulations

    @property
    def label(self) -> str:
        """The problem's display name (with the chain's dimension)."""
        base = P.problem_label(self.problem, self.env_kwargs_dict)
        return f"{base}-{self.dim}D" if self.dim is not None else base

    @property
    def layout(self) -> int | None:
        """The run's layout seed (``env_kwargs["layout_seed"]``), None if it has none."""
        return layout_of({"env_kwargs": self.env_kwargs_dict})

    @property
    def family_label(self) -> str:
        """:attr:`label` without the layout seed: the display name of the family."""
        base = P.problem_label(self.problem, family_kwargs(self.env_kwargs_dict))
        return f"{base}-{self.dim}D" if self.dim is not None else base

    def config(self) -> dict[str, Any]:
        """The row's ``config`` (JSON-serialisable; hashed into the run id)."""
        out = {
            "problem": self.problem,
            "dim": self.dim,
            "env_kwargs": self.env_kwargs_dict,
            "planner": self.planner,
            "params": self.params_dict,
            "simulations": self.simulations,
            "seed": self.seed,
            "protocol": PLAN_PROTOCOL,
        }
        if self.variant:
            out["variant"] = self.variant
        return out

    @property
    def run_id(self) -> str:
        return make_run_id(self.kind, self.config())

    def mcts_config(self) -> Any:
        return mcts_config(
            self.problem, self.dim, self.planner, self.params_dict, self.env_kwargs_dict
        )

    def run_config(self) -> Any:
        """The planner's config: an MCTSConfig, or a ShootingConfig (:func:`run_config`)."""
        return run_config(
            self.problem, self.dim, self.planner, self.params_dict, self.env_kwargs_dict
        )


def search_seed(spec: PlanSpec) -> np.random.SeedSequence:
    """Seed of the search of a run (the same for every hyperparameter of the planner)."""
    kwargs = json.dumps(spec.env_kwargs_dict, sort_keys=True)
    return np.random.SeedSequence(
        [
            int(spec.seed),
            name_key(spec.problem),
            int(spec.dim or 0),
            name_key(kwargs),
            name_key(spec.planner),
        ]
    )


def _int_list(values: Iterable[Any], what: str, minimum: int) -> list[int]:
    out = V.integers(values, what, minimum)
    if not out:
        raise ValueError(f"no {what} given")
    return list(dict.fromkeys(out))


def _horizon_param(planner: str, horizon: int | None) -> dict[str, int | None]:
    """``horizon`` as the planner's own parameters (empty if None): a sampling-based
    planner's sequence length, or a tree's depth limit :math:`H` counted from the root,
    without root commitment (which would let the horizon recede past ``H``)."""
    if horizon is None:
        return {}
    from voot.bench.sweep.rl import is_rl_planner
    from voot.tree.shooting import is_shooting_planner

    h = V.integer(horizon, "horizon", 1)
    if is_rl_planner(planner):
        raise ValueError(
            f"--horizon sets a planner's depth; the RL planner {planner!r} learns on whole"
            " episodes (set its max_episode_steps instead, e.g. --set max_episode_steps=5)"
        )
    if is_shooting_planner(planner):
        return {"horizon": h}
    return {"depth_limit": h, "root_commitment": None}


def build_plan_specs(
    problems: Sequence[str] = P.DEFAULT_PROBLEMS,
    dims: Sequence[int] | None = None,
    planners: Sequence[str] | None = None,
    seeds: Iterable[int] | None = None,
    *,
    simulations: int | None = None,
    grid: str = "paper",
    env_kwargs: Mapping[str, Any] | None = None,
    fixed: Mapping[str, Any] | None = None,
    record: str | None = None,
    horizon: int | None = None,
    layout_seeds: Iterable[int] | None = None,
) -> list[PlanSpec]:
    """Every run of a planning sweep, in grid order (problem, dim, planner, params,
    layout, seed).

    Args:
        problems: problem names (see :mod:`voot.bench.protocol.problems`; default: the Shekel chain).
        dims: dimensions of the chains (default: 10 and 20); ignored by environments.
        planners: planner names (default: the paper's planners of each problem).
        seeds: seeds (default: the paper's number of seeds of each problem, from 0).
        simulations: simulations per run (default: the paper's budget of each problem).
        grid: ``"paper"`` (:func:`planner_grid`) or ``"default"`` (defaults only).
        env_kwargs: keywords of ``gymnasium.make`` for the environments.
        fixed: parameters set in every run (e.g. ``{"depth_limit": 5}``); they join
            every setting's ``params`` (and so its label and run id).
        record: a ``.rrd`` path: record every run's search (see :func:`record_path`).
        horizon: one planning horizon for every planner, counted from the root: a tree
            planner's ``depth_limit`` (with no root commitment, which would let it recede)
            or a sampling-based planner's ``horizon`` (e.g. for gymnasium's control tasks,
            which do not end by themselves).
        layout_seeds: layout seeds of a generated family (:mod:`voot.bench.protocol.layouts`):
            every run is made once per layout, with ``layout_seed`` in its ``env_kwargs``
            (None: no layout axis; the runs and their ids are those of a sweep without it).

    Raises:
        ValueError: unknown problem, planner, parameter or grid; bad numbers; a chain
            dimension without a reference threshold; layout seeds for a problem that
            takes none, or beside a ``layout_seed`` env keyword. Messages list the valid
            choices.
    """
    from voot.bench.sweep.rl import is_rl_planner
    from voot.tree.shooting import is_shooting_planner

    names = [P.normalize_problem(p) for p in problems]
    if not names:
        raise ValueError("no problems given")
    dim_list = _int_list(dims, "dims", 1) if dims is not None else list(P.DEFAULT_CHAIN_DIMS)
    seed_list = _int_list(seeds, "seeds", 0) if seeds is not None else None
    layouts: list[int | None] = (
        list(_int_list(layout_seeds, "layout seeds", 0)) if layout_seeds is not None else [None]
    )
    planner_list = [normalize_plan_planner(p) for p in planners] if planners is not None else None
    if planner_list is not None and not planner_list:
        raise ValueError("no planners given")
    if planner_list is not None and any(is_rl_planner(p) for p in planner_list):
        from voot.rl import require_sb3

        require_sb3()  # a missing rl extra is an error now, naming the extra
    if simulations is not None:
        _int_list([simulations], "simulations", 1)
    if grid not in GRIDS:
        raise ValueError(f"unknown grid {grid!r}; valid grids are: {', '.join(GRIDS)}")
    kwargs = P.check_env_kwargs(env_kwargs)
    extra = dict(fixed or {})
    if "sampler_options" in extra:
        raise ValueError("set sampler options by name (e.g. omega=0.3), not sampler_options=")
    if record is not None and not str(record).endswith(".rrd"):
        raise ValueError(f"a recording file must end in .rrd, got {record!r}")
    from voot.tree.chains import make_chain

    specs: list[PlanSpec] = []
    checked: set[tuple[Any, ...]] = set()
    for problem in dict.fromkeys(names):
        setup = P.paper_setup(problem)
        fam = P.family(problem)
        chain = P.is_chain(problem)
        problem_dims: list[int | None] = list(dim_list) if chain else [None]
        if chain and kwargs:
            raise ValueError(
                f"--env-kwargs {sorted(kwargs)} apply to gymnasium environments; the"
                f" {problem} takes its dimension from --dims (or use its gymnasium id,"
                f" e.g. voot/ShekelChain-v0 with --env-kwargs dim=5)"
            )
        if layouts != [None]:
            if chain:
                raise ValueError(
                    f"layout seeds apply to generated environments; the {problem} has no layouts"
                )
            if LAYOUT_KEY in kwargs:
                raise ValueError(
                    f"{LAYOUT_KEY} is given both as an env keyword ({kwargs[LAYOUT_KEY]!r}) and"
                    " as layout seeds; give one"
                )
            check_layout_problem(problem)
        envs = [() if chain else tuple(sorted(with_layout(kwargs, lay).items())) for lay in layouts]
        n_sims = simulations if simulations is not None else setup.simulations
        seeds_here = seed_list if seed_list is not None else list(range(setup.seeds))
        for dim in problem_dims:
            if dim is not None:  # a chain: does it have a reference threshold?
                make_chain(P.CHAINS[problem], int(dim))
            for planner in dict.fromkeys(planner_list or setup.planners):
                for setting in planner_grid(planner, fam, grid):
                    params = {**setting, **extra, **_horizon_param(planner, horizon)}
                    key = (problem, dim, planner, json.dumps(params, sort_keys=True))
                    if key not in checked:
                        run_config(problem, dim, planner, params, kwargs)  # fail early
                        checked.add(key)
                    items = tuple(sorted(params.items()))
                    for env in envs:
                        for seed in seeds_here:
                            specs.append(
                                PlanSpec(problem, dim, env, planner, items, int(n_sims), seed)
                            )
    if record is not None:
        shooting = sorted(
            {s.planner for s in specs if is_shooting_planner(s.planner) or is_rl_planner(s.planner)}
        )
        if shooting:
            raise ValueError(
                f"recording draws a search tree; the sampling-based and RL planners {shooting}"
                " keep none (record tree planners only)"
            )
        if len(specs) > MAX_RECORDINGS:
            raise ValueError(
                f"recording would write {len(specs)} files (one per run, at most"
                f" {MAX_RECORDINGS}); narrow the sweep (e.g. one planner, --seeds 1)"
            )
        specs = [
            replace(s, record=path)
            for s, path in zip(specs, record_paths(specs, record), strict=True)
        ]
    return specs


def record_paths(specs: Sequence[PlanSpec], template: str) -> list[str]:
    """Where each run's recording goes: ``template`` itself for a single run, else
    ``<stem>-<problem>-<planner>[-<params>]-seed<N>.rrd`` beside it."""
    if len(specs) == 1:
        return [str(template)]
    base = Path(template)
    out = []
    for s in specs:
        parts = [base.stem, s.label, s.planner]
        parts += [f"{k}{v}" for k, v in s.params]
        if s.layout is not None:
            parts.append(f"layout{s.layout}")
        parts.append(f"seed{s.seed}")
        name = "-".join(parts)
        safe = "".join(c if c.isalnum() or c in "-_.=" else "_" for c in name)
        out.append(str(base.with_name(safe + base.suffix)))
    return out


def _jsonable(value: Any) -> Any:
    if isinstance(value, str | int | float | bool) or value is None:
        return value
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    return repr(value)


@one_blas_thread
def run_plan_spec(spec: PlanSpec) -> Row:
    """Run one planning spec and return its row (status ``"failed"`` on an exception)."""
    from voot.bench.sweep.rl import is_rl_planner, run_rl_spec

    if is_rl_planner(spec.planner):
        return run_rl_spec(spec)
    start = time.perf_counter()
    best: list[float] = []
    try:
        from voot.tree.mcts import MCTS
        from voot.tree.shooting import ShootingConfig, ShootingPlanner

        config = spec.run_config()
        inst = P.make_instance(spec.problem, spec.dim, spec.env_kwargs_dict, spec.seed)
        mcts: Any = (
            ShootingPlanner(inst.problem, config, seed=search_seed(spec))
            if isinstance(config, ShootingConfig)
            else MCTS(inst.problem, config, seed=search_seed(spec))
        )
        recorder: Any = None
        if spec.record is not None:
            from voot.record import SearchRecorder

            recorder = SearchRecorder(spec.record, inst.problem)
        elapsed: list[float] = []
        cpu_elapsed: list[float] = []
        calls: list[int] = []
        clock, cpu_clock = time.perf_counter, time.process_time
        t0, c0 = clock(), cpu_clock()

        def callback(m: Any, i: int) -> bool:
            elapsed.append(clock() - t0)
            cpu_elapsed.append(cpu_clock() - c0)
            # a sampling-based planner makes no pre-checks (no such counter)
            calls.append(int(m.n_steps) + int(getattr(m, "n_feasibility_checks", 0)))
            if recorder is not None:
                recorder(m, i)
            return False

        calls_before = getattr(inst.problem, "n_simulator_calls", None)
        try:
            res = mcts.search(spec.simulations, callback=callback, record_info=P.OBJECTS_KEY)
        finally:
            if recorder is not None:
                recorder.finish()
        best = res.best_return_curve.tolist()
        left = list(res.info_curve or ())
        has_objects = any(v is not None for v in left)
        # the problem's own count (SimulatorCalls), else every step and pre-check
        sim_calls = (
            inst.problem.n_simulator_calls - calls_before
            if calls_before is not None
            else res.n_steps + res.n_feasibility_checks
        )
        extra: dict[str, Any] = {
            "elapsed": [round(t, 6) for t in elapsed],
            "cpu_elapsed": [round(t, 6) for t in cpu_elapsed],
            "calls_curve": calls,
            "search_time": res.wall_time,
            "best_return": res.best_return,
            "simulator_calls": int(sim_calls),
            "n_steps": res.n_steps,
            "n_feasibility_checks": res.n_feasibility_checks,
            "n_nodes": res.n_nodes,
            "n_node_visits": res.n_node_visits,
            "plan_length": len(res.actions),
            "best_actions": [a.tolist() for a in res.actions],
            "best_rewards": res.rewards.tolist(),
            "problem_label": spec.label,
            "planner_config": _jsonable(config.to_dict()),
        }
        if has_objects:
            extra["objects_left"] = [None if v is None else float(v) for v in left]
            extra["objects_initial"] = inst.objects_initial
        if spec.record is not None:
            extra["recorded"] = spec.record
        return make_row(
            spec.kind,
            spec.config(),
            status="ok",
            wall_time=time.perf_counter() - start,
            best_so_far=best,
            **extra,
        )
    except Exception as exc:
        return exception_row(spec, exc, start, best, problem_label=spec.label)


register_runner(PlanSpec.kind, run_plan_spec)


def summarize_plan_specs(specs: Sequence[PlanSpec]) -> str:
    """One line per (problem family, simulations): runs per planner, the seeds and, on a
    layout axis, the layouts."""
    cells: dict[tuple[str, int], dict[str, int]] = {}
    seeds: dict[tuple[str, int], set[int]] = {}
    layouts: dict[tuple[str, int], set[int]] = {}
    for s in specs:
        key = (s.family_label, s.simulations)
        counts = cells.setdefault(key, {})
        counts[s.planner] = counts.get(s.planner, 0) + 1
        seeds.setdefault(key, set()).add(s.seed)
        if s.layout is not None:
            layouts.setdefault(key, set()).add(s.layout)
    lines = []
    for (label, sims), counts in cells.items():
        per = ", ".join(f"{m} {n}" for m, n in counts.items())
        n_layouts = len(layouts.get((label, sims), ()))
        where = f"{n_layouts} layouts x " if n_layouts else ""
        lines.append(f"{label} {sims} simulations, {where}{len(seeds[(label, sims)])} seeds: {per}")
    return "\n".join(lines)


def strip_timings(row: Row) -> Row:
    """``row`` without the keys that differ between two runs of one spec (timings)."""
    return {k: v for k, v in row.items() if k not in TIMING_KEYS}
