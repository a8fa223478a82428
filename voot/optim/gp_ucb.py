r"""GP-UCB (Srinivas et al. 2010), the paper's Bayesian-optimisation baseline.

Each ask fits (or updates) a Gaussian process to the points evaluated so far (mapped to
the unit cube, targets standardised, see :mod:`voot.optim.gp`) and proposes

.. math::

    x_{t+1} = \arg\max_{x \in X} \; \mu_t(x) + \zeta\, \sigma_t(x),

with a constant exploration weight :math:`\zeta` (the paper's grid
{0.01, 0.1, 1, 5, 10, 30}) rather than the theoretical :math:`\sqrt{\beta_t}` schedule.
The acquisition is maximised as in the authors' code: the best of 10^4 uniform random
points, refined by L-BFGS-B (theirs: one start with numerical gradients; here
``n_local_starts`` starts with the analytic gradient).

Until ``n_initial`` points are known (the shared ``initial_point`` counts) asks are
uniform in the box. Hyperparameters are refitted by marginal likelihood on the schedule of
:class:`~voot.optim._surrogate.SurrogateConfig`; between refits one new point costs a
rank-1 Cholesky update.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from voot.optim._surrogate import Surrogate, SurrogateConfig, _is_int, check_zeta, maximize_ucb
from voot.optim.base import FloatArray, Optimizer, OptimizerConfig


@dataclass(frozen=True)
class GPUCBConfig(SurrogateConfig):
    """GP-UCB hyperparameters (GP options: see :class:`SurrogateConfig`).

    Attributes:
        zeta: UCB exploration weight :math:`\\zeta \\ge 0` (paper grid
            {0.01, 0.1, 1, 5, 10, 30}).
        n_candidates: uniform random candidates scored per ask (paper: 10^4).
        n_local_starts: L-BFGS-B runs from the best candidates (original code: 1).
        local_maxiter: L-BFGS-B iterations per run (0 disables the local refinement).
        n_initial: uniform random asks before the GP is used (including ``initial_point``).
    """

    zeta: float = 1.0
    n_candidates: int = 10_000
    n_local_starts: int = 1
    local_maxiter: int = 100
    n_initial: int = 1

    def __post_init__(self) -> None:
        super().__post_init__()
        check_zeta(self.zeta)
        for name in ("n_candidates", "n_local_starts", "n_initial"):
            if not _is_int(getattr(self, name), 1):
                raise ValueError(f"{name} must be an integer >= 1, got {getattr(self, name)!r}")
        if not _is_int(self.local_maxiter, 0):
            raise ValueError(f"local_maxiter must be an integer >= 0, got {self.local_maxiter!r}")

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"zeta": [0.01, 0.1, 1.0, 5.0, 10.0, 30.0]}


class GPUCB(Optimizer):
    """GP-UCB maximiser on a box. See the module docstring."""

    name: ClassVar[str] = "gp_ucb"
    config_class: ClassVar[type[OptimizerConfig]] = GPUCBConfig
    supports_revalue: ClassVar[bool] = True
    config: GPUCBConfig

    def _setup(self) -> None:
        super()._setup()
        self.surrogate = Surrogate(self.bounds.dim, self.config, self.rng)
        #: Acquisition value of the last GP-proposed point (diagnostic).
        self.last_acquisition = float("nan")

    def _unit(self, x: FloatArray) -> FloatArray:
        return (x - self.bounds.lower) / self.bounds.width

    def _ask(self) -> FloatArray:
        cfg = self.config
        if self._n < cfg.n_initial:
            return self.bounds.sample(self.rng)
        gp = self.surrogate.sync(self._unit(self.xs), self.values)
        u, acq = maximize_ucb(
            gp,
            float(cfg.zeta),
            self.rng,
            n_candidates=cfg.n_candidates,
            n_starts=cfg.n_local_starts,
            maxiter=cfg.local_maxiter,
        )
        self.last_acquisition = acq
        return self.bounds.clip(self.bounds.lower + u * self.bounds.width)

    def _revalue(self, index: int, value: float) -> None:
        self.surrogate.invalidate()
