"""Base motion planning for the holonomic mobile base in a 2-D floor plan.

* :mod:`.planner`: :class:`BasePlanner`, the facade (queries, caches, ``DiscProbe``);
* :mod:`.planar`: ``Pose2D``, ``Box2D``, ``BasePath``, SE(2) path length;
* :mod:`.disc_geometry`: exact disc-against-box tests (arrays and floats);
* :mod:`.rects`: a rectangle inside or overlapping an axis-aligned region;
* :mod:`.visibility_graph`: the reduced visibility graph; :mod:`.graph_search`: A* on it;
* :mod:`.swept_volume`: the floor area swept along a path and the objects it meets;
* :mod:`.base_model`: the named base models (disc, footprint) of the environments;
* :mod:`.footprint`: the exact-footprint planner on an (x, y, theta) lattice (a package).
"""
