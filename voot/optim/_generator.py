"""Write an optimiser as a plain loop: a generator that yields points and receives values.

Algorithms such as SOO, DOO or BaMSOO are naturally a loop ("evaluate every candidate of
this sweep, then ..."). :class:`GeneratorOptimizer` turns such a loop into ask/tell::

    def _search(self):
        while True:
            value = yield point      # ask() returns `point`; tell(point, v) resumes with v
"""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Generator

import numpy as np

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
