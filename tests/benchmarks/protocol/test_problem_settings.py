"""The per-problem settings pinned: every registered id (and chain, alias) x every planner.

``problem_settings.json`` holds what :mod:`voot.bench.protocol.problems` answered before
the per-problem facts moved from its tables into the families' problem records
(:mod:`voot.problems`): the planner options of :func:`domain_options` (their keys in
order), the paper setups, labels, families and the names aliases resolve to. A change of
any of them changes the runs of ``voot-bench plan``, so it must be deliberate.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from voot.bench.protocol import problems as P
from voot.bench.sweep.planners import PLAN_PLANNERS

PINNED: dict[str, dict[str, Any]] = json.loads(
    Path(__file__).with_name("problem_settings.json").read_text()
)


def test_the_pins_cover_every_registered_id_and_planner() -> None:
    import gymnasium

    import voot  # noqa: F401 - registers the ids

    ids = {k for k in gymnasium.registry if k.startswith("voot/")}
    pinned = {key.split("|")[0] for key in PINNED["domain_options"]}
    assert ids | set(P.CHAINS) <= pinned
    assert {key.split("|")[2] for key in PINNED["domain_options"]} == set(PLAN_PLANNERS)


def test_domain_options_are_pinned() -> None:
    for key, items in PINNED["domain_options"].items():
        problem, dim, planner, kwargs = key.split("|")
        got = P.domain_options(
            problem, None if dim == "None" else int(dim), planner, json.loads(kwargs)
        )
        assert [[k, v] for k, v in got.items()] == items, key


def test_setups_labels_families_and_names_are_pinned() -> None:
    for problem, (simulations, seeds, planners) in PINNED["paper_setup"].items():
        assert P.paper_setup(problem) == P.PaperSetup(simulations, seeds, tuple(planners))
    for problem, label in PINNED["labels"].items():
        assert P.problem_label(problem) == label
    for problem, family in PINNED["family"].items():
        assert P.family(problem) == family
    for name, problem in PINNED["normalize"].items():
        assert P.normalize_problem(name) == problem
