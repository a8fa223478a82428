r"""Speed-up and quality of root-parallel search over 1, 2, 4 ... workers.

Run ``voot-bench measure root-parallel`` (options: ``--help``; :func:`run_and_report`).
The figure of the documentation was made by::

    voot-bench measure root-parallel --problems shekel kitchen \
        --budget 10000 240 --seeds 5 3 --workers 1 2 4

(5 minutes at a load average of 3 on two cores, 15 at 9). For every problem (the
Shekel chain in 10-D; the kitchen, which needs the ``envs`` extra) and seed it measures:

* **Fixed total budget** :math:`S`: :math:`K` trees of :math:`S / K` simulations on
  :math:`W \le K` warm worker processes (:class:`~voot.tree.root_parallel.LocalProcessExecutor`
  whose workers built the problem before the clock starts), for every :math:`(K, W)`:
  wall time of the call, the trees' CPU time, and the merged best return (which does not
  depend on :math:`W`: the search is deterministic). Speed-up is
  :math:`T(1, 1) / T(K, W)` (means over seeds). Every seed runs every configuration,
  in an order rotated from seed to seed, so that a drifting load from other users
  spreads over all configurations alike.
* **Equal wall time**: :math:`K \le W` trees of up to :math:`S` simulations each on
  :math:`W` workers (the most the machine has cores for), stopped after 1.25 times the
  single tree's search time; the best return known at the single tree's wall time
  :math:`T(1, 1)` (:meth:`~voot.tree.root_parallel.RootParallelResult.best_return_at`).
  More trees than workers run in waves, and by the seeds' nesting the first wave is the
  :math:`K = W` run, so :math:`K > W` is not run here.

It prints a table, the machine's load average before and after (the figures are only
as good as the cores the other users left), and draws the figure (``--figure``; needs the
``bench`` extra for matplotlib). Matplotlib and the environments are imported only when
used, so importing this module stays as light as :mod:`voot.tree`.
"""

from __future__ import annotations

import contextlib
import functools
import json
import math
import os
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from voot.bench.protocol.problems import domain_options
from voot.tree.chains import make_chain
from voot.tree.config import MCTSConfig, planner_config
from voot.tree.problem import PlanningProblem
from voot.tree.root_parallel import (
    LocalProcessExecutor,
    RootParallelResult,
    plan_root_parallel,
    prebuild_problem,
)

#: Where the figure goes by default (relative to the working directory).
DEFAULT_FIGURE = "docs/figures/root_parallel_speedup.png"
#: Problems this benchmark knows.
PROBLEMS = ("shekel", "kitchen")
#: Default total simulation budgets (a kitchen simulation costs about 150 times a Shekel one).
DEFAULT_BUDGETS = {"shekel": 10_000, "kitchen": 240}
#: Equal-wall-time runs stop after this many times the single tree's search time.
LONG_RUN_MARGIN = 1.25
#: The step-info key of the kitchen's objects left.
OBJECTS_KEY = "objects_left"


def shekel_problem(dim: int = 10) -> PlanningProblem:
    """The authors' Shekel chain (a picklable factory through ``functools.partial``)."""
    return make_chain("shekel", dim)


def kitchen_problem(seed: int = 0) -> PlanningProblem:
    """``voot/KitchenClearing-v0`` reset with ``seed``, as a planning problem (MuJoCo)."""
    import gymnasium

    import voot  # noqa: F401 - registers the voot/... ids
    from voot.envs.core.problem import EnvProblem

    env = gymnasium.make("voot/KitchenClearing-v0", disable_env_checker=True)
    return EnvProblem(env, seed=seed)


@dataclass(frozen=True)
class Setup:
    """One problem of the benchmark: how to build it and plan in it."""

    name: str
    factory: Any
    config: MCTSConfig
    budget: int
    record_info: str | None = None


def make_setup(name: str, budget: int | None = None, dim: int = 10) -> Setup:
    """The benchmark's settings for ``name`` (``shekel`` or ``kitchen``).

    Shekel: the authors' chain settings (:func:`~voot.tree.chain_planner_options`) with
    VOO in ``centered_uniform`` mode. Kitchen (v0): :math:`\\gamma = 0.9`, VOO in
    ``uniform`` mode. Both are ``voot-bench plan``'s settings (:func:`domain_options`).
    """
    if name == "shekel":
        cfg = planner_config("voot", **domain_options("shekel_chain", dim, "voot"))
        return Setup(
            f"shekel{dim}",
            functools.partial(shekel_problem, dim),
            cfg,
            budget or DEFAULT_BUDGETS["shekel"],
        )
    if name == "kitchen":
        cfg = planner_config("voot", **domain_options("voot/KitchenClearing-v0", None, "voot"))
        return Setup(
            "kitchen",
            functools.partial(kitchen_problem, 0),
            cfg,
            budget or DEFAULT_BUDGETS["kitchen"],
            OBJECTS_KEY,
        )
    raise ValueError(f"unknown problem {name!r}; valid problems are: {', '.join(PROBLEMS)}")


def load_average() -> tuple[float, float, float] | None:
    """The 1, 5 and 15 minute load averages (None where the OS does not say)."""
    try:
        return os.getloadavg()
    except OSError:  # pragma: no cover - not on this platform
        return None


@dataclass
class Measurements:
    """What :func:`measure` collected for one problem."""

    setup: Setup
    trees: list[int]
    workers: list[int]
    seeds: list[int]
    #: W of the equal-wall-time runs (the most workers the machine has cores for).
    long_workers: int
    #: (K, W) -> one fixed-budget result per seed.
    fixed: dict[tuple[int, int], list[RootParallelResult]] = field(default_factory=dict)
    #: K -> per seed, K trees of up to S simulations on ``long_workers`` workers,
    #: time-limited (K = 1: the fixed-budget run).
    long: dict[int, list[RootParallelResult]] = field(default_factory=dict)
    load_before: tuple[float, float, float] | None = None
    load_after: tuple[float, float, float] | None = None


def configurations(trees: Sequence[int], workers: Sequence[int]) -> list[tuple[int, int]]:
    """The (K, W) pairs measured: every W <= K (more workers than trees would idle)."""
    return [(k, w) for w in sorted(set(workers)) for k in sorted(set(trees)) if w <= k]


def measure(
    setup: Setup,
    trees: Sequence[int] = (1, 2, 4),
    workers: Sequence[int] = (1, 2),
    seeds: Sequence[int] = (0, 1, 2),
    merge: str = "max_q",
    *,
    long_runs: bool = True,
    log: Any = None,
) -> Measurements:
    """Run the benchmark's searches for one problem (see the module docstring)."""
    trees = sorted(set(trees))
    workers = sorted(set(workers))
    for k in trees:
        if setup.budget % k:
            raise ValueError(f"the budget {setup.budget} must be divisible by every K, not by {k}")
    if 1 not in trees or 1 not in workers:
        raise ValueError("trees and workers must include 1 (the baseline of the speed-up)")
    cores = os.cpu_count() or 1
    long_w = max([w for w in workers if w <= cores] or [1])
    out = Measurements(setup, trees, workers, list(seeds), long_w, load_before=load_average())

    def run(
        pool: LocalProcessExecutor, k: int, n: int, seed: int, limit: float | None = None
    ) -> RootParallelResult:
        return plan_root_parallel(
            setup.factory,
            setup.config,
            n,
            seed,
            n_trees=k,
            merge=merge,
            executor=pool,
            record_info=setup.record_info,
            time_limit=limit,
        )

    configs = configurations(trees, workers)
    with contextlib.ExitStack() as stack:
        pools = {
            w: stack.enter_context(
                LocalProcessExecutor(w, initializer=prebuild_problem, initargs=(setup.factory,))
            )
            for w in workers
        }
        for pool in pools.values():
            pool.warm_up()
        for j, seed in enumerate(seeds):
            # Every seed runs every configuration, in an order rotated from seed to seed,
            # so that the other users' load drifts over all configurations alike.
            shift = j % len(configs)
            for k, w in configs[shift:] + configs[:shift]:
                res = run(pools[w], k, setup.budget // k, seed)
                out.fixed.setdefault((k, w), []).append(res)
                if log is not None:
                    log(
                        f"{setup.name} seed={seed} K={k} W={w}: {res.wall_time:.2f} s"
                        f" (CPU {res.cpu_time:.2f} s), best {res.best_return:.4g}"
                    )
            if not long_runs:
                continue
            single = out.fixed[(1, 1)][-1]
            out.long.setdefault(1, []).append(single)
            for k in trees:
                if 1 < k <= long_w:
                    limit = LONG_RUN_MARGIN * max(t.plan.wall_time for t in single.trees)
                    res = run(pools[long_w], k, setup.budget, seed, limit)
                    out.long.setdefault(k, []).append(res)
                    if log is not None:
                        log(
                            f"{setup.name} seed={seed} K={k} W={long_w} for"
                            f" {limit:.1f} s: best {res.best_return_at(single.wall_time):.4g}"
                            f" at {single.wall_time:.2f} s"
                        )
    out.load_after = load_average()
    return out


def _mean(values: Sequence[float]) -> float:
    return float(np.mean(values)) if len(values) else math.nan


def critical_path(result: RootParallelResult) -> float:
    """CPU seconds of the busiest worker process (the trees it ran, summed): the wall
    time the run would take if every worker had a core of its own."""
    per_worker: dict[int, float] = {}
    for t in result.trees:
        per_worker[t.pid] = per_worker.get(t.pid, 0.0) + t.cpu_time
    return max(per_worker.values())


def cpu_speedups(m: Measurements) -> dict[tuple[int, int], float]:
    r"""Per (K, W <= cores): :math:`\mathrm{CPU}(1, 1)` over the mean critical path: the
    speed-up on otherwise idle cores, from the CPU time each worker spent."""
    cores = os.cpu_count() or 1
    base = _mean([r.cpu_time for r in m.fixed[(1, 1)]])
    return {
        kw: base / _mean([critical_path(r) for r in results])
        for kw, results in m.fixed.items()
        if kw[1] <= cores
    }


def table_rows(m: Measurements) -> list[dict[str, Any]]:
    """One row per (K, W): times, speed-up, quality at equal budget and equal wall time."""
    base = _mean([r.wall_time for r in m.fixed[(1, 1)]])
    t_single = [r.wall_time for r in m.fixed[(1, 1)]]
    cpu_up = cpu_speedups(m)
    rows = []
    for (k, w), results in sorted(m.fixed.items(), key=lambda kv: (kv[0][1], kv[0][0])):
        wall = _mean([r.wall_time for r in results])
        best = [r.best_return for r in results]
        row: dict[str, Any] = {
            "problem": m.setup.name,
            "K": k,
            "W": w,
            "sims_per_tree": m.setup.budget // k,
            "wall_s": wall,
            "speedup": base / wall,
            "efficiency": base / wall / w,
            "cpu_s": _mean([r.cpu_time for r in results]),
            "cores_used": _mean([r.cpu_time / r.wall_time for r in results]),
            "cpu_speedup": cpu_up.get((k, w), math.nan),
            "best_at_budget": _mean(best),
            "best_at_budget_sd": float(np.std(best)),
            "best_at_equal_time": math.nan,
            "sims_per_tree_at_equal_time": math.nan,
        }
        if k in m.long and (w == m.long_workers or k == 1):
            at = [float(r.best_return_at(t)) for r, t in zip(m.long[k], t_single, strict=True)]
            row["best_at_equal_time"] = _mean(at)
            row["sims_per_tree_at_equal_time"] = _mean(
                [sims_done_by(r, t) for r, t in zip(m.long[k], t_single, strict=True)]
            )
        rows.append(row)
    return rows


def sims_done_by(result: RootParallelResult, seconds: float) -> float:
    """Mean over trees of the simulations finished ``seconds`` after the call started."""
    done = [
        np.searchsorted(t.started - result.started + t.elapsed, seconds, side="right")
        for t in result.trees
    ]
    return float(np.mean(done))


def format_table(rows: Sequence[dict[str, Any]]) -> str:
    """The rows as a Markdown table."""
    head = (
        "| problem | K | W | sims/tree | wall s | speed-up | efficiency | CPU s | cores used |"
        " idle-core speed-up | best @ S (mean ± sd) | best @ T(1,1) | sims/tree by T(1,1) |"
    )
    lines = [head, "|" + "---|" * 13]
    for r in rows:
        eq = r["best_at_equal_time"]
        n_eq = r["sims_per_tree_at_equal_time"]
        lines.append(
            f"| {r['problem']} | {r['K']} | {r['W']} | {r['sims_per_tree']} | {r['wall_s']:.2f} |"
            f" {r['speedup']:.2f} | {r['efficiency']:.2f} | {r['cpu_s']:.2f} |"
            f" {r['cores_used']:.2f} |"
            f" {'-' if math.isnan(r['cpu_speedup']) else format(r['cpu_speedup'], '.2f')} |"
            f" {r['best_at_budget']:.4g} ± {r['best_at_budget_sd']:.2g} |"
            f" {'-' if math.isnan(eq) else f'{eq:.4g}'} |"
            f" {'-' if math.isnan(n_eq) else f'{n_eq:.0f}'} |"
        )
    return "\n".join(lines)


def _mean_curve(curves: Sequence[np.ndarray]) -> np.ndarray:
    n = min(c.size for c in curves)
    return np.mean(np.array([c[:n] for c in curves]), axis=0)


def plot(measurements: Sequence[Measurements], path: str | Path, note: str = "") -> Path:
    """Draw the figure: per problem, speed-up, best return against simulations (both
    views) and against wall time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = len(measurements)
    fig, axes = plt.subplots(rows, 3, figsize=(15, 4.2 * rows), squeeze=False)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for row, m in zip(axes, measurements, strict=True):
        ax = row[0]
        cpu_up = cpu_speedups(m)
        base = _mean([r.wall_time for r in m.fixed[(1, 1)]])
        ws = np.array(m.workers)
        ax.plot(ws, ws, "k--", lw=1, label="ideal")
        for i, k in enumerate(m.trees):
            pts = [
                (w, base / _mean([r.wall_time for r in m.fixed[(k, w)]]))
                for w in m.workers
                if (k, w) in m.fixed
            ]
            x, y = zip(*pts, strict=True)
            c = colors[i % len(colors)]
            ax.plot(x, y, "o-", color=c, label=f"K={k}, measured wall time")
            idle = [(w, cpu_up[(k, w)]) for w in m.workers if (k, w) in cpu_up]
            if k > 1 and idle:
                x, y = zip(*idle, strict=True)
                ax.plot(x, y, "s--", color=c, mfc="none", label=f"K={k}, idle cores (CPU)")
        ax.set_xlabel("worker processes W")
        ax.set_ylabel("speed-up  T(1 tree, 1 worker) / T(K, W)")
        ax.set_xticks(ws)
        ax.set_title(f"{m.setup.name}: fixed total budget S={m.setup.budget}")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)

        ax = row[1]
        for i, k in enumerate(m.trees):
            src = m.fixed[(k, 1)]
            curve = _mean_curve([r.best_return_curve for r in src])
            c = colors[i % len(colors)]
            n_total = min(curve.size, m.setup.budget // k)
            ax.plot(
                k * np.arange(1, n_total + 1),
                curve[:n_total],
                color=c,
                label=f"K={k}, vs total sims K·i",
            )
            if k > 1:
                ax.plot(
                    np.arange(1, curve.size + 1),
                    curve,
                    color=c,
                    ls=":",
                    label=f"K={k}, vs per-tree sims i",
                )
        ax.set_xlabel("simulations")
        ax.set_ylabel("best return (mean over seeds)")
        ax.set_xlim(1, m.setup.budget)
        ax.set_title("merged curve B_K(i) = max_k B_k(i), two views")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)

        ax = row[2]
        if m.long:
            t_max = max(r.wall_time for rs in m.long.values() for r in rs)
            grid = np.linspace(0.0, t_max, 400)
            for i, k in enumerate(m.trees):
                if k not in m.long:
                    continue
                vals = np.array([r.best_return_at(grid) for r in m.long[k]])
                ok = np.all(np.isfinite(vals), axis=0)
                ax.plot(
                    grid[ok],
                    vals[:, ok].mean(axis=0),
                    color=colors[i % len(colors)],
                    label=f"K={k}",
                )
            t1 = _mean([r.wall_time for r in m.fixed[(1, 1)]])
            ax.axvline(t1, color="k", lw=0.8, ls="--", label="T(1,1)")
            ax.set_title(f"best return against wall time, W={m.long_workers} workers")
        ax.set_xlabel("wall-clock seconds")
        ax.set_ylabel("best return (mean over seeds)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    if note:
        fig.text(0.5, 0.005, note, ha="center", fontsize=8)
    fig.tight_layout(rect=(0, 0.03 if note else 0, 1, 1))
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def _load(load: tuple[float, float, float] | None) -> str:
    return "?" if load is None else "/".join(f"{x:.1f}" for x in load)


def run_and_report(
    problems: Sequence[str],
    budgets: Sequence[int | None],
    seeds: Sequence[int],
    *,
    dim: int = 10,
    trees: Sequence[int] = (1, 2, 4),
    workers: Sequence[int] = (1, 2),
    merge: str = "max_q",
    long_runs: bool = True,
    figure: str = DEFAULT_FIGURE,
    json_path: str = "",
) -> None:
    """``voot-bench measure root-parallel``: :func:`measure` every problem (its budget
    :math:`S` and its number of seeds from ``budgets`` and ``seeds``, one each), print the
    table and the load averages, write the rows to ``json_path`` and draw ``figure``
    (each unless empty)."""

    def log(msg: str) -> None:
        print(msg, file=sys.stderr, flush=True)

    print(f"cores: {os.cpu_count()}, load average before: {load_average()}", flush=True)
    t0 = time.perf_counter()
    results = []
    for name, budget, n_seeds in zip(problems, budgets, seeds, strict=True):
        setup = make_setup(name, budget, dim)
        results.append(
            measure(
                setup,
                trees,
                workers,
                list(range(n_seeds)),
                merge,
                long_runs=long_runs,
                log=log,
            )
        )
    rows = [row for m in results for row in table_rows(m)]
    print(format_table(rows))
    loads = ", ".join(
        f"{m.setup.name}: {_load(m.load_before)} -> {_load(m.load_after)}" for m in results
    )
    print(f"load averages (1, 5, 15 min) before -> after: {loads}")
    print(f"total {time.perf_counter() - t0:.0f} s")
    if json_path:
        Path(json_path).write_text(json.dumps({"rows": rows, "loads": loads}, indent=1))
    if figure:
        note = (
            f"{os.cpu_count()} cores shared with other users; load average (1/5/15 min)"
            f" before -> after: {loads}; merge={merge}; seeds per problem {list(seeds)}"
        )
        print(f"figure: {plot(results, figure, note)}")
