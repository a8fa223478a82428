"""Rendering helpers (voot.envs.core.rendering): visual-only markers in a render's scene."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from voot.envs.core.rendering import CAMERAS, add_marker_box, add_marker_segment, ensure_headless_gl


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
