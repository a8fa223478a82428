"""MuJoCo benchmark environments (needs the ``[envs]`` extra).

Importing this package on a Linux machine without a display selects MuJoCo's EGL
backend (``MUJOCO_GL=egl``) for headless rendering, unless ``MUJOCO_GL`` is already set;
this only takes effect if MuJoCo has not been imported yet.
"""

import os
import sys

if (
    sys.platform.startswith("linux")
    and "MUJOCO_GL" not in os.environ
    and not os.environ.get("DISPLAY")
):
    os.environ["MUJOCO_GL"] = "egl"
