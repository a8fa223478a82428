"""Benchmark runner, result store, plots and the ``voot-bench`` command line.

* :mod:`voot.bench.store`: the result store (one atomic JSON row per finished run), with
  :mod:`voot.bench.store_format` (rows), :mod:`voot.bench.store_index` (atomic writes,
  the index) and :mod:`voot.bench.store_speed` (its benchmark);
* :mod:`voot.bench.sweep`: the black-box sweep (Figure 3), the sweep loop and backends;
* :mod:`voot.bench.problems`, :mod:`voot.bench.plan_sweep`: the planning sweep (Figure 4);
* :mod:`voot.bench.ray_backend`: sweeps on a Ray cluster;
* :mod:`voot.bench.select`: the paper's hyperparameter selection (best mean final value);
* :mod:`voot.bench.tuning`, :mod:`voot.bench.layouts`: tuning apart from evaluation, on
  other seeds or on held-out layouts of a generated family;
* :mod:`voot.bench.plot`: Figure 3 and its tables; :mod:`voot.bench.plan_runs`,
  :mod:`voot.bench.plan_plot`, :mod:`voot.bench.plan_tables`: Figure 4's data, drawing
  and tables;
* :mod:`voot.bench.kitchen_demo`, :mod:`voot.bench.kitchen_figure5`: the kitchen demo and
  Figure 5; :mod:`voot.bench.difficulty`: planner-agnostic difficulty of the domains;
* :mod:`voot.bench.overhead`, :mod:`voot.bench.env_speed`, :mod:`voot.bench.speedup`,
  :mod:`voot.bench.root_parallel_bench`, :mod:`voot.bench.record_demo`: measurements;
* :mod:`voot.bench.cli`: ``voot-bench`` (``voot-bench --help``), its subcommands in the
  ``voot.bench.cli_*`` modules.
"""
