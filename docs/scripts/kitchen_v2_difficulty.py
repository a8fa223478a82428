"""Feasible shares of uniform actions in generated kitchens, per difficulty level.

For each level and layout seeds ``0 .. n-1``: ``--samples`` uniform actions at the first
pick node (after ``reset()``) and as many at the first place node (after the witness's
first pick), each checked from the same state: the share that passes the v1 pre-check
(:meth:`~voot.envs.kitchen.checks.KitchenChecks.precheck`) and the share that passes the
whole step, pooled over the seeds; also the objects to clear and the witness's length.
The same measure as ``voot-bench difficulty`` for v1 (docs/environments.md), without a
planner. Run from the repository root (about half a minute)::

    python docs/scripts/kitchen_v2_difficulty.py [--seeds 10] [--samples 300]
"""

from __future__ import annotations

import argparse
import collections

import numpy as np

from voot.envs.kitchen.generated.env import GeneratedKitchenEnv
from voot.envs.kitchen.generated.layout import DIFFICULTIES


def _shares(
    env: GeneratedKitchenEnv, actions: np.ndarray, reasons: collections.Counter[str]
) -> tuple[int, int]:
    """Actions passing the pre-check and the step, each from the current state."""
    state = env.get_state()
    pre = ok = 0
    for a in actions:
        passed, _ = env.precheck(a)
        pre += passed
        if passed:
            _, _, _, _, info = env.step(a)
            ok += info["feasible"]
            if not info["feasible"]:
                reasons[info["reason_code"]] += 1
            env.set_state(state)
    return pre, ok


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--samples", type=int, default=300)
    args = parser.parse_args()
    rng = np.random.default_rng(0)
    print("| level | node | pass pre-check | pass the step | step failures | obstacles |")
    print("|---|---|---:|---:|---|---:|")
    for level in DIFFICULTIES:
        totals = {"pick": [0, 0], "place": [0, 0]}
        reasons: dict[str, collections.Counter[str]] = {
            "pick": collections.Counter(),
            "place": collections.Counter(),
        }
        obstacles = []
        for seed in range(args.seeds):
            env = GeneratedKitchenEnv(layout_seed=seed, difficulty=level)
            env.reset()
            obstacles.append(env.initial_obstacles)
            for node in ("pick", "place"):
                if node == "place":
                    env.step(env.witness_actions()[0])
                actions = rng.uniform(-1.0, 1.0, (args.samples, 6))
                pre, ok = _shares(env, actions, reasons[node])
                totals[node][0] += pre
                totals[node][1] += ok
            env.close()
        n = args.seeds * args.samples
        for node in ("pick", "place"):
            pre, ok = totals[node]
            fails = ", ".join(f"{r} {100 * c / n:.1f}%" for r, c in reasons[node].most_common(2))
            print(
                f"| {level} | {node} | {100 * pre / n:.1f}% | {100 * ok / n:.1f}% |"
                f" {fails or '-'} | {np.mean(obstacles):.1f} |"
            )


if __name__ == "__main__":
    main()
