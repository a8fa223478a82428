"""The runs of a leaderboard: tuning on training layouts, evaluation on held-out layouts,
and their cost before anything runs.

For every family of the suite and every entry, the entry's **setting** is fixed first
(:func:`choose_settings`), on training layouts only:

* ``protocol``: the committed protocol's selection
  (:func:`voot.bench.protocol.settings.protocol_selection`), when the suite reuses it and
  the protocol selected one for that planner on the family's training layouts (not for a
  variant: its options differ from the runs selected on);
* ``single``: the entry's grid has one setting (nothing to select);
* ``tuned``: else every setting of the entry's grid runs on the suite's training layouts
  x tuning seeds at the tuning level (:func:`tuning_specs`), and the setting with the
  best mean final return is selected (:func:`voot.bench.protocol.tuning.tuning_selections`,
  the protocol's rule). Until every tuning run of the pair is finished its selection is
  unknown, and its evaluation waits.

The **evaluation** (:func:`evaluation_specs`) runs the chosen setting at every level x
held-out layout x seed, with the family's budget. Every run is an ordinary plan run
(:class:`voot.bench.sweep.plan.PlanSpec`, its id the hash of its config), so the store
resumes at any point: finished runs are skipped, selections are recomputed from the
finished tuning runs (deterministically), nothing is redone and nothing lost.
:func:`run_suite` runs family by family, tuning first, then level by level, so an
interrupted run leaves whole (family, level) cells.

**Cost** (:func:`estimate_suite`): CPU seconds per simulation per (family, entry)
(:func:`run_cpu_seconds`: the process's CPU time of the search, which a machine shared
with other work does not inflate as it does wall time), from
the store's finished rows of the pair, else the committed stores' rows of the same env
and planner (``docs/data``: the held-out protocol's runs), else a short probe
(:func:`voot.bench.protocol.estimate.probe_cost`); times the simulations still to run.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from voot.bench.leaderboard.suite import Entry, Family, Suite
from voot.bench.protocol.estimate import CostLine, cost_table
from voot.bench.store.format import Row
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.plan import PlanSpec, build_plan_specs

#: The command that runs (and resumes) a suite, as the report prints it.
RUN_COMMAND = "voot-bench leaderboard run --suite {suite} --out {out} --workers 1"
#: Where the committed stores are (reference costs for the estimate).
REFERENCE_DATA = Path(__file__).resolve().parents[2] / "docs" / "data"


def canonical_problem(problem: str) -> str:
    """The gymnasium id a (possibly renamed) problem runs: ``voot/KitchenClearing-v2`` ->
    ``voot/GeneratedKitchen-v0``."""
    from voot.bench.protocol.problems import normalize_problem
    from voot.problems import find_record

    name = normalize_problem(problem)
    record = find_record(name)
    return record.renamed_to if record is not None and record.renamed_to else name


def entry_grid(entry: Entry, family: str = "robot") -> list[dict[str, Any]]:
    """The settings searched for ``entry``: its own axes, else its planner's grid; each
    with the entry's fixed options."""
    import itertools

    from voot.bench.sweep.planners import planner_grid

    if entry.axes:
        names = [k for k, _ in entry.axes]
        grid = [
            dict(zip(names, values, strict=True))
            for values in itertools.product(*(v for _, v in entry.axes))
        ]
    else:
        grid = planner_grid(entry.planner, family, "paper")
    return [{**g, **dict(entry.set)} for g in grid]


@dataclass(frozen=True)
class Choice:
    """The setting of an entry on a family, and where it comes from.

    Attributes:
        problem: the family.
        entry: the entry's name.
        params: the setting (None while its tuning runs are not all finished).
        source: ``protocol``, ``single`` or ``tuned``.
        note: one line saying how it was selected.
    """

    problem: str
    entry: str
    params: Mapping[str, Any] | None
    source: str
    note: str


def protocol_params(
    suite: Suite, family: Family, entry: Entry
) -> tuple[dict[str, Any], str] | None:
    """The committed protocol's selection of ``entry`` on ``family`` if the suite reuses
    it and it was made on the suite's training layouts; None otherwise."""
    if not suite.reuse_protocol or entry.variant or entry.set or entry.axes:
        return None
    from voot.bench.protocol.settings import protocol_selection

    try:
        sel = protocol_selection(family.problem, entry.planner, suite.tuning_level)
    except (ValueError, KeyError):
        return None
    if "training layouts" not in sel.tuned_on or sel.simulations != family.simulations:
        return None
    note = f"committed protocol ({sel.store}, {sel.tuned_on}, level {sel.difficulty})"
    return dict(sel.params), note


def tuning_specs(suite: Suite, family: Family, entry: Entry) -> list[PlanSpec]:
    """Every setting of ``entry``'s grid on the training layouts x tuning seeds (none if
    its setting comes from the protocol or it has a single setting)."""
    if protocol_params(suite, family, entry) is not None:
        return []
    grid = entry_grid(entry)
    if len(grid) <= 1:
        return []
    return [
        s
        for setting in grid
        for s in _specs(
            family, entry, setting, suite.tuning_level, suite.tuning_layouts, suite.tuning_seeds
        )
    ]


def _specs(
    family: Family,
    entry: Entry,
    params: Mapping[str, Any],
    level: str,
    layouts: Sequence[int],
    seeds: Sequence[int],
) -> list[PlanSpec]:
    specs = build_plan_specs(
        [family.problem],
        planners=[entry.planner],
        seeds=seeds,
        simulations=family.simulations,
        grid="default",
        env_kwargs={"difficulty": level},
        fixed=dict(params),
        layout_seeds=layouts,
    )
    return [replace(s, variant=entry.variant) for s in specs] if entry.variant else specs


def choose_settings(
    suite: Suite, entries: Sequence[Entry], rows: Iterable[Row]
) -> dict[tuple[str, str], Choice]:
    """Each (family, entry)'s :class:`Choice`, from the protocol or the finished tuning
    ``rows`` (see the module)."""
    from voot.bench.protocol.tuning import tuning_note, tuning_selections

    done = {r["run_id"]: r for r in rows if r.get("status") == "ok"}
    out: dict[tuple[str, str], Choice] = {}
    for family in suite.families:
        for entry in entries:
            key = (family.problem, entry.name)
            reused = protocol_params(suite, family, entry)
            if reused is not None:
                out[key] = Choice(family.problem, entry.name, reused[0], "protocol", reused[1])
                continue
            tuning = tuning_specs(suite, family, entry)
            if not tuning:
                (only,) = entry_grid(entry)
                out[key] = Choice(family.problem, entry.name, only, "single", "one setting")
                continue
            note = (
                f"tuned here: {len(entry_grid(entry))} settings, "
                + tuning_note(suite.tuning_seeds, suite.tuning_layouts)
                + f", level {suite.tuning_level}"
            )
            if any(s.run_id not in done for s in tuning):
                out[key] = Choice(family.problem, entry.name, None, "tuned", note)
                continue
            (sel,) = tuning_selections(tuning, done.values())
            out[key] = Choice(family.problem, entry.name, dict(sel.params), "tuned", note)
    return out


def evaluation_specs(
    suite: Suite,
    family: Family,
    entry: Entry,
    params: Mapping[str, Any],
    levels: Sequence[str] | None = None,
) -> list[PlanSpec]:
    """The evaluation runs of ``entry`` with ``params`` on ``family``: every level (or
    ``levels``) x held-out layout x seed."""
    return [
        s
        for level in (levels or suite.levels)
        for s in _specs(family, entry, params, level, suite.heldout_layouts, suite.seeds)
    ]


def stand_in_specs(suite: Suite, family: Family, entry: Entry) -> list[PlanSpec]:
    """The evaluation runs with the grid's first setting: stand-ins of a pair whose
    selection is not known yet (same count, same budget: for the estimate)."""
    return evaluation_specs(suite, family, entry, entry_grid(entry)[0])


def all_specs(
    suite: Suite, entries: Sequence[Entry], rows: Iterable[Row]
) -> tuple[list[PlanSpec], list[PlanSpec], dict[tuple[str, str], Choice]]:
    """``(tuning specs, evaluation specs, choices)`` of the suite for ``entries``; the
    evaluation of a pair still tuning is its stand-ins (:func:`stand_in_specs`)."""
    rows = list(rows)
    choices = choose_settings(suite, entries, rows)
    tuning: list[PlanSpec] = []
    evaluation: list[PlanSpec] = []
    for family in suite.families:
        for entry in entries:
            tuning += tuning_specs(suite, family, entry)
            params = choices[(family.problem, entry.name)].params
            evaluation += (
                stand_in_specs(suite, family, entry)
                if params is None
                else evaluation_specs(suite, family, entry, params)
            )
    return tuning, evaluation, choices


# ----- the cost ------------------------------------------------------------------------------
def pair_key(row_or_spec: Any) -> tuple[str, str]:
    cfg = row_or_spec["config"] if isinstance(row_or_spec, dict) else row_or_spec.config()
    from voot.bench.protocol.select import planner_label

    return (
        canonical_problem(str(cfg["problem"])),
        planner_label(str(cfg["planner"]), cfg.get("variant")),
    )


def run_cpu_seconds(row: Row) -> float | None:
    """A run's CPU seconds of search: the last of its ``cpu_elapsed`` curve (exact in a
    compact store), else its ``search_time`` (wall seconds of a one-thread search, an
    older row's only timing); None without either."""
    cpu = row.get("cpu_elapsed")
    if cpu is not None and len(cpu) > 0:
        return float(cpu[-1])
    t = row.get("search_time")
    return float(t) if isinstance(t, int | float) else None


def measured_cost(rows: Sequence[Row], budget: int) -> tuple[float, int] | None:
    """``(CPU seconds per simulation, rows used)`` over ``rows``, rows of ``budget``
    simulations preferred (a simulation gets dearer as a tree grows)."""
    ok = [r for r in rows if run_cpu_seconds(r) is not None]
    same = [r for r in ok if int(r["config"]["simulations"]) == budget]
    use = same or ok
    sims = sum(int(r["config"]["simulations"]) for r in use)
    if not use or sims <= 0:
        return None
    return math.fsum(run_cpu_seconds(r) or 0.0 for r in use) / sims, len(use)


def reference_rows(data: Path = REFERENCE_DATA) -> list[Row]:
    """The committed held-out protocol's finished plan rows (reference costs)."""
    out: list[Row] = []
    for name in ("heldout-kitchen-v2", "heldout-conveyor-v2", "ladder-kitchen-v2"):
        path = data / name
        if path.is_dir():
            out += ResultStore(path, create=False).load(kind="plan", status="ok")
    return out


def estimate_suite(
    specs: Sequence[PlanSpec],
    rows: Sequence[Row],
    pending_ids: Iterable[str],
    *,
    reference: Sequence[Row] = (),
    probe_simulations: int = 20,
    run: Any = None,
) -> list[CostLine]:
    """One :class:`~voot.bench.protocol.estimate.CostLine` per (family, entry) of
    ``specs`` (see the module): its ``problem`` the family, its ``planner`` the entry."""
    from voot.bench.protocol.estimate import probe_cost

    pending = set(pending_ids)
    groups: dict[tuple[str, str], list[PlanSpec]] = {}
    for s in dict.fromkeys(specs):
        groups.setdefault(pair_key(s), []).append(s)
    by_pair: dict[tuple[str, str], list[Row]] = {}
    for r in rows:
        if r.get("status") == "ok" and r.get("kind") == "plan":
            by_pair.setdefault(pair_key(r), []).append(r)
    ref_pair: dict[tuple[str, str], list[Row]] = {}
    for r in reference:
        ref_pair.setdefault(pair_key(r), []).append(r)
    out = []
    for pair, group in groups.items():
        budget = max(s.simulations for s in group)
        got = measured_cost(by_pair.get(pair, []), budget)
        source = f"store: {got[1]} rows" if got else ""
        if got is None:
            got = measured_cost(ref_pair.get(pair, []), budget)
            source = f"committed stores: {got[1]} rows" if got else ""
        if got is None:
            probe = next((s for s in group if s.run_id in pending), group[0])
            cost = probe_cost(probe, min(probe_simulations, budget), run)
            source = f"probe: {probe_simulations} simulations"
        else:
            cost = got[0]
        todo = [s for s in group if s.run_id in pending]
        out.append(
            CostLine(
                pair[0],
                pair[1],
                len(group),
                len(todo),
                sum(s.simulations for s in todo),
                cost,
                source,
            )
        )
    return out


def format_costs(costs: Sequence[CostLine], workers: int) -> str:
    """The estimate as a markdown table, its total, and the wall-hours on ``workers``."""
    lines = cost_table(costs, ("family", "entry"), short_name)
    total = math.fsum(c.cpu_hours for c in costs)
    runs = sum(c.pending for c in costs)
    lines += [
        "",
        f"total: {runs} runs to run, {total:.3g} CPU-hours of search; about"
        f" {total / max(1, workers):.3g} wall-hours on {workers} worker"
        f"{'s' if workers != 1 else ''} (perfect packing; making each layout's env adds"
        " to it). Cost per simulation: the store's rows, else the committed stores' rows of"
        " the same env and planner, else a short probe (underestimates long runs).",
    ]
    return "\n".join(lines)


def short_name(problem: str) -> str:
    """``voot/GeneratedKitchen-v0`` -> ``GeneratedKitchen``."""
    return problem.split("/")[-1].rsplit("-v", 1)[0]


def pending_of(specs: Sequence[PlanSpec], store: ResultStore | None) -> list[PlanSpec]:
    """The specs not finished in ``store`` (all of them without a store)."""
    from voot.bench.sweep.engine import pending_specs

    return list(specs) if store is None else list(pending_specs(specs, store))


def run_suite(
    suite: Suite,
    entries: Sequence[Entry],
    store: ResultStore,
    run_specs: Any,
) -> int:
    """Run the suite for ``entries`` into ``store``: per family its tuning runs, then per
    level its evaluation runs (``run_specs(specs)`` runs a batch and returns its number
    of failed runs). Returns the number of failed runs."""
    failed = 0
    for family in suite.families:
        tuning = [s for e in entries for s in tuning_specs(suite, family, e)]
        if tuning:
            failed += run_specs(tuning)
        choices = choose_settings(suite, entries, store.load(kind="plan", status="ok"))
        for level in suite.levels:
            batch = []
            for entry in entries:
                params = choices[(family.problem, entry.name)].params
                if params is not None:
                    batch += evaluation_specs(suite, family, entry, params, [level])
            if batch:
                failed += run_specs(batch)
    return failed
