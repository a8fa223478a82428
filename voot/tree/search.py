"""What every planner over the protocol shares: its budget, its loop and its result.

The tree search (:class:`voot.tree.mcts.MCTS`) and the sampling-based planners
(:class:`voot.tree.shooting.ShootingPlanner`) both run *simulations* from a root state,
one at a time, and report the best return after every one (the paper's curve). They
differ only in what a simulation is and what "the best so far" means, so the loop
(:meth:`Search.iterate`: budget check, curve, step-info curve, wall time; :meth:`Search.search`
adds the callback) lives here once and each planner says what one simulation does (:meth:`Search._simulate`).

Both return the same :class:`PlanResult`, so sweeps, the result store and the plots
treat every planner alike.

A search leaves the problem where it found it: when :meth:`Search.search` returns (or
raises), the problem is restored to the root's snapshot, so the best plan's actions,
executed on the problem (or on the env it adapts), give the plan's rewards.
"""

from __future__ import annotations

import time
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from voot import validation as V
from voot.optim.base import FloatArray

if TYPE_CHECKING:
    from voot.tree.mcts import MCTS


def check_n_simulations(n_simulations: object) -> int:
    """A number of simulations must be an integer >= 1."""
    return V.integer(n_simulations, "n_simulations", 1)


@dataclass(frozen=True)
class PlanResult:
    """The outcome of a search (everything since the tree was created or re-rooted).

    Attributes:
        actions: the best plan: the actions from the root to the best leaf.
        rewards: their rewards (goal bonus excluded).
        bonuses: their goal bonuses.
        feasible: whether each action of the plan was feasible.
        best_return: :math:`\\sum_t \\gamma^t r_t` of the best plan (bonus excluded).
        best_return_curve: best return after every simulation (the paper's curve).
        info_curve: ``best leaf info[record_info]`` after every simulation, if asked.
        best_action: the recommended root action (``final_action`` rule), None if the
            root has no action.
        best_leaf_info: the step info of the last action of the best plan.
        n_simulations: simulations run.
        n_nodes: nodes in the tree (0 for a planner that keeps no tree).
        n_steps: calls of ``problem.step`` (simulator steps).
        n_feasibility_checks: calls of ``problem.is_feasible``.
        n_node_visits: node visits (actions taken inside simulations, new or not).
        wall_time: seconds spent in the simulations (``search`` or ``iterate``).
        mcts: the tree search object, for inspecting the tree (None without a tree).
    """

    actions: tuple[FloatArray, ...]
    rewards: FloatArray
    bonuses: FloatArray
    feasible: tuple[bool, ...]
    best_return: float
    best_return_curve: FloatArray
    info_curve: tuple[Any, ...] | None
    best_action: FloatArray | None
    best_leaf_info: Mapping[str, Any]
    n_simulations: int
    n_nodes: int
    n_steps: int
    n_feasibility_checks: int
    n_node_visits: int
    wall_time: float
    mcts: MCTS | None = field(default=None, repr=False, compare=False)

    def summary(self) -> dict[str, Any]:
        """Plain values for a results row (the curve as a list)."""
        return {
            "best_return": self.best_return,
            "plan_length": len(self.actions),
            "n_simulations": self.n_simulations,
            "n_nodes": self.n_nodes,
            "n_steps": self.n_steps,
            "n_feasibility_checks": self.n_feasibility_checks,
            "n_node_visits": self.n_node_visits,
            "wall_time": self.wall_time,
            "best_return_curve": self.best_return_curve.tolist(),
        }


class Search(ABC):
    """A planner that runs simulations one at a time and keeps the best return's curve.

    A subclass sets up its state (:attr:`problem` among it), calls :meth:`_start_curve`,
    and says what one simulation does (:meth:`_simulate`), which snapshot is the root
    (:meth:`_root_snapshot`), what the best return is so far (:attr:`best_return`), the
    step info at the end of the best path (:meth:`_best_info`) and what a result holds
    (:meth:`result`).
    """

    #: The planning problem searched (its state at the root is :meth:`_root_snapshot`).
    problem: Any

    #: Best return after every simulation (the paper's curve).
    best_return_curve: list[float]
    #: ``best info[record_info]`` after every simulation, when a search asked for it.
    info_curve: list[Any]
    #: Simulations run so far.
    n_simulations: int
    #: Seconds spent in :meth:`search`.
    wall_time: float

    def _start_curve(self) -> None:
        """Empty curves and counters (a new search, or a tree re-rooted)."""
        self.best_return_curve = []
        self.info_curve = []
        self.n_simulations = 0
        self.wall_time = 0.0

    @abstractmethod
    def _simulate(self) -> None:
        """Run one simulation from the root."""

    @abstractmethod
    def _root_snapshot(self) -> Any:
        """The problem's snapshot at the root (where :meth:`search` leaves the problem)."""

    @property
    @abstractmethod
    def best_return(self) -> float:
        """Best return (goal bonus excluded) so far."""

    @abstractmethod
    def _best_info(self) -> Mapping[str, Any]:
        """The step info at the end of the best path so far."""

    @abstractmethod
    def result(self, with_info_curve: bool = False) -> PlanResult:
        """The :class:`PlanResult` of the simulations so far."""

    def best_info(self) -> Mapping[str, Any]:
        """The step info at the end of the best path so far (``{}`` before any)."""
        return self._best_info()

    def iterate(self, n_simulations: int, record_info: str | None = None) -> Iterator[int]:
        """Run ``n_simulations`` more simulations, yielding after each one its index
        (0-based, counted over the planner's life): :meth:`search` one step at a time,
        for a caller that measures or stops between simulations
        (:func:`voot.planners.run_planner`).

        ``record_info`` as in :meth:`search`; :attr:`wall_time` counts the simulations
        only, not the caller's time between them.
        """
        n = check_n_simulations(n_simulations)
        for _ in range(n):
            t0 = time.perf_counter()
            try:
                self._simulate()
                self.n_simulations += 1
                self.best_return_curve.append(self.best_return)
                if record_info is not None:
                    self.info_curve.append(self._best_info().get(record_info))
            finally:
                self.wall_time += time.perf_counter() - t0
            yield self.n_simulations - 1

    def search(
        self,
        n_simulations: int,
        callback: Callable[[Any, int], Any] | None = None,
        record_info: str | None = None,
    ) -> PlanResult:
        """Run ``n_simulations`` more simulations and return the result so far.

        Args:
            n_simulations: number of simulations (>= 1).
            callback: called as ``callback(planner, i)`` after simulation ``i`` (0-based,
                counted over the planner's life); returning True stops the search.
            record_info: a step-info key (e.g. ``"objects_left"``) to record at the end of
                the best path after every simulation, into :attr:`PlanResult.info_curve`.

        The problem is left at the root's state (restored even if a simulation raises),
        wherever the last simulation ended.
        """
        try:
            for i in self.iterate(n_simulations, record_info):
                if callback is not None and callback(self, i):
                    break
        finally:
            self.problem.restore(self._root_snapshot())
        return self.result(record_info is not None)
