"""The conveyor-packing family: pack the boxes arriving on a belt into storage rooms.

* :mod:`.env`: :class:`ConveyorPackingEnv` (``voot/ConveyorPacking-v0`` and ``-v1``).

Storage rooms generated from a seed (``voot/GeneratedStorage-v0``) are in :mod:`.generated`.
"""
