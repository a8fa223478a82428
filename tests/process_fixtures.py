"""Helpers for tests that compare a run with the same run in a fresh interpreter (not a
test module itself)."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from collections.abc import Mapping
from typing import Any


def run_pickled(
    script: str, payload: Any, timeout: float = 120, env: Mapping[str, str] | None = None
) -> Any:
    """Run ``script`` in a fresh Python with ``payload`` pickled on its stdin; what it
    pickles on its stdout, unpickled. ``env``: variables set for the child."""
    proc = subprocess.run(
        [sys.executable, "-c", script],
        input=pickle.dumps(payload),
        capture_output=True,
        check=True,
        timeout=timeout,
        env=None if env is None else {**os.environ, **env},
    )
    return pickle.loads(proc.stdout)
