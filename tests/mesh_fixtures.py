"""Shared values of the mesh tests (tests/envs/assets/test_mesh_shapes.py, test_meshes.py): the sizes
per kind (their fresh cache is the ``mesh_cache`` fixture of tests/conftest.py)."""

from __future__ import annotations

from voot.bench.measure.mesh_speed import SIZES

__all__ = ["SIZES"]
