r"""One-factor-at-a-time ablation of the remaining departures from the authors' code.

The v1 protocol reverses the paper's headline (PW-UCT, not VOOT, wins the kitchen). Each
:class:`Switch` below flips one planner option from voot's v1 default to what the authors'
code does (or, for root commitment, off), for VOOT and PW-UCT; ``authors`` flips all of
them at once. The domains never change: a switch is a set of planner options only.

Every switch is a *variant* of its planners (:attr:`voot.bench.sweep.plan.PlanSpec.variant`):
its rows carry the variant's name, so selections, figures and tables treat
``voot[kappa_off]`` as a planner of its own, and each variant's setting is selected on the
tuning seeds like any planner's (the protocol). The search seed does not depend on the
variant, so a variant and the v1 default see the same random numbers until their choices
differ (common random numbers: the comparison is paired per seed).

The switches (``voot-bench ablation --list`` prints them):

======================  ===================================================================
switch                  what it flips (v1 default -> the authors' code)
======================  ===================================================================
pw_authors              PW-UCT's widening: standard :math:`|A| \le k\sqrt N` -> the coded
                        linear, inverted test (``widening="authors"``, :math:`k \in \{0.8, 1\}`)
backup_hybrid           :math:`\hat Q`: max -> jump to a new max, else running mean
voo_centered_uniform    VOO's best-cell sampler: uniform (switching to gaussian after 1000
                        tries) -> centered_uniform (their synthetic default)
voo_gaussian            -> gaussian from the start
voo_uniform_no_switch   -> uniform without the switch to gaussian
voo_random_ties         VOO's best point among ties: the first -> drawn at random
kappa_off               re-evaluation decay :math:`\kappa_r`: 0.8 (paper) -> 1 (the code: off)
reevaluations_5         re-evaluations tuned in {2, 5} -> fixed at the original's 5
commit_off              root commitment -> off
commit_no_return        after a goal, return to the original root -> keep descending
commit_root_goal_child  return when any goal leaf exists -> when the root has a goal child
commit_10               conveyor only: commitment after 1 root action -> after 10
authors                 all of the above as the authors coded them, at once
authors_commit_10       conveyor only: ``authors`` with commitment after 10 root actions
                        (the stored test script's ``n_switch`` for the conveyor)
======================  ===================================================================
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from voot.bench.protocol import problems as P
from voot.bench.sweep.plan import PlanSpec
from voot.bench.sweep.planners import UCB_CS, planner_grid

#: The planners the ablation compares.
ABLATION_PLANNERS: tuple[str, ...] = ("voot", "pw_uct")
#: The problems of the ablation (the v1 domains).
ABLATION_PROBLEMS: tuple[str, ...] = ("voot/KitchenClearing-v1", "voot/ConveyorPacking-v1")
#: Evaluation seeds per problem (the issue's 20 on both domains) and the tuning seeds.
ABLATION_SEEDS: tuple[int, ...] = tuple(range(20))
ABLATION_TUNING_SEEDS: tuple[int, ...] = tuple(range(1000, 1005))
#: The original PW-UCT's widening parameters (its runs asserted 0 < w <= 1).
AUTHORS_PW_KS: tuple[float, ...] = (0.8, 1.0)
#: Name of the v1 defaults in tables (the runs of no variant).
BASELINE = "v1"


@dataclass(frozen=True)
class Switch:
    """One departure from the authors' code, as planner options.

    Attributes:
        name: the variant's name (in rows, selections, tables).
        what: what it flips, in one line.
        overrides: per planner, the options set in every run of the variant (planners
            absent here do not run the variant).
        axes: per planner, grid axes that replace the planner's tuning grid's.
        problems: the problems the variant runs on (default: both v1 domains).
    """

    name: str
    what: str
    overrides: Mapping[str, Mapping[str, Any]]
    axes: Mapping[str, Mapping[str, tuple[Any, ...]]] = field(default_factory=dict)
    problems: tuple[str, ...] = ABLATION_PROBLEMS

    def planners(self) -> list[str]:
        return [p for p in ABLATION_PLANNERS if p in self.overrides]


_HYBRID = {"backup": "jump_max_else_mean"}
_AUTHORS_PW_AXES = {"pw_k": AUTHORS_PW_KS, "ucb_c": UCB_CS}
_AUTHORS_VOOT = {
    **_HYBRID,
    "kappa_r": 1.0,
    "commit_reset_trigger": "root_goal_child",
    "tie_break": "random",
}
_AUTHORS_PW_UCT = {**_HYBRID, "widening": "authors", "commit_reset_trigger": "root_goal_child"}

SWITCHES: Mapping[str, Switch] = MappingProxyType(
    {
        s.name: s
        for s in (
            Switch(
                "pw_authors",
                "PW-UCT's widening as coded: linear and inverted (UCB when |A| <= w N)",
                {"pw_uct": {"widening": "authors"}},
                {"pw_uct": _AUTHORS_PW_AXES},
            ),
            Switch(
                "backup_hybrid",
                "Q-hat: jump to a new maximum, else running mean (the code's use_max_backup)",
                {"voot": _HYBRID, "pw_uct": _HYBRID},
            ),
            Switch(
                "voo_centered_uniform",
                "VOO's best cell sampled centered_uniform (their synthetic default)",
                {"voot": {"sampler.sampler": "centered_uniform"}},
            ),
            Switch(
                "voo_gaussian",
                "VOO's best cell sampled gaussian from the first ask",
                {"voot": {"sampler.sampler": "gaussian"}},
            ),
            Switch(
                "voo_uniform_no_switch",
                "VOO's uniform best-cell sampler without the switch to gaussian",
                {"voot": {"sampler.uniform_switch_to_gaussian": False}},
            ),
            Switch(
                "voo_random_ties",
                "VOO's best point drawn at random among points tied at the best value",
                {"voot": {"tie_break": "random"}},
            ),
            Switch(
                "kappa_off",
                "re-evaluation decay kappa_r 1 (the code overwrote 0.8^depth: decay off)",
                {"voot": {"kappa_r": 1.0}},
            ),
            Switch(
                "reevaluations_5",
                "re-evaluations fixed at the original's w = 5 (v1 tunes {2, 5})",
                {"voot": {}},
                {"voot": {"reevaluations": (5,)}},
            ),
            Switch(
                "commit_off",
                "no root commitment",
                {"voot": {"root_commitment": None}, "pw_uct": {"root_commitment": None}},
            ),
            Switch(
                "commit_no_return",
                "after a goal the committed root keeps descending (no return, no doubling)",
                {
                    "voot": {"commit_reset_on_goal": False},
                    "pw_uct": {"commit_reset_on_goal": False},
                },
            ),
            Switch(
                "commit_root_goal_child",
                "return to the original root only when the root has a goal child (the code)",
                {
                    "voot": {"commit_reset_trigger": "root_goal_child"},
                    "pw_uct": {"commit_reset_trigger": "root_goal_child"},
                },
            ),
            Switch(
                "commit_10",
                "conveyor: commitment after 10 root actions with reward >= 0 (v1: 1)",
                {"voot": {"root_commitment": 10}, "pw_uct": {"root_commitment": 10}},
                problems=("voot/ConveyorPacking-v1",),
            ),
            Switch(
                "authors",
                "everything as the authors coded it, at once",
                {"voot": _AUTHORS_VOOT, "pw_uct": _AUTHORS_PW_UCT},
                {"voot": {"reevaluations": (5,)}, "pw_uct": _AUTHORS_PW_AXES},
            ),
            Switch(
                "authors_commit_10",
                "conveyor: everything as coded, with commitment after 10 root actions",
                {
                    "voot": {**_AUTHORS_VOOT, "root_commitment": 10},
                    "pw_uct": {**_AUTHORS_PW_UCT, "root_commitment": 10},
                },
                {"voot": {"reevaluations": (5,)}, "pw_uct": _AUTHORS_PW_AXES},
                problems=("voot/ConveyorPacking-v1",),
            ),
        )
    }
)


def check_switches(names: Iterable[str] | None) -> list[Switch]:
    """The named switches (all, in table order, for None); a ValueError lists them."""
    if names is None:
        return list(SWITCHES.values())
    out = []
    for name in names:
        key = str(name).strip().lower().replace("-", "_")
        if key not in SWITCHES and key != BASELINE:
            raise ValueError(
                f"unknown ablation switch {name!r}; valid switches are: {BASELINE} (the"
                f" defaults), {', '.join(SWITCHES)}"
            )
        if key != BASELINE and SWITCHES[key] not in out:
            out.append(SWITCHES[key])
    return out


def check_applicable(
    switches: Sequence[Switch], problems: Sequence[str], *, named: bool = True
) -> None:
    """Raise ValueError unless every switch runs on some of ``problems`` and every problem
    runs some switch.

    A switch is a variant on the problems of its :attr:`Switch.problems` only; a run asked
    for elsewhere would silently not happen. So a switch that applies to none of
    ``problems`` (``named``: the user chose it; the default list keeps its conveyor-only
    switches beside the kitchen) and, when switches are asked for, a problem on which none
    of them applies (it would run the v1 defaults only) are refused, naming the problems
    each switch applies to.
    """
    names = [P.normalize_problem(p) for p in problems]
    if named:
        for switch in switches:
            if not set(switch.problems) & set(names):
                raise ValueError(
                    f"ablation switch {switch.name} applies to {', '.join(switch.problems)}"
                    f" only, not to {', '.join(names)}; add one of those to --problems or"
                    " leave the switch out"
                )
    if not switches:
        return
    for problem in names:
        if not any(problem in s.problems for s in switches):
            where = sorted({p for s in switches for p in s.problems})
            raise ValueError(
                f"no ablation switch applies to {problem} (the switches"
                f" {', '.join(s.name for s in switches)} apply to {', '.join(where)});"
                f" give --problems among those, or --switches {BASELINE} for the v1 defaults"
                " alone"
            )


def variant_grid(switch: Switch | None, planner: str) -> list[dict[str, Any]]:
    """The settings a variant's tuning runs: the planner's grid (axes replaced by the
    switch's), each with the switch's overrides."""
    base = planner_grid(planner, "robot")
    if switch is None:
        return base
    axes = switch.axes.get(planner)
    if axes:
        names = sorted({*base[0], *axes})
        values = [axes.get(n) or tuple(dict.fromkeys(g[n] for g in base)) for n in names]
        base = [dict(zip(names, v, strict=True)) for v in itertools.product(*values)]
    return [{**g, **switch.overrides[planner]} for g in base]


def ablation_specs(
    switches: Sequence[Switch],
    seeds: Iterable[int],
    *,
    problems: Sequence[str] = ABLATION_PROBLEMS,
    include_baseline: bool = True,
    simulations: int | None = None,
    env_kwargs: Mapping[str, Any] | None = None,
) -> list[PlanSpec]:
    """Every run of the ablation on ``seeds``: the v1 defaults (no variant) and each
    switch's variant, for VOOT and PW-UCT, every setting of their grids.

    ``env_kwargs`` (keywords of ``gymnasium.make``, e.g. a domain switch of
    :mod:`voot.bench.protocol.domain_ablation`) run every variant on that version of the
    domain: the runs are its own (their problem label names the keywords), tuned and
    tabled apart from the plain domain's."""
    if simulations is not None and (
        isinstance(simulations, bool) or not isinstance(simulations, int) or simulations < 1
    ):
        raise ValueError(
            f"simulations must be an integer >= 1 (None: the paper's), got {simulations!r}"
        )
    seed_list = list(dict.fromkeys(int(s) for s in seeds))
    names = [P.normalize_problem(p) for p in problems]
    kwargs = tuple(sorted(P.check_env_kwargs(env_kwargs).items()))
    variants: list[Switch | None] = [None] if include_baseline else []
    variants += list(switches)
    out = []
    for problem in names:
        n_sims = simulations if simulations is not None else P.paper_setup(problem).simulations
        for switch in variants:
            if switch is not None and problem not in switch.problems:
                continue
            planners = ABLATION_PLANNERS if switch is None else switch.planners()
            for planner in planners:
                for params in variant_grid(switch, planner):
                    items = tuple(sorted(params.items()))
                    for seed in seed_list:
                        out.append(
                            PlanSpec(
                                problem,
                                None,
                                kwargs,
                                planner,
                                items,
                                n_sims,
                                seed,
                                variant="" if switch is None else switch.name,
                            )
                        )
    return out


def switch_list() -> str:
    """The switches, one per line (``voot-bench ablation --list``)."""
    width = max(len(n) for n in SWITCHES)
    lines = [f"{BASELINE:<{width}}  the v1 defaults (docs/environments.md)"]
    for s in SWITCHES.values():
        where = "" if s.problems == ABLATION_PROBLEMS else " [conveyor only]"
        lines.append(f"{s.name:<{width}}  {s.what} ({', '.join(s.planners())}){where}")
    return "\n".join(lines)


__all__ = [
    "ABLATION_PLANNERS",
    "ABLATION_PROBLEMS",
    "ABLATION_SEEDS",
    "ABLATION_TUNING_SEEDS",
    "BASELINE",
    "SWITCHES",
    "Switch",
    "ablation_specs",
    "check_applicable",
    "check_switches",
    "switch_list",
    "variant_grid",
]
