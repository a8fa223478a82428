"""What every robot domain is built on: the env base, its state, action units, the scene.

* :mod:`.env`: :class:`ManipulationEnv`, the shared env base (scene, robot, action
  validation, snapshots, rendering);
* :mod:`.state`: snapshots, task-record copies and checks, step timings;
* :mod:`.units`: the affine map between ``[-1, 1]^d`` and parameter ranges;
* :mod:`.presets`: named config versions (``v0``, ``v1``);
* :mod:`.scene`: loading MJCF scenes, reading their floor plan back as footprints;
* :mod:`.generation`: what the generated families share (levels, seeds, the rejection
  loop, the instance record and its cache);
* :mod:`.splits`: the protocol's split of layout seeds (training, held out);
* :mod:`.family`: a generated family as one env a learner trains across (one
  observation space, the layout chosen at reset, the training / held-out split);
* :mod:`.rendering`: cameras, headless OpenGL, visual-only markers;
* :mod:`.problem`: :class:`EnvProblem`, a robot env as a :mod:`voot.tree` planning problem;
* :mod:`.metrics`: the authors' per-operator distances between actions (VOO's cells);
* :mod:`.names`: typed names at the env seam (:class:`Difficulty` ...).
"""
