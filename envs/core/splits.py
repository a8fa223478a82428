"""The protocol's layout split: which layout seeds of a generated family are trained (tuned)
on and which are held out for the report.

Kept apart from :mod:`voot.envs.core.generation` because the problem records
(:mod:`voot.problems`) carry a family's split and are read at ``import voot``: this module
imports only :mod:`voot.validation` and the typed names.
"""

from __future__ import annotations

from dataclasses import dataclass

from voot import validation as V
from voot.envs.core.names import Split

#: Layouts the protocol trains (tunes) on: never reported.
TRAINING_LAYOUTS: tuple[int, ...] = tuple(range(1000, 1020))
#: Layouts the protocol reports: the held-out test set, never trained on.
HELDOUT_LAYOUTS: tuple[int, ...] = tuple(range(0, 20))


@dataclass(frozen=True)
class LayoutSplit:
    """A family's fixed split of layout seeds: ``training`` and ``heldout``, disjoint and
    each non-empty (checked when built; duplicates dropped, order kept)."""

    training: tuple[int, ...]
    heldout: tuple[int, ...]

    def __post_init__(self) -> None:
        for name in ("training", "heldout"):
            values = V.integers(getattr(self, name), f"{name} layouts", 0)
            if not values:
                raise ValueError(f"a layout split needs {name} layouts")
            object.__setattr__(self, name, tuple(dict.fromkeys(values)))
        both = sorted(set(self.training) & set(self.heldout))
        if both:
            raise ValueError(
                f"layout seeds {', '.join(map(str, both))} are both training and held-out"
                " layouts: a split never trains on what it holds out"
            )

    def seeds(self, split: object) -> tuple[int, ...]:
        """The seeds of ``split`` (a :class:`~voot.envs.core.names.Split` or its string).

        Raises:
            ValueError: not a split (the message names the valid ones).
        """
        part = V.choice(Split, split, "split", "splits")
        return self.training if part == Split.TRAINING else self.heldout


#: The protocol's split, the same for every generated family: layouts 1000-1019 to train
#: (tune) on, 0-19 held out.
PROTOCOL_SPLIT = LayoutSplit(TRAINING_LAYOUTS, HELDOUT_LAYOUTS)
