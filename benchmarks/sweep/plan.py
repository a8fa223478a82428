r"""The planning sweep of ``voot-bench plan``: planners x problems x seeds (paper Figure 4).

A sweep is a grid of problems (:mod:`voot.bench.protocol.problems`) x planners (each with its
hyperparameter grid, :func:`~voot.bench.sweep.planners.planner_grid`) x seeds, every run with a budget of
simulations. :func:`build_plan_specs` turns the grid into :class:`PlanSpec` values and
:func:`run_plan_spec` runs one with :class:`voot.tree.MCTS` (or, for the sampling-based
planners ``cem``, ``mppi``, ``predictive_sampling`` and ``random_shooting``, with
:class:`voot.tree.shooting.ShootingPlanner`: the same row, :mod:`voot.bench.sweep.search`;
for an outside planner, a plug-in of :mod:`voot.planners`, through the same run; for the
RL planners ``ppo`` and ``ddpg``, by :mod:`voot.bench.sweep.rl`, with a budget matched to
a tree search), returning a result row of kind ``"plan"`` for the same store,
backends and resume logic as the black-box sweep (:func:`voot.bench.sweep.engine.run_sweep`).
The planners themselves, their grids and configs, are in :mod:`voot.bench.sweep.planners`.

The protocol of one run (``PLAN_PROTOCOL = 1``):

* **Problem**: a chain is built fresh; an environment is made once per process
  (:func:`voot.bench.protocol.problems.cached_env`) and reset with the run's ``seed``, so every
  planner plans from the same initial state for a given seed.
* **Planner**: the named planner (:func:`voot.tree.planner_config`) with the problem's
  settings (:func:`voot.bench.protocol.problems.domain_options`) and the grid's ``params``.
  A parameter that is an :class:`~voot.tree.MCTSConfig` field (``reevaluations``,
  ``pw_k``, ``ucb_c`` ...) sets that field; any other one (``omega``, ``epsilon``,
  ``v1`` ...) is an option of the per-node sampler. A sampling-based planner takes the
  problem's discount and its own options (:func:`~voot.bench.sweep.planners.run_config`); its row has the
  same fields (``n_nodes`` 0, ``n_feasibility_checks`` 0). An outside planner takes its own
  settings (``params``; the problem's discount is ``problem.discount``), and its row has
  the same fields too (``n_nodes`` 0, its ``planner_config`` its name, version, discount
  and settings).
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

Every search (voot's planners and outside ones alike) runs through
:func:`voot.planners.run_planner`: the counts and times below are measured by voot around
the problem, not reported by the planner, and the returned plan is replayed and checked.

Two call counts, on purpose: ``simulator_calls`` is the problem's own count when it
keeps one (the v1 robot domains count executed steps only, their pre-checks are cheap
kinematic tests), else steps plus pre-checks; ``calls_curve`` always counts both, the
x axis "simulator calls" of :mod:`voot.bench.protocol.axes` (a sampling-based planner makes no
pre-checks, so its curve counts rollout steps).

Same spec -> bit-identical ``best_so_far``, ``objects_left`` and ``calls_curve``, in any
process, on any backend (only the timings differ: ``elapsed``, ``cpu_elapsed`` ...).
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, ClassVar

from voot.bench.protocol import problems as P
from voot.bench.protocol.layouts import (
    LAYOUT_KEY,
    check_layout_problem,
    family_kwargs,
    layout_of,
    with_layout,
)
from voot.bench.store.format import Row
from voot.bench.sweep.engine import (
    SpecBase,
    check_grid,
    int_list,
    one_blas_thread,
    params_key,
    register_runner,
)
from voot.bench.sweep.planners import (
    horizon_param,
    is_rl_planner,
    keeps_tree,
    normalize_plan_planner,
    planner_grid,
    run_config,
)
from voot.bench.sweep.rl import run_rl_spec
from voot.bench.sweep.search import run_search_spec

#: Version of the plan-run protocol (problem set-up and seeding rules); in every run id.
PLAN_PROTOCOL = 1
#: Most runs one sweep may record (one ``.rrd`` file each).
MAX_RECORDINGS = 50
#: Row keys that hold timings (they differ between two runs of the same spec).
TIMING_KEYS = ("wall_time", "elapsed", "cpu_elapsed", "search_time", "finished_at")


@dataclass(frozen=True)
class PlanSpec(SpecBase):
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
    protocol: ClassVar[int] = PLAN_PROTOCOL
    mapping_fields: ClassVar[tuple[str, ...]] = ("env_kwargs", "params")
    optional_fields: ClassVar[tuple[str, ...]] = ("variant",)

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

    def run_config(self) -> Any:
        """The planner's config: an MCTSConfig, a ShootingConfig or an RLConfig
        (:func:`~voot.bench.sweep.planners.run_config`)."""
        return run_config(
            self.problem, self.dim, self.planner, self.params_dict, self.env_kwargs_dict
        )


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
    names = [P.normalize_problem(p) for p in problems]
    if not names:
        raise ValueError("no problems given")
    dim_list = int_list(dims, "dims", 1) if dims is not None else list(P.DEFAULT_CHAIN_DIMS)
    seed_list = int_list(seeds, "seeds", 0) if seeds is not None else None
    layouts: list[int | None] = (
        list(int_list(layout_seeds, "layout seeds", 0)) if layout_seeds is not None else [None]
    )
    planner_list = [normalize_plan_planner(p) for p in planners] if planners is not None else None
    if planner_list is not None and not planner_list:
        raise ValueError("no planners given")
    if planner_list is not None and any(is_rl_planner(p) for p in planner_list):
        from voot.rl import require_sb3

        require_sb3()  # a missing rl extra is an error now, naming the extra
    if simulations is not None:
        int_list([simulations], "simulations", 1)
    check_grid(grid)
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
                    params = {**setting, **extra, **horizon_param(planner, horizon)}
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
        treeless = sorted({s.planner for s in specs if not keeps_tree(s.planner)})
        if treeless:
            raise ValueError(
                f"recording draws a search tree; the planners {treeless} (sampling-based, RL"
                " or outside planners) keep none (record voot's tree planners only)"
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


@one_blas_thread
def run_plan_spec(spec: PlanSpec) -> Row:
    """Run one planning spec and return its row (status ``"failed"`` on an exception):
    an RL run (:func:`voot.bench.sweep.rl.run_rl_spec`) or a search
    (:func:`voot.bench.sweep.search.run_search_spec`)."""
    if is_rl_planner(spec.planner):
        return run_rl_spec(spec)
    return run_search_spec(spec)


def describe_config(config: Mapping[str, Any]) -> str:
    """A one-line description of a planning run from its row's ``config``."""
    params = config.get("params") or {}
    label = P.problem_label(str(config.get("problem")), config.get("env_kwargs"))
    if config.get("dim") is not None:
        label += f"-{config['dim']}D"
    return f"{config.get('planner')} [{params_key(params)}] on {label} seed {config.get('seed')}"


register_runner(PlanSpec.kind, run_plan_spec, describe_config)


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
