"""Demos and documentation pictures.

:mod:`.kitchen_demo` (``voot-bench demo``), :mod:`.figure5` (the paper's Figure 5),
:mod:`.record_demo` (the tiny pick-and-place demo), :mod:`.env_figures`,
:mod:`.mesh_gallery`.
"""
