"""The project's own measurements: costs of the optimisers, the search, the envs, the store.

:mod:`.speed` (cost per ask), :mod:`.overhead` (the search's own cost), :mod:`.memory`,
:mod:`.env_speed`, :mod:`.mesh_speed`, :mod:`.store_speed`, :mod:`.speedup` (against an
old commit), :mod:`.root_parallel` (speed-up over workers).
"""
