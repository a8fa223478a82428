"""Write an optimiser as a plain loop: a generator that yields points and receives values.

Algorithms such as SOO, DOO or BaMSOO are naturally a loop ("evaluate every candidate of
this sweep, then ..."). :class:`GeneratorOptimizer` turns such a loop into ask/tell::

    def _search(self):
        while True:
            value = yield point      # ask() returns `point`; tell(point, v) resumes with v

A running generator cannot be pickled, so a :class:`GeneratorOptimizer` keeps the recipe
of its state instead: its box, config, initial point and the state of its random
generator when it was made, and every ``ask``/``tell``/``revalue`` call since (with the
random generator's state before each, as a generator shared with others may have moved
between calls). Unpickling (and ``copy.deepcopy``) makes the optimiser anew and replays
those calls, which rebuilds the generator at the same point; the copy then continues bit
for bit like the original. Replaying costs what the calls cost (for BaMSOO, its GP fits).
"""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Generator, Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from voot.optim.base import FloatArray, Optimizer

Search = Generator[FloatArray, float, None]


class GeneratorOptimizer(Optimizer):
    """An :class:`Optimizer` whose search is the generator returned by :meth:`_search`.

    Points told that the generator did not propose (e.g. a common ``initial_point``) are
    kept in the history but not sent to the generator. When the generator finishes (its
    partition is exhausted), further asks are uniform in the box.
    """

    _search_gen: Search | None = None
    _proposed: FloatArray | None = None
    _exhausted: bool = False

    def _setup(self) -> None:
        super()._setup()
        #: What made this optimiser: the first part of its pickle (module docstring).
        self._birth: tuple[Any, ...] = (
            self.bounds,
            self.config,
            self.initial_point,
            type(self.rng.bit_generator),
            self.rng.bit_generator.state,
        )
        #: The calls since, each ``(name, arguments, random state before it)``; the state
        #: is None where it was the state the previous call left.
        self._calls: list[tuple[str, tuple[Any, ...], Mapping[str, Any] | None]] = []
        self._rng_after: Mapping[str, Any] = self._birth[4]

    def ask(self) -> FloatArray:
        before = self._state_before()
        x = super().ask()
        self._record("ask", (), before)
        return x

    def tell(self, x: ArrayLike, value: float) -> None:
        before = self._state_before()
        super().tell(x, value)  # checks first: a refused call is not recorded
        self._record("tell", (np.array(x, dtype=np.float64, copy=True), value), before)

    def revalue(self, index: int, value: float) -> None:
        before = self._state_before()
        super().revalue(index, value)
        self._record("revalue", (index, value), before)

    def _state_before(self) -> Mapping[str, Any] | None:
        """The random state now, or None if it is where the last call left it (most calls
        draw nothing, and nothing else drew since): the log keeps only what a replay needs."""
        state = self.rng.bit_generator.state
        return None if state == self._rng_after else state

    def _record(self, name: str, args: tuple[Any, ...], before: Mapping[str, Any] | None) -> None:
        self._calls.append((name, args, before))
        self._rng_after = self.rng.bit_generator.state

    def __getstate__(self) -> dict[str, Any]:
        """The recipe (module docstring): the birth, the calls and the random state now."""
        return {
            "birth": self._birth,
            "calls": self._calls,
            "rng_state": self.rng.bit_generator.state,
        }

    def __setstate__(self, state: dict[str, Any]) -> None:
        """Make the optimiser anew from its birth and replay its calls."""
        bounds, config, initial_point, bit_generator, birth_state = state["birth"]
        rng = np.random.Generator(bit_generator())
        rng.bit_generator.state = birth_state
        # made anew in place: the replayed generator's frame holds this very object
        Optimizer.__init__(self, bounds, config, seed=rng, initial_point=initial_point)
        for name, args, before in state["calls"]:
            if before is not None:
                self.rng.bit_generator.state = before
            getattr(self, name)(*args)
        self.rng.bit_generator.state = state["rng_state"]

    @abstractmethod
    def _search(self) -> Search:
        """The algorithm: ``value = yield x`` for every point it wants evaluated."""

    def _ask(self) -> FloatArray:
        if self._exhausted:
            return self.bounds.sample(self.rng)
        if self._proposed is None:
            try:
                if self._search_gen is None:
                    self._search_gen = self._search()
                    self._proposed = np.asarray(next(self._search_gen), dtype=np.float64)
                else:  # the last proposal was skipped by the caller: propose it again
                    return self.bounds.sample(self.rng)
            except StopIteration:
                self._exhausted = True
                return self.bounds.sample(self.rng)
        return self._proposed.copy()

    def _tell(self, x: FloatArray, value: float) -> None:
        if self._proposed is None or self._search_gen is None:
            return
        if not np.array_equal(x, self._proposed):
            return
        try:
            self._proposed = np.asarray(self._search_gen.send(value), dtype=np.float64)
        except StopIteration:
            self._proposed = None
            self._exhausted = True
