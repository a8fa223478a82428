"""Per-node action samplers: the seam between the tree search and an action optimiser.

A node of :class:`voot.tree.MCTS` owns one :class:`ActionSampler`. The search asks it for
a new action (:meth:`~ActionSampler.propose`), tells it which proposals failed the
feasibility check (:meth:`~ActionSampler.reject`), which one was executed and its first
:math:`\\hat Q` (:meth:`~ActionSampler.add`) and, later, every change of an executed
action's :math:`\\hat Q` (:meth:`~ActionSampler.update`): the node's optimiser always sees
the node's current :math:`\\hat Q` of its tried actions (paper Algorithm 2, line 10).

:class:`OptimizerSampler` adapts any :class:`voot.optim.Optimizer` (ask / tell /
revalue); :class:`UniformSampler` draws independent uniform actions (PW-UCT). Action
index ``i`` of the node is the optimiser's ``i``-th told point.
"""

from __future__ import annotations

from typing import Any, Protocol, cast

import numpy as np

from voot.optim.base import Bounds, FloatArray, Optimizer


class ActionSampler(Protocol):
    """What a tree node needs from its action optimiser."""

    def propose(self) -> FloatArray:
        """A new candidate action inside the node's box."""
        ...

    def reject(self, action: FloatArray) -> None:
        """``action`` (the last proposal) failed the feasibility check: not executed."""
        ...

    def add(self, action: FloatArray, value: float, feasible: bool) -> None:
        """``action`` was executed as the node's next action; its first value."""
        ...

    def update(self, index: int, value: float) -> None:
        """The value of the node's ``index``-th action changed."""
        ...


class UniformSampler:
    """Independent uniform draws in the box; keeps no state (the PW-UCT sampler)."""

    __slots__ = ("bounds", "rng")

    def __init__(self, bounds: Bounds, rng: np.random.Generator) -> None:
        self.bounds = bounds
        self.rng = rng

    def propose(self) -> FloatArray:
        return self.bounds.sample(self.rng)

    def reject(self, action: FloatArray) -> None:
        pass

    def add(self, action: FloatArray, value: float, feasible: bool) -> None:
        pass

    def update(self, index: int, value: float) -> None:
        pass


class OptimizerSampler:
    """A :class:`voot.optim.Optimizer` as a node's action sampler.

    * ``propose`` is ``ask`` (or, with ``uniform_until_feasible``, a uniform draw while
      no executed action was feasible: the authors' VOO sampler);
    * ``add`` is ``tell``; an infeasible executed action is also passed to the
      optimiser's ``mark_infeasible(index)`` when it has one (RAND-DOO: infeasible
      samples do not split their cell);
    * ``update`` is ``revalue`` (ignored by optimisers that do not support it).
    """

    __slots__ = ("_mark", "_n_feasible", "_revalue", "optimizer", "uniform_until_feasible")

    def __init__(self, optimizer: Optimizer, uniform_until_feasible: bool = False) -> None:
        self.optimizer = optimizer
        self.uniform_until_feasible = uniform_until_feasible
        self._n_feasible = 0
        self._revalue = optimizer.revalue if optimizer.supports_revalue else None
        self._mark = getattr(optimizer, "mark_infeasible", None)

    def propose(self) -> FloatArray:
        opt = self.optimizer
        if self.uniform_until_feasible and self._n_feasible == 0:
            return opt.bounds.sample(opt.rng)
        return opt.ask()

    def reject(self, action: FloatArray) -> None:
        pass

    def add(self, action: FloatArray, value: float, feasible: bool) -> None:
        opt = self.optimizer
        opt.tell(action, value)
        if feasible:
            self._n_feasible += 1
        elif self._mark is not None:
            self._mark(opt.n_told - 1)

    def update(self, index: int, value: float) -> None:
        if self._revalue is not None:
            self._revalue(index, value)


def same_point(a: FloatArray, b: FloatArray) -> bool:
    """``np.array_equal(a, b)`` for two proposals, at a fraction of its cost.

    Two float64 arrays compare as lists of Python floats: the same shape and every
    entry ``==`` (so NaN differs from NaN and ``-0.0`` equals ``0.0``, as in
    ``np.array_equal``); anything else goes to ``np.array_equal``. The search asks it
    at every redraw, to notice a deterministic sampler repeating itself.
    """
    if (
        type(a) is np.ndarray
        and type(b) is np.ndarray
        and a.dtype == np.float64
        and b.dtype == np.float64
        and a.shape == b.shape
    ):
        return bool(a.tolist() == b.tolist())
    return bool(np.array_equal(a, b))


def make_optimizer_sampler(
    cls: type[Optimizer],
    config: Any,
    bounds: Bounds,
    rng: np.random.Generator,
    uniform_until_feasible: bool,
) -> OptimizerSampler:
    """An :class:`OptimizerSampler` over a fresh ``cls`` optimiser sharing ``rng``.

    All nodes of a tree share the tree's generator, so one seed fixes the whole search.
    """
    # default_rng(generator) returns the generator itself: no seeding cost per node.
    opt = cls(bounds, config=config, seed=cast(Any, rng))
    return OptimizerSampler(opt, uniform_until_feasible)
