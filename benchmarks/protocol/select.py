"""Per-optimiser hyperparameter selection, as in the paper.

The paper tuned every optimiser on every problem: for each (function, dim) and each
method, run every setting of the method's grid on all seeds and keep the setting with the
**best mean final value** (the mean over seeds of the best value after the whole budget;
the functions are maximised, so higher is better). Figure 3 then draws each method with
its selected setting.

Ties (equal means) go to the setting whose label sorts first, so the choice is
deterministic. Only rows with status ``"ok"`` count; runs of different budgets are kept
apart (the budget is part of the cell).

Rows of different test-function instances (``config["instance"]``, see
:mod:`voot.bench.sweep.bbfo`) are never mixed: :func:`one_instance` keeps the rows of one
instance, and :func:`select_hyperparameters` refuses rows of several.

The same rule selects the planners' settings of the planning sweep (rows of kind
``"plan"``): there a cell is (problem, dim, simulations, planner) and the final value is
the best return after the last simulation (:func:`cell_of` maps both kinds of row).
Runs on the layouts of a generated family (:mod:`voot.bench.protocol.layouts`) share their
family's cell: the mean final return of a setting is pooled over its layouts and seeds.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from voot.bench.protocol.layouts import family_kwargs
from voot.bench.protocol.problems import CHAINS, aliases, problem_label
from voot.bench.store.format import Row
from voot.bench.sweep.bbfo import PAPER_FUNCTIONS, PAPER_METHODS, instance_of
from voot.bench.sweep.engine import params_key
from voot.bench.sweep.planners import PLAN_PLANNERS

#: (function, dim, budget, method); for plan rows (problem, dim or 0, simulations, planner)
CellKey = tuple[str, int, int, str]

#: Problems of the planning sweep in plotting order (the robot domains, then the chains).
PLAN_PROBLEMS: tuple[str, ...] = (*aliases(), *CHAINS)


def planner_label(planner: str, variant: str | None = None) -> str:
    """A plan row's planner as cells name it: ``voot``, or ``voot[variant]`` for a run of
    an ablation variant (:mod:`voot.bench.protocol.ablation`)."""
    return f"{planner}[{variant}]" if variant else planner


def cell_of(row: Row) -> CellKey:
    """The cell of a row: ``(function, dim, budget, method)`` of a bbfo row, or
    ``(problem label, dim or 0, simulations, planner)`` of a plan row (the planner with
    its ablation variant, :func:`planner_label`). The label is the problem's *family*:
    its env keywords except ``layout_seed`` (:mod:`voot.bench.protocol.layouts`), so the runs of
    every layout of a generated family share one cell."""
    cfg = row["config"]
    if row.get("kind") == "plan":
        label = problem_label(str(cfg["problem"]), family_kwargs(cfg.get("env_kwargs")))
        planner = planner_label(str(cfg["planner"]), cfg.get("variant"))
        return (label, int(cfg.get("dim") or 0), int(cfg["simulations"]), planner)
    return (str(cfg["function"]), int(cfg["dim"]), int(cfg["budget"]), str(cfg["method"]))


def one_instance(rows: Iterable[Row], instance: int | None = None) -> tuple[int, list[Row]]:
    """The rows of one test-function instance, and that instance.

    Args:
        rows: result rows (plan rows, which have no instance, count as instance 0).
        instance: the instance to keep; ``None`` keeps the only one present.

    Raises:
        ValueError: ``instance`` is None and the rows hold several instances (the message
            lists them), or no row is of ``instance``.
    """
    rows = list(rows)
    present = sorted({instance_of(r["config"]) for r in rows})
    if instance is None:
        if len(present) > 1:
            raise ValueError(
                f"the runs are of several test-function instances ({', '.join(map(str, present))});"
                " they are different problems and are never mixed: choose one with --instance K"
                " (instance= in Python; 0 = the paper's functions)"
            )
        return (present[0] if present else 0), rows
    kept = [r for r in rows if instance_of(r["config"]) == instance]
    if rows and not kept:
        raise ValueError(
            f"no runs of instance {instance}; the runs are of instance(s)"
            f" {', '.join(map(str, present))}"
        )
    return instance, kept


@dataclass(frozen=True)
class Candidate:
    """One hyperparameter setting of a method in a cell, summarised over seeds."""

    params: dict[str, Any]
    label: str
    finals: tuple[float, ...]

    @property
    def n(self) -> int:
        return len(self.finals)

    @property
    def mean(self) -> float:
        return float(np.mean(self.finals))


@dataclass(frozen=True)
class Selection:
    """The selected setting of ``method`` on ``function``-``dim`` at ``budget``.

    ``candidates`` are all settings tried, best mean first; ``candidates[0]`` is the
    selected one.
    """

    function: str
    dim: int
    budget: int
    method: str
    candidates: tuple[Candidate, ...]

    @property
    def best(self) -> Candidate:
        return self.candidates[0]

    @property
    def params(self) -> dict[str, Any]:
        return self.best.params

    @property
    def key(self) -> CellKey:
        return (self.function, self.dim, self.budget, self.method)


def _order(names: Iterable[str], preferred: Sequence[str]) -> list[str]:
    rank = {n: i for i, n in enumerate(preferred)}
    return sorted(set(names), key=lambda n: (rank.get(n, len(rank)), n))


def function_order(names: Iterable[str]) -> list[str]:
    """The paper's functions first (Griewank, Rastrigin, Shekel), then the planning
    problems (kitchen, conveyor, chains), then the rest by name."""
    return _order(names, (*PAPER_FUNCTIONS, *PLAN_PROBLEMS))


def method_order(names: Iterable[str]) -> list[str]:
    """Methods in the paper's order (VOO first), then the planners (VOOT first), then
    the rest by name."""
    return _order(names, (*PAPER_METHODS, *PLAN_PLANNERS))


def final_value(row: Row) -> float:
    """The best value after the last evaluation of a row."""
    best = row["best_so_far"]
    if len(best) == 0:
        raise ValueError(f"row {row.get('run_id')} has an empty best_so_far")
    return float(best[-1])


def select_hyperparameters(rows: Iterable[Row]) -> list[Selection]:
    """Select each method's setting per (function, dim, budget): best mean final value.

    Returns the selections sorted by function (paper order), dim, budget and method.

    Raises:
        ValueError: the rows are of several test-function instances (filter them with
            :func:`one_instance` first).
    """
    groups: dict[CellKey, dict[str, tuple[dict[str, Any], list[float]]]] = {}
    ok = [row for row in rows if row.get("status") == "ok"]
    one_instance(ok)  # raises on a mix
    for row in ok:
        key = cell_of(row)
        params = dict(row["config"].get("params") or {})
        label = params_key(params)
        entry = groups.setdefault(key, {}).setdefault(label, (params, []))
        entry[1].append(final_value(row))
    selections = []
    for key, settings in groups.items():
        cands = [Candidate(p, label, tuple(f)) for label, (p, f) in settings.items()]
        cands.sort(key=lambda c: (-c.mean, c.label))
        selections.append(Selection(*key, candidates=tuple(cands)))
    f_rank = {f: i for i, f in enumerate(function_order(s.function for s in selections))}
    m_rank = {m: i for i, m in enumerate(method_order(s.method for s in selections))}
    selections.sort(key=lambda s: (f_rank[s.function], s.dim, s.budget, m_rank[s.method]))
    return selections


def largest_budget(rows: Iterable[Row]) -> list[Row]:
    """Keep, per (function, dim), only the rows of the largest budget present.

    A store can hold a quick scaled-down sweep beside the full one; plots and tables
    compare methods at one budget per cell.
    """
    rows = list(rows)
    top: dict[tuple[str, int], int] = {}
    cells = [cell_of(r) for r in rows]
    for function, dim, budget, _ in cells:
        top[(function, dim)] = max(top.get((function, dim), 0), budget)
    return [r for r, c in zip(rows, cells, strict=True) if c[2] == top[(c[0], c[1])]]


def selected_rows(rows: Iterable[Row], selections: Iterable[Selection]) -> list[Row]:
    """The ``"ok"`` rows that belong to a selected setting."""
    chosen = {s.key: s.best.label for s in selections}
    out = []
    for r in rows:
        if r.get("status") != "ok":
            continue
        if chosen.get(cell_of(r)) == params_key(r["config"].get("params") or {}):
            out.append(r)
    return out


def selection_table(
    selections: Sequence[Selection], *, all_candidates: bool = False, kind: str = "bbfo"
) -> str:
    """A markdown table of the selected settings (mean final value, seeds, runner-up).

    With ``all_candidates`` every setting gets a row (selected ones marked ``*``).
    ``kind="plan"`` names the columns for planners (problem, simulations, planner, mean
    final return); a dim of 0 (an environment) is left blank.
    """
    if kind == "plan":
        head = "| problem | dim | simulations | planner | selected | mean final return |"
    else:
        head = "| function | dim | budget | method | selected | mean final |"
    lines = [
        f"{head} seeds | settings tried |",
        "| --- | ---: | ---: | --- | --- | ---: | ---: | ---: |",
    ]
    for s in selections:
        cands = s.candidates if all_candidates else s.candidates[:1]
        dim = "" if kind == "plan" and s.dim == 0 else str(s.dim)
        for i, c in enumerate(cands):
            mark = "*" if all_candidates and i == 0 else ""
            lines.append(
                f"| {s.function} | {dim} | {s.budget} | {s.method} | {c.label}{mark} |"
                f" {c.mean:.6g} | {c.n} | {len(s.candidates)} |"
            )
    return "\n".join(lines)
