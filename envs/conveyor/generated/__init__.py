"""Storage rooms generated from ``(layout_seed, difficulty)``, each proven solvable.

The pipeline, one module a step: :mod:`.layout` (rooms, doors and boxes from a seed, pure
numpy) -> :mod:`.scene` (its MJCF and compiled model) -> :mod:`.witness` (a greedy packing
that proves it solvable) -> :mod:`.instance` (generation with rejections, and its cache)
-> :mod:`.env` (:class:`ConveyorFamilyEnv`).
"""
