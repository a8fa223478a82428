"""The generated families' arguments, each checked by one function that every family, their
reset options and the command line share.

A generated family's env (:class:`voot.envs.core.family.LayoutFamily`) is made on a layout
``(layout_seed, difficulty)``, optionally in a ``split`` mode, with the three render
arguments every env takes. Each has one check here, called **before anything else**: before
a cache key is built, a layout generated or a file written, so that a refused value can
never be served what a cache holds for another (``layout_seed=1.5`` is not layout 1).

* :func:`check_layout_seed`: an integer (Python's or numpy's; not a bool, not a float,
  not a string) in :data:`LAYOUT_SEEDS`, the same range for every family;
* :func:`check_difficulty`: one of the family's levels by its exact name (or its
  :class:`~voot.envs.core.names.Difficulty` member);
* :func:`check_split`: None or a :class:`~voot.envs.core.names.Split` by its exact name;
* :func:`check_render`: ``render_mode`` (None or :data:`RENDER_MODES`), ``render_camera``
  (:data:`CAMERAS`) and ``render_size`` (two integers within :data:`RENDER_WIDTHS` x
  :data:`RENDER_HEIGHTS`).

Each returns the canonical value (a Python ``int``, an enum member, a tuple of ints) or
raises a :class:`ValueError` that names the parameter, the valid choices and what was
given. Light on purpose (no MuJoCo, no numpy-heavy code): ``voot.bench`` imports it to
check a command line's options before the first run.
"""

from __future__ import annotations

from collections.abc import Collection

from voot import validation as V
from voot.envs.core.names import Difficulty, Split, choices

__all__ = [
    "CAMERAS",
    "LAYOUT_SEEDS",
    "RENDER_HEIGHTS",
    "RENDER_MODES",
    "RENDER_WIDTHS",
    "check_difficulty",
    "check_layout_seed",
    "check_render",
    "check_split",
]

#: The layout seeds of every generated family: ``range(0, 2**63)`` (what numpy's seeding
#: takes as one int64 word), the same for both families and the command line.
LAYOUT_SEEDS = range(0, 2**63)
#: Cameras every scene defines, for ``render_camera``.
CAMERAS = ("perspective", "top_down")
#: Render modes.
RENDER_MODES = ("rgb_array",)
#: The valid widths and heights of rendered images, in pixels.
RENDER_WIDTHS = range(16, 1281)
RENDER_HEIGHTS = range(16, 961)


def check_layout_seed(value: object) -> int:
    """``value`` as a layout seed: an ``int`` in :data:`LAYOUT_SEEDS`.

    Python and numpy integers are accepted; bools, floats (even ``1.0``), numpy floats and
    strings are refused.

    Raises:
        ValueError: Anything else (the message names ``layout_seed`` and the range).
    """
    return V.integer(
        value,
        "layout_seed",
        LAYOUT_SEEDS.start,
        LAYOUT_SEEDS.stop - 1,
        hint="a generated layout's seed; bools, floats and strings are refused",
    )


def check_difficulty(
    value: object, levels: Collection[Difficulty] = tuple(Difficulty)
) -> Difficulty:
    """``value`` as one of ``levels`` (default: every :class:`Difficulty`), by exact name.

    A :class:`Difficulty` member or its exact string (``"easy"``; not ``"Easy"`` nor
    ``" easy"``).

    Raises:
        ValueError: Not one of ``levels`` (the message names them).
    """
    level = None
    if isinstance(value, str):
        try:
            level = Difficulty(value)
        except ValueError:
            level = None
    if level is None or level not in levels:
        raise ValueError(
            f"unknown difficulty {value!r}; valid levels are: {', '.join(map(str, levels))}"
        )
    return level


def check_split(value: object) -> Split | None:
    """``value`` as None or a :class:`Split`, by exact name.

    Raises:
        ValueError: Another value (the message names the splits).
    """
    if value is None:
        return None
    if isinstance(value, str):
        try:
            return Split(value)
        except ValueError:
            pass
    raise ValueError(f"unknown split {value!r}; valid splits are: {choices(Split)} (or None)")


def check_render(
    render_mode: object, render_camera: object, render_size: object
) -> tuple[str | None, str, tuple[int, int]]:
    """The three render arguments, checked: ``(render_mode, render_camera, (w, h))``.

    ``render_size`` is a pair of integers (not bools, not floats: ``640.7`` is not a
    width) within :data:`RENDER_WIDTHS` x :data:`RENDER_HEIGHTS`.

    Raises:
        ValueError: The first bad argument, named with its valid values.
    """
    if render_mode is not None and (
        not isinstance(render_mode, str) or render_mode not in RENDER_MODES
    ):
        raise ValueError(
            f"render_mode must be None or one of {', '.join(RENDER_MODES)}; got {render_mode!r}"
        )
    if not isinstance(render_camera, str) or render_camera not in CAMERAS:
        raise ValueError(
            f"render_camera must be one of {', '.join(CAMERAS)}; got {render_camera!r}"
        )
    w = h = -1
    if isinstance(render_size, tuple | list) and len(render_size) == 2:
        w, h = (V.integer(v, "render_size") if V.is_integer(v) else -1 for v in render_size)
    if w not in RENDER_WIDTHS or h not in RENDER_HEIGHTS:
        raise ValueError(
            "render_size must be (width, height), two integers within"
            f" {RENDER_WIDTHS.start}..{RENDER_WIDTHS.stop - 1} x"
            f" {RENDER_HEIGHTS.start}..{RENDER_HEIGHTS.stop - 1}, got {render_size!r}"
        )
    return render_mode, render_camera, (w, h)
