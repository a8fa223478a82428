"""The result store: one atomic JSON row per finished run, resumable sweeps.

* :mod:`.result_store`: :class:`ResultStore` (header, write, load, resume, compaction);
* :mod:`.format`: the row format and :class:`StoreError`; :mod:`.index`: atomic writes and
  the index; :mod:`.lock`: one writer per store; :mod:`.compact`: compact rows;
* :mod:`.shipped`: the stores that ship under ``docs/data/`` and their redraw.
"""
