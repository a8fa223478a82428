"""Every planner by name, and :func:`plan`, the one call that runs any of them.

Two kinds of planner search the same protocol: the tree planners
(:data:`voot.tree.config.PLANNERS`: VOOT and its baselines, one :class:`MCTS` each) and
the sampling-based MPC planners (:data:`voot.tree.shooting.SHOOTING_PLANNERS`). This
module sits above both, so that neither needs the other.
"""

from __future__ import annotations

from typing import Any

from voot import validation as V
from voot.tree.config import MCTSConfig, available_planners, normalize_planner, planner_config
from voot.tree.mcts import MCTS, Callback
from voot.tree.problem import PlanningProblem
from voot.tree.search import PlanResult, check_n_simulations
from voot.tree.shooting import (
    ShootingConfig,
    available_shooting_planners,
    is_shooting_planner,
    plan_shooting,
)


def normalize_any_planner(name: str) -> str:
    """The canonical name of a tree planner or a sampling-based one; a ValueError listing
    both kinds if it is neither."""
    if is_shooting_planner(name):
        return V.name_key(name)
    try:
        return normalize_planner(name)
    except ValueError:
        valid = sorted(available_planners() + available_shooting_planners())
        raise ValueError(
            f"unknown planner {name!r}; valid planners are: {', '.join(valid)}"
        ) from None


def plan(
    problem: PlanningProblem,
    planner: str | MCTSConfig | ShootingConfig = "voot",
    n_simulations: int = 1000,
    seed: int | None = 0,
    *,
    callback: Callback | None = None,
    record_info: str | None = None,
    **options: Any,
) -> PlanResult:
    """Run one planner on one problem with one seed: the unit of a benchmark.

    Args:
        problem: the planning problem (its current state is the root).
        planner: a planner name (see :func:`voot.tree.available_planners`) or a config;
            a sampling-based planner's name or config
            (:func:`voot.tree.shooting.available_shooting_planners`) runs
            :func:`voot.tree.shooting.plan_shooting` instead.
        n_simulations: number of simulations.
        seed: seed of the search.
        callback: see :meth:`voot.tree.search.Search.search`.
        record_info: see :meth:`voot.tree.search.Search.search`.
        **options: config fields overriding the planner's.

    >>> from voot.tree.null_problem import NullProblem
    >>> res = plan(NullProblem(dim=2), "voot", n_simulations=50, seed=0, depth_limit=3)
    >>> res.best_return_curve.shape
    (50,)
    """
    check_n_simulations(n_simulations)
    V.seed(seed)
    if isinstance(planner, ShootingConfig) or is_shooting_planner(planner):
        return plan_shooting(
            problem,
            planner,  # type: ignore[arg-type]
            n_simulations,
            seed,
            callback=callback,  # type: ignore[arg-type]
            record_info=record_info,
            **options,
        )
    if isinstance(planner, MCTSConfig):
        config = planner.replace(**options) if options else planner
    else:
        config = planner_config(planner, **options)
    return MCTS(problem, config, seed=seed).search(
        n_simulations, callback=callback, record_info=record_info
    )
