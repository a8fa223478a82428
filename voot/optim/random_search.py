"""Uniform random search: the floor every optimiser should beat."""

from __future__ import annotations

from dataclasses import dataclass

from voot.optim.base import FloatArray, Optimizer, OptimizerConfig


@dataclass(frozen=True)
class RandomSearchConfig(OptimizerConfig):
    """Uniform random search has no hyperparameters."""


class RandomSearch(
    Optimizer, name="random", config_class=RandomSearchConfig, supports_revalue=True
):
    """Samples every point uniformly in the box, independently of past values."""

    def _ask(self) -> FloatArray:
        return self.bounds.sample(self.rng)
