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
from typing import Any

from voot.optim._surrogate import Surrogate, UCBConfig
from voot.optim.base import FloatArray, Optimizer


@dataclass(frozen=True)
class GPUCBConfig(UCBConfig):
    """GP-UCB hyperparameters: the acquisition's (:class:`~voot.optim._surrogate.UCBConfig`;
    the paper's grid of ``zeta`` is {0.01, 0.1, 1, 5, 10, 30}) and the GP's
    (:class:`~voot.optim._surrogate.SurrogateConfig`)."""

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"zeta": [0.01, 0.1, 1.0, 5.0, 10.0, 30.0]}


class GPUCB(Optimizer, name="gp_ucb", config_class=GPUCBConfig, supports_revalue=True):
    """GP-UCB maximiser on a box. See the module docstring."""

    config: GPUCBConfig

    def _setup(self) -> None:
        super()._setup()
        self.surrogate = Surrogate(self.bounds.dim, self.config, self.rng)
        #: Acquisition value of the last GP-proposed point (diagnostic).
        self.last_acquisition = float("nan")

    def _ask(self) -> FloatArray:
        cfg = self.config
        if self._n < cfg.n_initial:
            return self.bounds.sample(self.rng)
        gp = self.surrogate.sync(self.bounds.to_unit(self.xs), self.values)
        u, self.last_acquisition = cfg.maximize_ucb(gp, self.rng)
        return self.bounds.from_unit(u)

    def _revalue(self, index: int, value: float) -> None:
        self.surrogate.invalidate()
