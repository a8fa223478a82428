"""Time generated kitchens (``voot/KitchenClearing-v2``): cold generation vs a cached scene.

First the object catalogue's meshes and grasp tables (:data:`~voot.envs.kitchen.generated.layout.
CATALOGUE`): built with trimesh if the mesh cache is empty, else read from it. Then for
each difficulty level and layout seeds ``0 .. n-1`` (one process, no kitchen cached at
the start), prints:

* **cold**: :func:`~voot.envs.kitchen.generated.instance.generated_kitchen` the first time (every
  attempt drawn, compiled and checked by the constructive solver, rejections included);
* **rejections** per accepted kitchen, and the solver's stepped actions;
* **cached scene**: the kept kitchen's model loaded again, as an env does it (a copy of
  the compiled model), and compiling its kept MJCF afresh;
* **cached env**: a whole ``GeneratedKitchenEnv`` of a kept kitchen (the scene, the
  collision checker, the fixed path and the handling order; what ``gym.make`` costs).

Run from the repository root (about a minute); with an empty mesh cache::

    VOOT_CACHE=$(mktemp -d) python docs/scripts/kitchen_v2_timing.py [--seeds 10]
"""

from __future__ import annotations

import argparse
import copy
import statistics
import time

from voot.envs.assets.meshes import ShapeSpec, mesh_assets
from voot.envs.kitchen.generated.env import GeneratedKitchenEnv
from voot.envs.kitchen.generated.instance import generated_kitchen
from voot.envs.kitchen.generated.layout import CATALOGUE, DIFFICULTIES
from voot.envs.kitchen.generated.scene import compile_kitchen
from voot.envs.robot.mesh_grasp import grasp_set


def _ms(seconds: list[float]) -> str:
    return f"{1000 * statistics.median(seconds):7.1f} ms (max {1000 * max(seconds):7.1f})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    args = parser.parse_args()
    t0 = time.perf_counter()
    for item in CATALOGUE:
        spec = ShapeSpec(item.kind, item.size, item.variant)
        mesh_assets([spec])
        grasp_set(spec)
    print(
        f"catalogue: {len(CATALOGUE)} meshes and grasp tables in {time.perf_counter() - t0:.2f} s"
    )
    print(f"median over layout seeds 0..{args.seeds - 1}")
    for level in DIFFICULTIES:
        cold, copied, compiled, env_s, rejections, tries = [], [], [], [], [], []
        for seed in range(args.seeds):
            t0 = time.perf_counter()
            kitchen = generated_kitchen(seed, level)
            cold.append(time.perf_counter() - t0)
            rejections.append(len(kitchen.rejections))
            tries.append(kitchen.tries)
            t0 = time.perf_counter()
            copy.copy(kitchen.model)
            copied.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            compile_kitchen(kitchen.xml, kitchen.layout)
            compiled.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            GeneratedKitchenEnv(layout_seed=seed, difficulty=level).close()
            env_s.append(time.perf_counter() - t0)
        print(
            f"{level:6s}  cold {_ms(cold)}  rejections {statistics.mean(rejections):4.1f}"
            f" (max {max(rejections)})  solver steps {statistics.median(tries):5.0f}\n"
            f"        cached scene: model copy {_ms(copied)}, compile kept MJCF {_ms(compiled)}\n"
            f"        cached env {_ms(env_s)}"
        )


if __name__ == "__main__":
    main()
