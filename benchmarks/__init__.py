"""Benchmark runner, result store, plots and the ``voot-bench`` command line."""
