"""Test-session settings shared by every test module."""

import os

# Headless rendering: MuJoCo reads MUJOCO_GL when it is first imported, so set it before
# any test module imports mujoco (CI sets it too; a user's own value wins).
os.environ.setdefault("MUJOCO_GL", "egl")
