"""The one vocabulary of argument checks that every config and entry point uses.

Each check returns the value in its canonical type (a Python ``int``, ``float``, ``bool``
or enum member) or raises a :class:`ValueError` that names the argument, says what is
valid and shows what was given, e.g. ``n_trees must be an integer >= 1, got 0``. Booleans
are not numbers here (``True`` is not ``1``), NaN is never a valid number, and numpy's
integer and float scalars are accepted like Python's.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable, Iterable, Mapping
from enum import Enum
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray

E = TypeVar("E", bound=Enum)

_INTEGER_TYPES = (int, np.integer)
_NUMBER_TYPES = (int, float, np.integer, np.floating)


def is_integer(value: object) -> bool:
    """Whether ``value`` is an integer (Python or numpy), not a bool."""
    return isinstance(value, _INTEGER_TYPES) and not isinstance(value, bool | np.bool_)


def is_number(value: object) -> bool:
    """Whether ``value`` is a real number (Python or numpy), not a bool."""
    return isinstance(value, _NUMBER_TYPES) and not isinstance(value, bool | np.bool_)


def _as_int(value: object) -> int | None:
    """``value`` as an ``int`` if it is an integer (not a bool), else None."""
    return int(value) if is_integer(value) else None  # type: ignore[call-overload]


def integer(
    value: object, name: str, low: int | None = None, high: int | None = None, *, hint: str = ""
) -> int:
    """``value`` as an ``int`` in ``[low, high]`` (either end may be open: None).

    ``hint`` is said in parentheses after the valid range (what the numbers mean).
    """
    v = _as_int(value)
    if v is None or (low is not None and v < low) or (high is not None and v > high):
        more = f" ({hint})" if hint else ""
        raise ValueError(f"{name} must be {_integer_range(low, high)}{more}, got {value!r}")
    return v


def optional_integer(value: object, name: str, low: int | None = None) -> int | None:
    """None, or ``value`` as an ``int >= low``."""
    if value is None:
        return None
    v = _as_int(value)
    if v is None or (low is not None and v < low):
        raise ValueError(f"{name} must be {_integer_range(low, None)} or None, got {value!r}")
    return v


def integers(values: Iterable[object], name: str, low: int | None = None) -> list[int]:
    """Every item of ``values`` as an ``int >= low``."""
    out = []
    for value in values:
        v = _as_int(value)
        if v is None or (low is not None and v < low):
            what = "integers" if low is None else f"integers >= {low}"
            raise ValueError(f"{name} must be {what}, got {value!r}")
        out.append(v)
    return out


def number(
    value: object,
    name: str,
    low: float = -math.inf,
    high: float = math.inf,
    *,
    open_low: bool = False,
    open_high: bool = False,
) -> float:
    """``value`` as a finite ``float`` in the interval ``low .. high``.

    The ends are closed unless ``open_low`` / ``open_high``; an infinite end is no bound.
    """
    ok = is_number(value) and math.isfinite(float(value))  # type: ignore[arg-type]
    if ok:
        v = float(value)  # type: ignore[arg-type]
        ok = (v > low if open_low else v >= low) and (v < high if open_high else v <= high)
    if not ok:
        what = _number_range(low, high, open_low, open_high)
        raise ValueError(f"{name} must be {what}, got {value!r}")
    return float(value)  # type: ignore[arg-type]


def positive(value: object, name: str, *, allow_zero: bool = False) -> float:
    """``value`` as a finite ``float > 0`` (``>= 0`` with ``allow_zero``)."""
    return number(value, name, 0.0, open_low=not allow_zero)


def probability(value: object, name: str) -> float:
    """``value`` as a ``float`` in ``[0, 1]``."""
    return number(value, name, 0.0, 1.0)


def flag(value: object, name: str) -> bool:
    """``value`` as a ``bool`` (only ``True`` or ``False``, numpy's included)."""
    if not isinstance(value, bool | np.bool_):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def seed(value: object, name: str = "seed") -> Any:
    """A random seed: None, an integer >= 0, or a numpy ``SeedSequence`` / ``Generator``.

    Returned unchanged (an integer as a Python ``int``), ready for
    ``np.random.default_rng``. Booleans, negative integers, floats and strings are a
    ValueError naming ``name`` (numpy's own message names no argument). A ``Generator``
    is passed through as is: the tree search hands its one generator to every node.
    """
    if value is None or isinstance(value, np.random.Generator | np.random.SeedSequence):
        return value
    v = _as_int(value)
    if v is None or v < 0:
        raise ValueError(
            f"{name} must be None, an integer >= 0 or a numpy SeedSequence, got {value!r}"
        )
    return v


def choice(enum: type[E], value: object, name: str, plural: str = "choices") -> E:
    """``value`` as a member of ``enum`` (by value), or an error listing the valid ones
    (``unknown sampler 'x'; valid samplers are: ...`` with ``plural="samplers"``)."""
    try:
        return enum(value)
    except ValueError:
        valid = ", ".join(str(e.value) for e in enum)
        raise ValueError(f"unknown {name} {value!r}; valid {plural} are: {valid}") from None


def one_of(value: Any, name: str, valid: Iterable[Any]) -> Any:
    """``value`` if it is one of ``valid``, or an error listing them."""
    options = tuple(valid)
    if value not in options:
        raise ValueError(
            f"{name} must be one of {', '.join(str(v) for v in options)}, got {value!r}"
        )
    return value


def real_number(value: object, name: str) -> float:
    """``value`` as a ``float`` if it is one real number: a Python or numpy int or float
    (any width), another :class:`numbers.Real` (e.g. a ``Fraction``), or a 0-d numpy
    array of one. NaN and infinities pass (the caller decides).

    A bool (not 1.0 in disguise), a complex number (its imaginary part would be lost), a
    string (not parsed), None or any other object is a ValueError naming ``name`` and the
    type given.
    """
    if type(value) is float:
        return value
    if isinstance(value, bool | np.bool_) or not (
        isinstance(value, numbers.Real)
        or (isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf")
    ):
        raise ValueError(
            f"{name} must be a real number (an int or a float; not a bool, a complex number,"
            f" a string or None), got {value!r} of type {type(value).__name__}"
        )
    return float(value)  # type: ignore[arg-type]


# ----- arrays (actions) ----------------------------------------------------------------
_F64 = np.dtype(np.float64)
#: numpy dtype kinds of real numbers: signed and unsigned integers, floats.
_REAL_KINDS = "iuf"


def real_array(value: object, name: str) -> NDArray[np.float64]:
    """``value`` as a float64 array whose entries were real numbers (any shape).

    Ints and floats of any width (Python's or numpy's, in lists or arrays) are taken.
    Booleans, complex numbers (numpy would drop the imaginary part with only a warning),
    strings (numpy would parse ``"0.1"``), ``None`` and other objects are a ValueError
    naming ``name``: each would otherwise be read as some number without a word. A
    float64 array is returned as is (no copy). NaN and infinities are left to the caller.
    """
    if type(value) is np.ndarray and value.dtype == _F64:
        return value
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.dtype.kind not in _REAL_KINDS:
        kind = "a ragged sequence" if arr is None else f"dtype {arr.dtype}"
        raise ValueError(
            f"{name} must be numeric, real numbers (ints or floats; not bools, complex numbers,"
            f" strings or objects), got {kind}: {value!r}"
        )
    return arr.astype(np.float64)


# ----- tuples and configs (the environments' settings) ----------------------------------
def _floats(value: Any) -> tuple[float, ...]:
    """The items of ``value`` as floats (anything ``float()`` takes but a bool)."""
    if isinstance(value, str | bytes):
        raise TypeError
    items = tuple(value)
    if any(isinstance(v, bool | np.bool_) for v in items):
        raise TypeError
    return tuple(float(v) for v in items)


def range_pair(name: str, value: Any) -> tuple[float, float]:
    """A ``(low, high)`` pair of finite floats with ``low < high``."""
    try:
        lo, hi = _floats(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a (low, high) pair of numbers, got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"{name} must be finite with low < high, got ({lo}, {hi})")
    return lo, hi


def _finite_tuple(name: str, value: Any, fields: str, n: int) -> tuple[float, ...]:
    """``n`` finite floats named ``fields`` (e.g. ``"(x, y, theta)"``), or a ValueError."""
    try:
        vals = _floats(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be {fields}, got {value!r}") from None
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise ValueError(f"{name} must be {n} finite numbers {fields}, got {value!r}")
    return vals


def region(name: str, value: Any) -> tuple[float, float, float, float]:
    """An axis-aligned region ``(xmin, xmax, ymin, ymax)`` of finite floats."""
    vals = _finite_tuple(name, value, "(xmin, xmax, ymin, ymax)", 4)
    if not (vals[0] < vals[1] and vals[2] < vals[3]):
        raise ValueError(f"{name} needs xmin < xmax and ymin < ymax, got {vals}")
    return vals[0], vals[1], vals[2], vals[3]


def pose(name: str, value: Any) -> tuple[float, float, float]:
    """An ``(x, y, theta)`` pose of finite floats."""
    vals = _finite_tuple(name, value, "(x, y, theta)", 3)
    return vals[0], vals[1], vals[2]


def positive_number(name: str, value: Any, allow_zero: bool = False) -> float:
    """A finite number > 0 (or >= 0), from anything ``float()`` takes but a bool."""
    if isinstance(value, bool | np.bool_):
        raise ValueError(f"{name} must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        raise ValueError(f"{name} must be a finite number {'>=' if allow_zero else '>'} 0, got {v}")
    return v


#: A field's check in a :func:`check_fields` table: ``check(value, name)`` returns the value
#: in its canonical type or raises a ValueError naming the field (e.g. :func:`flag`, or
#: ``functools.partial(integer, low=1)``).
Check = Callable[[Any, str], Any]


def check_fields(config: Any, checks: Mapping[str, Check]) -> None:
    """Check the fields of the frozen dataclass ``config`` named in ``checks`` (field name ->
    :data:`Check`), in the table's order, and store each one's canonical value back.

    A config's ``__post_init__`` runs its table with this, then checks what ties fields
    together (e.g. ``batch_size <= n_steps``) on the canonical values.
    """
    for name, check in checks.items():
        object.__setattr__(config, name, check(getattr(config, name), name))


def at_most(value: float, name: str, bound: float, bound_name: str, why: str = "") -> None:
    """Raise a ValueError unless ``value <= bound`` (two fields of one config, already
    checked alone), e.g. ``elites must be <= population (8), got 9``; ``why`` is said after
    the bound."""
    if value > bound:
        shown = f"{bound:g}" if isinstance(bound, float) else f"{bound}"
        because = f": {why}" if why else ""
        raise ValueError(f"{name} must be <= {bound_name} ({shown}){because}, got {value!r}")


def config_options(config_class: Any, options: Mapping[str, Any], what: str = "") -> None:
    """Raise a ValueError naming the valid fields if ``options`` has an unknown one.

    ``what`` names the thing configured in the message (default: the class's name).
    """
    valid = sorted(f.name for f in dataclasses.fields(config_class))
    unknown = sorted(set(options) - set(valid))
    if unknown:
        raise ValueError(
            f"unknown option(s) {unknown} for {what or config_class.__name__};"
            f" valid options are: {valid}"
        )


# ----- names (planners, optimisers, algorithms) -----------------------------------------
def name_key(value: object) -> str:
    """A name as a registry key: stripped, lower-case, ``-`` as ``_`` (``"RAND-DOOT"`` ->
    ``"rand_doot"``)."""
    return str(value).strip().lower().replace("-", "_")


def registered_name(value: object, valid: Iterable[str], what: str, plural: str = "") -> str:
    """``value``'s :func:`name_key` if it is one of ``valid``, or an error listing them.

    E.g. ``unknown planner 'vot'; valid planners are: doot, voot`` for ``what="planner"``;
    ``plural`` is how the list is called (default: ``what`` + "s").
    """
    key = name_key(value)
    names = sorted(valid)
    if key not in names:
        raise ValueError(
            f"unknown {what} {value!r}; valid {plural or what + 's'} are: {', '.join(names)}"
        )
    return key


def _integer_range(low: int | None, high: int | None) -> str:
    if low is not None and high is not None:
        return f"an integer in [{low}, {high}]"
    if low is not None:
        return f"an integer >= {low}"
    if high is not None:
        return f"an integer <= {high}"
    return "an integer"


def _number_range(low: float, high: float, open_low: bool, open_high: bool) -> str:
    if math.isfinite(low) and math.isfinite(high):
        left, right = "(" if open_low else "[", ")" if open_high else "]"
        return f"a finite number in {left}{low:g}, {high:g}{right}"
    if math.isfinite(low):
        return f"a finite number {'>' if open_low else '>='} {low:g}"
    if math.isfinite(high):
        return f"a finite number {'<' if open_high else '<='} {high:g}"
    return "a finite number"
