"""Sweeps: specs fanned out to workers, each finished run written to a store.

* :mod:`.bbfo`: the black-box sweep (Figure 3) and the sweep loop;
* :mod:`.plan`: the planning sweep (Figure 4); :mod:`.rl`: its RL runs;
* :mod:`.backends`: where runs execute; :mod:`.ray_backend`, :mod:`.ray_reaper`: on Ray.
"""
