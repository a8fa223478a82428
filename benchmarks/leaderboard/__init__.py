"""The leaderboard: a versioned benchmark suite any planner enters, its runs, result cards
and the table the field trusts (IQM, performance profiles, probability of improvement).

* :mod:`~voot.bench.leaderboard.suite`: the suite definition (``suite_v1.toml``), loaded
  into a validated frozen :class:`~voot.bench.leaderboard.suite.Suite` with a content digest;
* :mod:`~voot.bench.leaderboard.plan`: the suite's runs (tuning on training layouts,
  evaluation on held-out layouts) and their CPU-cost estimate;
* :mod:`~voot.bench.leaderboard.scores`: per-run scores at matched simulator calls and CPU time;
* :mod:`~voot.bench.leaderboard.table`: the leaderboard's tables, figure and page;
* :mod:`~voot.bench.leaderboard.card`: result cards and the re-run check of a store.
"""
