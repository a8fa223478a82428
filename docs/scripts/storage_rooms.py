"""The numbers and the figure of docs/environments.md, "Generated storage rooms".

Three parts, each printed as Markdown (run from the repository root):

* ``figure``: ``docs/figures/storage_rooms_layouts.png``, six generated layouts (two per
  difficulty level) seen from the top after their witness packing, and
  ``docs/figures/storage_rooms_perspective.png``, one hard layout in perspective;
* ``benchmark``: generation cost per instance, cold (draw, build the meshes, compile,
  prove, write the caches) and cached (read the cache, with the process's memory
  caches emptied as in a new process), and what the levels draw, over ``--layouts``
  seeds per level, in a fresh temporary cache folder;
* ``difficulty``: at the first node of ``--layouts`` layouts per level, the share of
  uniform actions (``--samples`` each) that pass the pre-check and, of those,
  execution, with the execution failures by cause (as ``voot-bench difficulty`` does for
  v1);
* ``planners``: a first look at planners on the levels: ``voot-bench plan`` with VOOT
  and PW-UCT (the default grid's settings, v1's domain options) on ``--layouts`` layouts
  x ``--seeds`` seeds per level at ``--simulations`` simulations, into ``--out``
  (resumable), and the share of runs that pack every box, of boxes packed and the mean
  best return.

::

    python docs/scripts/storage_rooms.py figure
    python docs/scripts/storage_rooms.py benchmark [--layouts 20]
    python docs/scripts/storage_rooms.py difficulty [--layouts 5] [--samples 1000]
    python docs/scripts/storage_rooms.py planners [--layouts 3] [--seeds 2] [--simulations 300]

Timings are wall-clock on whatever machine runs it (the docs say which).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np

FIGURES = Path("docs/figures")
LEVELS = ("easy", "medium", "hard")


def _make(seed: int, difficulty: str, **kw: object) -> object:
    import gymnasium as gym

    import voot  # noqa: F401 - registers the ids

    return gym.make(
        "voot/ConveyorPacking-v2",
        layout_seed=seed,
        difficulty=difficulty,
        disable_env_checker=True,
        **kw,
    ).unwrapped


def _describe(env: object) -> str:
    lay = env.layout  # type: ignore[attr-defined]
    doors = [d.width for d in lay.doors]
    big = sum(b.big for b in lay.boxes)
    return (
        f"{lay.difficulty}, layout_seed {lay.layout_seed}: {len(lay.rooms)} rooms,"
        f" doors {min(doors):.2f}-{max(doors):.2f} m, {lay.n_boxes} boxes ({big} big)"
    )


def figure(size: tuple[int, int] = (560, 420)) -> None:
    """Render the layouts figure and the perspective view (see the module docstring)."""
    from PIL import Image, ImageDraw

    FIGURES.mkdir(parents=True, exist_ok=True)
    tiles = []
    for difficulty in LEVELS:
        for seed in (0, 1):
            env = _make(
                seed,
                difficulty,
                render_mode="rgb_array",
                render_camera="top_down",
                render_size=size,
            )
            env.reset(seed=0)  # type: ignore[attr-defined]
            for a in env.witness_actions():  # type: ignore[attr-defined]
                env.step(a)  # type: ignore[attr-defined]
            img = Image.fromarray(env.render())  # type: ignore[attr-defined]
            draw = ImageDraw.Draw(img)
            label = _describe(env)
            draw.rectangle((0, 0, size[0], 18), fill=(255, 255, 255))
            draw.text((4, 3), label, fill=(0, 0, 0))
            tiles.append(img)
            print(f"* {label}")
            env.close()  # type: ignore[attr-defined]
    w, h = size
    sheet = Image.new("RGB", (2 * w, 3 * h), (255, 255, 255))
    for k, tile in enumerate(tiles):
        sheet.paste(tile, ((k % 2) * w, (k // 2) * h))
    out = FIGURES / "storage_rooms_layouts.png"
    sheet.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(out, optimize=True)
    print(f"wrote {out}")
    env = _make(1, "hard", render_mode="rgb_array", render_size=(800, 600))
    env.reset(seed=0)  # type: ignore[attr-defined]
    for a in env.witness_actions()[:3]:  # type: ignore[attr-defined]
        env.step(a)  # type: ignore[attr-defined]
    out = FIGURES / "storage_rooms_perspective.png"
    img = Image.fromarray(env.render())  # type: ignore[attr-defined]
    img.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(out, optimize=True)
    print(f"wrote {out}")


def benchmark(layouts: int) -> None:
    """Cold and cached cost per instance, and what each level draws."""
    from voot.envs.assets.meshes import clear_memory_cache
    from voot.envs.conveyor.generated import instance as SI

    def forget() -> None:  # what a new process knows: nothing but the disk cache
        SI.clear_memo()
        clear_memory_cache()

    with tempfile.TemporaryDirectory() as tmp:
        os.environ["VOOT_CACHE"] = tmp
        _make(0, "easy")  # imports and warm-up, not measured
        rows = []
        for difficulty in LEVELS:
            cold, cached, make, checks, draws, rejected = [], [], [], [], 0, 0
            rooms, boxes, doors, min_door, kb = [], [], [], [], []
            for seed in range(1000, 1000 + layouts):
                forget()
                t = time.perf_counter()
                inst = SI.storage_instance(seed, difficulty)
                cold.append(time.perf_counter() - t)
                forget()
                t = time.perf_counter()
                SI.storage_instance(seed, difficulty)
                cached.append(time.perf_counter() - t)
                forget()
                t = time.perf_counter()
                _make(seed, difficulty)
                make.append(time.perf_counter() - t)
                lay = inst.layout
                checks.append(inst.witness.checks)
                draws += lay.attempt + 1
                rejected += len(inst.rejections)
                rooms.append(len(lay.rooms))
                boxes.append(lay.n_boxes)
                doors.append(np.mean([d.width for d in lay.doors]))
                min_door.append(min(d.width for d in lay.doors))
                kb.append(
                    sum(p.stat().st_size for p in SI.cache_dir().glob(f"{difficulty}-{seed}.*"))
                    / 1e3
                )
            ms = [1e3 * statistics.median(v) for v in (cold, cached, make)]
            rows.append(
                f"| {difficulty} | {layouts} | {np.mean(rooms):.1f} | {np.mean(boxes):.1f}"
                f" | {np.mean(doors):.2f} ({min(min_door):.2f}) | {rejected} of {draws}"
                f" | {np.mean(checks):.0f} | {ms[0]:.0f} ({1e3 * max(cold):.0f})"
                f" | {ms[1]:.0f} ({1e3 * max(cached):.0f}) | {ms[2]:.0f} | {np.mean(kb):.0f} |"
            )
    print(
        f"Layout seeds 1000-{999 + layouts} per level; times: median (max) milliseconds.\n\n"
        "| level | layouts | rooms | boxes | door width, mean (min) m | draws rejected"
        " | witness checks | cold ms | cached load ms | gym.make, cached ms | cache kB |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    )
    print("\n".join(rows))


def difficulty(layouts: int, samples: int) -> None:
    """Uniform actions at the first node per level (see the module docstring)."""
    from voot.bench.protocol.difficulty import node_stats
    from voot.envs.conveyor.generated.env import witness_return

    rows = []
    for level in LEVELS:
        passed = executed = total = 0
        failures: Counter[str] = Counter()
        returns = []
        for seed in range(layouts):
            returns.append(witness_return(_make(seed, level), 0.99))  # type: ignore[arg-type]
            kwargs = {"layout_seed": seed, "difficulty": level}
            (stats,) = node_stats("voot/ConveyorPacking-v2", samples, seed, kwargs)
            total += stats.samples
            passed += stats.passed_precheck
            executed += stats.passed_execution
            failures.update(stats.execution_failures)
        fails = ", ".join(f"{k} {v / total:.1%}" for k, v in failures.most_common())
        exe = f"{executed / passed:.1%}" if passed else "-"
        rows.append(
            f"| {level} | {layouts} x {samples} | {passed / total:.1%} | {exe} | {fails or '-'}"
            f" | {np.mean(returns):.2f} |"
        )
    print(
        "| level | layouts x samples | pass pre-check | of those, pass execution"
        " | execution failures | witness return (gamma 0.99) |\n|---|---:|---:|---:|---|---:|"
    )
    print("\n".join(rows))


def planners(layouts: int, seeds: int, simulations: int, out: str) -> None:
    """Runs of VOOT and PW-UCT per level (see the module docstring) and their summary."""
    from voot.bench.store.result_store import ResultStore

    for level in LEVELS:
        for seed in range(layouts):
            cmd = [
                *("voot-bench", "plan", "--out", out, "--problems", "conveyor_v2"),
                *("--env-kwargs", f"layout_seed={seed}", f"difficulty={level}"),
                *("--planners", "voot", "pw_uct", "--seeds", str(seeds)),
                *("--simulations", str(simulations), "--grid", "default", "--workers", "1"),
            ]
            done = subprocess.run(cmd, capture_output=True, text=True)
            if done.returncode:
                sys.exit(f"{' '.join(cmd)} failed:\n{done.stderr}")
    runs: dict[tuple[str, str], list[tuple[bool, float, float]]] = {}
    for row in ResultStore(out, create=False).iter_rows():
        cfg = row["config"]
        kw = cfg["env_kwargs"]
        if kw["layout_seed"] >= layouts or cfg["simulations"] != simulations:
            continue
        left = float(row["objects_left"][-1])
        initial = float(row["objects_initial"])
        key = (kw["difficulty"], cfg["planner"])
        runs.setdefault(key, []).append((left == 0, 1 - left / initial, row["best_return"]))
    print(
        f"{layouts} layouts x {seeds} seeds per level, {simulations} simulations:\n\n"
        "| level | planner | runs | pack every box | boxes packed (mean) | best return (mean) |\n"
        "|---|---|---:|---:|---:|---:|"
    )
    for level in LEVELS:
        for planner in ("voot", "pw_uct"):
            got = runs.get((level, planner), [])
            if got:
                solved = sum(g[0] for g in got)
                print(
                    f"| {level} | {planner} | {len(got)} | {solved} of {len(got)}"
                    f" | {np.mean([g[1] for g in got]):.0%} | {np.mean([g[2] for g in got]):.2f} |"
                )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("part", choices=("figure", "benchmark", "difficulty", "planners"))
    parser.add_argument("--layouts", type=int, default=None, help="layout seeds per level")
    parser.add_argument("--samples", type=int, default=1000, help="uniform actions per layout")
    parser.add_argument("--seeds", type=int, default=2, help="planner seeds per layout")
    parser.add_argument("--simulations", type=int, default=300, help="simulations per run")
    parser.add_argument("--out", default="/tmp/voot-storage-planners", help="result store")
    args = parser.parse_args()
    if args.part == "figure":
        figure()
    elif args.part == "benchmark":
        benchmark(args.layouts or 20)
    elif args.part == "difficulty":
        difficulty(args.layouts or 5, args.samples)
    else:
        planners(args.layouts or 3, args.seeds, args.simulations, args.out)


if __name__ == "__main__":
    main()
