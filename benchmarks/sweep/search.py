"""The run of a tree or sampling-based planner in the planning sweep: one search, one row.

:func:`run_search_spec` runs a plan spec (:class:`voot.bench.sweep.plan.PlanSpec`) whose
planner is a tree planner (:class:`voot.tree.MCTS`) or a sampling-based one
(:class:`voot.tree.shooting.ShootingPlanner`) and returns its row; the row's fields and
the run protocol are described in :mod:`voot.bench.sweep.plan`. The RL runs
(:mod:`voot.bench.sweep.rl`) run such a search first, as the reference their budget is
matched to, and draw their algorithm's seed from the same :func:`search_seed`.
"""

from __future__ import annotations

import json
import time
from typing import TYPE_CHECKING, Any

import numpy as np

from voot.bench.protocol import problems as P
from voot.bench.store.format import Row
from voot.bench.sweep.engine import jsonable, name_key, one_blas_thread, timed_row

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
    """Run the search of ``spec``: its row's fields (``best_so_far`` first)."""
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
    left = list(res.info_curve or ())
    # the problem's own count (SimulatorCalls), else every step and pre-check
    sim_calls = (
        inst.problem.n_simulator_calls - calls_before
        if calls_before is not None
        else res.n_steps + res.n_feasibility_checks
    )
    fields: dict[str, Any] = {
        "best_so_far": res.best_return_curve.tolist(),
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
        "planner_config": jsonable(config.to_dict()),
    }
    if any(v is not None for v in left):
        fields["objects_left"] = [None if v is None else float(v) for v in left]
        fields["objects_initial"] = inst.objects_initial
    if spec.record is not None:
        fields["recorded"] = spec.record
    return fields
