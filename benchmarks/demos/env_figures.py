"""Render the documentation figures of the two scenes (headless, ``MUJOCO_GL=egl``).

``voot-bench env-figures [out_dir]`` (default ``docs/figures``; :func:`render_all`) writes:

* ``kitchen_top_down.png``, ``kitchen_perspective.png``: the kitchen at the start, with
  the swept corridor of the fixed path (blue) and the forbidden rooms (red);
* ``kitchen_cleared_top_down.png``: after the scripted solution
  (:mod:`voot.envs.kitchen.scripted`, :mod:`voot.envs.conveyor.scripted`);
* ``conveyor_top_down.png``, ``conveyor_perspective.png``: the storage rooms and the
  belt at the start, the loading region tinted yellow;
* ``conveyor_packed_top_down.png``: after the scripted solution (20 boxes packed);
* ``robot_grasp.png``: a close-up of the robot holding a box after a pick.
"""

from __future__ import annotations

from pathlib import Path

import imageio.v3 as iio
import mujoco
import numpy as np

from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.scripted import conveyor_actions
from voot.envs.core.rendering import new_renderer
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.scripted import kitchen_actions

SIZE = (1280, 960)


def _save(path: Path, image: np.ndarray) -> None:
    iio.imwrite(path, image)
    print(f"wrote {path}")


def render_all(out_dir: Path) -> None:
    """Render every figure into ``out_dir``."""
    out_dir.mkdir(parents=True, exist_ok=True)
    kitchen = KitchenClearingEnv(render_mode="rgb_array", render_size=SIZE)
    kitchen.reset(seed=0)
    for cam in ("top_down", "perspective"):
        _save(out_dir / f"kitchen_{cam}.png", kitchen.render_image(cam))
    actions = kitchen_actions(kitchen)
    kitchen.step(actions[0])  # the first pick: a close-up of the grasp
    renderer = new_renderer(kitchen.model, height=720, width=960)
    cam = mujoco.MjvCamera()
    base = kitchen.robot.base_pose(kitchen.data)
    obj = kitchen.object_pose(kitchen.task.held)
    cam.lookat[:] = (0.5 * (base[0] + obj[0]), 0.5 * (base[1] + obj[1]), 0.6)
    # look from the robot's right-hand side, slightly from the front
    cam.distance, cam.azimuth, cam.elevation = 2.2, float(np.degrees(base[2])) + 120.0, -22.0
    mujoco.mj_kinematics(kitchen.model, kitchen.data)
    mujoco.mj_camlight(kitchen.model, kitchen.data)
    renderer.update_scene(kitchen.data, cam)
    _save(out_dir / "robot_grasp.png", renderer.render())
    renderer.close()
    for a in actions[1:]:
        kitchen.step(a)
    _save(out_dir / "kitchen_cleared_top_down.png", kitchen.render_image("top_down"))
    kitchen.close()

    conveyor = ConveyorPackingEnv(render_mode="rgb_array", render_size=SIZE)
    conveyor.reset(seed=0)
    for cam_name in ("top_down", "perspective"):
        _save(out_dir / f"conveyor_{cam_name}.png", conveyor.render_image(cam_name))
    for a in conveyor_actions(conveyor):
        conveyor.step(a)
    _save(out_dir / "conveyor_packed_top_down.png", conveyor.render_image("top_down"))
    conveyor.close()
