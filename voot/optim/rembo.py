r"""REMBO: Bayesian optimisation in a random embedding (Wang et al. 2013).

REMBO assumes the objective varies mostly along a few directions of the D-dimensional
box. It draws a random matrix :math:`A \in \mathbb R^{D \times d}` with i.i.d.
:math:`\mathcal N(0, 1)` entries once (from the optimiser's seed) and runs GP-UCB over the
low-dimensional box :math:`Z = [-\sqrt d, \sqrt d]^d` (Wang et al.'s choice), evaluating
each :math:`z` at

.. math::

    x(z) = \text{lower} + \tfrac12\,(p(Az) + 1) \odot (\text{upper} - \text{lower}),
    \qquad p(y) = \operatorname{clip}(y, -1, 1),

i.e. the box is normalised to :math:`[-1, 1]^D` and :math:`Az` is projected onto it by
clipping. The GP lives on :math:`Z` (mapped to the unit cube) with the low-dimensional
RBF kernel; hyperparameters, refit schedule, acquisition maximisation and costs are
those of :mod:`voot.optim.gp_ucb` (GP cost depends on the number of points, not on d).

``low_dim`` defaults to the paper's choice: 2 for D = 10 and 3 for D = 20 (generally 2 up
to D = 10, else 3). REMBO needs ``low_dim < D``; the paper omits it on the 3-D functions,
and here ``D <= low_dim`` is a ValueError (use ``gp_ucb`` there).

Points the optimiser did not propose, such as the shared ``initial_point``, have no
preimage in the embedding: they are kept in the history (and in ``best_x``) but the GP
does not condition on them.

The authors' code differs (documented, not reproduced): A uniform in the *original* box
bounds and a low-dimensional box of half-width ``sqrt(upper)/2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from voot import validation as V
from voot.optim._surrogate import Surrogate, UCBConfig
from voot.optim.base import FloatArray, Optimizer


def default_low_dim(dim: int) -> int:
    """The paper's embedding dimension: 2 for D <= 10 (used at D = 10), else 3 (D = 20)."""
    return 2 if dim <= 10 else 3


@dataclass(frozen=True)
class REMBOConfig(UCBConfig):
    """REMBO hyperparameters: the embedding's (below), the acquisition's in the low box
    (:class:`~voot.optim._surrogate.UCBConfig`: candidates are drawn in the low box, the
    first ``n_initial`` points are uniform there; the authors' REMBO grid of ``zeta`` is
    {0.01, 0.1, 0.5, 1}) and the GP's (:class:`~voot.optim._surrogate.SurrogateConfig`).

    Attributes:
        low_dim: embedding dimension d (None: :func:`default_low_dim`); must be < D.
        box_half_width: half-width of the low-dimensional box (None: :math:`\\sqrt d`).
    """

    low_dim: int | None = None
    box_half_width: float | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        V.optional_integer(self.low_dim, "low_dim", 1)
        b = self.box_half_width
        if b is not None:
            V.positive(b, "box_half_width")

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"zeta": [0.01, 0.1, 0.5, 1.0]}


class REMBO(Optimizer, name="rembo", config_class=REMBOConfig, supports_revalue=True):
    """GP-UCB in a random linear embedding. See the module docstring."""

    config: REMBOConfig

    def _setup(self) -> None:
        super()._setup()
        D = self.bounds.dim
        d = self.config.low_dim if self.config.low_dim is not None else default_low_dim(D)
        if d >= D:
            raise ValueError(
                f"REMBO needs low_dim < dim, got low_dim={d} for a {D}-D box (the paper omits"
                " REMBO on 3-D problems); use a smaller low_dim or method 'gp_ucb'"
            )
        self.low_dim = int(d)
        hw = self.config.box_half_width
        #: Half-width of the low-dimensional box Z = [-b, b]^d.
        self.half_width = float(math.sqrt(d) if hw is None else hw)
        #: The random embedding A (D x d), i.i.d. standard normal.
        self.A = self.rng.standard_normal((D, self.low_dim))
        self.surrogate = Surrogate(self.low_dim, self.config, self.rng)
        self._us = np.empty((0, self.low_dim))  # embedded points, unit-cube coordinates
        self._uvals = np.empty(0)
        self._u_index: dict[int, int] = {}  # told index -> row of _us
        self._pending_u: FloatArray | None = None
        self._pending_x: FloatArray | None = None
        self.last_acquisition = float("nan")

    # ----- the embedding ------------------------------------------------------------
    def low_to_box(self, z: ArrayLike) -> FloatArray:
        """Map low-dimensional point(s) ``z`` in Z to the box: clip(Az) rescaled."""
        za = np.asarray(z, dtype=np.float64)
        y = np.clip(za @ self.A.T, -1.0, 1.0)
        return self.bounds.clip(self.bounds.lower + 0.5 * (y + 1.0) * self.bounds.width)

    def _unit_to_low(self, u: FloatArray) -> FloatArray:
        return self.half_width * (2.0 * u - 1.0)

    # ----- ask/tell -----------------------------------------------------------------
    def _ask(self) -> FloatArray:
        cfg = self.config
        if self._uvals.size < cfg.n_initial:
            u = self.rng.random(self.low_dim)
        else:
            gp = self.surrogate.sync(self._us, self._uvals)
            u, self.last_acquisition = cfg.maximize_ucb(gp, self.rng)
        x = self.low_to_box(self._unit_to_low(u))
        self._pending_u, self._pending_x = u, x
        return x.copy()

    def _tell(self, x: FloatArray, value: float) -> None:
        if self._pending_x is None or self._pending_u is None:
            return
        if not np.array_equal(x, self._pending_x):
            return  # not an embedded point (e.g. the initial point): history only
        self._u_index[self._n - 1] = self._uvals.size
        self._us = np.vstack([self._us, self._pending_u[None, :]])
        self._uvals = np.append(self._uvals, value)
        self._pending_u = self._pending_x = None

    def _revalue(self, index: int, value: float) -> None:
        row = self._u_index.get(index)
        if row is not None:
            self._uvals[row] = value
            self.surrogate.invalidate()
