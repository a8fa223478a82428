"""Uniform random search: the floor every optimiser should beat."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from voot.optim.base import FloatArray, Optimizer, OptimizerConfig


@dataclass(frozen=True)
class RandomSearchConfig(OptimizerConfig):
    """Uniform random search has no hyperparameters."""


class RandomSearch(Optimizer):
    """Samples every point uniformly in the box, independently of past values."""

    name: ClassVar[str] = "random"
    config_class: ClassVar[type[OptimizerConfig]] = RandomSearchConfig
    supports_revalue: ClassVar[bool] = True

    def _ask(self) -> FloatArray:
        return self.bounds.sample(self.rng)
