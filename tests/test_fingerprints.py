"""Pinned reference fingerprints: a change of behaviour that stays deterministic fails here.

The hashes are the committed ``tools/behaviour_hashes.json`` (recomputed by
``python tools/behaviour_hashes.py record``); this test recomputes the fast ones: black-box
runs of VOO and DOO, and tree searches on the Shekel chain and on both kitchens; a
60-simulation run of every tree and sampling planner on both v1 domains
(``tools/v1_fingerprints.json``); and CMA-ES's curve (``tools/behaviour_curves.json``) within a relative tolerance, since its last
bits depend on the CPU's BLAS kernel. The RL planners' v1 fingerprints
(``tools/v1_rl_fingerprints.json``) are checked where torch is installed (marked ``rl``):
counts exactly, returns within a relative tolerance, since their last bits depend on
torch's CPU kernel.
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "behaviour_hashes.py"


@pytest.fixture(scope="module")
def hashes() -> object:
    spec = importlib.util.spec_from_file_location("behaviour_hashes", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_optimiser_and_tree_search_fingerprints(hashes: object) -> None:
    pinned = json.loads((ROOT / "tools" / "behaviour_hashes.json").read_text())
    got = {**hashes._bbfo(), **hashes._plan_rows()}  # type: ignore[attr-defined]
    assert got.keys() <= pinned.keys()
    changed = {k: (pinned[k], v) for k, v in got.items() if pinned[k] != v}
    assert not changed, f"behaviour changed (pinned, now): {changed}"


def test_cmaes_curve_within_the_blas_tolerance(hashes: object) -> None:
    pinned = json.loads((ROOT / "tools" / "behaviour_curves.json").read_text())["bbfo/cmaes"]
    got = hashes.cmaes_curve()  # type: ignore[attr-defined]
    moved = hashes.cmaes_curve_changes(pinned, got)  # type: ignore[attr-defined]
    assert not moved, f"CMA-ES's curve moved at evaluations {moved[:5]}"


def test_the_cmaes_tolerance_catches_a_real_change(hashes: object) -> None:
    pinned = json.loads((ROOT / "tools" / "behaviour_curves.json").read_text())["bbfo/cmaes"]
    nudged = [v * (1 + 1e-12) for v in pinned]  # a BLAS kernel's size of difference
    assert hashes.cmaes_curve_changes(pinned, nudged) == []  # type: ignore[attr-defined]
    changed = list(pinned)
    changed[100] *= 1 + 1e-6
    assert hashes.cmaes_curve_changes(pinned, changed) == [100]  # type: ignore[attr-defined]
    assert hashes.cmaes_curve_changes(pinned, pinned[:-1])  # type: ignore[attr-defined]


def test_v1_fingerprints_of_every_planner(hashes: object) -> None:
    from voot.tree import available_planners, available_shooting_planners

    planners = set(hashes.V1_PLANNERS)  # type: ignore[attr-defined]
    # every tree and sampling planner is pinned (the RL planners need torch: not here)
    assert planners == set(available_planners()) | set(available_shooting_planners())
    pinned = json.loads((ROOT / "tools" / "v1_fingerprints.json").read_text())
    got = hashes.v1_fingerprints()  # type: ignore[attr-defined]
    assert set(got) == {f"v1/{p}/{q}" for p in ("kitchen_v1", "conveyor_v1") for q in planners}
    changed = {k: (pinned.get(k), v) for k, v in got.items() if pinned.get(k) != v}
    assert not changed, f"v1 behaviour changed (pinned, now): {changed}"


def test_every_rl_planner_is_pinned_and_the_tolerance_catches_a_real_change(
    hashes: object,
) -> None:
    from voot.bench.sweep.planners import RL_PLANNERS

    assert set(hashes.V1_RL_PLANNERS) == set(RL_PLANNERS)  # type: ignore[attr-defined]
    changes = hashes.v1_rl_changes  # type: ignore[attr-defined]
    pinned = json.loads((ROOT / "tools" / "v1_rl_fingerprints.json").read_text())
    assert set(pinned) == {
        f"v1/{p}/{q}" for p in ("kitchen_v1", "conveyor_v1") for q in RL_PLANNERS
    }
    assert changes(pinned, pinned) == {}
    run = pinned["v1/kitchen_v1/ddpg"]
    # a torch kernel's size of difference (the scalar kernel moved it by 5.5e-6) passes
    kernel = {**run, "best_by_step": [v * (1 + 1e-5) for v in run["best_by_step"]]}
    assert changes(pinned, {**pinned, "v1/kitchen_v1/ddpg": kernel}) == {}
    moved = {**run, "best_by_step": [v * (1 + 1e-3) for v in run["best_by_step"]]}
    assert changes(pinned, {**pinned, "v1/kitchen_v1/ddpg": moved}) == {
        "v1/kitchen_v1/ddpg": ["best_by_step"]
    }
    shorter = {**run, "best_so_far": run["best_so_far"][:-1], "exact": "0" * 16}
    assert changes(pinned, {**pinned, "v1/kitchen_v1/ddpg": shorter}) == {
        "v1/kitchen_v1/ddpg": ["exact", "best_so_far"]
    }
    fewer = {k: v for k, v in pinned.items() if k != "v1/conveyor_v1/ppo"}
    assert changes(pinned, fewer) == {"v1/conveyor_v1/ppo": ["missing"]}


@pytest.mark.rl
def test_v1_fingerprints_of_the_rl_planners(hashes: object) -> None:
    pinned = json.loads((ROOT / "tools" / "v1_rl_fingerprints.json").read_text())
    # In a fresh interpreter: torch's first optimiser imports triton, which crashed (a
    # segmentation fault, torch 2.14.1 + CUDA wheels) inside a pytest process that had
    # already loaded Ray and pyarrow for the other rl tests; alone it runs fine.
    code = (
        "import importlib.util, json, sys\n"
        "spec = importlib.util.spec_from_file_location('h', 'tools/behaviour_hashes.py')\n"
        "h = importlib.util.module_from_spec(spec); spec.loader.exec_module(h)\n"
        "sys.stdout.write(json.dumps(h.v1_rl_fingerprints()))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=False
    )
    assert done.returncode == 0, done.stderr[-2000:]
    got = json.loads(done.stdout)
    changed = hashes.v1_rl_changes(pinned, got)  # type: ignore[attr-defined]
    assert not changed, f"v1 RL behaviour changed: {changed}"
    # each run trains: DDPG past its warm-up steps, PPO past its first whole rollout
    from voot.rl import DDPGConfig, PPOConfig

    starts = {"ppo": PPOConfig().n_steps, "ddpg": DDPGConfig().learning_starts}
    for key, run in got.items():
        assert run["rl_steps"] > starts[key.rsplit("/", 1)[1]] + 150, key
