"""A process's resident memory (RSS) while a generated family's env visits many layouts.

One env of the family, reset onto layouts ``0, 1, ..., N-1`` in turn (what a learner or an
evaluation across layouts does), in one process with an empty cache (run it with
``VOOT_CACHE`` a fresh folder, so every layout is generated); the RSS after every
``--every`` layouts (after a garbage collection), read from ``/proc/self/statm`` (Linux).
With ``--trim`` the freed heap is first handed back to the system (glibc's
``malloc_trim``), so the figure is what the process holds rather than what the allocator
kept of freed memory (a generated layout's cold path allocates and frees a lot).
The in-process caches are bounded (docs/environments.md, "Caches"), so the RSS levels off
once they are full instead of growing with every layout. MuJoCo's own asset cache (the
compiler keeps every mesh it processed, up to 500 MiB by default) is bypassed by a
generated scene's compile unless ``--mujoco-cache-mb`` gives it a capacity (as
``$VOOT_MUJOCO_CACHE_MB`` does; ``0`` turns it off); its size is the last column.

Run from the repository root (a few minutes per family)::

    VOOT_CACHE=$(mktemp -d) python docs/scripts/family_memory.py --family storage [--layouts 200]
"""

from __future__ import annotations

import argparse
import ctypes
import gc
import os
import time

import gymnasium as gym
import mujoco

import voot  # noqa: F401  (registers the ids)
from voot.envs.core.caches import MUJOCO_CACHE_VAR

IDS = {"kitchen": "voot/GeneratedKitchen-v0", "storage": "voot/GeneratedStorage-v0"}


def rss_mb() -> float:
    """This process's resident set size, in MB (Linux)."""
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE") / 1e6


def settle(trim: bool) -> float:
    """The RSS in MB after a garbage collection (and glibc's ``malloc_trim`` if ``trim``)."""
    gc.collect()
    if trim:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    return rss_mb()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--family", choices=sorted(IDS), required=True)
    parser.add_argument("--layouts", type=int, default=200)
    parser.add_argument("--every", type=int, default=20)
    parser.add_argument("--difficulty", default="easy")
    parser.add_argument("--trim", action="store_true", help="malloc_trim before each reading")
    parser.add_argument(
        "--mujoco-cache-mb",
        help=f"capacity of MuJoCo's asset cache in MB (sets {MUJOCO_CACHE_VAR}; 0: off)",
    )
    args = parser.parse_args()
    if args.mujoco_cache_mb is not None:
        os.environ[MUJOCO_CACHE_VAR] = args.mujoco_cache_mb
    cache = mujoco.mj_getCache()
    env = gym.make(IDS[args.family], layout_seed=0, difficulty=args.difficulty)
    env.reset(seed=0)
    start = settle(args.trim)
    t0 = time.perf_counter()
    trimmed = ", malloc_trim" if args.trim else ""
    capacity = mujoco.mj_getCacheCapacity(cache) / 1e6
    print(
        f"{IDS[args.family]} ({args.difficulty}{trimmed}), VOOT_CACHE={os.environ.get('VOOT_CACHE')},"
        f" MuJoCo asset cache capacity {capacity:.0f} MB"
    )
    print(f"{'layouts':>8} {'RSS MB':>8} {'growth MB':>10} {'seconds':>8} {'mj cache MB':>12}")
    size = mujoco.mj_getCacheSize(cache) / 1e6
    print(f"{1:>8} {start:>8.1f} {0.0:>10.1f} {0.0:>8.1f} {size:>12.1f}", flush=True)
    for k in range(1, args.layouts):
        env.reset(seed=0, options={"layout_seed": k})
        if (k + 1) % args.every == 0:
            now = settle(args.trim)
            size = mujoco.mj_getCacheSize(cache) / 1e6
            seconds = time.perf_counter() - t0
            print(
                f"{k + 1:>8} {now:>8.1f} {now - start:>10.1f} {seconds:>8.1f} {size:>12.1f}",
                flush=True,
            )


if __name__ == "__main__":
    main()
