"""Benchmark runner, result store, plots and the ``voot-bench`` command line.

* :mod:`voot.bench.store.result_store`: the result store (one atomic JSON row per finished run), with
  :mod:`voot.bench.store.format` (rows), :mod:`voot.bench.store.index` (atomic writes,
  the index) and :mod:`voot.bench.measure.store_speed` (its benchmark);
* :mod:`voot.bench.sweep.engine`: the resumable sweep loop, on the backends of
  :mod:`voot.bench.sweep.backends`; :mod:`voot.bench.sweep.bbfo`: the black-box sweep (Figure 3);
* :mod:`voot.bench.protocol.problems`, :mod:`voot.bench.sweep.planners`,
  :mod:`voot.bench.sweep.plan`: the planning sweep (Figure 4), its runs in
  :mod:`voot.bench.sweep.search` and :mod:`voot.bench.sweep.rl`;
* :mod:`voot.bench.sweep.ray_backend`: sweeps on a Ray cluster;
* :mod:`voot.bench.protocol.select`: the paper's hyperparameter selection (best mean final value);
* :mod:`voot.bench.protocol.tuning`, :mod:`voot.bench.protocol.layouts`: tuning apart from evaluation, on
  other seeds or on held-out layouts of a generated family;
* :mod:`voot.bench.report.bbfo_plot`: Figure 3 and its tables; :mod:`voot.bench.report.plan_runs`,
  :mod:`voot.bench.report.plan_plot`, :mod:`voot.bench.report.plan_tables`: Figure 4's data, drawing
  and tables;
* :mod:`voot.bench.demos.kitchen_demo`, :mod:`voot.bench.demos.figure5`: the kitchen demo and
  Figure 5; :mod:`voot.bench.protocol.difficulty`: planner-agnostic difficulty of the domains;
* :mod:`voot.bench.measure.overhead`, :mod:`voot.bench.measure.env_speed`, :mod:`voot.bench.measure.speedup`,
  :mod:`voot.bench.measure.root_parallel`, :mod:`voot.bench.demos.record_demo`: measurements;
* :mod:`voot.bench.cli.main`: ``voot-bench`` (``voot-bench --help``), its subcommands in the
  ``voot.bench.cli_*`` modules.
"""
