"""MuJoCo benchmark environments (needs the ``[envs]`` extra)."""
