"""What the base planner's exact-footprint option costs on the conveyor (a command, not a test).

``voot-bench measure footprint-speed [--rollouts N] [--seed S] [--coarse-first]
[--engine compiled|python] [--heuristic euclidean|geodesic] [--repeats R]`` prints
(:func:`run`, :func:`report`):

* the one-off time to compile the A* loop (``engine="compiled"``, numba; or to load it
  from numba's disk cache when an earlier process compiled it);
* the CPU time of the exact lattice search per query (the queries where the disc finds
  no path, so :meth:`~voot.envs.motion.planner.BasePlanner.plan_footprint` searches the
  lattice): median, 90th percentile and count, with the static occupancy of every
  carried box's footprint built beforehand (its one-off cost per footprint is printed
  apart);
* the CPU cost of conveyor simulations with the option against the disc
  (``ConveyorPacking-v1``, ``BasePlannerConfig(footprint=FootprintConfig())`` vs the
  default): the same random rollouts (from the start, each action uniform in the 9-D
  box, redrawn up to 50 times until it passes the pre-check, executed, until a step is
  infeasible or every box is placed), measured in the same run, with and without the
  one-off static occupancy;
* the same cost per placement checked (a step stops at its first infeasible placement,
  so the footprint, under which more placements succeed, checks more of them in the
  same steps), and the ratio with the exact queries' time taken out: what the ratio
  would be if the exact search cost nothing;
* a digest (sha256) of every exact query's answer: the engines give the same paths, so
  the same digest;

and the rollouts' boxes placed with each model. The issue's goals: a median exact query
under 10 ms, a simulation at most 3x the disc's CPU cost.

With ``--repeats R`` the replays run R times, each with fresh environments (so nothing a
replay computed is reused by the next), and every time is the least of the R (each query's
own least, each model's least total, the least of the footprint's totals less that
replay's queries): on a shared machine the least is the time least
disturbed by other work, ``timeit``'s convention. The queries are the same in every
repeat (the digest says so).
"""

from __future__ import annotations

import hashlib
import math
import statistics
import time
from dataclasses import replace
from typing import Any

import numpy as np

#: Draws of an action per step before the last one is executed (the authors' 50).
RETRIES = 50


def _record(env: Any, n: int, seed: int) -> tuple[list[tuple[Any, list[Any], Any]], list[int]]:
    """``n`` random rollouts of ``env``: per step its state, the pre-checked draws and the
    executed action; and the boxes each rollout placed."""
    rng = np.random.default_rng(seed)
    steps: list[tuple[Any, list[Any], Any]] = []
    placed: list[int] = []
    for _ in range(n):
        env.reset(seed=seed)
        while True:
            state = env.get_state()
            draws = []
            for _ in range(RETRIES):
                a = rng.uniform(-1.0, 1.0, env.action_dim)
                draws.append(a)
                ok, _ = env.precheck(a)
                if ok:
                    break
            steps.append((state, draws, a))
            _, terminated, truncated, info = env.transition(a)
            if not info["feasible"] or terminated or truncated:
                break
        placed.append(env.task.placed)
    return steps, placed


def _replay(env: Any, steps: list[tuple[Any, list[Any], Any]]) -> tuple[float, int, int]:
    """CPU seconds of the recorded steps' pre-checks and transitions in ``env``; feasible
    steps; placements checked.

    A step checks its (up to three) placements in turn and stops at the first that fails,
    so a model under which more placements succeed checks more of them in the same steps:
    the count puts the two models' costs on the same work.
    """
    total = 0.0
    feasible = 0
    checked = 0
    for state, draws, action in steps:
        env.set_state(state)
        t0 = time.process_time()
        for a in draws:
            env.precheck(a)
        _, _, _, info = env.transition(action)
        total += time.process_time() - t0
        feasible += bool(info["feasible"])
        failed = info["failed_box"]  # the first placement that failed, -1 if none
        checked += failed + 1 if failed >= 0 else len(info["placements"])
    return total, feasible, checked


def run(
    rollouts: int = 20,
    seed: int = 0,
    coarse_first: bool = False,
    engine: str = "compiled",
    label_after: int | None = None,
    heuristic: str = "euclidean",
    repeats: int = 1,
) -> dict[str, Any]:
    """Measure the exact queries and the simulation cost ratio (see the module doc).

    ``coarse_first`` sets :attr:`FootprintConfig.coarse_first` (the option answers
    "a path exists" as the default does, so the rollouts take the same steps), ``engine``
    :attr:`FootprintConfig.engine`, ``label_after`` (None: the default)
    :attr:`FootprintConfig.label_after` (the answers do not depend on it), ``heuristic``
    :attr:`FootprintConfig.heuristic` ("a path exists" answered alike, other paths);
    ``repeats`` the replays (fresh environments each; the least times are kept).
    """
    if repeats < 1:
        raise ValueError(f"repeats must be >= 1, got {repeats}")
    from voot.envs.conveyor.env import ConveyorPackingEnv
    from voot.envs.motion.footprint import FootprintConfig
    from voot.envs.motion.planner import BasePlannerConfig

    # the one-off compile of the A* loop (numba), before any search
    t0 = time.process_time()
    if engine == "compiled":
        from voot.envs.motion.footprint.astar import warm_compiled

        warm_compiled()
    compile_seconds = time.process_time() - t0
    fcfg = FootprintConfig(
        static_cache_size=20, coarse_first=coarse_first, engine=engine, heuristic=heuristic
    )
    if label_after is not None:
        fcfg = replace(fcfg, label_after=label_after)
    option = BasePlannerConfig(footprint=fcfg)
    # the steps of random rollouts with the option (they go deeper than the disc's)
    steps, placed = _record(ConveyorPackingEnv(preset="v1", planner=option), rollouts, seed)
    static = disc_cpu = exact_cpu = beyond_queries = math.inf
    queries: list[float] = []
    digests = set()
    for _ in range(repeats):
        disc = ConveyorPackingEnv(preset="v1")
        exact = ConveyorPackingEnv(preset="v1", planner=option)
        search = exact.planner.footprint_search()
        # what each box's footprint's first query would build (its scene, its static
        # occupancy where the query reads it)
        t0 = time.process_time()
        for i in range(exact.n):
            search.warm(exact.footprint(i))
        static = min(static, time.process_time() - t0)
        times: list[float] = []
        search.timings = times
        digest = hashlib.sha256()
        plan = search.plan

        def digested(*args: Any, plan: Any = plan, digest: Any = digest, **kwargs: Any) -> Any:
            out = plan(*args, **kwargs)
            digest.update(b"none" if out is None else np.ascontiguousarray(out).tobytes())
            return out

        search.plan = digested  # type: ignore[method-assign]
        cpu, disc_ok, disc_checked = _replay(disc, steps)
        disc_cpu = min(disc_cpu, cpu)
        cpu, exact_ok, exact_checked = _replay(exact, steps)
        exact_cpu = min(exact_cpu, cpu)
        beyond_queries = min(beyond_queries, cpu - sum(times))
        queries = times if not queries else [min(a, b) for a, b in zip(queries, times, strict=True)]
        digests.add(digest.hexdigest())
    if len(digests) != 1:
        raise RuntimeError(f"the repeats' exact answers differ: {sorted(digests)}")
    return {
        "rollouts": rollouts,
        "seed": seed,
        "lattice": (fcfg.xy_step, fcfg.headings),
        "coarse_first": coarse_first,
        "engine": engine,
        "label_after": fcfg.label_after,
        "heuristic": heuristic,
        "compile_seconds": compile_seconds,
        "paths_sha256": digests.pop(),
        "repeats": repeats,
        "static_seconds": static,
        "boxes": exact.n,
        "steps": len(steps),
        "disc_cpu": disc_cpu,
        "exact_cpu": exact_cpu,
        "beyond_queries_cpu": beyond_queries,
        "disc_feasible": disc_ok,
        "exact_feasible": exact_ok,
        "disc_checked": disc_checked,
        "exact_checked": exact_checked,
        "placed": placed,
        "queries": queries,
    }


def report(r: dict[str, Any]) -> str:
    """The figures of :func:`run` as text."""
    q = sorted(r["queries"])
    step, headings = r["lattice"]
    lines = [
        f"exact-footprint option on ConveyorPacking-v1, lattice {step * 100:g} cm x "
        f"{360 / headings:g} deg{', coarse_first' if r.get('coarse_first') else ''}, "
        f"engine {r['engine']}, label_after {r.get('label_after', 20_000)}, "
        f"{r.get('heuristic', 'euclidean')} heuristic, {r['rollouts']} random rollouts (seed {r['seed']}), CPU time"
        + (f", least of {r['repeats']} repeats" if r.get("repeats", 1) > 1 else ""),
        f"compiling the A* loop (or loading numba's cache): {r['compile_seconds']:.2f} s "
        "(once per process)",
        f"static occupancy: {r['static_seconds']:.1f} s for {r['boxes']} footprints "
        f"({r['static_seconds'] / r['boxes'] * 1000:.0f} ms each, once per env)",
    ]
    if q:
        p90 = q[min(len(q) - 1, int(0.9 * len(q)))]
        lines.append(
            f"exact queries (the disc found no path): {len(q)}, median "
            f"{statistics.median(q) * 1000:.1f} ms, 90th percentile {p90 * 1000:.1f} ms, "
            f"max {q[-1] * 1000:.0f} ms, total {sum(q):.2f} s (goal: median < 10 ms)"
        )
    else:
        lines.append("exact queries: none (the disc found every path)")
    ratio = r["exact_cpu"] / r["disc_cpu"] if r["disc_cpu"] > 0 else float("nan")
    with_static = (r["exact_cpu"] + r["static_seconds"]) / r["disc_cpu"]
    n = r["steps"]
    dc, ec = r["disc_checked"], r["exact_checked"]
    per_check = (r["exact_cpu"] / ec) / (r["disc_cpu"] / dc)
    floor = r["beyond_queries_cpu"] / r["disc_cpu"]
    lines += [
        f"the same {n} steps (pre-checks and execution; states of the footprint's rollouts): "
        f"disc {r['disc_cpu']:.2f} s ({r['disc_cpu'] / n * 1000:.1f} ms a step, "
        f"{r['disc_feasible']} feasible), footprint {r['exact_cpu']:.2f} s "
        f"({r['exact_cpu'] / n * 1000:.1f} ms a step, {r['exact_feasible']} feasible): "
        f"ratio {ratio:.1f}x, {with_static:.1f}x with the static occupancy (goal: <= 3x)",
        f"placements checked in those steps: disc {dc}, footprint {ec}; a placement "
        f"checked costs {r['disc_cpu'] / dc * 1000:.2f} ms with the disc, "
        f"{r['exact_cpu'] / ec * 1000:.2f} ms with the footprint: ratio {per_check:.1f}x",
        f"the footprint's steps without their exact queries: {r['beyond_queries_cpu']:.2f} s, "
        f"ratio {floor:.1f}x (the ratio if the exact search cost nothing)",
        f"boxes placed per rollout with the footprint: mean {np.mean(r['placed']):.2f}",
        f"exact answers' sha256: {r['paths_sha256'][:16]} (the same for both engines)",
    ]
    return "\n".join(lines)
