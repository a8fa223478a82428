"""Figures and tables drawn from result stores (they run nothing).

* :mod:`.bbfo_plot`: Figure 3 and its table;
* :mod:`.plan_runs`, :mod:`.plan_plot`, :mod:`.plan_tables`: Figure 4's data, drawing, tables;
* :mod:`.ablation_table`: the ablation's tables;
* :mod:`.stats`: IQM, performance profiles, P(X > Y) with stratified-bootstrap intervals;
* :mod:`.docs_pages`: the generated sections of the docs pages (``docs/scripts/``).
"""
