"""What a generated family's ``reset`` costs when it changes the layout, cold and cached.

For each family (``voot/GeneratedKitchen-v0``, ``voot/GeneratedStorage-v0``) at one level,
one env made once, then in one process with an empty cache (``VOOT_CACHE`` in a fresh
folder, so the storage rooms' disk cache is empty too), the median over layouts of:

* **cold**: ``reset(options={"layout_seed": k})`` onto a layout this process has not
  made: generation (every attempt drawn, compiled and proven solvable) and the env
  rebuilt on it;
* **cached**: the same reset onto a layout made before (the instance cache holds it):
  the env rebuilt on the kept model;
* **same layout**: ``reset(seed=s)`` on the current layout (no rebuild), what an
  episode's reset costs without a change of layout;
* **step**: one random step, for scale (no step ever generates).

Run from the repository root (about a minute)::

    VOOT_CACHE=$(mktemp -d) python docs/scripts/family_reset_cost.py [--layouts 10] [--difficulty medium]
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

import gymnasium as gym

import voot  # noqa: F401  (registers the ids)

FAMILIES = ("voot/GeneratedKitchen-v0", "voot/GeneratedStorage-v0")


def _seconds(fn: Callable[[], object]) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def measure(env_id: str, layouts: int, difficulty: str) -> dict[str, float]:
    """Median seconds of each kind of reset (module docstring) over ``layouts`` layouts."""
    env = gym.make(env_id, layout_seed=100_000, difficulty=difficulty)
    seeds = range(200, 200 + layouts)
    cold = [_seconds(lambda k=k: env.reset(seed=0, options={"layout_seed": k})) for k in seeds]
    cached = [_seconds(lambda k=k: env.reset(seed=0, options={"layout_seed": k})) for k in seeds]
    same = [_seconds(lambda s=s: env.reset(seed=s)) for s in range(layouts)]
    env.action_space.seed(0)
    steps = []
    for _ in range(50):
        steps.append(_seconds(lambda: env.step(env.action_space.sample())))
        env.reset()
    env.close()
    return {
        "cold": statistics.median(cold),
        "cached": statistics.median(cached),
        "same layout": statistics.median(same),
        "step": statistics.median(steps),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--layouts", type=int, default=10)
    parser.add_argument("--difficulty", default="medium")
    args = parser.parse_args()
    print(f"| family | {args.difficulty}: cold reset | cached reset | same layout | step |")
    print("|---|---|---|---|---|")
    for env_id in FAMILIES:
        m = measure(env_id, args.layouts, args.difficulty)
        cells = " | ".join(
            f"{1e3 * m[k]:.1f} ms" for k in ("cold", "cached", "same layout", "step")
        )
        print(f"| {env_id} | {cells} |")


if __name__ == "__main__":
    main()
