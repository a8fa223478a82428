"""Scene assets: the MJCF writers and the object meshes, built with trimesh, as MuJoCo assets.

* :mod:`.mjcf`: the MJCF building blocks and their shared constants (collision classes,
  materials, wall heights, the belt ...), used by every scene voot writes;
* :mod:`.fixed_scenes`: the paper's ``kitchen.xml`` and ``conveyor.xml``
  (``models/generate_scenes.py`` writes them);
* :mod:`.mesh_shapes`: shapes from a spec (watertight mesh, convex parts, mass, inertia);
* :mod:`.meshes`: those shapes as MuJoCo assets (STL files, disk cache, MJCF bodies).
"""
