r"""RL runs of ``voot-bench plan``: PPO and DDPG with the budget of a tree search.

The paper trains its RL baselines "with the same amount of simulated experience" as the
tree search and reports the best trajectory found during training. An RL run on
(problem, env keywords, seed, simulations) here:

1. runs the **reference search**: the planner ``match`` (default ``"voot"``) at its
   default settings for that problem (the same :class:`~voot.bench.sweep.plan.PlanSpec`
   machinery, ``params`` empty) on the same problem, seed and number of simulations;
   it is deterministic, so it is the search of the store's default-grid row of that
   planner (and is computed once per process for PPO and DDPG alike);
2. trains for exactly ``rl_steps = n_steps + n_feasibility_checks`` env steps of that
   search: **every executed step and every pre-check counts as one simulator call**
   (the v1 robot domains' kinematic pre-checks are cheaper than a step, so this is the
   generous side for RL; on v0 and the chains the search makes no separate pre-checks);
3. writes a row of kind ``"plan"`` with the tree rows' fields, ``best_so_far`` with one
   entry per simulation of the reference: entry :math:`i` is the best return found
   within the first :math:`\lfloor (i+1)\,s + 1/2 \rfloor` env steps, :math:`s` =
   ``steps_per_simulation = rl_steps / simulations`` (rounded half up, in exact integer
   arithmetic), so the RL curve is drawn against the tree's simulations;
   ``calls_curve`` those step counts (cumulative simulator calls), ``elapsed`` and
   ``cpu_elapsed`` the wall and CPU seconds since training started at them,
   ``best_by_step`` the compact ``[step, best]`` improvements, ``objects_left`` (at the
   best episode's end) and ``objects_initial`` where the env reports objects,
   ``n_steps = simulator_calls = rl_steps``, ``n_feasibility_checks = 0``, and
   ``reference`` (planner, simulations, n_steps, n_feasibility_checks).

The RL env is the problem's gymnasium env (a chain name becomes its gymnasium id with
``dim``), made fresh for the run and wrapped by :class:`voot.rl.PlanningTask` with the
run's seed and the reference planner's discount. The algorithm's seed is drawn from the
run's search seed (:func:`~voot.bench.sweep.plan.search_seed`).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from voot.bench.protocol import problems as P

#: The RL planners of ``voot-bench plan`` (their ``planner_grid`` is the one default
#: setting in both grids: the paper gives no RL hyperparameters to search).
RL_PLANNERS: tuple[str, ...] = ("ppo", "ddpg")
#: The run parameter naming the reference search's planner.
MATCH_PARAM = "match"
#: The default reference planner: the paper's.
DEFAULT_MATCH = "voot"
#: Chain problem names -> their gymnasium ids (the RL env of a chain).
CHAIN_GYM_IDS: Mapping[str, str] = {
    "shekel_chain": "voot/ShekelChain-v0",
    "griewank_chain": "voot/GriewankChain-v0",
    "rastrigin_chain": "voot/RastriginChain-v0",
}


def is_rl_planner(name: object) -> bool:
    """Whether ``name`` is an RL planner (``"PPO"``, ``"ddpg"``)."""
    return isinstance(name, str) and name.strip().lower() in RL_PLANNERS


def split_params(planner: str, params: Mapping[str, Any]) -> tuple[str, dict[str, Any]]:
    """``(reference planner, algorithm options)`` of an RL run's ``params``.

    Raises:
        ValueError: the reference is unknown, is itself an RL planner, or an option is
            not a field of the algorithm's config (the message lists the valid ones).
    """
    from voot.rl import rl_config
    from voot.tree.planners import normalize_any_planner

    options = dict(params)
    match = normalize_any_planner(str(options.pop(MATCH_PARAM, DEFAULT_MATCH)))
    if "gamma" in options:
        raise ValueError(
            f"{planner}: gamma is the problem's discount (the reference search's); it is not"
            " a parameter of an RL run"
        )
    rl_config(planner, **options)  # unknown options name the valid ones
    return match, options


def rl_run_config(
    problem: str,
    dim: int | None,
    planner: str,
    params: Mapping[str, Any],
    env_kwargs: Mapping[str, Any] | None = None,
) -> Any:
    """The :class:`~voot.rl.RLConfig` of an RL run: SB3's defaults, the problem's discount
    (the reference planner's ``gamma`` on this problem), ``params``."""
    from voot.bench.sweep.plan import run_config
    from voot.rl import rl_config

    match, options = split_params(planner, params)
    gamma = float(run_config(problem, dim, match, {}, env_kwargs).gamma)
    return rl_config(planner, gamma=gamma, **options)


def make_rl_env(problem: str, dim: int | None, env_kwargs: Mapping[str, Any]) -> Any:
    """A fresh gymnasium env of ``problem`` (a chain by its gymnasium id with ``dim``)."""
    import gymnasium

    import voot  # noqa: F401 - registers the voot/... ids

    if P.is_chain(problem):
        if dim is None:
            raise ValueError(f"the {problem} needs a dimension")
        return gymnasium.make(CHAIN_GYM_IDS[problem], dim=int(dim), disable_env_checker=True)
    return gymnasium.make(problem, disable_env_checker=True, **dict(env_kwargs))


@dataclass(frozen=True)
class Reference:
    """What an RL run takes from its reference search."""

    planner: str
    simulations: int
    n_steps: int
    n_feasibility_checks: int
    wall_time: float

    @property
    def calls(self) -> int:
        """Simulator calls of the search: executed steps plus pre-checks."""
        return self.n_steps + self.n_feasibility_checks

    def to_dict(self) -> dict[str, Any]:
        return {
            "planner": self.planner,
            "simulations": self.simulations,
            "n_steps": self.n_steps,
            "n_feasibility_checks": self.n_feasibility_checks,
        }


#: This process's reference searches by run id (PPO and DDPG on one seed share one).
_REFERENCES: dict[str, Reference] = {}
#: Most references kept per process.
MAX_REFERENCES = 64


def reference_search(spec: Any) -> Reference:
    """Run (or recall) the reference search of the RL run ``spec``."""
    from dataclasses import replace

    from voot.bench.sweep.plan import run_plan_spec

    match, _ = split_params(spec.planner, spec.params_dict)
    ref = replace(spec, planner=match, params=(), record=None)
    hit = _REFERENCES.get(ref.run_id)
    if hit is not None:
        return hit
    row = run_plan_spec(ref)
    if row.get("status") != "ok":
        raise RuntimeError(f"the reference {match} search failed: {row.get('error')}")
    out = Reference(
        match,
        int(ref.simulations),
        int(row["n_steps"]),
        int(row["n_feasibility_checks"]),
        float(row.get("wall_time", 0.0)),
    )
    if len(_REFERENCES) >= MAX_REFERENCES:
        _REFERENCES.pop(next(iter(_REFERENCES)))
    _REFERENCES[ref.run_id] = out
    return out


def matched_steps(rl_steps: int, simulations: int) -> list[int]:
    r"""The env steps matched to each simulation: :math:`\lfloor (i+1)\,s + 1/2\rfloor`,
    :math:`s` = ``rl_steps / simulations``, for :math:`i = 0 .. simulations - 1`
    (exact integers; the last is ``rl_steps``)."""
    return [(2 * (i + 1) * rl_steps + simulations) // (2 * simulations) for i in range(simulations)]


def algorithm_seed(spec: Any) -> int:
    """The algorithm's seed: a 32-bit integer from the run's search seed."""
    from voot.bench.sweep.plan import search_seed

    return int(search_seed(spec).generate_state(1, dtype=np.uint32)[0])


def rl_row_fields(spec: Any) -> dict[str, Any]:
    """Run the RL spec and return the row's fields (``best_so_far`` included)."""
    from voot.rl import PlanningTask, require_sb3, train

    require_sb3()  # before the reference search: a missing extra fails at once
    config = spec.run_config()
    ref = reference_search(spec)
    rl_steps = ref.calls
    if rl_steps < 1:
        raise ValueError(f"the reference {ref.planner} search made no simulator call")
    env = make_rl_env(spec.problem, spec.dim, spec.env_kwargs_dict)
    try:
        task = PlanningTask(env, spec.seed, config.gamma, config.max_episode_steps)
        marks = matched_steps(rl_steps, spec.simulations)
        res = train(config, task, rl_steps, algorithm_seed(spec), marks)
        points = [task.best_at(m) for m in marks]
    finally:
        env.close()
    fields: dict[str, Any] = {
        "best_so_far": [b for b, _ in points],
        "elapsed": [round(t, 6) for t in res.elapsed],
        "cpu_elapsed": [round(t, 6) for t in res.cpu_elapsed],
        "calls_curve": marks,
        "best_by_step": [[s, b] for s, b in res.best_by_step],
        "search_time": res.wall_time,
        "best_return": res.best_return,
        "rl_steps": rl_steps,
        "steps_per_simulation": rl_steps / spec.simulations,
        "reference": ref.to_dict(),
        "n_episodes": res.n_episodes,
        "simulator_calls": rl_steps,
        "n_steps": rl_steps,
        "n_feasibility_checks": 0,
        "n_nodes": 0,
        "problem_label": spec.label,
        "planner_config": config.to_dict(),
    }
    if task.objects_initial is not None:
        fields["objects_left"] = [o for _, o in points]
        fields["objects_initial"] = task.objects_initial
    return fields


def run_rl_spec(spec: Any) -> dict[str, Any]:
    """The row of the RL spec (called by :func:`voot.bench.sweep.plan.run_plan_spec`)."""
    from voot.bench.store.format import make_row
    from voot.bench.sweep.bbfo import exception_row

    start = time.perf_counter()
    try:
        fields = rl_row_fields(spec)
        best = fields.pop("best_so_far")
        return make_row(
            spec.kind,
            spec.config(),
            status="ok",
            wall_time=time.perf_counter() - start,
            best_so_far=best,
            **fields,
        )
    except Exception as exc:
        return exception_row(spec, exc, start, [], problem_label=spec.label)
