"""Tests of voot.bench.measure.footprint_speed: the exact-footprint option's cost benchmark."""

from __future__ import annotations

import pytest

from voot.bench.measure import footprint_speed as F
from voot.envs.motion.footprint.astar import numba_available


@pytest.mark.skipif(not numba_available(), reason="numba is not installed")
def test_repeats_replay_the_same_queries_and_keep_the_least_times() -> None:
    r = F.run(rollouts=1, seed=3, repeats=2)
    assert r["repeats"] == 2 and r["steps"] >= 1
    assert len(r["queries"]) >= 1 and all(t > 0 for t in r["queries"])
    assert 0 < r["disc_cpu"] and 0 < r["exact_cpu"]
    assert r["exact_feasible"] >= r["disc_feasible"]  # a disc path is a footprint path
    # a step stops at its first failing placement, never earlier with the footprint
    assert r["exact_checked"] >= r["disc_checked"] >= r["steps"]
    text = F.report(r)
    assert "least of 2 repeats" in text
    assert f"disc {r['disc_checked']}, footprint {r['exact_checked']}" in text
    assert "if the exact search cost nothing" in text
    assert r["paths_sha256"][:16] in text
    # the answers are those of a single replay
    assert F.run(rollouts=1, seed=3)["paths_sha256"] == r["paths_sha256"]


def test_repeats_are_validated() -> None:
    with pytest.raises(ValueError, match="repeats must be >= 1"):
        F.run(rollouts=1, repeats=0)
