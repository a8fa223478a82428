r"""CMA-ES with IPOP/BIPOP restarts, an ask/tell adapter over pycma (the ``cma`` package).

The paper's CMA-ES baseline was weak (population 5, no restarts, best value logged per
generation). This adapter is a well-kept CMA-ES, as a fair comparison needs:

* **one point per ask**: pycma asks a whole population; the adapter buffers it, hands the
  members out one at a time and tells pycma the population once every member has a value,
  so the best-so-far can be logged after every single evaluation;
* **maximisation**: values are told to pycma negated (pycma minimises);
* **normalised coordinates**: pycma runs on :math:`[0, 1]^d`, mapped affinely to the box,
  so ``sigma0`` is a fraction of the box width in every dimension;
* **bounds**: pycma's ``BoundTransform`` (points are mapped into the box by a smooth
  transformation) or ``BoundPenalty`` (points are clipped to the box for evaluation and
  pycma adds a penalty proportional to the squared clipping distance). Either way every
  asked point lies inside the box;
* **restarts** when pycma's stop criteria fire: IPOP (the population grows by
  ``incpopsize`` at each restart, Auger & Hansen 2005) or BIPOP (interleaves such large
  runs with runs of small population and small step size, Hansen 2009, following
  pycma's ``fmin``). Evaluations are counted across restarts.

Determinism. pycma draws its samples with the ``randn`` option, by default
``np.random.randn``, and its ``seed`` option *seeds NumPy's global RNG*. The adapter
passes its own ``randn`` (a :class:`numpy.random.Generator` spawned from the optimiser's
``rng`` for each run) and ``seed=nan`` ("do nothing"), so results depend only on the
seed and the global RNG is neither read nor written. pycma's file-based signals
(``cma_signals.in``) and logging are switched off for the same reason.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from enum import StrEnum
from types import MappingProxyType
from typing import Any

import cma
import numpy as np

from voot import validation as V
from voot.optim.base import FloatArray, Optimizer, OptimizerConfig


class RestartStrategy(StrEnum):
    """What happens when pycma's stop criteria fire.

    ``ipop``
        Restart with the population multiplied by ``incpopsize`` (Auger & Hansen 2005).
    ``bipop``
        Alternate large-population runs (as IPOP) with small-population runs of smaller,
        random initial step size, giving each regime about the same budget (Hansen 2009).
    ``none``
        Never restart: keep asking the stopped run (the paper's original baseline).
    """

    IPOP = "ipop"
    BIPOP = "bipop"
    NONE = "none"


class BoundHandling(StrEnum):
    """pycma's bound handler: ``transform`` (``BoundTransform``) or ``penalty`` (``BoundPenalty``)."""

    TRANSFORM = "transform"
    PENALTY = "penalty"


class StartPoint(StrEnum):
    """Where a run's initial mean comes from: the box ``center``, ``random`` (uniform in
    the box) or, for restarts, the ``initial`` mean of the first run."""

    CENTER = "center"
    RANDOM = "random"
    INITIAL = "initial"


#: pycma options the adapter sets itself (they cannot be overridden by ``pycma_options``).
RESERVED_PYCMA_OPTIONS = frozenset(
    {
        "bounds",
        "BoundaryHandler",
        "popsize",
        "randn",
        "seed",
        "verbose",
        "verb_log",
        "verb_disp",
        "signals_filename",
    }
)


@dataclass(frozen=True)
class CMAESConfig(OptimizerConfig):
    """CMA-ES hyperparameters.

    Attributes:
        sigma0: initial step size as a fraction of the box width (pycma runs on the unit
            cube). The paper's grid: {0.1, 0.3, 0.5}. Note that pycma caps each
            coordinate's standard deviation at ``maxstd_boundrange`` = 1/3 of the width
            (a pycma option, which ``pycma_options`` may change), so 0.5 starts as 1/3.
        restarts: restart strategy, see :class:`RestartStrategy` (default IPOP).
        incpopsize: factor by which IPOP (and BIPOP's large regime) grows the population
            at each restart (pycma's default 2).
        popsize: population size of the first run; None for pycma's default
            :math:`4 + \\lfloor 3 \\ln d \\rfloor`.
        max_restarts: stop restarting after this many restarts (then behave as
            ``restarts="none"``); None for no limit.
        bound_handling: ``transform`` (pycma's default) or ``penalty``, see
            :class:`BoundHandling`.
        initial_mean: mean of the first run when no ``initial_point`` is given:
            ``center`` of the box or uniform ``random``.
        restart_mean: mean of every restarted run: uniform ``random`` in the box (as in
            the IPOP/BIPOP papers' experiments) or the ``initial`` mean again (as pycma's
            ``fmin`` with a fixed ``x0``).
        pycma_options: further pycma options (e.g. ``{"tolfun": 1e-12}``), checked
            against ``cma.CMAOptions()``; those the adapter sets itself are refused.
    """

    sigma0: float = 0.3
    restarts: RestartStrategy | str = RestartStrategy.IPOP
    incpopsize: float = 2.0
    popsize: int | None = None
    max_restarts: int | None = None
    bound_handling: BoundHandling | str = BoundHandling.TRANSFORM
    initial_mean: StartPoint | str = StartPoint.CENTER
    restart_mean: StartPoint | str = StartPoint.RANDOM
    pycma_options: Mapping[str, Any] | None = field(default=None)

    def __post_init__(self) -> None:
        if not (
            isinstance(self.sigma0, int | float)
            and not isinstance(self.sigma0, bool)
            and 0.0 < float(self.sigma0) <= 1.0
        ):
            raise ValueError(
                f"sigma0 must be a fraction of the box width in (0, 1], got {self.sigma0!r}"
            )
        object.__setattr__(
            self, "restarts", V.choice(RestartStrategy, self.restarts, "restarts", "values")
        )
        object.__setattr__(
            self,
            "bound_handling",
            V.choice(BoundHandling, self.bound_handling, "bound_handling", "values"),
        )
        initial = V.choice(StartPoint, self.initial_mean, "initial_mean", "values")
        if initial is StartPoint.INITIAL:
            raise ValueError("initial_mean must be 'center' or 'random', got 'initial'")
        object.__setattr__(self, "initial_mean", initial)
        restart = V.choice(StartPoint, self.restart_mean, "restart_mean", "values")
        if restart is StartPoint.CENTER:
            raise ValueError(
                "restart_mean must be 'random' or 'initial' (use initial_mean='center'"
                " with restart_mean='initial' to restart from the centre), got 'center'"
            )
        object.__setattr__(self, "restart_mean", restart)
        if not (
            isinstance(self.incpopsize, int | float)
            and not isinstance(self.incpopsize, bool)
            and math.isfinite(self.incpopsize)
            and self.incpopsize >= 1.0
        ):
            raise ValueError(f"incpopsize must be a finite number >= 1, got {self.incpopsize!r}")
        V.optional_integer(self.popsize, "popsize", 2)
        V.optional_integer(self.max_restarts, "max_restarts", 0)
        if self.pycma_options is not None:
            if not isinstance(self.pycma_options, Mapping):
                raise ValueError("pycma_options must be a mapping of pycma option names to values")
            valid = set(cma.CMAOptions())
            unknown = sorted(set(self.pycma_options) - valid)
            if unknown:
                raise ValueError(
                    f"unknown pycma option(s) {unknown}; see cma.CMAOptions() for valid names"
                )
            reserved = sorted(set(self.pycma_options) & RESERVED_PYCMA_OPTIONS)
            if reserved:
                raise ValueError(
                    f"pycma option(s) {reserved} are set by the adapter; use the config"
                    " fields sigma0, popsize, bound_handling and the optimiser's seed instead"
                )
            object.__setattr__(self, "pycma_options", MappingProxyType(dict(self.pycma_options)))

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        return {"sigma0": [0.1, 0.3, 0.5]}


class _Randn:
    """pycma's ``randn(lam, N)`` drawn from a private :class:`numpy.random.Generator`."""

    def __init__(self, rng: np.random.Generator) -> None:
        self.rng = rng

    def __call__(self, *shape: int) -> FloatArray:
        return self.rng.standard_normal(shape)


@dataclass
class RunRecord:
    """One CMA-ES run between restarts."""

    popsize: int
    sigma0: float
    regime: str
    evaluations: int = 0
    stop: dict[str, Any] = field(default_factory=dict)


class CMAES(Optimizer, name="cmaes", config_class=CMAESConfig, supports_revalue=False):
    """CMA-ES with restarts (maximisation), one point per ask. See the module docstring.

    Points told that the adapter did not ask (e.g. the common ``initial_point``, which
    instead becomes the first run's mean) are kept in the history but not told to pycma.
    If every member of the current population has been asked but some were not told,
    further asks hand out the untold members again.
    """

    config: CMAESConfig

    def _setup(self) -> None:
        super()._setup()
        cfg = self.config
        d = self.bounds.dim
        if self.initial_point is not None:
            mean0 = self.bounds.to_unit(self.initial_point)
        elif cfg.initial_mean is StartPoint.RANDOM:
            mean0 = self.rng.random(d)
        else:
            mean0 = np.full(d, 0.5)
        self._mean0 = np.clip(mean0, 0.0, 1.0)
        #: One record per run (the current run last); ``len(runs) - 1`` restarts so far.
        self.runs: list[RunRecord] = []
        self._popsize0 = 0
        self._maxiter0 = math.inf
        self._small_evals = 0
        self._large_evals = 0
        self._restarting = True  # restarts allowed (False after max_restarts)
        self._es: Any = None
        self._start_run(self._mean0, float(cfg.sigma0), cfg.popsize, "first", None)

    # ----- public diagnostics -----------------------------------------------------------
    @property
    def n_restarts(self) -> int:
        """Number of restarts so far."""
        return len(self.runs) - 1

    @property
    def es(self) -> Any:
        """The current ``cma.CMAEvolutionStrategy`` (for inspection only)."""
        return self._es

    # ----- runs -------------------------------------------------------------------------
    def _start_run(
        self,
        mean: FloatArray,
        sigma0: float,
        popsize: int | None,
        regime: str,
        maxiter: float | None,
    ) -> None:
        cfg = self.config
        transform = cfg.bound_handling is BoundHandling.TRANSFORM
        handler = cma.BoundTransform if transform else cma.BoundPenalty
        opts: dict[str, Any] = dict(cfg.pycma_options or {})
        opts.update(
            bounds=[0.0, 1.0],
            BoundaryHandler=handler,
            randn=_Randn(self.rng.spawn(1)[0]),
            seed=math.nan,
            verbose=-9,
            verb_log=0,
            verb_disp=0,
            signals_filename=None,
        )
        if popsize is not None:
            opts["popsize"] = int(popsize)
        if maxiter is not None:
            opts["maxiter"] = maxiter
        if self.bounds.dim == 1:
            # pycma does not support 1-D well: its std capping (maxstd, by default 1/3 of
            # the width) raises there. Switch the capping off and cap sigma0 here instead;
            # the bound handler still keeps every point inside.
            opts["maxstd"] = math.inf
            sigma0 = min(sigma0, 1.0 / 3.0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            self._es = cma.CMAEvolutionStrategy(mean, sigma0, opts)
        if not self.runs:
            self._popsize0 = int(self._es.popsize)
            self._maxiter0 = float(self._es.opts["maxiter"])
        self.runs.append(RunRecord(popsize=int(self._es.popsize), sigma0=sigma0, regime=regime))
        self._population: list[FloatArray] = []  # pycma's solutions (unit cube)
        self._points: list[FloatArray] = []  # the same, mapped into the box
        self._told: list[float | None] = []
        self._next = 0
        self._keys: dict[bytes, list[int]] = {}

    def _restart(self) -> None:
        cfg = self.config
        run = self.runs[-1]
        run.stop = dict(self._es.stop())
        if run.regime == "large":
            self._large_evals += run.evaluations
        else:  # pycma's fmin counts the first run in the small regime
            self._small_evals += run.evaluations
        if cfg.max_restarts is not None and self.n_restarts >= cfg.max_restarts:
            self._restarting = False
            return
        if cfg.restart_mean is StartPoint.RANDOM:
            mean = self.rng.random(self.bounds.dim)
        else:
            mean = self._mean0.copy()
        sigma0 = float(cfg.sigma0)
        n_large = sum(1 for r in self.runs if r.regime != "small")  # runs so far, first included
        bipop = cfg.restarts is RestartStrategy.BIPOP
        if bipop and self._small_evals < max(1, self._large_evals):
            # small regime: random popsize between the default and half the last large one,
            # step size down to 1/100 of sigma0 (pycma's fmin, Hansen 2009)
            mult = float(cfg.incpopsize) ** (n_large - 1)
            u_sigma, u_pop = self.rng.random(2)
            sigma0 *= float(0.01**u_sigma)
            popsize = max(2, int(self._popsize0 * mult ** (u_pop**2)))
            maxiter = min(self._maxiter0, 0.5 * self._large_evals / popsize)
            self._start_run(mean, sigma0, popsize, "small", max(1.0, maxiter))
        else:
            popsize = round(self._popsize0 * float(cfg.incpopsize) ** n_large)
            self._start_run(mean, sigma0, popsize, "large", None)

    # ----- ask / tell -------------------------------------------------------------------
    def _ask(self) -> FloatArray:
        if self._next >= len(self._population):
            if not self._population:
                self._new_population()
            else:  # everything handed out, some not told: hand those out again
                untold = [i for i, v in enumerate(self._told) if v is None]
                return self._points[untold[0]].copy()
        i = self._next
        self._next += 1
        return self._points[i].copy()

    def _new_population(self) -> None:
        pop = self._es.ask()
        lo, width = self.bounds.lower, self.bounds.width
        self._population = list(pop)
        self._points = []
        self._keys = {}
        for i, u in enumerate(pop):
            # BoundPenalty asks points outside the unit cube: evaluate the clipped point
            x = self.bounds.clip(lo + np.clip(u, 0.0, 1.0) * width)
            self._points.append(x)
            # clipping can map several members to one point: keep them all
            self._keys.setdefault(x.tobytes(), []).append(i)
        self._told = [None] * len(pop)
        self._next = 0

    def _tell(self, x: FloatArray, value: float) -> None:
        untold = [j for j in self._keys.get(x.tobytes(), ()) if self._told[j] is None]
        if not untold:
            return  # not asked by this run (or told already): history only
        i = untold[0]
        self._told[i] = value
        self.runs[-1].evaluations += 1
        if any(v is None for v in self._told):
            return
        told = np.array(self._told, dtype=np.float64)
        losses = -told
        bad = ~np.isfinite(losses)  # -inf values: worse than every finite one
        if bad.any():
            finite = losses[~bad]
            worst = float(finite.max()) if finite.size else 0.0
            losses[bad] = worst + 1.0 + abs(worst)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            self._es.tell(self._population, losses.tolist())
            stopped = bool(self._es.stop())
        self._population = []
        self._points = []
        self._told = []
        self._keys = {}
        self._next = 0
        if stopped and self._restarting and self.config.restarts is not RestartStrategy.NONE:
            self._restart()
