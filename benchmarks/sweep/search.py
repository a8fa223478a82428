"""The run of a planner over the planning protocol in the planning sweep: one search, one row.

:func:`run_search_spec` runs a plan spec (:class:`voot.bench.sweep.plan.PlanSpec`) whose
planner is a tree planner (:class:`voot.tree.MCTS`), a sampling-based one
(:class:`voot.tree.shooting.ShootingPlanner`) or an outside one (a plug-in,
:mod:`voot.planners`), all through :func:`voot.planners.run_planner`, and returns its row; the row's fields and
the run protocol are described in :mod:`voot.bench.sweep.plan`. The RL runs
(:mod:`voot.bench.sweep.rl`) run such a search first, as the reference their budget is
matched to, and draw their algorithm's seed from the same :func:`search_seed`.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

import numpy as np

from voot.bench.protocol import problems as P
from voot.bench.store.format import Row
from voot.bench.sweep.engine import jsonable, name_key, one_blas_thread, timed_row
from voot.bench.sweep.planners import planner_entry, run_settings

if TYPE_CHECKING:
    from voot.bench.sweep.plan import PlanSpec


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


@one_blas_thread
def run_search_spec(spec: PlanSpec) -> Row:
    """Run the search of one plan spec and return its row (status ``"failed"`` on an
    exception)."""
    return timed_row(spec, lambda: search_fields(spec), problem_label=spec.label)


def search_fields(spec: PlanSpec) -> dict[str, Any]:
    """Run the search of ``spec``: its row's fields (``best_so_far`` first).

    Every planner, voot's own or an outside one, runs through
    :func:`voot.planners.run_planner`, which measures its simulator calls and CPU time
    around the problem and checks that its plan replays.
    """
    from voot.planners import run_planner

    config = spec.run_config()
    entry = planner_entry(spec.planner)
    domain = P.domain_options(spec.problem, spec.dim, spec.planner, spec.env_kwargs_dict)
    settings = run_settings(spec.planner, spec.params_dict, domain)
    inst = P.make_instance(spec.problem, spec.dim, spec.env_kwargs_dict, spec.seed)
    recorder: Any = None
    if spec.record is not None:
        from voot.record import SearchRecorder

        recorder = SearchRecorder(spec.record, inst.problem)
    try:
        out = run_planner(
            entry,
            inst.problem,
            spec.simulations,
            search_seed(spec),
            settings,
            discount=float(config.gamma),
            record_info=P.OBJECTS_KEY,
            on_simulation=None if recorder is None else lambda i, p: recorder(p.search, i),
        )
    finally:
        if recorder is not None:
            recorder.finish()
    left = out.info_curve
    fields: dict[str, Any] = {
        "best_so_far": out.best_so_far,
        "elapsed": [round(t, 6) for t in out.elapsed],
        "cpu_elapsed": [round(t, 6) for t in out.cpu_elapsed],
        "calls_curve": out.calls_curve,
        "search_time": out.wall_time,
        "best_return": out.best_so_far[-1],
        "simulator_calls": out.simulator_calls,
        "n_steps": out.n_steps,
        "n_feasibility_checks": out.n_feasibility_checks,
        "n_nodes": int(getattr(out.returned, "n_nodes", 0)),
        "n_node_visits": int(getattr(out.returned, "n_node_visits", out.n_steps)),
        "plan_length": len(out.actions),
        "best_actions": [a.tolist() for a in out.actions],
        "best_rewards": out.rewards,
        "problem_label": spec.label,
        "planner_config": jsonable(config.to_dict()),
    }
    if any(v is not None for v in left):
        fields["objects_left"] = [None if v is None else float(v) for v in left]
        fields["objects_initial"] = inst.objects_initial
    if spec.record is not None:
        fields["recorded"] = spec.record
    return fields
