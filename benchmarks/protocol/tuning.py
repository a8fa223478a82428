"""Tuning separate from evaluation: select settings on tuning seeds, report other seeds.

The paper picked every planner's hyperparameters by best mean final value on the very
seeds it reported, which flatters every planner by the luck of its selection. The full
protocol selects instead on **tuning seeds** (e.g. 1000-1004) disjoint from
the **evaluation seeds** (e.g. 0-19) and reports only the evaluation seeds:

1. every setting of every planner's grid runs on the tuning seeds;
2. per (problem, planner) the setting with the best mean final return on the tuning
   seeds is selected, by the paper's rule (:func:`voot.bench.protocol.select.select_hyperparameters`);
3. only that setting runs on the evaluation seeds.

The rows are the ordinary rows of :mod:`voot.bench.sweep.plan` (a tuned run has the run
id it would have if run by hand), so the protocol resumes at any point: finished tuning
runs are skipped, the selection is recomputed from them (it is deterministic), and the
evaluation runs already in the store are skipped. ``voot-bench plot --tuning-seeds`` and
``voot-bench claims --tuning-seeds`` repeat steps 2 and 3 on a store's rows
(:func:`select_on_tuning`).

On a generated family the phases differ by **layout** instead (:mod:`voot.bench.protocol.layouts`):
tuning on the tuning seeds x the training layouts, evaluation on the evaluation seeds x
the held-out layouts (``--tuning-layouts``, ``--heldout``); the selection pools every
training layout of the family. A row is then a tuning row if its layout is a tuning
layout (and its seed a tuning seed, when those are given), an evaluation row if its
layout is not (:func:`split_rows`).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from voot.bench.protocol.layouts import TuningLayoutsArg as TuningLayouts
from voot.bench.protocol.layouts import layout_of, layouts_text
from voot.bench.protocol.select import (
    CellKey,
    Selection,
    cell_of,
    select_hyperparameters,
    selected_rows,
)
from voot.bench.store.format import Row
from voot.bench.sweep.engine import params_key


def seeds_text(seeds: Iterable[int]) -> str:
    """Seeds as ranges: ``[1000, 1001, 1002, 7]`` -> ``"7, 1000-1002"``."""
    return layouts_text(seeds)


def tuning_note(tuning_seeds: Iterable[int], tuning_layouts: Iterable[int] = ()) -> str:
    """The sentence the captions carry when settings were selected on tuning seeds (and,
    on a generated family, on training layouts disjoint from the reported ones)."""
    layouts = sorted(set(int(v) for v in tuning_layouts))
    if layouts:
        seeds = sorted(set(int(s) for s in tuning_seeds))
        on_seeds = f" (seeds {seeds_text(seeds)})" if seeds else ""
        return (
            f"settings selected on training layouts {layouts_text(layouts)}{on_seeds},"
            " disjoint from the held-out layouts reported"
        )
    return (
        f"settings selected on tuning seeds {seeds_text(tuning_seeds)}, disjoint from the"
        " evaluation seeds"
    )


def tuning_sentence(tuning_seeds: Iterable[int], tuning_layouts: Iterable[int] = ()) -> str:
    """:func:`tuning_note` as a sentence (capital letter, full stop)."""
    note = tuning_note(tuning_seeds, tuning_layouts)
    return note[:1].upper() + note[1:] + "."


def check_tuning_split(rows: Iterable[Row], tuning_seeds: Iterable[int]) -> None:
    """Raise ValueError unless ``rows`` hold runs of both a tuning seed and another seed.

    Reading a store with tuning seeds (``plot``/``claims --tuning-seeds``) selects on
    the rows of ``tuning_seeds`` and reports every other seed. Without a tuning row the
    selection would have nothing to select on (and the caption would claim a tuning
    that did not happen); without an evaluation row every reported number would come
    from the seeds the settings were selected on: tuning on the test set. The error
    names the seeds the store has.
    """
    tuning = set(int(s) for s in tuning_seeds)
    present = {int(r["config"]["seed"]) for r in rows}
    if not present & tuning:
        raise ValueError(
            f"no runs of the tuning seeds {seeds_text(tuning)} in the store (its seeds:"
            f" {seeds_text(present) or 'none'}): there is nothing to select the settings on"
        )
    if not present - tuning:
        raise ValueError(
            f"every seed of the store ({seeds_text(present)}) is a tuning seed: no"
            " evaluation seeds are left, and reporting the seeds the settings were"
            " selected on would be tuning on the test set"
        )


def check_layout_split(rows: Iterable[Row], tuning_layouts: TuningLayouts) -> None:
    """Raise ValueError unless ``rows`` hold runs of both a tuning layout and another
    layout: :func:`check_tuning_split` for the held-out protocol's layouts.

    ``tuning_layouts`` is one collection for every problem, or per problem (``--heldout``:
    each family's training layouts), checked on the rows of that problem. Without a run on
    a tuning layout there is nothing to select on; without a run on another layout every
    number reported would come from the layouts the settings were selected on. The error
    names the layouts the store has.
    """
    rows = list(rows)
    if isinstance(tuning_layouts, Mapping):
        for problem, layouts in tuning_layouts.items():
            mine = [r for r in rows if str(r["config"].get("problem")) == problem]
            _check_layouts(mine, layouts, f" of {problem}")
        return
    _check_layouts(rows, tuning_layouts, "")


def _check_layouts(rows: Sequence[Row], tuning_layouts: Iterable[int], where: str) -> None:
    tuning = {int(v) for v in tuning_layouts}
    present = {v for v in (layout_of(r["config"]) for r in rows) if v is not None}
    if not present & tuning:
        raise ValueError(
            f"no runs on the tuning layouts {layouts_text(tuning)}{where} in the store (its"
            f" layouts: {layouts_text(present) if present else 'none'}): there is nothing to"
            " select the settings on"
        )
    if not present - tuning:
        raise ValueError(
            f"every layout{where} of the store ({layouts_text(present)}) is a tuning layout:"
            " no held-out layouts are left, and reporting the layouts the settings were"
            " selected on would be tuning on the test set"
        )


def _layouts_of_problem(tuning_layouts: TuningLayouts | None, problem: str) -> set[int] | None:
    """The tuning layouts that apply to ``problem`` (None: no layout split)."""
    if tuning_layouts is None:
        return None
    if isinstance(tuning_layouts, Mapping):
        chosen = tuning_layouts.get(problem)
        return None if chosen is None else set(int(v) for v in chosen)
    return set(int(v) for v in tuning_layouts)


def split_rows(
    rows: Iterable[Row],
    tuning_seeds: Collection[int] | None,
    tuning_layouts: TuningLayouts | None = None,
) -> tuple[list[Row], list[Row]]:
    """``(tuning rows, evaluation rows)``.

    Without tuning layouts (or for a row without a layout): rows of a tuning seed, and all
    the others. A row with a layout, given tuning layouts (one collection, or per problem
    id): a tuning row if its layout is a tuning layout and (when ``tuning_seeds`` are
    given) its seed a tuning seed; an evaluation row if its layout is not a tuning layout
    (any seed: another layout is another problem); neither otherwise (a training layout
    on a seed that is not tuned).
    """
    tuning: list[Row] = []
    evaluation: list[Row] = []
    seeds = None if tuning_seeds is None else set(int(s) for s in tuning_seeds)
    for r in rows:
        cfg = r["config"]
        layout = layout_of(cfg)
        train = _layouts_of_problem(tuning_layouts, str(cfg.get("problem")))
        seed_tuned = seeds is not None and int(cfg["seed"]) in seeds
        if layout is None or train is None:
            (tuning if seed_tuned else evaluation).append(r)
        elif layout not in train:
            evaluation.append(r)
        elif seeds is None or seed_tuned:
            tuning.append(r)
    return tuning, evaluation


@dataclass(frozen=True)
class TunedRows:
    """The outcome of :func:`select_on_tuning`.

    Attributes:
        selections: per cell, the setting selected on the tuning seeds.
        rows: the evaluation rows of the selected settings.
        untuned: cells with evaluation rows of several settings but no finished tuning
            row (left out); a cell whose evaluation rows all share one setting (a planner
            without a grid, such as the RL baselines) needs no tuning and is kept.
    """

    selections: tuple[Selection, ...]
    rows: tuple[Row, ...]
    untuned: tuple[CellKey, ...]


def select_on_tuning(
    rows: Iterable[Row],
    tuning_seeds: Collection[int] | None,
    tuning_layouts: TuningLayouts | None = None,
) -> TunedRows:
    """Select each cell's setting on the tuning rows; keep the evaluation rows of that
    setting (:func:`split_rows`: every other seed, or every layout that is not a tuning
    layout).

    ``rows`` should already be of one budget per problem
    (:func:`voot.bench.protocol.select.largest_budget`), so tuning and evaluation share the cell.
    """
    ok = [r for r in rows if r.get("status") == "ok"]
    tuning, evaluation = split_rows(ok, tuning_seeds, tuning_layouts)
    selections = select_hyperparameters(tuning)
    selected = {s.key for s in selections}
    missing = {cell_of(r) for r in evaluation} - selected
    # a planner without a grid (e.g. the RL baselines, uniform random shooting) has nothing
    # to select: its evaluation rows at its default setting are kept without tuning rows
    single = {
        cell_of(r)
        for r in evaluation
        if cell_of(r) in missing and _has_no_grid(r) and not r["config"].get("params")
    }
    fixed = [r for r in evaluation if cell_of(r) in single and not r["config"].get("params")]
    # their one setting, as a selection of one candidate (so tables and figures list them)
    selections = [*selections, *select_hyperparameters(fixed)]
    kept = selected_rows(evaluation, selections)
    return TunedRows(tuple(selections), tuple(kept), tuple(sorted(missing - single)))


def _has_no_grid(row: Row) -> bool:
    """Whether the row's planner has a single setting in every grid (nothing to tune)."""
    from voot.bench.protocol.problems import family
    from voot.bench.sweep.planners import planner_grid

    cfg = row["config"]
    try:
        return planner_grid(str(cfg["planner"]), family(str(cfg["problem"]))) == [{}]
    except ValueError:
        return False


def selected_specs(candidates: Sequence[Any], selections: Iterable[Selection]) -> list[Any]:
    """The specs of ``candidates`` (plan specs, e.g. every setting on the evaluation seeds)
    whose setting is the one selected in their cell; cells without a selection give none."""
    chosen = {s.key: s.best.label for s in selections}
    out = []
    for spec in candidates:
        cell = cell_of({"kind": spec.kind, "config": spec.config()})
        if chosen.get(cell) == params_key(spec.params_dict):
            out.append(spec)
    return out


def tuning_selections(specs: Sequence[Any], rows: Iterable[Row]) -> list[Selection]:
    """The selections made on the finished rows of the tuning ``specs`` (by run id)."""
    ids = {s.run_id for s in specs}
    mine = [r for r in rows if r.get("run_id") in ids and r.get("status") == "ok"]
    return select_hyperparameters(mine)
