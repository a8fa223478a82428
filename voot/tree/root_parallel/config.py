"""The options of root-parallel search and the seeds of its trees.

:class:`RootParallelConfig` holds the choices (number of trees, merge rule and its vote
radius), :class:`MergeRule` names the rules and :func:`tree_seeds` gives tree :math:`k`
the seed ``SeedSequence(seed).spawn(K)[k]``, which does not depend on :math:`K`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np

from voot import validation as V


class MergeRule(StrEnum):
    """How the root statistics of the trees choose the merged root action.

    See the module docstring for the exact rules and their tie-breaking.
    """

    MAX_Q = "max_q"
    MOST_VISITED = "most_visited"
    VOTE = "vote"


@dataclass(frozen=True)
class RootParallelConfig:
    """Options of root-parallel search (not paper constants: the paper runs one tree).

    Attributes:
        n_trees: :math:`K \\ge 1`, the number of independent trees.
        merge: the root merge rule, see :class:`MergeRule`.
        vote_radius: :math:`r \\in [0, 1]`, the neighbourhood radius of the ``vote`` rule
            in root-mean-square box widths (0.1: actions within a tenth of the box of each
            other, coordinate-wise on average, vote together). Ignored by other rules.
    """

    n_trees: int = 2
    merge: MergeRule | str = MergeRule.MAX_Q
    vote_radius: float = 0.1

    def __post_init__(self) -> None:
        k = self.n_trees
        V.integer(k, "n_trees", 1)
        object.__setattr__(self, "n_trees", int(k))
        object.__setattr__(self, "merge", merge_rule(self.merge))
        r = self.vote_radius
        if (
            isinstance(r, bool)
            or not isinstance(r, int | float | np.floating)
            or not math.isfinite(r)
            or not 0.0 <= float(r) <= 1.0
        ):
            raise ValueError(f"vote_radius must be a number in [0, 1], got {r!r}")
        object.__setattr__(self, "vote_radius", float(r))

    def to_dict(self) -> dict[str, Any]:
        """Plain values (the rule as a string), e.g. for a results row."""
        return {
            "n_trees": self.n_trees,
            "merge": MergeRule(self.merge).value,
            "vote_radius": self.vote_radius,
        }


def merge_rule(value: object) -> MergeRule:
    """``value`` as a :class:`MergeRule`, or a ValueError listing the valid rules."""
    try:
        return MergeRule(str(value).strip().lower().replace("-", "_"))
    except ValueError:
        valid = ", ".join(r.value for r in MergeRule)
        raise ValueError(f"unknown merge rule {value!r}; valid merge rules are: {valid}") from None


def tree_seeds(
    seed: int | Sequence[int] | np.random.SeedSequence | None, n_trees: int
) -> list[np.random.SeedSequence]:
    """The seeds of ``n_trees`` trees: ``SeedSequence(seed).spawn(n_trees)``.

    A :class:`~numpy.random.SeedSequence` passed as ``seed`` is not advanced (a copy with
    its entropy and spawn key is spawned from), so the same call always gives the same
    seeds. Tree ``k``'s seed does not depend on ``n_trees``.
    """
    V.integer(n_trees, "n_trees", 1)
    if isinstance(seed, np.random.SeedSequence):
        base = np.random.SeedSequence(
            seed.entropy, spawn_key=seed.spawn_key, pool_size=seed.pool_size
        )
    elif isinstance(seed, Sequence) and not isinstance(seed, str | bytes):
        base = np.random.SeedSequence(V.integers(seed, "seed", 0))
    else:
        base = np.random.SeedSequence(V.seed(seed))
    return base.spawn(int(n_trees))
