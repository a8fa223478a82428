"""Rendering helpers (voot.envs.core.rendering): visual-only markers in a render's scene."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest

from voot.envs.core.rendering import (
    CAMERAS,
    add_marker_box,
    add_marker_segment,
    ensure_headless_gl,
    new_renderer,
)


def test_every_scene_camera_is_named() -> None:
    assert CAMERAS == ("perspective", "top_down")
    ensure_headless_gl()  # idempotent, and a no-op where a display or EGL is set
    ensure_headless_gl()


def test_markers_are_appended_while_the_scene_has_room() -> None:
    scene = mujoco.MjvScene(mujoco.MjModel.from_xml_string("<mujoco/>"), maxgeom=2)
    add_marker_box(scene, (1.0, 2.0, 0.01), (0.5, 0.25, 0.002), math.pi / 2, (1, 0, 0, 0.5))
    assert scene.ngeom == 1
    g = scene.geoms[0]
    assert g.type == mujoco.mjtGeom.mjGEOM_BOX
    np.testing.assert_allclose(g.pos, (1.0, 2.0, 0.01))
    np.testing.assert_allclose(g.size, (0.5, 0.25, 0.002))
    np.testing.assert_allclose(g.mat.reshape(3, 3)[:, 0], (0.0, 1.0, 0.0), atol=1e-12)
    add_marker_segment(scene, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 0.1, (0, 0, 1, 1))
    assert scene.ngeom == 1  # a segment of no length draws nothing
    add_marker_segment(scene, (0.0, 0.0, 0.0), (3.0, 4.0, 0.0), 0.2, (0, 0, 1, 1))
    assert scene.ngeom == 2
    seg = scene.geoms[1]
    np.testing.assert_allclose(seg.pos, (1.5, 2.0, 0.0))
    assert seg.size[0] == pytest.approx(2.5) and seg.size[1] == pytest.approx(0.1)
    add_marker_box(scene, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), 0.0, (1, 1, 1, 1))
    assert scene.ngeom == 2  # full: nothing more is added


NEW_RENDERER = """
import sys, mujoco
from voot.envs.core.rendering import new_renderer
try:
    new_renderer(mujoco.MjModel.from_xml_string("<mujoco/>"), 8, 8).close()
except Exception:
    pass  # no OpenGL here: triton is loaded before the attempt all the same
print("triton" in sys.modules, getattr(sys.modules.get("triton"), "MARK", None))
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the guard is for Linux's Mesa")
def test_new_renderer_loads_an_installed_triton_before_any_gl_context(tmp_path: Path) -> None:
    (tmp_path / "triton").mkdir()
    (tmp_path / "triton" / "__init__.py").write_text("MARK = 'fake'\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), *sys.path])}
    out = subprocess.run(
        [sys.executable, "-c", NEW_RENDERER], env=env, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["True", "fake"]


def test_new_renderer_makes_a_renderer_of_the_model() -> None:
    model = mujoco.MjModel.from_xml_string("<mujoco/>")
    try:
        renderer = new_renderer(model, 8, 16)
    except Exception as exc:  # a machine with no off-screen OpenGL at all
        pytest.skip(f"no off-screen OpenGL: {exc}")
    with renderer:
        assert (renderer.width, renderer.height) == (16, 8)


#: A renderer (EGL) and a numba-compiled function in one process, in the order given by argv.
NUMBA_AND_GL = """
import os, sys
os.environ["MUJOCO_GL"] = "egl"
import mujoco, numpy as np

def render():
    model = mujoco.MjModel.from_xml_string(
        "<mujoco><worldbody><geom type='box' size='.1 .1 .1'/></worldbody></mujoco>")
    with mujoco.Renderer(model, 32, 32) as renderer:
        renderer.update_scene(mujoco.MjData(model))
        return renderer.render().shape

def jit():
    import numba
    @numba.njit
    def total(a):
        s = 0.0
        for x in a:
            s += x
        return s
    return total(np.arange(10.0))

order = (render, jit) if sys.argv[1] == "gl-first" else (jit, render)
out = {f.__name__: f() for f in order}
print(out["render"], out["jit"])
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the guard is for Linux's Mesa")
@pytest.mark.parametrize("order", ["gl-first", "numba-first"])
def test_numba_and_an_egl_renderer_share_a_process_in_either_order(
    order: str, tmp_path: Path
) -> None:
    """numba's LLVM (llvmlite) beside Mesa's: no crash in either order (unlike triton's).

    So voot does not need to load numba before a renderer (the exact-footprint search
    compiles with numba, :mod:`voot.envs.motion.footprint.kernels`).
    """
    pytest.importorskip("numba")
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    out = subprocess.run(
        [sys.executable, "-c", NUMBA_AND_GL, order], env=env, capture_output=True, text=True
    )
    if out.returncode == 1 and "mujoco" in out.stderr and "gl" in out.stderr.lower():
        pytest.skip(f"no EGL here: {out.stderr[-200:]}")
    assert out.returncode == 0, out.stderr  # a segmentation fault is -11
    assert out.stdout.split()[-1] == "45.0"
