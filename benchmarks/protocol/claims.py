r"""The paper's claims about Figure 4, checked against a result store (``voot-bench claims``).

Each claim of the paper is split into small declarative records (:class:`Claim`): a
problem, a metric, the planners it is about, a checkpoint (simulations), a threshold
and the side of it the paper puts those planners' value on. "VOOT reaches a reward a
little above 3 at 1,000 simulations, the others below 1" is two records: VOOT's return
at 1,000 above 3, and every other planner's return at 1,000 below 1. A later session
adds a claim by adding a record to :data:`PAPER_CLAIMS` (or passing its own list to
:func:`evaluate`).

**Metrics and their 95% intervals** (over seeds):

``return``
    the best discounted return after ``checkpoint`` simulations; mean, t-interval.
``objects_left``
    objects still to handle at the best leaf (kitchen: obstacles on the path); mean,
    t-interval.
``objects_handled``
    objects at the start minus objects left (conveyor: boxes placed); mean, t-interval.
``simulations_to_clear``
    simulations until the best plan first handles every object (a seed that never does
    within the budget counts as infinitely many); median, distribution-free interval
    from order statistics (binomial, :func:`voot.bench.report.plan_runs.median_ci`).
    ``checkpoint`` is ignored.

The paper reports means over seeds (its curves), so its claims use the mean metrics;
the median is there for claims about "how many simulations until".

**Verdicts**, for a claim that the value is ``below`` (``above``) the threshold ``T``,
with our 95% interval ``[low, high]``:

* **reproduced**: the whole interval is on the paper's side: ``high < T`` (``low > T``);
* **reversed**: the whole interval is on the other side: ``low > T`` (``high < T``),
  the opposite of the claim holds;
* **not reproduced**: the interval contains ``T``; our seeds do not settle it;
* **no data**: no evaluation runs of the planner on the problem, runs shorter than the
  checkpoint, no object counts, or fewer than 2 seeds (no interval).

The data are those :func:`voot.bench.report.plan_runs.plan_data` gives, so the claims honour
the same selection as the figures: the paper's same-seed rule by default, or settings
selected on tuning seeds (``tuning_seeds``) with the evaluation seeds reported.

On a generated family (runs on layout seeds, :mod:`voot.bench.protocol.layouts`) the unit of every
interval is the layout: the t-interval is over the per-layout means, the order-statistics
interval over the per-layout medians, and ``n`` counts layouts.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

from voot import validation as V
from voot.bench.report.plan_runs import PlannerRuns, first_reach, mean_ci, median_ci

#: Metrics a claim can be about (see the module docstring).
METRICS: tuple[str, ...] = ("return", "objects_left", "objects_handled", "simulations_to_clear")
#: Sides of the threshold the paper can put the value on.
SIDES: tuple[str, ...] = ("above", "below")
#: The verdicts, in the table's vocabulary.
REPRODUCED, NOT_REPRODUCED, REVERSED, NO_DATA = (
    "reproduced",
    "not reproduced",
    "reversed",
    "no data",
)
#: Every tree and MPC planner of the protocol except VOOT: "the others" of the paper.
OTHER_PLANNERS: tuple[str, ...] = (
    "doot",
    "rand_doot",
    "pw_uct",
    "voronoi_pw",
    "hoot",
    "cem",
    "mppi",
    "predictive_sampling",
)
#: The reinforcement-learning baselines.
RL_PLANNERS: tuple[str, ...] = ("ppo", "ddpg")


@dataclass(frozen=True)
class Claim:
    """One checkable statement of the paper.

    Attributes:
        claim: the paper's claim in a few words (lines of one claim share it).
        problem: the problem's display name (e.g. ``kitchen_v1``, ``conveyor_v1``).
        metric: one of :data:`METRICS`.
        planners: the planners it is about (one table line each).
        checkpoint: simulations at which the metric is read.
        threshold: the value the paper's statement is measured against.
        side: ``"above"`` or ``"below"``: where the paper puts the planners' value.
        paper: the paper's figure, as the paper says it.
    """

    claim: str
    problem: str
    metric: str
    planners: tuple[str, ...]
    checkpoint: int
    threshold: float
    side: str
    paper: str

    def __post_init__(self) -> None:
        V.one_of(self.metric, "metric", METRICS)
        V.one_of(self.side, "side", SIDES)
        V.integer(self.checkpoint, "checkpoint", 1)
        V.number(self.threshold, "threshold")
        if not self.planners:
            raise ValueError(f"claim {self.claim!r}: no planners given")


#: The paper's claims about Figure 4. Thresholds: "almost every obstacle"
#: = at most 1 obstacle left on average; "about 4" = above 3.5; "15 objects" = above
#: 14.5 boxes; "12-13" = below 13.5; "1-2 obstacles" = below 2.5; "at most 8" = below 8.5.
PAPER_CLAIMS: tuple[Claim, ...] = (
    Claim(
        "kitchen: VOOT clears almost every obstacle within 750 simulations",
        "kitchen_v1",
        "objects_left",
        ("voot",),
        750,
        1.0,
        "below",
        "almost all obstacles cleared at 750 simulations",
    ),
    Claim(
        "kitchen: the others need more than 1,700 simulations (about 2.3x)",
        "kitchen_v1",
        "objects_left",
        OTHER_PLANNERS,
        1700,
        1.0,
        "above",
        "more than 1 obstacle left at 1,700 simulations",
    ),
    Claim(
        "conveyor: VOOT's reward is a little above 3 at 1,000 simulations",
        "conveyor_v1",
        "return",
        ("voot",),
        1000,
        3.0,
        "above",
        "a little above 3",
    ),
    Claim(
        "conveyor: the others' reward is below 1 at 1,000 simulations",
        "conveyor_v1",
        "return",
        OTHER_PLANNERS,
        1000,
        1.0,
        "below",
        "below 1",
    ),
    Claim(
        "conveyor: VOOT's reward is about 4 at 3,000 simulations",
        "conveyor_v1",
        "return",
        ("voot",),
        3000,
        3.5,
        "above",
        "about 4",
    ),
    Claim(
        "conveyor: the others' reward is below 2 at 3,000 simulations",
        "conveyor_v1",
        "return",
        OTHER_PLANNERS,
        3000,
        2.0,
        "below",
        "below 2",
    ),
    Claim(
        "conveyor: VOOT places 15 objects within 1,000 simulations",
        "conveyor_v1",
        "objects_handled",
        ("voot",),
        1000,
        14.5,
        "above",
        "15 objects",
    ),
    Claim(
        "conveyor: the others place 12-13 objects after 3,000 simulations",
        "conveyor_v1",
        "objects_handled",
        OTHER_PLANNERS,
        3000,
        13.5,
        "below",
        "12-13 objects",
    ),
    Claim(
        "kitchen: RL is stuck at 1-2 obstacles",
        "kitchen_v1",
        "objects_handled",
        RL_PLANNERS,
        2000,
        2.5,
        "below",
        "1-2 obstacles cleared",
    ),
    Claim(
        "conveyor: RL packs at most 8 boxes",
        "conveyor_v1",
        "objects_handled",
        RL_PLANNERS,
        3000,
        8.5,
        "below",
        "at most 8 boxes",
    ),
)


@dataclass(frozen=True)
class ClaimResult:
    """One line of the claims table: a claim about one planner, measured.

    Attributes:
        claim: the claim.
        planner: the planner of this line.
        value: our mean (median for ``simulations_to_clear``); NaN without data.
        low, high: our 95% interval (NaN without one).
        n: seeds measured.
        interval: ``"t"`` or ``"order statistics"`` (empty without data).
        verdict: one of reproduced, not reproduced, reversed, no data.
        note: why there is no data, if there is none.
    """

    claim: Claim
    planner: str
    value: float
    low: float
    high: float
    n: int
    interval: str
    verdict: str
    note: str = ""


def verdict(side: str, threshold: float, low: float, high: float) -> str:
    """The verdict of an interval ``[low, high]`` against a claim that the value is on
    ``side`` of ``threshold`` (the rules of the module docstring)."""
    V.one_of(side, "side", SIDES)
    if math.isnan(low) or math.isnan(high):
        return NO_DATA
    on_paper_side = high < threshold if side == "below" else low > threshold
    on_other_side = low > threshold if side == "below" else high < threshold
    if on_paper_side:
        return REPRODUCED
    if on_other_side:
        return REVERSED
    return NOT_REPRODUCED


def _no_data(claim: Claim, planner: str, note: str, n: int = 0) -> ClaimResult:
    nan = math.nan
    return ClaimResult(claim, planner, nan, nan, nan, n, "", NO_DATA, note)


def measure(claim: Claim, planner: str, runs: PlannerRuns | None) -> ClaimResult:
    """The line of ``claim`` for ``planner`` from its runs (None: no runs)."""
    if runs is None:
        return _no_data(claim, planner, "no runs")
    k = claim.checkpoint
    if claim.metric == "simulations_to_clear":
        if runs.objects_left is None:
            return _no_data(claim, planner, "no object counts")
        med, low, high = median_ci(runs.unit_medians(first_reach(runs.objects_left)))
        result = ClaimResult(claim, planner, med, low, high, runs.n_units, "order statistics", "")
    else:
        if k > runs.returns.shape[1]:
            return _no_data(claim, planner, f"runs of {runs.simulations} simulations")
        if claim.metric == "return":
            values = runs.returns[:, k - 1]
        elif runs.objects_left is None:
            return _no_data(claim, planner, "no object counts")
        elif claim.metric == "objects_left":
            values = runs.objects_left[:, k - 1]
        else:
            initial = runs.objects_initial
            assert initial is not None
            values = initial - runs.objects_left[:, k - 1]
        mean, half, count = mean_ci(runs.units(values[:, None]))
        m, h = float(mean[0]), float(half[0])
        result = ClaimResult(claim, planner, m, m - h, m + h, int(count[0]), "t", "")
    if result.n < 2 or math.isnan(result.low):
        return _no_data(claim, planner, f"{result.n} seeds: no interval", result.n)
    return replace(result, verdict=verdict(claim.side, claim.threshold, result.low, result.high))


def evaluate(
    data: Sequence[PlannerRuns], claims: Iterable[Claim] = PAPER_CLAIMS
) -> list[ClaimResult]:
    """Every claim's lines, one per planner, from :func:`voot.bench.report.plan_runs.plan_data`."""
    runs = {(d.problem, d.planner): d for d in data if not d.dim}
    out = []
    for c in claims:
        for p in c.planners:
            out.append(measure(c, p, runs.get((c.problem, p))))
    return out


def _num(x: float) -> str:
    if math.isinf(x):
        return "never" if x > 0 else "-inf"
    return f"{x:.3g}"


def claims_table(results: Sequence[ClaimResult], note: str = "") -> str:
    """The claims as one markdown table, with the rules under it."""
    lines = [
        "| claim | problem | planner | metric | at | paper | threshold | ours (95% CI, seeds)"
        " | verdict |",
        "| --- | --- | --- | --- | ---: | --- | --- | --- | --- |",
    ]
    previous: Claim | None = None
    for r in results:
        c = r.claim
        text = c.claim if c != previous else "″"  # the claim once, ditto below it
        previous = c
        at = "" if c.metric == "simulations_to_clear" else str(c.checkpoint)
        side = "<" if c.side == "below" else ">"
        if r.verdict == NO_DATA and math.isnan(r.value):
            ours = f"— ({r.note})"
        elif r.verdict == NO_DATA:
            ours = f"{_num(r.value)} ({r.note})"
        else:
            ours = f"{_num(r.value)} [{_num(r.low)}, {_num(r.high)}] ({r.n})"
        lines.append(
            f"| {text} | {c.problem} | {r.planner} | {c.metric} | {at} | {c.paper}"
            f" | {side} {c.threshold:g} | {ours} | {r.verdict} |"
        )
    counts = {
        v: sum(r.verdict == v for r in results)
        for v in (REPRODUCED, NOT_REPRODUCED, REVERSED, NO_DATA)
    }
    summary = ", ".join(f"{v}: {n}" for v, n in counts.items())
    rules = (
        "Ours: mean with a 95% t-interval over seeds (median with a distribution-free"
        " order-statistics interval for simulations_to_clear). Reproduced: the whole"
        " interval is on the paper's side of the threshold; reversed: the whole interval"
        " is on the other side; not reproduced: the interval contains the threshold; no"
        " data: no runs, runs shorter than the checkpoint, or fewer than 2 seeds."
    )
    text = "\n".join(lines) + f"\n\n{summary}.\n\n{rules}"
    if note:
        text += f" {note}"
    return text
