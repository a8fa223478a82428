"""Sweeps: specs fanned out to workers, each finished run written to a store.

* :mod:`.engine`: the generic resumable sweep (spec identity, runners, ``run_sweep``);
* :mod:`.bbfo`: the black-box sweep (Figure 3);
* :mod:`.planners`: the planners of the planning sweep, their grids and configs;
  :mod:`.plan`: the planning sweep (Figure 4); :mod:`.search`: its tree and sampling-based
  runs; :mod:`.rl`: its RL runs;
* :mod:`.backends`: where runs execute; :mod:`.ray_backend`, :mod:`.ray_reaper`: on Ray.

Modules import downward in that list's reverse: ``plan`` -> ``rl`` -> ``search`` ->
``planners`` -> ``engine`` -> ``backends``.
"""
