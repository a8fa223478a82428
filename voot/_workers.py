"""Environment for worker processes that voot starts (process pools of sweeps and of
root-parallel search)."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator

#: Thread-count variables of the BLAS/OpenMP runtimes numpy and scipy may load.
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


@contextlib.contextmanager
def single_threaded_children() -> Iterator[None]:
    """Worker processes started inside this block get one BLAS/OpenMP thread each
    (unless the user set these variables): ``K`` processes with many threads each would
    oversubscribe the cores. The variables are removed again on exit."""
    added = [n for n in THREAD_VARIABLES if n not in os.environ]
    for n in added:
        os.environ[n] = "1"
    try:
        yield
    finally:
        for n in added:
            os.environ.pop(n, None)
