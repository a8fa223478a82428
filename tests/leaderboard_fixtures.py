"""A tiny leaderboard suite and its store, run once per test session (the leaderboard's
tests share it: the generated kitchen at one level, two held-out layouts, a few
simulations; one tuned variant and one planner without a grid)."""

from __future__ import annotations

import functools
import shutil
import tempfile
from pathlib import Path

TINY_SUITE = """
version = 1
description = "tiny: the tests' suite"
levels = ["easy"]
heldout_layouts = "0:2"
seeds = [0]

[tuning]
layouts = "1000:1001"
seeds = [0]
level = "easy"
reuse_protocol = false

[[families]]
problem = "voot/GeneratedKitchen-v0"
simulations = 4

[[entries]]
planner = "random_shooting"

[[entries]]
planner = "doot"
variant = "small"
set = { reevaluations = 2 }
axes = { epsilon = [0.1, 1.0] }
"""


@functools.cache
def tiny_suite_file() -> Path:
    """The tiny suite's file (in a folder of its own, kept for the session)."""
    folder = Path(tempfile.mkdtemp(prefix="voot-tiny-suite-"))
    path = folder / "tiny.toml"
    path.write_text(TINY_SUITE)
    return path


@functools.cache
def _tiny_store() -> Path:
    from voot.bench.leaderboard.card import write_cards
    from voot.bench.leaderboard.plan import run_suite
    from voot.bench.leaderboard.suite import load_suite
    from voot.bench.store.compact import CompactConfig
    from voot.bench.store.result_store import ResultStore
    from voot.bench.sweep.engine import run_sweep

    suite = load_suite(str(tiny_suite_file()))
    path = Path(tempfile.mkdtemp(prefix="voot-tiny-store-")) / "tiny-store"
    store = ResultStore(path, compact=CompactConfig(points=3))
    failed = run_suite(
        suite, suite.entries, store, lambda specs: run_sweep(specs, store, progress=False).failed
    )
    assert failed == 0
    write_cards(path, suite)
    return path


def tiny_store(into: Path) -> Path:
    """A copy of the tiny suite's finished store (with its cards) under ``into``."""
    target = into / "tiny-store"
    shutil.copytree(_tiny_store(), target)
    return target
