r"""Per-run scores of a leaderboard store, at the suite's budget, at matched simulator
calls and at matched CPU time.

**The score** is the fraction of the task's objects handled by the best plan found,
:math:`1 - \text{objects left} / \text{objects at the start}`, in :math:`[0, 1]` on every
family and level: a bounded, comparable scale, so it aggregates across families and
levels without a normalisation chosen after the fact (returns differ in scale between
the kitchens and the storage rooms). The best return (goal bonus excluded) is reported
beside it per (family, level), where its scale is one.

**Matched budgets.** Planners spend their simulations differently: a shooting planner's
simulation is a whole rollout (up to its horizon of simulator steps), a tree
simulation one new step plus pre-checks. Each run records, after every simulation, its
cumulative simulator calls (``calls_curve``: steps plus pre-checks, counted by voot
around the problem) and CPU seconds (``cpu_elapsed``). Per (family, level) cell the
matched point is the **smallest, over the entries, of an entry's median final count**
(:func:`matched_points`): what the most frugal entry typically spends on its whole
budget. Each run's score there is the score of the best plan it had found by then (the
last simulation whose count is at most the point; :func:`value_at`); a run that spent
its whole budget below the point is read at its end (it could do no more within the
suite's budget), and a run that had finished no simulation by then handled nothing
(score 0, return 0: the empty plan's). In a compact store the cost curves are kept at about
100 log-spaced simulations and interpolated between (their final values are exact), so a
matched point falls within one kept interval of where the full curve would put it.

**Which runs.** Only the evaluation runs the suite lists for each entry's chosen setting
(:func:`voot.bench.leaderboard.plan.evaluation_specs`), matched by run id: tuning runs and
runs of other settings never enter a score. A cell is **complete** when every entry has
every listed run of it (:func:`coverage`); only complete cells are scored.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.bench.leaderboard.suite import Entry, Suite
from voot.bench.store.format import Row

F64 = NDArray[np.float64]
#: A (family, level) cell.
Cell = tuple[str, str]


class Budget(StrEnum):
    """Where a run's score is read."""

    #: At the suite's budget of simulations (the run's end).
    SIMULATIONS = "simulations"
    #: At the cell's matched simulator calls.
    CALLS = "calls"
    #: At the cell's matched CPU seconds.
    CPU = "cpu"


#: The row curve each matched budget is read on.
CURVES: Mapping[Budget, str] = {Budget.CALLS: "calls_curve", Budget.CPU: "cpu_elapsed"}


@dataclass(frozen=True)
class RunScore:
    """One evaluation run's scores: ``handled[b]`` (fraction of objects handled) and
    ``ret[b]`` (best return) at each :class:`Budget`."""

    entry: str
    cell: Cell
    layout: int
    seed: int
    handled: Mapping[Budget, float]
    ret: Mapping[Budget, float]


def value_at(cost: F64, x: float) -> int:
    """The index of the last simulation whose cumulative ``cost`` is at most ``x`` (-1:
    none)."""
    return int(np.searchsorted(np.asarray(cost, dtype=np.float64), x, side="right")) - 1


def _handled(row: Row, i: int) -> float:
    """The fraction of objects handled at simulation ``i`` (-1: none yet)."""
    start = float(row.get("objects_initial") or 0.0)
    if start <= 0:
        raise ValueError(
            f"run {row.get('run_id')}: no objects_initial, so no fraction handled (a leaderboard"
            " family's env reports objects_left in its step info)"
        )
    if i < 0:
        return 0.0
    left = float(np.asarray(row["objects_left"], dtype=np.float64)[i])
    if np.isnan(left):
        return 0.0
    return float(np.clip(1.0 - left / start, 0.0, 1.0))


def _return(row: Row, i: int) -> float:
    return 0.0 if i < 0 else float(np.asarray(row["best_so_far"], dtype=np.float64)[i])


def listed_runs(
    suite: Suite, entries: Sequence[Entry], rows: Sequence[Row]
) -> dict[str, tuple[str, Cell]]:
    """run id -> (entry, cell) of every evaluation run the suite lists for the entries'
    chosen settings (pairs still tuning list none)."""
    from voot.bench.leaderboard.plan import choose_settings, evaluation_specs

    choices = choose_settings(suite, entries, rows)
    out: dict[str, tuple[str, Cell]] = {}
    for family in suite.families:
        for entry in entries:
            params = choices[(family.problem, entry.name)].params
            if params is None:
                continue
            for s in evaluation_specs(suite, family, entry, params):
                out[s.run_id] = (entry.name, (family.problem, str(s.env_kwargs_dict["difficulty"])))
    return out


@dataclass(frozen=True)
class Coverage:
    """What a store holds of the suite: finished evaluation runs per (cell, entry), the
    runs listed per (cell, entry), and the complete cells (every entry finished)."""

    done: Mapping[tuple[Cell, str], int]
    listed: Mapping[tuple[Cell, str], int]
    cells: tuple[Cell, ...]
    entries: tuple[str, ...]

    @property
    def complete(self) -> tuple[Cell, ...]:
        return tuple(
            c
            for c in self.cells
            if all(
                self.listed.get((c, e), 0) > 0 and self.done.get((c, e), 0) == self.listed[(c, e)]
                for e in self.entries
            )
        )

    @property
    def finished_runs(self) -> int:
        return sum(self.done.values())


def coverage(suite: Suite, entries: Sequence[Entry], rows: Sequence[Row]) -> Coverage:
    """The :class:`Coverage` of ``rows`` (a pair still tuning lists its runs as the
    suite's count of them, none finished)."""
    listed_ids = listed_runs(suite, entries, rows)
    ok = {r["run_id"] for r in rows if r.get("status") == "ok"}
    cells = tuple((f.problem, lv) for f in suite.families for lv in suite.levels)
    per_cell = len(suite.heldout_layouts) * len(suite.seeds)
    listed = {(c, e.name): per_cell for c in cells for e in entries}
    done: dict[tuple[Cell, str], int] = {}
    for rid, (entry, cell) in listed_ids.items():
        if rid in ok:
            done[(cell, entry)] = done.get((cell, entry), 0) + 1
    return Coverage(done, listed, cells, tuple(e.name for e in entries))


def matched_points(rows: Iterable[tuple[str, Row]]) -> dict[Budget, float]:
    """The matched calls and CPU seconds of a cell's ``(entry, row)`` pairs: the smallest
    over the entries of the median final value of each cost curve."""
    finals: dict[Budget, dict[str, list[float]]] = {b: {} for b in CURVES}
    for entry, r in rows:
        for b, key in CURVES.items():
            finals[b].setdefault(entry, []).append(float(np.asarray(r[key], dtype=np.float64)[-1]))
    if not finals[Budget.CALLS]:
        raise ValueError("no runs to match budgets over")
    return {b: float(min(np.median(v) for v in per.values())) for b, per in finals.items()}


def run_scores(
    suite: Suite, entries: Sequence[Entry], rows: Sequence[Row], cells: Sequence[Cell]
) -> tuple[list[RunScore], dict[Cell, dict[Budget, float]]]:
    """Every listed evaluation run's :class:`RunScore` in ``cells``, and each cell's
    matched points."""
    listed = listed_runs(suite, entries, rows)
    mine: dict[Cell, list[tuple[str, Row]]] = {c: [] for c in cells}
    for r in rows:
        hit = listed.get(r["run_id"])
        if hit is not None and r.get("status") == "ok" and hit[1] in mine:
            mine[hit[1]].append((hit[0], r))
    scores: list[RunScore] = []
    points: dict[Cell, dict[Budget, float]] = {}
    for cell in cells:
        pts = matched_points(mine[cell])
        points[cell] = pts
        for entry, r in mine[cell]:
            idx = {Budget.SIMULATIONS: len(r["best_so_far"]) - 1}
            for b, key in CURVES.items():
                idx[b] = value_at(np.asarray(r[key], dtype=np.float64), pts[b])
            cfg: Mapping[str, Any] = r["config"]
            scores.append(
                RunScore(
                    entry,
                    cell,
                    int(cfg["env_kwargs"]["layout_seed"]),
                    int(cfg["seed"]),
                    {b: _handled(r, i) for b, i in idx.items()},
                    {b: _return(r, i) for b, i in idx.items()},
                )
            )
    return scores, points


def score_matrix(
    scores: Sequence[RunScore],
    entry: str,
    cells: Sequence[Cell],
    budget: Budget,
    what: str = "handled",
) -> F64:
    """An entry's ``(runs, tasks)`` array over ``cells`` (runs ordered by layout and seed),
    for :mod:`voot.bench.report.stats`; every cell must hold as many runs of it."""
    columns = []
    for cell in cells:
        mine = sorted(
            (s for s in scores if s.entry == entry and s.cell == cell),
            key=lambda s: (s.layout, s.seed),
        )
        columns.append([getattr(s, what)[budget] for s in mine])
    lengths = {len(c) for c in columns}
    if len(lengths) != 1 or 0 in lengths:
        raise ValueError(f"{entry}: unequal or empty runs per cell {sorted(lengths)}")
    return np.asarray(columns, dtype=np.float64).T
