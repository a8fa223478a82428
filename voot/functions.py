r"""Test functions for black-box maximisation, with their domains and known optima.

The paper's synthetic benchmark (Figure 3) maximises three functions from DEAP's
``benchmarks`` module in 3, 10 and 20 dimensions; this module adds three more classics.
Every function here is in **maximisation form**: the usual minimisation benchmarks are
negated, Shekel (a sum of peaks) is used as is.

| name | :math:`f(x)` (as maximised) | domain | optimum |
| --- | --- | --- | --- |
| ``griewank`` | :math:`-\bigl(1 + \tfrac{1}{4000}\sum_i x_i^2 - \prod_i \cos(x_i/\sqrt{i})\bigr)` | :math:`[-600, 600]^d` | 0 at 0 |
| ``rastrigin`` | :math:`-\bigl(10d + \sum_i x_i^2 - 10\cos(2\pi x_i)\bigr)` | :math:`[-5.12, 5.12]^d` | 0 at 0 |
| ``shekel`` | :math:`\sum_{i=1}^{10} 1/(c_i + \lVert x - a_i\rVert^2)` | :math:`[-500, 500]^d` | numerical, see below |
| ``ackley`` | :math:`-\bigl(20 - 20e^{-0.2\sqrt{\bar{x^2}}} + e - e^{\overline{\cos 2\pi x}}\bigr)` | :math:`[-30, 30]^d` | 0 at 0 |
| ``rosenbrock`` | :math:`-\sum_{i<d} 100(x_i^2 - x_{i+1})^2 + (1 - x_i)^2` | :math:`[-100, 100]^d` | 0 at 1 |
| ``schwefel`` | :math:`-\bigl(418.9828872724339\,d - \sum_i x_i \sin\sqrt{\lvert x_i\rvert}\bigr)` | :math:`[-500, 500]^d` | :math:`\approx 0` at 420.9687... |

The formulas are DEAP's, term for term (``tests/test_functions.py`` checks every value
against ``deap.benchmarks``). Domains of Griewank, Rastrigin and Shekel are the paper's;
those of Ackley, Rosenbrock and Schwefel are the ones in the authors' benchmark script
(other common choices: Ackley :math:`[-32.768, 32.768]^d`, Rosenbrock :math:`[-5, 10]^d`).

**Shekel instances.** The paper's :math:`A` (10 x d) and :math:`c` (10) come from the
legacy global NumPy generator (:class:`numpy.random.RandomState`)::

    np.random.seed(seed); A = np.random.rand(10, d) * 10; C = np.random.rand(10)

with ``seed = 0`` for d = 3 and ``seed = 301`` for d = 10 and d = 20 (the reference
writes ``rand(10, 3)`` for d = 3; the same recipe with shape ``(10, d)`` is used for the
other dimensions, A drawn before C from one stream). All peaks lie in :math:`[0, 10]^d`,
so the function is nearly flat on almost all of :math:`[-500, 500]^d`. Its optimum is not
known in closed form; it was computed by L-BFGS-B (analytic gradient) started at every
:math:`a_i`, kept the best, and is stored in :data:`SHEKEL_OPTIMA` (a test recomputes it;
300 extra random starts in :math:`[0, 10]^d` found nothing better):

| d | seed | optimum (this module) | reference line in the original plots |
| --- | --- | --- | --- |
| 3 | 0 | 53.404324 | 4.78739 |
| 10 | 301 | 4.931945 | 6.04759 |
| 20 | 301 | 5.330106 | 3.93869 |

None of the original's reference values agrees with these A, C: no local maximum of the
three instances has those values (the second-highest ones are 4.383, 3.612 and 5.276), and
the 10-D reference exceeds the true maximum, so it cannot be a shortfall of the
genetic algorithm the paper used to estimate optima. The original loaded A and C from
pickled files that the published recipe does not reproduce (seeds 0-1999 of the same
recipe do not give these values either). This module uses the published recipe and the
true optima of its instances. Note that the 3-D instance has a needle: :math:`c_i = 0.0188`
gives a peak of height 53.4 and width about :math:`\sqrt{0.0188} \approx 0.14`, while the
second-best peak is 4.38.

``get_function("shekel", d)`` accepts d in :data:`SHEKEL_DIMS` only; build other
instances (any A, c, box) with :func:`make_shekel`, which computes the optimum the same
way when it is called.

**Centred optima and shifted instances.** Griewank, Rastrigin and Ackley have their
optimum at the origin, the centre of their symmetric boxes, and Shekel's peaks lie in
:math:`[0, 10]^d`, within 1% of the box width of the centre. A method that evaluates the
centre of the box (SOO and BaMSOO do so at their 3rd and 2nd evaluation) scores the exact
optimum of Griewank and Rastrigin there: an artifact of the benchmark, not a merit of the
method (COCO/BBOB avoids it by shifting every instance at random). ``get_function(name, d, instance=k)``
gives instance ``k``:

* ``k = 0`` (default): the paper's function, unshifted.
* ``k >= 1``: :math:`f_k(x) = f(x - s_k)`, whose maximiser is
  :math:`x^\star_k = x^\star + s_k`, drawn uniformly in the **central 80%** of the box
  (:data:`INSTANCE_MARGIN` = 10% of each coordinate range left out on each side), from
  ``default_rng(SeedSequence([key("voot.functions.instance"), key(name), d, k]))`` with
  ``key`` a SHA-256 prefix of the name: the same ``k`` gives the same function in every
  process, different ``k``, names or dimensions give independent shifts. The shift is
  rounded to a multiple of :math:`2^{-16}`, so :math:`f_k(x^\star_k)` is exactly
  :math:`f(x^\star)` (0 for the closed-form functions; Shekel to within rounding).
  The box, and so every method's initial point, stays the same.

This is valid because :math:`x^\star` maximises :math:`f` on all of
:math:`\mathbb{R}^d`, not only on the box, for the functions in
:data:`SHIFTED_FUNCTIONS` (Griewank, Rastrigin, Ackley, Rosenbrock, Shekel). It is not
for **Schwefel**, whose formula grows beyond :math:`[-500, 500]` (a shifted Schwefel would
have a higher, different optimum): Schwefel is left unshifted in every instance, which is
harmless since its optimum (420.97, ...) is near a corner, far from the centre.
:func:`shifted` shifts any other function by a given offset.

Size: one registry of test functions with the paper's instances and their optima; each
function is a few lines, the Shekel instances and their documented optima most of it.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from voot import validation as V
from voot.optim.base import Bounds, FloatArray

__all__ = [
    "INSTANCE_MARGIN",
    "SCHWEFEL_ARGMAX",
    "SHEKEL_DIMS",
    "SHEKEL_OPTIMA",
    "SHEKEL_REFERENCE_OPTIMA",
    "SHEKEL_SEEDS",
    "SHIFTED_FUNCTIONS",
    "TestFunction",
    "available_functions",
    "get_function",
    "make_shekel",
    "shekel_optimum",
    "shekel_parameters",
    "shifted",
]

Kernel = Callable[[FloatArray], FloatArray]
"""Vectorised formula of a test function: points ``(n, d)`` -> values ``(n,)``."""


# ----------------------------------------------------------------------------------------
# The function object
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False, repr=False)
class TestFunction:
    """A function to maximise on a box, with its known optimum.

    Calling it evaluates one point or a batch: ``f(x)`` with ``x`` of shape ``(d,)``
    returns a ``float``; ``f(X)`` with ``X`` of shape ``(n, d)`` returns an array of
    shape ``(n,)``. Points outside :attr:`bounds` are evaluated too (the formulas are
    defined everywhere); non-finite coordinates and wrong shapes raise ``ValueError``.

    Attributes:
        name: registry name, e.g. ``"shekel"``.
        dim: number of variables d.
        bounds: the search box (the paper's domain).
        optimum_value: :math:`\\max_{x \\in \\text{bounds}} f(x)` (exactly ``f(optimum_x)``).
        optimum_x: a maximiser, shape ``(d,)``, read-only.
        kernel: the vectorised formula, ``(n, d) -> (n,)``, without input checks.
        instance: 0 for the paper's function, k >= 1 for a shifted instance (see the
            module docstring).
        shift: the offset :math:`s` of the formula, :math:`f(x - s)`, shape ``(d,)``,
            read-only; zeros when unshifted (``None`` is taken as zeros).
    """

    __test__: ClassVar[bool] = False  # not a pytest test class despite its name

    name: str
    dim: int
    bounds: Bounds
    optimum_value: float
    optimum_x: FloatArray
    kernel: Kernel = field(repr=False)
    instance: int = 0
    shift: FloatArray | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        V.integer(self.dim, f"{self.name}: dim", 1)
        if self.bounds.dim != self.dim:
            raise ValueError(
                f"{self.name}: bounds have {self.bounds.dim} dimensions but dim is {self.dim}"
            )
        x = np.array(self.optimum_x, dtype=np.float64, copy=True).reshape(-1)
        if x.shape != (self.dim,) or not np.all(np.isfinite(x)):
            raise ValueError(
                f"{self.name}: optimum_x must be {self.dim} finite numbers, got {x.tolist()}"
            )
        x.setflags(write=False)
        object.__setattr__(self, "optimum_x", x)
        object.__setattr__(self, "optimum_value", float(self.optimum_value))
        object.__setattr__(self, "instance", _check_instance(self.instance, self.name))
        s = np.zeros(self.dim) if self.shift is None else np.array(self.shift, dtype=np.float64)
        if s.shape != (self.dim,) or not np.all(np.isfinite(s)):
            raise ValueError(f"{self.name}: shift must be {self.dim} finite numbers, got {s!r}")
        s.setflags(write=False)
        object.__setattr__(self, "shift", s)

    # ----- evaluation -----------------------------------------------------------------
    def __call__(self, x: ArrayLike) -> Any:
        """``f(x)``: a float for one point ``(d,)``, an array ``(n,)`` for ``(n, d)``."""
        pts = self._points(x)
        values = self.kernel(pts if pts.ndim == 2 else pts[None, :])
        return values if pts.ndim == 2 else float(values[0])

    def value(self, x: ArrayLike) -> float:
        """``f(x)`` of one point of shape ``(d,)`` (typed as ``float``)."""
        pts = self._points(x)
        if pts.ndim != 1:
            raise ValueError(f"{self}: value() takes one point of shape ({self.dim},)")
        return float(self.kernel(pts[None, :])[0])

    def values(self, xs: ArrayLike) -> FloatArray:
        """``f`` of each row of ``xs`` (shape ``(n, d)``) as an array of shape ``(n,)``."""
        pts = self._points(xs)
        if pts.ndim != 2:
            raise ValueError(f"{self}: values() takes points of shape (n, {self.dim})")
        return self.kernel(pts)

    def regret(self, value: ArrayLike) -> Any:
        """Simple regret ``optimum_value - value`` (float, or array for an array input).

        Not clipped at 0: a negative regret would reveal a wrong stored optimum.
        """
        arr = np.asarray(value, dtype=np.float64)
        if np.any(np.isnan(arr)):
            raise ValueError(f"{self}: regret of NaN is undefined")
        out = self.optimum_value - arr
        return float(out) if out.ndim == 0 else out

    # ----- helpers ----------------------------------------------------------------------
    def _points(self, x: ArrayLike) -> FloatArray:
        try:
            pts = np.asarray(x, dtype=np.float64)
        except (TypeError, ValueError) as err:
            raise ValueError(f"{self}: x must be an array of real numbers ({err})") from None
        d = self.dim
        if not ((pts.ndim == 1 and pts.shape[0] == d) or (pts.ndim == 2 and pts.shape[1] == d)):
            raise ValueError(
                f"{self}: x must have shape ({d},) for one point or (n, {d}) for a batch,"
                f" got {pts.shape}"
            )
        if not np.all(np.isfinite(pts)):
            row, col = (int(i) for i in np.argwhere(~np.isfinite(np.atleast_2d(pts)))[0])
            where = f"row {row}, coordinate {col}" if pts.ndim == 2 else f"coordinate {col}"
            raise ValueError(
                f"{self}: x must be finite; found {np.atleast_2d(pts)[row, col]} at {where}"
            )
        return pts

    def __str__(self) -> str:
        return f"{self.name}-{self.dim}d" + (f"-i{self.instance}" if self.instance else "")

    def __repr__(self) -> str:
        lo, hi = self.bounds.lower[0], self.bounds.upper[0]
        box = (
            f"[{lo:g}, {hi:g}]^{self.dim}"
            if np.all(self.bounds.lower == lo) and np.all(self.bounds.upper == hi)
            else repr(self.bounds)
        )
        return (
            f"TestFunction(name={self.name!r}, dim={self.dim}, bounds={box},"
            f" optimum_value={self.optimum_value!r}"
            + (f", instance={self.instance}" if self.instance else "")
            + ")"
        )


# ----------------------------------------------------------------------------------------
# Kernels (maximisation form), each (n, d) -> (n,)
# ----------------------------------------------------------------------------------------
def _griewank(xs: FloatArray) -> FloatArray:
    i = np.arange(1, xs.shape[1] + 1, dtype=np.float64)
    value: FloatArray = (
        np.sum(xs * xs, axis=1) / 4000.0 - np.prod(np.cos(xs / np.sqrt(i)), axis=1) + 1.0
    )
    return 0.0 - value  # not -value: keeps +0.0 at the optimum


def _rastrigin(xs: FloatArray) -> FloatArray:
    value: FloatArray = 10.0 * xs.shape[1] + np.sum(
        xs * xs - 10.0 * np.cos(2.0 * np.pi * xs), axis=1
    )
    return 0.0 - value  # not -value: keeps +0.0 at the optimum


def _ackley(xs: FloatArray) -> FloatArray:
    n = xs.shape[1]
    value: FloatArray = (
        20.0
        - 20.0 * np.exp(-0.2 * np.sqrt(np.sum(xs * xs, axis=1) / n))
        + math.e
        - np.exp(np.sum(np.cos(2.0 * np.pi * xs), axis=1) / n)
    )
    return 0.0 - value  # not -value: keeps +0.0 at the optimum


def _rosenbrock(xs: FloatArray) -> FloatArray:
    x, y = xs[:, :-1], xs[:, 1:]
    value: FloatArray = np.sum(100.0 * (x * x - y) ** 2 + (1.0 - x) ** 2, axis=1)
    return 0.0 - value  # not -value: keeps +0.0 at the optimum


#: DEAP's Schwefel offset, :math:`\max_x x \sin\sqrt{|x|}` to 16 digits.
_SCHWEFEL_OFFSET = 418.9828872724339
SCHWEFEL_ARGMAX = 420.96874635998194
r"""Maximiser of :math:`x \sin\sqrt{|x|}` on [-500, 500]: the root of
:math:`\sin u + \tfrac{u}{2}\cos u = 0` with :math:`u = \sqrt{x}` (Brent's method)."""


def _schwefel(xs: FloatArray) -> FloatArray:
    value: FloatArray = _SCHWEFEL_OFFSET * xs.shape[1] - np.sum(
        xs * np.sin(np.sqrt(np.abs(xs))), axis=1
    )
    return 0.0 - value  # not -value: keeps +0.0 at the optimum


class _Shekel:
    """Shekel kernel :math:`\\sum_i 1/(c_i + \\lVert x - a_i\\rVert^2)` (picklable)."""

    def __init__(self, a: FloatArray, c: FloatArray) -> None:
        self.a = a
        self.c = c

    def __call__(self, xs: FloatArray) -> FloatArray:
        diff = xs[:, None, :] - self.a[None, :, :]
        sq = np.einsum("nmd,nmd->nm", diff, diff)
        out: FloatArray = np.sum(1.0 / (self.c + sq), axis=1)
        return out

    def gradient(self, x: FloatArray) -> FloatArray:
        diff = x - self.a
        den = self.c + np.einsum("md,md->m", diff, diff)
        grad: FloatArray = -2.0 * np.sum(diff / (den * den)[:, None], axis=0)
        return grad


class _Shifted:
    """Kernel of :math:`f(x - s)` (picklable, unlike a closure)."""

    def __init__(self, kernel: Kernel, shift: FloatArray) -> None:
        self.kernel = kernel
        self.shift = shift

    def __call__(self, xs: FloatArray) -> FloatArray:
        return self.kernel(xs - self.shift)


# ----------------------------------------------------------------------------------------
# Shekel instances
# ----------------------------------------------------------------------------------------
SHEKEL_DIMS: tuple[int, ...] = (3, 10, 20)
"""Dimensions of the paper's Shekel instances."""
SHEKEL_SEEDS: dict[int, int] = {3: 0, 10: 301, 20: 301}
"""Legacy ``np.random.seed`` of each instance's A and c."""
SHEKEL_REFERENCE_OPTIMA: dict[int, float] = {3: 4.78739, 10: 6.04759, 20: 3.93869}
"""Optimum lines drawn in the original's Figure-3 plots (they do not match these A, c)."""

SHEKEL_OPTIMA: dict[int, tuple[tuple[float, ...], float]] = {
    3: (
        (
            5.680443650933277,
            9.255962195296856,
            0.7103674923382978,
        ),
        53.40432382499213,
    ),
    10: (
        (
            6.087031505162543,
            2.005493016215589,
            6.116444652425887,
            2.0089029277307366,
            8.821792045679555,
            9.30806284803083,
            4.450261943633243,
            0.7146134746597057,
            8.532761007578278,
            9.896754066341371,
        ),
        4.931945217232023,
    ),
    20: (
        (
            8.059935646686785,
            5.206940545434662,
            5.331206344884027,
            3.312634664647785,
            2.234096712745616,
            4.619647493928551,
            9.280592215019519,
            6.106478506125196,
            8.786512764648782,
            7.789044085207219,
            1.5398264237804808,
            4.966442206195494,
            5.115364570226316,
            7.560015541064387,
            9.459637414820877,
            5.304963235376008,
            5.187335063103078,
            5.724896977028404,
            2.932895757571808,
            5.41331151149023,
        ),
        5.330105852882616,
    ),
}
"""Maximiser and maximum of each paper instance, from :func:`shekel_optimum`
(``tests/test_functions.py`` recomputes them)."""


def shekel_parameters(dim: int) -> tuple[FloatArray, FloatArray]:
    """The paper's Shekel ``A`` (10 x dim) and ``c`` (10,) for ``dim`` in :data:`SHEKEL_DIMS`.

    ``np.random.seed(SHEKEL_SEEDS[dim]); A = np.random.rand(10, dim) * 10;
    C = np.random.rand(10)``, drawn from a private :class:`numpy.random.RandomState`
    (same stream as the legacy global generator, without touching it).
    """
    _check_shekel_dim(dim)
    rs = np.random.RandomState(SHEKEL_SEEDS[dim])
    a = rs.rand(10, dim) * 10.0
    c = rs.rand(10)
    return a, c


def shekel_optimum(
    a: ArrayLike, c: ArrayLike, bounds: Bounds | ArrayLike | None = None
) -> tuple[FloatArray, float]:
    """Maximise the Shekel function of ``a`` (m x d), ``c`` (m,) numerically.

    L-BFGS-B with the analytic gradient, started at every peak centre :math:`a_i`
    (clipped to ``bounds``), tolerances near machine precision; the best end point wins.
    Peaks are where the maximum must be, so this finds the global maximum unless two
    peaks merge in a way that puts it far from every centre.

    Returns:
        ``(x_star, f(x_star))``.
    """
    a_arr, c_arr = _check_shekel_arrays(a, c)
    box = (
        Bounds.coerce(bounds) if bounds is not None else Bounds.cube(-500.0, 500.0, a_arr.shape[1])
    )
    if box.dim != a_arr.shape[1]:
        raise ValueError(f"bounds have {box.dim} dimensions but a has {a_arr.shape[1]} columns")
    from scipy.optimize import minimize  # local: scipy.optimize is slow to import

    kernel = _Shekel(a_arr, c_arr)
    limits = list(zip(box.lower.tolist(), box.upper.tolist(), strict=True))
    best_x, best_v = box.clip(a_arr[0]), -math.inf
    for start in a_arr:
        res = minimize(
            lambda x: -float(kernel(x[None, :])[0]),
            box.clip(start),
            jac=lambda x: -kernel.gradient(x),
            method="L-BFGS-B",
            bounds=limits,
            options={"ftol": 1e-15, "gtol": 1e-12, "maxiter": 10_000},
        )
        x = box.clip(res.x)
        v = float(kernel(x[None, :])[0])
        if v > best_v:
            best_x, best_v = x, v
    return best_x, best_v


def make_shekel(
    a: ArrayLike,
    c: ArrayLike,
    bounds: Bounds | ArrayLike | None = None,
    name: str = "shekel",
) -> TestFunction:
    """A Shekel function with custom peaks ``a`` (m x d) and widths ``c`` (m,), c > 0.

    ``bounds`` defaults to :math:`[-500, 500]^d`. The optimum is computed now with
    :func:`shekel_optimum` (m local searches; milliseconds for m = 10, d <= 20).
    """
    a_arr, c_arr = _check_shekel_arrays(a, c)
    d = a_arr.shape[1]
    box = Bounds.coerce(bounds) if bounds is not None else Bounds.cube(-500.0, 500.0, d)
    x_star, _ = shekel_optimum(a_arr, c_arr, box)
    kernel = _Shekel(a_arr, c_arr)
    return TestFunction(name, d, box, float(kernel(x_star[None, :])[0]), x_star, kernel)


def _check_shekel_arrays(a: ArrayLike, c: ArrayLike) -> tuple[FloatArray, FloatArray]:
    a_arr = np.array(a, dtype=np.float64, copy=True)
    c_arr = np.array(c, dtype=np.float64, copy=True).reshape(-1)
    if a_arr.ndim != 2 or a_arr.shape[0] < 1 or a_arr.shape[1] < 1:
        raise ValueError(
            f"shekel: a must be a (m, d) array of peak centres, got shape {a_arr.shape}"
        )
    if c_arr.shape != (a_arr.shape[0],):
        raise ValueError(
            f"shekel: c must have one entry per row of a ({a_arr.shape[0]}), got {c_arr.shape[0]}"
        )
    if not (np.all(np.isfinite(a_arr)) and np.all(np.isfinite(c_arr))):
        raise ValueError("shekel: a and c must be finite")
    if np.any(c_arr <= 0):
        raise ValueError(f"shekel: every c_i must be > 0 (peak height 1/c_i), got {c_arr.tolist()}")
    a_arr.setflags(write=False)
    c_arr.setflags(write=False)
    return a_arr, c_arr


def _check_shekel_dim(dim: int) -> None:
    if dim not in SHEKEL_DIMS or isinstance(dim, bool):
        raise ValueError(
            f"shekel: the paper's instances exist for dim in {list(SHEKEL_DIMS)}, got {dim!r};"
            " build another instance with voot.functions.make_shekel(a, c, bounds)"
        )


# ----------------------------------------------------------------------------------------
# Registry
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Spec:
    kernel: Kernel
    low: float
    high: float
    argmax: float  # every coordinate of the maximiser
    min_dim: int = 1


_SPECS: dict[str, _Spec] = {
    "griewank": _Spec(_griewank, -600.0, 600.0, 0.0),
    "rastrigin": _Spec(_rastrigin, -5.12, 5.12, 0.0),
    "ackley": _Spec(_ackley, -30.0, 30.0, 0.0),
    "rosenbrock": _Spec(_rosenbrock, -100.0, 100.0, 1.0, min_dim=2),
    "schwefel": _Spec(_schwefel, -500.0, 500.0, SCHWEFEL_ARGMAX),
}


def available_functions() -> list[str]:
    """Names accepted by :func:`get_function`."""
    return sorted([*_SPECS, "shekel"])


def get_function(
    name: str, dim: int | np.integer[Any], instance: int | np.integer[Any] = 0
) -> TestFunction:
    """The test function ``name`` in ``dim`` dimensions, in maximisation form.

    >>> f = get_function("rastrigin", 3)
    >>> f([0.0, 0.0, 0.0]), f.optimum_value
    (0.0, 0.0)
    >>> g = get_function("rastrigin", 3, instance=1)
    >>> g(g.optimum_x), bool(g([0.0, 0.0, 0.0]) < 0.0)
    (0.0, True)

    Args:
        name: one of :func:`available_functions` (case-insensitive).
        dim: number of variables.
        instance: 0 for the paper's function; k >= 1 for the function with its optimum
            moved to a random point of the central 80% of the box, drawn
            deterministically from ``(name, dim, k)`` (module docstring). Schwefel is
            the same in every instance.

    Raises:
        ValueError: unknown name (the message lists the valid ones), a dimension the
            function does not have (Rosenbrock needs dim >= 2, Shekel dim in 3, 10, 20),
            or an instance that is not an integer >= 0.
    """
    key = str(name).strip().lower()
    if key not in available_functions():
        raise ValueError(
            f"unknown test function {name!r}; valid names are: {', '.join(available_functions())}"
        )
    V.integer(dim, f"{key}: dim", 1)
    dim = int(dim)
    k = _check_instance(instance, key)
    if key == "shekel":
        _check_shekel_dim(dim)
        a, c = shekel_parameters(dim)
        kernel: Kernel = _Shekel(a, c)
        x_star = np.array(SHEKEL_OPTIMA[dim][0])
        box = Bounds.cube(-500.0, 500.0, dim)
    else:
        spec = _SPECS[key]
        if dim < spec.min_dim:
            raise ValueError(f"{key}: dim must be >= {spec.min_dim}, got {dim}")
        kernel = spec.kernel
        x_star = np.full(dim, spec.argmax)
        box = Bounds.cube(spec.low, spec.high, dim)
    optimum = float(kernel(x_star[None, :])[0])
    base = TestFunction(key, dim, box, optimum, x_star, kernel)
    if k == 0:
        return base
    if key not in SHIFTED_FUNCTIONS:  # Schwefel: optimum already off-centre, not shiftable
        return dataclasses.replace(base, instance=k)
    return shifted(base, _instance_offset(base, k), instance=k)


# ----------------------------------------------------------------------------------------
# Shifted instances
# ----------------------------------------------------------------------------------------
SHIFTED_FUNCTIONS: tuple[str, ...] = ("ackley", "griewank", "rastrigin", "rosenbrock", "shekel")
r"""Functions whose instances k >= 1 are shifted: their maximiser maximises them on all of
:math:`\mathbb{R}^d`, so :math:`f(x - s)` has its maximum at :math:`x^\star + s`."""
INSTANCE_MARGIN = 0.1
"""Fraction of each coordinate range left out on each side when drawing an instance's
optimum: the optimum is uniform in the central ``1 - 2 * INSTANCE_MARGIN`` (80%)."""
_SHIFT_GRID = 2.0**-16  # shifts are multiples of this: x* + s - s == x* exactly


def _name_key(name: str) -> int:
    """A process-independent 32-bit integer for a name (never Python's ``hash``)."""
    return int.from_bytes(hashlib.sha256(name.encode()).digest()[:4], "little")


def _check_instance(instance: object, name: str) -> int:
    return V.integer(
        instance, f"{name}: instance", 0, hint="0 = the paper's function, k >= 1 = shifted"
    )


def _instance_offset(f: TestFunction, instance: int) -> FloatArray:
    """The shift :math:`s_k` that moves ``f``'s optimum to a uniform point of the central
    80% of its box, drawn from ``(name, dim, instance)`` and rounded to the shift grid."""
    ss = np.random.SeedSequence(
        [_name_key("voot.functions.instance"), _name_key(f.name), f.dim, instance]
    )
    u = np.random.default_rng(ss).random(f.dim)
    lo, width = f.bounds.lower, f.bounds.upper - f.bounds.lower
    target = lo + (INSTANCE_MARGIN + (1.0 - 2.0 * INSTANCE_MARGIN) * u) * width
    offset: FloatArray = np.round((target - f.optimum_x) / _SHIFT_GRID) * _SHIFT_GRID
    return offset


def shifted(
    function: TestFunction, offset: ArrayLike, *, instance: int | None = None
) -> TestFunction:
    r"""``function`` moved by ``offset``: :math:`x \mapsto f(x - s)` on the same box.

    The optimum moves to ``optimum_x + offset`` and ``optimum_value`` is recomputed there.
    Valid only when ``function.optimum_x`` maximises the formula on all of
    :math:`\mathbb{R}^d` (true of every function of :data:`SHIFTED_FUNCTIONS`; not of
    Schwefel, which is refused, nor of a :func:`make_shekel` instance whose optimum was
    clipped to its box).

    Args:
        function: the function to move (may itself be shifted; shifts add up).
        offset: :math:`s`, shape ``(d,)``.
        instance: the ``instance`` of the result (default: that of ``function``).

    Raises:
        ValueError: Schwefel, an offset of the wrong shape or not finite, or one that
            moves the optimum out of the box.
    """
    if function.name == "schwefel":
        raise ValueError(
            "schwefel cannot be shifted: its formula grows beyond [-500, 500], so f(x - s)"
            " would have a different optimum; shiftable: " + ", ".join(SHIFTED_FUNCTIONS)
        )
    s = np.array(offset, dtype=np.float64).reshape(-1)
    if s.shape != (function.dim,) or not np.all(np.isfinite(s)):
        raise ValueError(
            f"{function}: offset must be {function.dim} finite numbers, got {np.asarray(offset)!r}"
        )
    x_star = function.optimum_x + s
    if not function.bounds.contains(x_star):
        raise ValueError(
            f"{function}: the offset moves the optimum to {x_star.tolist()}, outside the box"
            f" {function.bounds!r}"
        )
    kernel = _Shifted(function.kernel, s)
    return TestFunction(
        function.name,
        function.dim,
        function.bounds,
        float(kernel(x_star[None, :])[0]),
        x_star,
        kernel,
        instance=function.instance if instance is None else instance,
        shift=s if function.shift is None else function.shift + s,
    )
