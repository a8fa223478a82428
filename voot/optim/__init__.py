"""Black-box maximisers on a box with one ask/tell interface.

VOO (the paper's Algorithm 3) and the baselines it is compared with: DOO, SOO,
RAND-DOO, GP-UCB, CMA-ES (pycma), REMBO, BaMSOO and uniform random search.
This layer needs numpy, scipy and pycma only (no MuJoCo).
"""

from voot.optim.base import Bounds, Optimizer, OptimizerConfig
from voot.optim.registry import (
    MaximizeResult,
    available_methods,
    make_config,
    make_optimizer,
    maximize,
    optimizer_class,
)

__all__ = [
    "Bounds",
    "MaximizeResult",
    "Optimizer",
    "OptimizerConfig",
    "available_methods",
    "make_config",
    "make_optimizer",
    "maximize",
    "optimizer_class",
]
