"""Kitchens generated from ``(layout_seed, difficulty)``, each proven solvable.

The pipeline, one module a step: :mod:`.layout` (the floor plan and objects from a seed,
pure numpy) -> :mod:`.scene` (its MJCF with mesh objects) -> :mod:`.env`
(:class:`GeneratedKitchenEnv`, the solvability check and the kitchen cache).
"""
