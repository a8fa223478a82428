"""Tests of voot.bench.protocol.difficulty (small samples; the full tables are in docs)."""

from __future__ import annotations

import math

from voot.bench.cli.main import main
from voot.bench.protocol import difficulty


def test_node_stats_two_stages() -> None:
    v0 = difficulty.node_stats("voot/KitchenClearing-v0", samples=120, seed=0)
    v1 = difficulty.node_stats("voot/KitchenClearing-v1", samples=120, seed=0)
    assert [s.node for s in v0] == ["pick", "place"]
    for s in v0:  # v0's pre-check is the whole step
        assert s.passed_execution == s.passed_precheck and not s.execution_failures
    place = v1[1]
    assert place.passed_precheck > place.passed_execution  # failures left to execution
    assert set(place.execution_failures) <= {
        "forbidden room",
        "no base path",
        "non-clearing place at the penalty cap",
    }
    assert 0.0 <= place.precheck_rate <= 1.0


def test_rollouts_scripted_and_report(tmp_path: object) -> None:
    r = difficulty.rollout_stats("voot/KitchenClearing-v1", rollouts=5, seed=0)
    assert r.initial_objects == 7 and 0 <= r.solved <= 5
    lo, hi = r.interval()
    assert 0.0 <= lo <= hi <= 1.0
    for env_id in ("voot/KitchenClearing-v1", "voot/ConveyorPacking-v1"):
        s = difficulty.scripted_stats(env_id)
        assert s.solved and not s.failure
    assert difficulty.wilson(0, 10)[0] == 0.0 and math.isnan(difficulty.wilson(0, 0)[0])


def test_cli(tmp_path: object, capsys: object) -> None:
    import pathlib

    out = pathlib.Path(str(tmp_path)) / "d.md"
    code = main(
        [
            "difficulty",
            "--envs",
            "kitchen_v1",
            "--samples",
            "20",
            "--rollouts",
            "2",
            "--markdown",
            str(out),
        ]
    )
    assert code == 0
    text = out.read_text()
    assert "voot/KitchenClearing-v1" in text and "scripted solution" in text
    assert main(["difficulty", "--samples", "0"]) == 2
