"""The difficulty ladder of a generated task family, measured: ``voot-bench ladder``.

A generated family (``voot/KitchenClearing-v2``, ``voot/ConveyorPacking-v2``) has named
difficulty levels. Whether a level is harder than the one below is a claim about the
instances, so it is measured, per level, over a fixed set of layouts:

* **without a planner** (:mod:`voot.bench.protocol.difficulty`, on each layout): the share of
  uniform actions at the first nodes that pass the pre-check and then execution, with
  the execution failures by cause, and the share of random pre-check-feasible rollouts
  that solve the instance;
* **with the planners**, from a plan store holding runs on the levels' layouts (e.g.
  ``voot-bench plan --problems kitchen_v2 --layout-seeds 0:5 --env-kwargs
  difficulty=hard ...``): per planner, the share of runs that solve the instance within
  the budget and the mean share of the objects handled.

:func:`monotone` says whether a statistic orders the levels as their names do; the
report prints the verdict per statistic, whatever it is (a ladder that is not monotone
in some statistic is reported as such, never re-tuned).
"""

from __future__ import annotations

import itertools
import math
from collections import Counter, defaultdict
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from voot import validation as V
from voot.bench.protocol.difficulty import node_stats, rollout_stats, wilson

#: The levels of the generated families, easiest first.
LEVELS: tuple[str, ...] = ("easy", "medium", "hard")
#: Layouts measured per level by default (the first held-out layouts).
DEFAULT_LAYOUTS: tuple[int, ...] = (0, 1, 2, 3, 4)


@dataclass(frozen=True)
class LevelStats:
    """Planner-agnostic statistics of one level, pooled over its layouts.

    Attributes:
        env_id: The family's gymnasium id.
        level: The difficulty level.
        layouts: The layout seeds measured.
        samples: Uniform actions per node type and layout.
        precheck: Node name -> actions that passed the pre-check (all layouts).
        executed: Node name -> of those, actions executed feasibly.
        failures: Node name -> execution failures by reason code (the step info's ``reason_code``).
        rollouts: Random rollouts (all layouts).
        solved: Rollouts that solved their instance.
        handled: Mean share of the objects a rollout handled.
    """

    env_id: str
    level: str
    layouts: tuple[int, ...]
    samples: int
    precheck: Mapping[str, int]
    executed: Mapping[str, int]
    failures: Mapping[str, Mapping[str, int]] = field(default_factory=dict)
    rollouts: int = 0
    solved: int = 0
    handled: float = math.nan

    @property
    def feasible_share(self) -> float:
        """Share of uniform actions, over every node type, that pass both stages."""
        total = self.samples * len(self.layouts) * len(self.precheck)
        return sum(self.executed.values()) / total if total else math.nan


def level_stats(
    env_id: str,
    level: str,
    layouts: Sequence[int] = DEFAULT_LAYOUTS,
    samples: int = 500,
    rollouts: int = 40,
    seed: int = 0,
) -> LevelStats:
    """Measure ``level`` of the family ``env_id`` on ``layouts`` (deterministic)."""
    V.integer(samples, "samples", 1)
    V.integer(rollouts, "rollouts", 1)
    if not layouts:
        raise ValueError("layouts must name at least one layout seed")
    precheck: Counter[str] = Counter()
    executed: Counter[str] = Counter()
    failures: dict[str, Counter[str]] = defaultdict(Counter)
    solved, handled_share = 0, 0.0
    for layout in layouts:
        kwargs = {"layout_seed": int(layout), "difficulty": level}
        for s in node_stats(env_id, samples, seed, env_kwargs=kwargs):
            precheck[s.node] += s.passed_precheck
            executed[s.node] += s.passed_execution
            failures[s.node].update(s.execution_failures)
        r = rollout_stats(env_id, rollouts, seed, env_kwargs=kwargs)
        solved += r.solved
        handled_share += r.mean_handled / r.initial_objects
    return LevelStats(
        env_id,
        level,
        tuple(int(v) for v in layouts),
        samples,
        dict(precheck),
        dict(executed),
        {k: dict(v) for k, v in failures.items()},
        rollouts * len(layouts),
        solved,
        handled_share / len(layouts),
    )


@dataclass(frozen=True)
class PlannerLevel:
    """A planner's runs on one level: how many solved their instance, objects handled."""

    planner: str
    level: str
    runs: int
    solved: int
    handled: float

    def interval(self) -> tuple[float, float]:
        """95% Wilson interval of the solve rate (runs on different layouts)."""
        return wilson(self.solved, self.runs)


def planner_levels(rows: Iterable[Mapping[str, Any]], env_id: str) -> list[PlannerLevel]:
    """Per planner and level, the plan rows of ``env_id`` that solved their instance.

    A run solves its instance if no object is left after its last simulation; the
    objects handled are ``1 - left / initial`` then. Rows without the objects curve (or
    on another problem, or failed) are left out.
    """
    groups: dict[tuple[str, str], list[tuple[bool, float]]] = defaultdict(list)
    for r in rows:
        cfg = r.get("config", {})
        left = r.get("objects_left")
        initial = r.get("objects_initial")
        if cfg.get("problem") != env_id or r.get("status") != "ok" or left is None:
            continue
        level = str(cfg.get("env_kwargs", {}).get("difficulty", "?"))
        last = float(np.asarray(left, dtype=float)[-1])
        share = 1.0 - last / float(initial) if initial else math.nan
        label = str(cfg["planner"]) + (f"[{cfg['variant']}]" if cfg.get("variant") else "")
        groups[(label, level)].append((last == 0.0, share))
    out = []
    for (planner, level), runs in sorted(
        groups.items(), key=lambda kv: (kv[0][0], _rank(kv[0][1]))
    ):
        out.append(
            PlannerLevel(
                planner,
                level,
                len(runs),
                sum(s for s, _ in runs),
                float(np.mean([h for _, h in runs])),
            )
        )
    return out


def _rank(level: str) -> int:
    return LEVELS.index(level) if level in LEVELS else len(LEVELS)


def monotone(values: Sequence[float], decreasing: bool = True) -> bool:
    """Whether ``values`` (one per level, easiest first) never get easier up the ladder.

    Ties count as monotone; a NaN (no data) does not.
    """
    if any(math.isnan(v) for v in values):
        return False
    pairs = list(itertools.pairwise(values))
    return all(b <= a for a, b in pairs) if decreasing else all(b >= a for a, b in pairs)


def ladder_report(
    env_id: str,
    levels: Sequence[str] = LEVELS,
    layouts: Sequence[int] = DEFAULT_LAYOUTS,
    samples: int = 500,
    rollouts: int = 40,
    seed: int = 0,
    rows: Sequence[Mapping[str, Any]] = (),
) -> str:
    """The ladder's tables as Markdown (what ``voot-bench ladder`` prints)."""
    stats = [level_stats(env_id, lv, layouts, samples, rollouts, seed) for lv in levels]
    nodes = sorted({n for s in stats for n in s.precheck}, key=lambda n: (n != "pick", n))
    lines = [
        f"Difficulty ladder of {env_id}: layouts {', '.join(map(str, layouts))}; {samples}"
        f" uniform actions per node type and layout; {rollouts} random rollouts per layout"
        f" (seed {seed}).",
        "",
        "| level | node | pass pre-check | of those, pass execution | feasible | execution failures |",
        "|---|---|---:|---:|---:|---|",
    ]
    for s in stats:
        n = s.samples * len(s.layouts)
        for node in nodes:
            pre, exe = s.precheck.get(node, 0), s.executed.get(node, 0)
            fails = ", ".join(
                f"{k} {v / n:.1%}"
                for k, v in sorted(s.failures.get(node, {}).items(), key=lambda kv: -kv[1])
            )
            rate = f"{exe / pre:.1%}" if pre else "-"
            lines.append(
                f"| {s.level} | {node} | {pre / n:.1%} | {rate} | {exe / n:.1%} | {fails or '-'} |"
            )
    lines += [
        "",
        "| level | random rollouts | solved (95% CI) | objects handled (mean share) |",
        "|---|---:|---:|---:|",
    ]
    for s in stats:
        lo, hi = wilson(s.solved, s.rollouts)
        lines.append(
            f"| {s.level} | {s.rollouts} | {s.solved / s.rollouts:.1%} [{lo:.1%}, {hi:.1%}]"
            f" | {s.handled:.1%} |"
        )
    verdicts = [
        ("feasible share of uniform actions", [s.feasible_share for s in stats]),
        ("random-rollout solve rate", [s.solved / s.rollouts for s in stats]),
        ("objects handled by random rollouts", [s.handled for s in stats]),
    ]
    planners = planner_levels(rows, env_id)
    if planners:
        lines += [
            "",
            "| planner | level | runs | solved (95% CI) | objects handled (mean share) |",
            "|---|---|---:|---:|---:|",
        ]
        for p in planners:
            lo, hi = p.interval()
            lines.append(
                f"| {p.planner} | {p.level} | {p.runs} | {p.solved / p.runs:.0%}"
                f" [{lo:.0%}, {hi:.0%}] | {p.handled:.1%} |"
            )
        by_planner: dict[str, dict[str, float]] = defaultdict(dict)
        for p in planners:
            by_planner[p.planner][p.level] = p.handled
        for planner, per in sorted(by_planner.items()):
            verdicts.append(
                (f"objects handled by {planner}", [per.get(lv, math.nan) for lv in levels])
            )
    lines += ["", "Monotone in the levels (each level at least as hard as the one below):", ""]
    for name, values in verdicts:
        shown = " / ".join("-" if math.isnan(v) else f"{v:.1%}" for v in values)
        lines.append(f"- {name}: {'yes' if monotone(values) else 'no'} ({shown})")
    return "\n".join(lines)
