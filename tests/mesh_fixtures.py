"""Shared values of the mesh tests (tests/test_mesh_shapes.py, tests/test_meshes.py)."""

from __future__ import annotations

#: A plausible size per kind (metres).
SIZES: dict[str, tuple[float, float, float]] = {
    "box": (0.1, 0.15, 0.2),
    "crate": (0.4, 0.3, 0.25),
    "tray": (0.4, 0.3, 0.04),
    "bin": (0.3, 0.2, 0.2),
    "bowl": (0.16, 0.16, 0.07),
    "plate": (0.26, 0.26, 0.025),
    "mug": (0.12, 0.085, 0.1),
    "bucket": (0.28, 0.28, 0.3),
    "bottle": (0.07, 0.07, 0.25),
    "jug": (0.16, 0.11, 0.25),
}
