"""Kitchens generated from ``(layout_seed, difficulty)``, each proven solvable.

The pipeline, one module a step (as the storage rooms'): :mod:`.layout` (the floor plan
and objects from a seed, pure numpy) -> :mod:`.scene` (its MJCF with mesh objects) ->
:mod:`.witness` (a constructive solution that proves it solvable) -> :mod:`.instance`
(generation with rejections, and its cache) -> :mod:`.env` (:class:`GeneratedKitchenEnv`).
"""
