"""The ablation's tables, drawn from its store (:mod:`voot.bench.protocol.ablation`); runs nothing.

Two tables, both with the settings selected on the tuning seeds (the protocol):

* **claims per switch**: for every switch (and the v1 defaults), VOOT's and PW-UCT's
  metric at each of the paper's checkpoints that concern them
  (:data:`voot.bench.protocol.claims.PAPER_CLAIMS`), with its 95% interval and verdict, and
  whether the verdict differs from the v1 defaults' (*flips*);
* **the ranking per switch**: VOOT against PW-UCT, each with the switch where it applies
  (the v1 default otherwise), as the paired difference over the common evaluation seeds
  of the objects handled (kitchen) or the return (conveyor) at the paper's checkpoints,
  with a 95% t-interval: *VOOT ahead* when the whole interval is above 0, *PW-UCT ahead*
  when below, *tied* otherwise. The paper's ranking returns where VOOT is ahead.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from voot.bench.protocol.ablation import ABLATION_PLANNERS, BASELINE, SWITCHES
from voot.bench.protocol.claims import NO_DATA, PAPER_CLAIMS, ClaimResult, measure
from voot.bench.protocol.layouts import layout_means
from voot.bench.protocol.problems import problem_label
from voot.bench.protocol.select import planner_label
from voot.bench.protocol.tuning import tuning_sentence
from voot.bench.report.plan_runs import PlannerRuns, mean_ci, plan_data
from voot.bench.store.format import Row

#: The paired comparison's metric and checkpoints per problem (the paper's).
RANKING: dict[str, tuple[str, tuple[int, ...]]] = {
    "kitchen_v1": ("objects_handled", (750, 1700, 2000)),
    "conveyor_v1": ("return", (1000, 3000)),
}


def _fmt(x: float) -> str:
    if math.isnan(x):
        return "-"
    return f"{x:.3g}"


def _ours(r: ClaimResult) -> str:
    if r.verdict == NO_DATA:
        return f"no data ({r.note})"
    return f"{_fmt(r.value)} [{_fmt(r.low)}, {_fmt(r.high)}] ({r.n})"


def _variants() -> list[str]:
    return [BASELINE, *SWITCHES]


def _label(planner: str, variant: str) -> str | None:
    """The cell's planner label of ``planner`` under ``variant`` (None: not run there)."""
    if variant == BASELINE:
        return planner
    return planner_label(planner, variant) if planner in SWITCHES[variant].overrides else None


def claims_rows(runs: dict[tuple[str, str], PlannerRuns]) -> list[str]:
    """The markdown rows of the claims-per-switch table."""
    problems = {p for p, _ in runs}
    base: dict[tuple[str, str, int, str], str] = {}
    lines = []
    for variant in _variants():
        for planner in ABLATION_PLANNERS:
            label = _label(planner, variant)
            if label is None:
                continue
            for claim in PAPER_CLAIMS:
                if planner not in claim.planners or claim.problem not in problems:
                    continue
                if (claim.problem, label) not in runs and variant != BASELINE:
                    continue
                r = measure(claim, label, runs.get((claim.problem, label)))
                key = (claim.problem, claim.metric, claim.checkpoint, planner)
                if variant == BASELINE:
                    base[key] = r.verdict
                    flip = ""
                else:
                    before = base.get(key, NO_DATA)
                    flip = (
                        f"**{before} -> {r.verdict}**"
                        if NO_DATA not in (before, r.verdict) and before != r.verdict
                        else "no"
                    )
                side = "<" if claim.side == "below" else ">"
                lines.append(
                    f"| {variant} | {claim.problem} | {planner} | {claim.metric} |"
                    f" {claim.checkpoint} | {side} {_fmt(claim.threshold)} | {_ours(r)} |"
                    f" {r.verdict} | {flip} |"
                )
    return lines


def _metric(runs: PlannerRuns, metric: str, k: int) -> dict[tuple[int | None, int], float]:
    """Per (layout, seed) run, ``metric`` after simulation ``k`` (empty: runs shorter than
    ``k``); the layout is None for a problem without layouts."""
    if k > runs.returns.shape[1]:
        return {}
    if metric == "return":
        values = runs.returns[:, k - 1]
    else:
        if runs.objects_left is None or runs.objects_initial is None:
            return {}
        values = runs.objects_initial - runs.objects_left[:, k - 1]
    layouts = runs.layouts or (None,) * runs.n_seeds
    keys = zip(layouts, runs.seeds, strict=True)
    return {key: float(v) for key, v in zip(keys, values, strict=True)}


def ranking_rows(runs: dict[tuple[str, str], PlannerRuns]) -> list[str]:
    """The markdown rows of the ranking-per-switch table."""
    lines = []
    for problem, (metric, checkpoints) in RANKING.items():
        for variant in _variants():
            voot = _label("voot", variant) or "voot"
            pw = _label("pw_uct", variant) or "pw_uct"
            a, b = runs.get((problem, voot)), runs.get((problem, pw))
            if a is None or b is None or (variant != BASELINE and (voot, pw) == ("voot", "pw_uct")):
                continue
            cells = []
            for k in checkpoints:
                va, vb = _metric(a, metric, k), _metric(b, metric, k)
                seeds = sorted(set(va) & set(vb))
                if len(seeds) < 2:
                    cells.append("no data")
                    continue
                diff = np.array([va[s] - vb[s] for s in seeds])[:, None]
                # paired by run; on layouts, the per-layout mean difference is the unit
                mean, half, _ = mean_ci(layout_means(diff, [s[0] for s in seeds]))
                m, h = float(mean[0]), float(half[0])
                who = "VOOT ahead" if m - h > 0 else "PW-UCT ahead" if m + h < 0 else "tied"
                cells.append(f"{m:+.3g} [{m - h:+.3g}, {m + h:+.3g}] {who}")
            lines.append(f"| {variant} | {problem} | {voot} vs {pw} | {' | '.join(cells)} |")
    return lines


def ablation_table(
    rows: Iterable[Row],
    tuning_seeds: Collection[int],
    problems: Sequence[str] | None = None,
    env_kwargs: Mapping[str, Any] | None = None,
) -> str:
    """Both tables as markdown, from the store's rows (settings selected on ``tuning_seeds``;
    only ``problems``, display names such as ``kitchen_v1``, if given).

    With ``env_kwargs``, the table is of the runs in that domain (e.g. the authors' domain
    of the conveyor, ``voot/ConveyorPacking-v3``'s keywords on ``conveyor_v1``), each
    judged against the paper's claims and ranking of its problem; without, of the runs
    without keywords.
    """
    names = list(problems) if problems is not None else None
    labels: dict[str, str] | None = None
    if env_kwargs:
        labels = {problem_label(p, env_kwargs): p for p in names or RANKING}
        names = list(labels)
    data = plan_data(list(rows), tuning_seeds=tuning_seeds, problems=names)
    runs = {((labels or {}).get(d.problem, d.problem), d.planner): d for d in data if not d.dim}
    if not runs:
        raise ValueError("no tuned plan runs of the ablation in these rows")
    head = [
        "| switch | problem | planner | metric | at | paper | ours (95% CI, seeds) | verdict | flips |",
        "| --- | --- | --- | --- | ---: | --- | --- | --- | --- |",
    ]
    rank: list[str] = []
    for problem, (metric, checkpoints) in RANKING.items():
        if any(p == problem for p, _ in runs):
            rank.append(
                f"\n{problem}: VOOT minus PW-UCT, {metric.replace('_', ' ')}, paired by seed"
            )
            rank.append("")
            rank.append(
                "| switch | problem | planners | "
                + " | ".join(f"at {k}" for k in checkpoints)
                + " |"
            )
            rank.append("| --- | --- | --- | " + " | ".join("---" for _ in checkpoints) + " |")
            rank.extend(r for r in ranking_rows(runs) if f"| {problem} |" in r)
    note = (
        f"{tuning_sentence(tuning_seeds)} Each switch is selected and judged as its own"
        " planner; a switch that does not concern a planner leaves it at the v1 default."
    )
    if env_kwargs:
        domain = ", ".join(f"{k}={env_kwargs[k]}" for k in sorted(env_kwargs))
        note += f" Every run is in the domain {domain}."
    return "\n".join([*head, *claims_rows(runs), *rank, "", note])


def selected_settings(rows: Iterable[Row], tuning_seeds: Collection[int]) -> list[str]:
    """``planner: setting`` of every tuned cell (for the docs)."""
    data = plan_data(list(rows), tuning_seeds=tuning_seeds)
    return [f"{d.problem} {d.planner}: {d.label}" for d in data if not d.dim]


__all__: Sequence[str] = ["RANKING", "ablation_table", "selected_settings"]
