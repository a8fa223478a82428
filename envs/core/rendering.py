"""Rendering helpers of the envs: cameras, headless OpenGL, visual-only markers.

The envs render with :class:`mujoco.Renderer` from the cameras every scene defines
(:data:`CAMERAS`); every env takes the same three render arguments
(:class:`RenderOptions`). :func:`new_renderer` makes every renderer voot opens, so that
it works on a machine without a display (:func:`ensure_headless_gl`) and in a process
that also trains with PyTorch (:func:`load_triton_first`); :func:`add_marker_box` and :func:`add_marker_segment` draw overlays (the
kitchen's swept corridor and forbidden rooms, the conveyor's regions) into a render's
scene without touching the model, so rendering never changes a state.
"""

from __future__ import annotations

import importlib.util
import math
import os
import sys
from typing import TypedDict

import mujoco
import numpy as np
from numpy.typing import ArrayLike

from voot.envs.core.arguments import CAMERAS as CAMERAS  # the cameras, checked there
from voot.envs.core.arguments import RENDER_MODES as RENDER_MODES


class RenderOptions(TypedDict, total=False):
    """The render arguments every env takes, as the keywords of an env that passes them on
    to its base unchanged (``**render: Unpack[RenderOptions]``).

    Attributes:
        render_mode: None or ``"rgb_array"`` (:data:`RENDER_MODES`).
        render_camera: ``"perspective"`` or ``"top_down"`` (:data:`CAMERAS`).
        render_size: ``(width, height)`` of rendered images.
    """

    render_mode: str | None
    render_camera: str
    render_size: tuple[int, int]


def ensure_headless_gl() -> None:
    """Use EGL for off-screen rendering on a Linux machine without a display.

    MuJoCo picks its OpenGL backend from ``MUJOCO_GL`` when it is first imported
    (``voot.envs`` sets ``MUJOCO_GL=egl`` if it is imported first). If MuJoCo was imported
    earlier with the default GLFW backend and there is no display, GLFW cannot create a
    context; this switches the renderer's context class to EGL instead.
    """
    if not sys.platform.startswith("linux") or os.environ.get("DISPLAY"):
        return
    from mujoco.rendering.classic import gl_context

    if getattr(gl_context, "_MUJOCO_GL", "") in ("egl", "osmesa"):
        return
    from mujoco.egl import GLContext

    gl_context.GLContext = GLContext  # type: ignore[attr-defined]


def load_triton_first() -> None:
    """Import triton, where it is installed, before the first OpenGL context is made.

    PyTorch's CUDA wheels (what ``pip install torch`` takes from PyPI on Linux) bring
    triton, whose bundled LLVM crashes the process with a segmentation fault when it is
    loaded after Mesa's EGL driver has loaded its own LLVM; in the other order both work.
    torch imports triton lazily (its first optimiser does), so a process that renders and
    then trains (a demo, then PPO; the test suite with ``-m "rl or not rl"``) would crash.
    Importing triton first costs about 0.2 s, and nothing where triton is not installed.
    """
    if "triton" in sys.modules or not sys.platform.startswith("linux"):
        return
    try:
        if importlib.util.find_spec("triton") is None:
            return
        import triton  # noqa: F401  # the side effect: its LLVM is loaded first
    except Exception:  # a broken triton fails later, in torch, with its own message
        return


def new_renderer(model: mujoco.MjModel, height: int, width: int) -> mujoco.Renderer:
    """A :class:`mujoco.Renderer` of ``model``, made safely headless and beside PyTorch.

    Every renderer voot opens is made here, after :func:`ensure_headless_gl` and
    :func:`load_triton_first`.
    """
    ensure_headless_gl()
    load_triton_first()
    return mujoco.Renderer(model, height=height, width=width)


def add_marker_box(
    scene: mujoco.MjvScene,
    center: ArrayLike,
    half: ArrayLike,
    yaw: float,
    rgba: ArrayLike,
) -> None:
    """Append a flat, visual-only box to a render scene (if it has room)."""
    if scene.ngeom >= scene.maxgeom:
        return
    c, s = math.cos(yaw), math.sin(yaw)
    mat = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]).reshape(-1)
    mujoco.mjv_initGeom(
        scene.geoms[scene.ngeom],
        int(mujoco.mjtGeom.mjGEOM_BOX),
        np.asarray(half, dtype=np.float64),
        np.asarray(center, dtype=np.float64),
        mat,
        np.asarray(rgba, dtype=np.float32),
    )
    scene.ngeom += 1


def add_marker_segment(
    scene: mujoco.MjvScene, a: ArrayLike, b: ArrayLike, width: float, rgba: ArrayLike
) -> None:
    """Append a flat strip from ``a`` to ``b`` (``(x, y, z)`` points) to a render scene."""
    pa, pb = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    d = pb - pa
    length = float(np.hypot(d[0], d[1]))
    if length < 1e-9:
        return
    add_marker_box(
        scene,
        0.5 * (pa + pb),
        (0.5 * length, 0.5 * width, 0.002),
        math.atan2(d[1], d[0]),
        rgba,
    )
