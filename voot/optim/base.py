"""The ask/tell interface shared by every black-box optimiser in voot.

All optimisers *maximise* a function over a box ``[lower, upper]`` (a :class:`Bounds`).
The loop a user writes is::

    opt = make_optimizer("voo", bounds, seed=0)
    for _ in range(budget):
        x = opt.ask()
        opt.tell(x, f(x))
    opt.best_x, opt.best_value

``ask`` proposes one point, ``tell`` reports its value. Optimisers that work in batches
(CMA-ES) buffer internally, so the caller always sees one point at a time and the
best-so-far can be logged after every single evaluation.

Tree search (:mod:`voot.tree`) uses the same objects as per-node action samplers. There
the value of a tried action (its Q-hat) changes as the subtree below it is explored, so
optimisers that can take a changed value implement :meth:`Optimizer.revalue`.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V

FloatArray = NDArray[np.float64]


def _as_float_array(value: object, name: str, what: str) -> FloatArray:
    """``value`` as a float64 array, or a ValueError that names ``name`` and says ``what``.

    Numbers only: strings, booleans and ragged nestings are refused with a word about
    the argument, rather than numpy's "could not convert" or "inhomogeneous shape".
    """
    try:
        arr = value if isinstance(value, np.ndarray) else np.asarray(value)
        ok = arr.dtype.kind in "iuf"
    except (TypeError, ValueError):  # ragged
        ok = False
    if not ok:
        raise ValueError(f"{name} must be {what}, got {value!r}")
    return np.asarray(arr, dtype=np.float64)


def _as_point(x: object, name: str) -> FloatArray:
    """A point as a float64 array: float arrays pass as they are (the asked points)."""
    if type(x) is np.ndarray and x.dtype == np.float64:
        return x
    return _as_float_array(x, name, "a vector of numbers")


def _bound_vector(value: ArrayLike, name: str) -> FloatArray:
    """A bound (``lower`` or ``upper``) as a fresh, flat float64 vector."""
    arr = _as_float_array(value, f"bounds: {name}", "a vector of numbers")
    return np.array(arr, dtype=np.float64, copy=True).reshape(-1)


#: How far (a fraction of the box's width) a told point may lie outside the box and be
#: taken as rounding: it is clipped onto the face (see :meth:`Bounds.check_inside`).
FACE_TOLERANCE = 1e-12

#: The boxes :meth:`Bounds.cube` has built, by ``(class, low, high, dim)``.
_CUBES: dict[tuple[type, float, float, int], Bounds] = {}


@dataclass(frozen=True, eq=False)
class Bounds:
    """A box ``[lower, upper]`` in R^d with finite, strictly ordered bounds.

    Arrays are stored as read-only float64 copies, so a ``Bounds`` can be shared safely.
    """

    lower: FloatArray
    upper: FloatArray

    def __init__(self, lower: ArrayLike, upper: ArrayLike) -> None:
        lo = _bound_vector(lower, "lower")
        hi = _bound_vector(upper, "upper")
        if lo.shape != hi.shape:
            raise ValueError(
                f"bounds: lower has {lo.size} entries but upper has {hi.size}; they must match"
            )
        if lo.size == 0:
            raise ValueError("bounds: the box must have at least one dimension")
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            raise ValueError(f"bounds must be finite, got lower={lo.tolist()} upper={hi.tolist()}")
        bad = np.flatnonzero(lo >= hi)
        if bad.size:
            i = int(bad[0])
            raise ValueError(
                f"bounds are inverted or empty in dimension {i}: lower={lo[i]} >= upper={hi[i]}"
                " (need lower < upper in every dimension)"
            )
        lo.setflags(write=False)
        hi.setflags(write=False)
        with np.errstate(over="ignore"):
            width = hi - lo
        wide = np.flatnonzero(~np.isfinite(width))
        if wide.size:
            i = int(wide[0])
            raise ValueError(
                f"bounds are too wide in dimension {i}: upper - lower = {float(hi[i])!r} - {float(lo[i])!r}"
                f" overflows a float64 (its largest is {np.finfo(np.float64).max:.4g}); points"
                " of such a box cannot be drawn, so shrink or rescale it"
            )
        width.setflags(write=False)
        object.__setattr__(self, "lower", lo)
        object.__setattr__(self, "upper", hi)
        # derived once: tree search samples a node's box at every proposal
        object.__setattr__(self, "_width", width)
        object.__setattr__(self, "_dim", int(lo.size))

    @classmethod
    def cube(cls, low: float, high: float, dim: int) -> Bounds:
        """The box ``[low, high]^dim``.

        Boxes are immutable, so one instance per ``(low, high, dim)`` is kept and handed
        out again: environments ask for their operator's cube at every step.
        """
        if not (type(low) is float and type(high) is float and type(dim) is int and dim >= 1):
            # the environments' hot path passes Python floats and ints: check the rest
            low, high = V.number(low, "low"), V.number(high, "high")
            if not (V.is_integer(dim) and dim >= 1):
                raise ValueError(f"dim must be >= 1 (an integer), got {dim!r}")
            dim = int(dim)
        key = (cls, low, high, dim)
        box = _CUBES.get(key)
        if box is None:
            box = cls(np.full(dim, low), np.full(dim, high))
            if len(_CUBES) >= 256:
                _CUBES.clear()
            _CUBES[key] = box
        return box

    @classmethod
    def coerce(cls, bounds: Bounds | Sequence[Sequence[float]] | ArrayLike) -> Bounds:
        """Accept a ``Bounds``, a ``(d, 2)`` array of ``[low, high]`` rows, or a
        ``(lower, upper)`` pair of vectors (d != 2; a (2, 2) array is read as rows)."""
        if isinstance(bounds, Bounds):
            return bounds
        arr = _as_float_array(
            bounds,
            "bounds",
            "numbers: a Bounds, a (lower, upper) pair of equal-length vectors or (d, 2) rows"
            " of [low, high]",
        )
        if arr.ndim == 2 and arr.shape[0] == 2 and arr.shape[1] != 2:
            return cls(arr[0], arr[1])
        if arr.ndim == 2 and arr.shape[1] == 2:
            # (d, 2) rows of [low, high], scipy's convention; this also decides the
            # ambiguous 2-D case (2, 2): pass Bounds(lower, upper) for a 2-D pair.
            return cls(arr[:, 0], arr[:, 1])
        raise ValueError(
            "bounds must be a Bounds, a (lower, upper) pair of equal-length vectors, or a"
            f" (d, 2) array of [low, high] rows; got an array of shape {arr.shape}"
        )

    @property
    def dim(self) -> int:
        return self._dim  # type: ignore[attr-defined,no-any-return]

    @property
    def width(self) -> FloatArray:
        """``upper - lower`` (read-only, computed once)."""
        return self._width  # type: ignore[attr-defined,no-any-return]

    @property
    def center(self) -> FloatArray:
        return 0.5 * (self.lower + self.upper)

    @property
    def diameter(self) -> float:
        """Euclidean length of the box diagonal (delta_max in the paper)."""
        return float(np.linalg.norm(self.width))

    def sample(self, rng: np.random.Generator, n: int | None = None) -> FloatArray:
        """Uniform samples: shape ``(d,)`` if ``n`` is None, else ``(n, d)``."""
        # lower + u * width, in place on the draw (the same two IEEE operations per entry:
        # addition commutes exactly); the search samples a node's box at every proposal
        u = rng.random(self._dim if n is None else (n, self._dim))  # type: ignore[attr-defined]
        np.multiply(u, self._width, out=u)  # type: ignore[attr-defined]
        np.add(u, self.lower, out=u)
        return u

    def clip(self, x: ArrayLike) -> FloatArray:
        return np.clip(np.asarray(x, dtype=np.float64), self.lower, self.upper)

    def to_unit(self, x: FloatArray) -> FloatArray:
        """Point(s) ``x`` of the box in unit-cube coordinates, ``(x - lower) / width`` (the
        coordinates a GP or pycma works in)."""
        return (x - self.lower) / self.width

    def from_unit(self, u: FloatArray) -> FloatArray:
        """Unit-cube point(s) ``u`` back in the box, ``lower + u * width``, clipped onto it."""
        return self.clip(self.lower + u * self.width)

    def contains(self, x: ArrayLike) -> bool:
        arr = np.asarray(x, dtype=np.float64)
        return bool(np.all(arr >= self.lower) and np.all(arr <= self.upper))

    def check_point(self, x: ArrayLike, name: str = "x") -> FloatArray:
        """Return ``x`` as a float vector of this box's dimension, or raise ValueError."""
        arr = _as_point(x, name)
        if arr.shape != (self.dim,):
            raise ValueError(f"{name} must have shape ({self.dim},), got {arr.shape}")
        if not np.isfinite(arr).all():
            raise ValueError(f"{name} must be finite, got {arr.tolist()}")
        return arr

    def check_inside(self, x: ArrayLike, name: str = "x") -> FloatArray:
        """:meth:`check_point`, and ``x`` must lie in the box (its faces included).

        One pair of comparisons checks both (NaN fails them), so the common case costs
        no more than the finiteness check alone. A point outside the box by no more than
        rounding (:data:`FACE_TOLERANCE` of the box's width per coordinate, e.g. an
        optimiser's ``lower + u * width`` one ulp past ``upper``) is returned clipped
        onto the face, not refused; anything farther out is a ValueError.
        """
        arr = _as_point(x, name)
        if arr.shape != (self.dim,):
            raise ValueError(f"{name} must have shape ({self.dim},), got {arr.shape}")
        if (arr >= self.lower).all() and (arr <= self.upper).all():
            return arr
        if not np.isfinite(arr).all():
            raise ValueError(f"{name} must be finite, got {arr.tolist()}")
        slack = FACE_TOLERANCE * self.width
        if (arr >= self.lower - slack).all() and (arr <= self.upper + slack).all():
            return np.clip(arr, self.lower, self.upper)
        i = int(np.flatnonzero((arr < self.lower) | (arr > self.upper))[0])
        raise ValueError(
            f"{name} = {arr.tolist()} lies outside the box {self!r} (dimension {i}:"
            f" {float(arr[i])!r} not in [{float(self.lower[i])!r}, {float(self.upper[i])!r}]);"
            " tell points inside the bounds (e.g. bounds.clip(x), with its own value)"
        )

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, Bounds)
            and np.array_equal(self.lower, other.lower)
            and np.array_equal(self.upper, other.upper)
        )

    def __hash__(self) -> int:
        return hash((self.lower.tobytes(), self.upper.tobytes()))

    def __repr__(self) -> str:
        return f"Bounds(lower={self.lower.tolist()}, upper={self.upper.tolist()})"


@dataclass(frozen=True)
class OptimizerConfig:
    """Base of every optimiser's configuration dataclass.

    Subclasses add their hyperparameters as fields with the paper's values as defaults
    and validate them in ``__post_init__`` (raise ValueError naming the field and the
    valid range).
    """

    def to_dict(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in fields(self)}

    @classmethod
    def paper_grid(cls) -> dict[str, list[Any]]:
        """Hyperparameter grid searched in the paper (field name -> values).

        The benchmark runs every combination and selects, per optimiser, the one with the
        best mean final value. Empty means "defaults only".
        """
        return {}


def check_value(value: float, name: str = "value") -> float:
    """A told value must be a real number other than NaN and ``+inf`` (NaN is an error,
    not a silent -inf); ``-inf`` is a failure. A bool, a complex number, a string, None
    or another object is refused naming its type (:func:`voot.validation.real_number`),
    rather than read as 1.0, parsed, or left to a bare TypeError."""
    v = value if type(value) is float else V.real_number(value, name)
    if math.isnan(v):
        raise ValueError(
            f"{name} is NaN; tell finite values (use a large negative number for failures)"
        )
    if math.isinf(v) and v > 0:
        raise ValueError(f"{name} is +inf; tell finite values")
    return v


class Optimizer(ABC):
    """Sequential ask/tell maximiser on a box.

    Determinism: all randomness comes from ``self.rng = np.random.default_rng(seed)``,
    so the same seed and the same told values give the same asked points.

    Subclasses implement :meth:`_ask`, may override :meth:`_tell` and build their own
    state in :meth:`_setup`; the base class owns the constructor, the history (``xs``,
    ``values``), the best point and input validation. A subclass declares what it is in
    its class line, ``class VOO(Optimizer, name="voo", config_class=VOOConfig,
    supports_revalue=True)``; a keyword left out is inherited.
    """

    #: Registry name (set by subclasses), e.g. ``"voo"``.
    name: ClassVar[str] = ""
    #: Configuration dataclass of this optimiser.
    config_class: ClassVar[type[OptimizerConfig]] = OptimizerConfig
    #: Whether :meth:`revalue` is supported (needed by tree search samplers).
    supports_revalue: ClassVar[bool] = False

    def __init_subclass__(
        cls,
        *,
        name: str | None = None,
        config_class: type[OptimizerConfig] | None = None,
        supports_revalue: bool | None = None,
        **kwargs: Any,
    ) -> None:
        """Set the class attributes above from the class line's keywords."""
        super().__init_subclass__(**kwargs)
        if name is not None:
            cls.name = name
        if config_class is not None:
            cls.config_class = config_class
        if supports_revalue is not None:
            cls.supports_revalue = supports_revalue

    def __init__(
        self,
        bounds: Bounds | ArrayLike,
        config: OptimizerConfig | None = None,
        seed: int | np.random.SeedSequence | np.random.Generator | None = None,
        initial_point: ArrayLike | None = None,
    ) -> None:
        self.bounds = Bounds.coerce(bounds)
        if config is None:
            config = self.config_class()
        if not isinstance(config, self.config_class):
            raise TypeError(
                f"{type(self).__name__} needs a {self.config_class.__name__}, got {type(config).__name__}"
            )
        self.config = config
        self.rng = np.random.default_rng(V.seed(seed))
        self.initial_point: FloatArray | None = None
        if initial_point is not None:
            x0 = self.bounds.check_point(initial_point, "initial_point")
            if not self.bounds.contains(x0):
                raise ValueError(f"initial_point {x0.tolist()} lies outside {self.bounds}")
            self.initial_point = x0
        self._xs = np.empty((16, self.bounds.dim))
        self._values = np.empty(16)
        self._n = 0
        self._best_index = -1
        self._pending: FloatArray | None = None
        self._setup()

    def _setup(self) -> None:
        """Hook: the method's own state, built once the common state above exists.

        Subclasses override it (calling ``super()._setup()`` first) instead of
        ``__init__``, so that every optimiser has the same constructor.
        """
        return None

    # ----- public API -----------------------------------------------------------------
    def ask(self) -> FloatArray:
        """Propose the next point to evaluate (shape ``(d,)``, inside the bounds)."""
        if self._n == 0 and self.initial_point is not None:
            x = self.initial_point.copy()
        else:
            x = self._ask()
        self._pending = x
        return x

    def tell(self, x: ArrayLike, value: float) -> None:
        """Report ``f(x) = value``. ``x`` is normally the point just asked.

        ``x`` must be a finite point of the box (faces included) and ``value`` a real
        number other than NaN and ``+inf``; anything else is a ValueError and leaves the
        optimiser unchanged (both are checked before anything is stored). A point
        outside the box is rejected, not clipped: its value belongs to that point, and
        storing it at the clipped one would mislead the method; clip it yourself and
        evaluate the clipped point. Only a point within rounding of a face
        (:data:`FACE_TOLERANCE` of the width) is stored clipped onto it.

        ``-inf`` is a valid value meaning "failed evaluation", worse than every finite
        value: it stays in :attr:`values` and is never :attr:`best_value` while a finite
        value exists. Each method reads it so: VOO, DOO, RAND-DOO, SOO and random search
        compare values only (a ``-inf`` cell is never the best); CMA-ES ranks it below
        every finite value of its population; GP-UCB, REMBO and BaMSOO condition their
        GP on it as the worst finite value told so far (0 while there is none), since a
        GP needs finite targets. The tree search never tells ``-inf`` (an infeasible
        action is worth its finite penalty, e.g. -2).
        """
        xa = self.bounds.check_inside(x)
        v = check_value(value)
        self._append(xa, v)
        self._tell(xa, v)
        self._pending = None

    def revalue(self, index: int, value: float) -> None:
        """Replace the value of the ``index``-th told point (its Q-hat changed)."""
        if not self.supports_revalue:
            raise NotImplementedError(f"{type(self).__name__} does not support revalue()")
        if not 0 <= index < self._n:
            raise IndexError(f"index {index} out of range for {self._n} told points")
        v = check_value(value)
        self._values[index] = v
        self._revalue(index, v)
        if index == self._best_index or v >= self._values[self._best_index]:
            self._best_index = int(np.argmax(self._values[: self._n]))

    @property
    def n_told(self) -> int:
        return self._n

    @property
    def xs(self) -> FloatArray:
        """Told points, shape ``(n, d)`` (a view: do not modify)."""
        return self._xs[: self._n]

    @property
    def values(self) -> FloatArray:
        """Told values, shape ``(n,)`` (a view: do not modify)."""
        return self._values[: self._n]

    @property
    def best_index(self) -> int:
        """Index of the best told point (first argmax); -1 before any tell."""
        return self._best_index

    @property
    def best_x(self) -> FloatArray | None:
        return None if self._best_index < 0 else self._xs[self._best_index].copy()

    @property
    def best_value(self) -> float:
        return -math.inf if self._best_index < 0 else float(self._values[self._best_index])

    # ----- for subclasses -------------------------------------------------------------
    @abstractmethod
    def _ask(self) -> FloatArray:
        """Return a new point inside the bounds."""

    def _tell(self, x: FloatArray, value: float) -> None:  # noqa: B027 - optional hook
        """Hook after ``x`` was appended to the history (index ``n_told - 1``)."""

    def _revalue(self, index: int, value: float) -> None:  # noqa: B027 - optional hook
        """Hook after the value of point ``index`` changed."""

    def _append(self, x: FloatArray, value: float) -> None:
        if self._n == self._xs.shape[0]:
            cap = 2 * self._n
            xs = np.empty((cap, self.bounds.dim))
            xs[: self._n] = self._xs[: self._n]
            vals = np.empty(cap)
            vals[: self._n] = self._values[: self._n]
            self._xs, self._values = xs, vals
        self._xs[self._n] = x
        self._values[self._n] = value
        if self._best_index < 0 or value > self._values[self._best_index]:
            self._best_index = self._n
        self._n += 1
