"""The protocol: problems, axes, tuning apart from evaluation, layouts, claims, ablation.

* :mod:`.problems`: problem names, the authors' settings per domain, construction;
* :mod:`.axes`: simulations, simulator calls, CPU seconds; :mod:`.estimate`: a sweep's cost;
* :mod:`.tuning`, :mod:`.select`: settings selected on tuning seeds; :mod:`.layouts`:
  layout seeds and the held-out set;
* :mod:`.claims`: the paper's claims checked; :mod:`.ablation`: the departures from the
  authors' code, one switch each; :mod:`.stall`: why a search stalls;
* :mod:`.difficulty`, :mod:`.ladder`: how hard a domain is, without any planner.
"""
