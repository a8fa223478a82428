"""Scene assets: object meshes built with trimesh and their MuJoCo assets.

* :mod:`.mesh_shapes`: shapes from a spec (watertight mesh, convex parts, mass, inertia);
* :mod:`.meshes`: those shapes as MuJoCo assets (STL files, disk cache, MJCF bodies).
"""
