"""Outside planners for the tests of the plug-in path (a helper, not a test module): one
that keeps the contract, and one of each way to break it. Named ``planner_fixtures:NAME``
(``tests/`` is on the path of a test session)."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any, ClassVar

import numpy as np


def rollouts(
    problem: Any, budget: int, seed: np.random.SeedSequence, horizon: int = 3
) -> Iterator[float]:
    """Uniform random rollouts of ``horizon`` actions from the root; the best prefix wins."""
    rng = np.random.default_rng(seed)
    root = problem.snapshot()
    best, best_plan = -np.inf, []
    for _ in range(budget):
        problem.restore(root)
        plan, ret, weight = [], 0.0, 1.0
        for _ in range(horizon):
            box = problem.action_bounds()
            action = rng.uniform(box.lower, box.upper)
            res = problem.step(action)
            plan.append(action)
            ret += weight * res.reward
            weight *= problem.discount
            if ret > best:
                best, best_plan = ret, list(plan)
            if not res.feasible or res.terminal:
                break
        yield best
    return best_plan


rollouts.grid = {"horizon": (2, 3)}  # type: ignore[attr-defined]


class Rollouts:
    """:func:`rollouts` as a class (its ``__iter__`` the generator)."""

    grid: ClassVar[dict[str, tuple[int, ...]]] = {"horizon": (1, 2)}
    version = "2.0"

    def __init__(self, problem: Any, budget: int, seed: Any, horizon: int = 3) -> None:
        self.args = (problem, budget, seed, horizon)

    def __iter__(self) -> Iterator[float]:
        return (yield from rollouts(*self.args))


def yields_nan(problem: Any, budget: int, seed: Any) -> Iterator[float]:
    yield 0.0
    yield float("nan")
    return []


def raises_midway(problem: Any, budget: int, seed: Any) -> Iterator[float]:
    yield from rollouts(problem, 2, seed)
    raise RuntimeError("the planner's own bug")


def no_replay(problem: Any, budget: int, seed: Any) -> Iterator[float]:
    """Claims a return of 5 for the empty plan (whose return is 0)."""
    for _ in range(budget):
        yield 5.0
    return []


def too_few(problem: Any, budget: int, seed: Any) -> Iterator[float]:
    yield 0.0
    return []


def wrong_signature(problem: Any) -> Iterator[float]:
    yield 0.0


not_a_planner = 42
