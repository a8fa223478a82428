"""The cost of a planning sweep before it runs (``voot-bench plan --estimate``).

The full protocol costs tens of CPU-hours, so it is estimated first from the measured
cost of a simulation, per (problem, planner):

* **from the store**, when it holds finished rows of that problem and planner (any
  setting, any seed): the sum of their ``search_time`` over the sum of their
  simulations. Rows of the sweep's own budget are preferred, because a simulation gets
  dearer as the tree grows (VOO's nearest-point queries, deeper paths); rows of another
  budget are used only when there are none of it.
* **else by a probe**: one run of the pair's first listed setting and seed with
  ``probe_simulations`` simulations (:data:`PROBE_SIMULATIONS`), not stored. A probe
  is short, so it measures the cost of a small tree and underestimates long runs; the
  report names the source of every line.

The estimate covers the runs not yet in the store (the listed ones already there cost
nothing more); wall-hours assume the CPU-hours spread perfectly over ``workers``
processes (a lower bound: the last runs leave cores idle). ``search_time`` is wall
time of a one-thread search (BLAS is pinned to one thread per run), which is close to
its CPU time when the cores are not oversubscribed.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any

from voot import validation as V
from voot.bench.protocol.select import cell_of, function_order, method_order
from voot.bench.store.format import Row

#: Simulations of a probe run (a pair without rows in the store).
PROBE_SIMULATIONS = 20

#: (problem label, dim or 0, planner): the pairs costs are measured for.
PairKey = tuple[str, int, str]


def pair_of(row_or_spec: Any) -> PairKey:
    """The (problem, dim, planner) of a row or a plan spec."""
    row = (
        row_or_spec
        if isinstance(row_or_spec, dict)
        else {"kind": "plan", "config": row_or_spec.config()}
    )
    label, dim, _, planner = cell_of(row)
    return (label, dim, planner)


@dataclass(frozen=True)
class CostLine:
    """The estimate of one (problem, planner).

    Attributes:
        problem: the problem's display name (with the chain's dimension).
        planner: the planner.
        runs: runs listed.
        pending: runs listed and not yet in the store.
        simulations: simulations of the pending runs.
        seconds_per_simulation: the measured cost of a simulation.
        source: where it was measured (``store: N rows`` or ``probe: K simulations``).
    """

    problem: str
    planner: str
    runs: int
    pending: int
    simulations: int
    seconds_per_simulation: float
    source: str

    @property
    def cpu_hours(self) -> float:
        return self.simulations * self.seconds_per_simulation / 3600.0


def stored_cost(rows: Iterable[Row], pair: PairKey, simulations: int) -> tuple[float, int] | None:
    """``(seconds per simulation, rows used)`` of ``pair`` from finished rows, preferring
    rows of budget ``simulations``; None without any."""
    matching = [
        r
        for r in rows
        if r.get("status") == "ok"
        and r.get("kind") == "plan"
        and isinstance(r.get("search_time"), int | float)
        and pair_of(r) == pair
    ]
    same = [r for r in matching if int(r["config"]["simulations"]) == simulations]
    use = same or matching
    sims = sum(int(r["config"]["simulations"]) for r in use)
    if not use or sims <= 0:
        return None
    return sum(float(r["search_time"]) for r in use) / sims, len(use)


def probe_cost(spec: Any, simulations: int, run: Callable[[Any], Row] | None = None) -> float:
    """Seconds per simulation of ``spec`` cut to ``simulations`` simulations (one run,
    not stored). Raises ValueError if the probe fails."""
    from voot.bench.sweep.plan import run_plan_spec

    runner = run_plan_spec if run is None else run
    row = runner(replace(spec, simulations=simulations, record=None))
    if row.get("status") != "ok":
        raise ValueError(f"the probe of {spec.planner} on {spec.label} failed: {row.get('error')}")
    return float(row["search_time"]) / simulations


def estimate(
    specs: Sequence[Any],
    rows: Iterable[Row],
    pending_ids: Iterable[str],
    *,
    probe_simulations: int = PROBE_SIMULATIONS,
    run: Callable[[Any], Row] | None = None,
) -> list[CostLine]:
    """One :class:`CostLine` per (problem, planner) of ``specs``, in plotting order.

    Args:
        specs: the listed plan specs.
        rows: the store's rows (measured costs).
        pending_ids: run ids of the listed specs not yet in the store.
        probe_simulations: simulations of a probe (pairs without rows).
        run: runs a probe spec (default :func:`voot.bench.sweep.plan.run_plan_spec`).
    """
    n_probe = V.integer(probe_simulations, "probe_simulations", 1)
    rows = list(rows)
    pending = set(pending_ids)
    groups: dict[PairKey, list[Any]] = {}
    for s in dict.fromkeys(specs):
        groups.setdefault(pair_of(s), []).append(s)
    out = []
    for pair, group in groups.items():
        budget = max(s.simulations for s in group)
        stored = stored_cost(rows, pair, budget)
        if stored is not None:
            cost, n = stored
            source = f"store: {n} rows"
        else:
            cost = probe_cost(group[0], n_probe, run)
            source = f"probe: {n_probe} simulations"
        todo = [s for s in group if s.run_id in pending]
        label = f"{pair[0]}-{pair[1]}D" if pair[1] else pair[0]
        out.append(
            CostLine(
                label,
                pair[2],
                len(group),
                len(todo),
                sum(s.simulations for s in todo),
                cost,
                source,
            )
        )
    problems = function_order(line.problem for line in out)
    planners = method_order(line.planner for line in out)
    out.sort(key=lambda c: (problems.index(c.problem), planners.index(c.planner)))
    return out


def cost_table(
    lines: Sequence[CostLine],
    columns: tuple[str, str] = ("problem", "planner"),
    name: Callable[[str], str] = str,
) -> list[str]:
    """The markdown rows (header first) of cost ``lines``: the first two ``columns``
    named as given, each problem written by ``name``."""
    table = [
        f"| {columns[0]} | {columns[1]} | runs | to run | simulations to run |"
        " ms per simulation | source | CPU-hours |",
        "| --- | --- | ---: | ---: | ---: | ---: | --- | ---: |",
    ]
    for c in lines:
        table.append(
            f"| {name(c.problem)} | {c.planner} | {c.runs} | {c.pending} | {c.simulations}"
            f" | {1000.0 * c.seconds_per_simulation:.3g} | {c.source} | {c.cpu_hours:.3g} |"
        )
    return table


def format_estimate(lines: Sequence[CostLine], workers: int) -> str:
    """The estimate as a markdown table, the total and the wall-hours at ``workers``."""
    n_workers = V.integer(workers, "workers", 1)
    table = cost_table(lines)
    total = math.fsum(c.cpu_hours for c in lines)
    runs = sum(c.pending for c in lines)
    table.append("")
    table.append(
        f"total: {runs} runs to run, {total:.3g} CPU-hours; about {total / n_workers:.3g}"
        f" wall-hours on {n_workers} worker{'s' if n_workers != 1 else ''} (perfect packing,"
        " a lower bound). Cost per simulation: store rows' search_time / simulations"
        " (same budget preferred), else a short probe run (underestimates long runs)."
    )
    return "\n".join(table)
