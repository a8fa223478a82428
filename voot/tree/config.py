r"""Configuration of the tree search: one frozen dataclass, and named planners as presets.

Every planner of the paper and its baselines is the same search (:class:`voot.tree.MCTS`)
with a different :class:`MCTSConfig`: a per-node *action sampler* (``sampler``) and a
*selection rule* that decides, at each visit of a node, whether to try a new action or
to go down an existing one (``selection``):

============  ==============  =============================================================
planner       sampler         selection
============  ==============  =============================================================
voot          ``voo``         ``reevaluate`` (paper Algorithm 2)
doot          ``doo``         ``reevaluate``
rand_doot     ``rand_doo``    ``reevaluate``
uniform_t     ``uniform``     ``reevaluate`` (the original's ``unif`` sampler, no PW)
pw_uct        ``uniform``     ``progressive_widening`` (:math:`|A| \le k N^\alpha`, UCB)
voronoi_pw    ``voo``         ``progressive_widening`` (Voronoi progressive widening)
hoot          ``hoo``         ``hoo`` (a HOO bandit per node chooses every action)
============  ==============  =============================================================

Defaults are the paper's values where it gives them and the authors' code's otherwise;
each field's docstring says which.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from enum import StrEnum
from types import MappingProxyType
from typing import Any

from voot import validation as V
from voot.optim.base import OptimizerConfig


class Selection(StrEnum):
    """How a node picks the action of a visit.

    ``reevaluate``
        Paper Algorithm 2: re-evaluate the newest action until it has been tried
        ``1 + reevaluations * kappa_r**depth`` times, then ask the sampler for a new one.
    ``progressive_widening``
        Add a new action when :math:`|A(s)| \\le k\\,N(s)^{\\alpha}`, otherwise choose
        among the feasible actions by UCB, :math:`\\hat Q + c\\sqrt{\\ln N(s) / n(s,a)}`.
    ``hoo``
        A HOO bandit over the action box chooses the action of every visit and is told
        the simulation's return (HOOT). Needs ``sampler="hoo"``.
    """

    REEVALUATE = "reevaluate"
    PROGRESSIVE_WIDENING = "progressive_widening"
    HOO = "hoo"


class Widening(StrEnum):
    """When progressive widening adds a new action at a node visited :math:`N` times.

    ``standard``
        A new action when :math:`|A(s)| \\le k\\,N(s)^{\\alpha}` (Couëtoux et al.; the
        fair baseline voot runs by default).
    ``authors``
        The authors' code: a re-evaluation (UCB) when :math:`|A(s)| \\le k\\,N(s)`,
        a new action otherwise: linear in :math:`N`, no :math:`\\alpha`, and inverted.
        Their runs asserted :math:`0 < k \\le 1`; with :math:`k < 1` every visit adds a
        new action (:math:`|A| = N > kN`) and UCB never runs, with :math:`k = 1` a node
        keeps its first feasible action for good (:math:`|A| \\le N` always after it).
    """

    STANDARD = "standard"
    AUTHORS = "authors"


class CommitReset(StrEnum):
    """When ``commit_reset_on_goal`` returns the root to the original root.

    ``goal_found``
        At a commitment check, once any goal leaf exists in the tree (voot's v1 rule).
    ``root_goal_child``
        At a commitment check, when the current root has a goal child (the authors'
        ``choose_child_node_to_descend_to``); a goal found deeper below the current root
        does not stop the descent.
    """

    GOAL_FOUND = "goal_found"
    ROOT_GOAL_CHILD = "root_goal_child"


class Backup(StrEnum):
    """How :math:`\\hat Q(s, a)` absorbs a new return :math:`G`.

    ``max``
        :math:`\\hat Q \\leftarrow \\max(\\hat Q, G)` (paper, deterministic domains).
    ``jump_max_else_mean``
        Jump to :math:`G` if it is a new maximum, otherwise the running mean
        :math:`\\hat Q \\leftarrow \\hat Q + (G - \\hat Q)/n` (the authors' code).
    ``mean``
        The running mean (plain UCT).
    """

    MAX = "max"
    JUMP_MAX_ELSE_MEAN = "jump_max_else_mean"
    MEAN = "mean"


class FinalAction(StrEnum):
    """Which root action a search recommends (the one an execution loop executes)."""

    MAX_Q = "max_q"
    MOST_VISITED = "most_visited"


class BestReturnOver(StrEnum):
    """Which paths the reported best return (the paper's curve) is a maximum over.

    ``leaves``
        Paths from the root to a leaf of the tree (the authors' code). A simulation
        always ends at a terminal state, an infeasible action or the depth limit, so the
        leaves are finished paths; but after a root commitment the horizon recedes, a
        leaf at the old depth limit can be expanded, and the curve can then dip.
    ``nodes``
        Paths from the root to any node (monotone in the number of simulations).
    ``complete``
        Paths that end at a terminal state, an infeasible action, or the depth limit
        (counted from the original root); monotone, and :math:`-\\infty` until one
        exists. Unlike ``nodes`` it never prefers an unfinished path (which matters when
        rewards are negative, e.g. a distance cost); unlike ``leaves`` it keeps a path
        counted once it is finished.
    """

    LEAVES = "leaves"
    NODES = "nodes"
    COMPLETE = "complete"


#: Samplers that are not voot.optim optimisers.
_TREE_SAMPLERS = ("uniform", "hoo")


def available_samplers() -> list[str]:
    """Valid ``sampler`` names: every :mod:`voot.optim` method, ``uniform`` and ``hoo``."""
    from voot.optim.registry import available_methods

    return sorted(set(available_methods()) | set(_TREE_SAMPLERS))


@dataclass(frozen=True)
class MCTSConfig:
    """Options of the tree search (paper Algorithms 1-2 and its baselines).

    Attributes:
        sampler: per-node action sampler: a :mod:`voot.optim` method name (``voo``,
            ``doo``, ``rand_doo``, ``random`` ...), ``uniform`` (independent uniform
            draws, no optimiser state) or ``hoo``. See :func:`available_samplers`.
        sampler_options: fields of the sampler's config (e.g. ``{"omega": 0.3,
            "sampler": "uniform"}`` for VOO; :class:`voot.tree.hoo.HOOConfig` for HOO).
        selection: the rule choosing between a new and an existing action, see
            :class:`Selection`.
        reevaluations: the authors' ``w``: how many times the newest action is
            re-evaluated after its first evaluation before a new one is sampled (the
            paper's :math:`N_r = 1 + w`). Original: 5 on the robot domains, 100 on the
            synthetic chains.
        kappa_r: per-depth decay :math:`\\kappa_r \\in [0, 1]` of the re-evaluation budget,
            ``reevaluations * kappa_r**depth`` at relative depth ``depth`` (paper
            Algorithm 2). 0.8 is the value the authors' code computes; their code then
            overwrote it, so ``kappa_r=1.0`` reproduces the code as it ran (decay off).
        depth_limit: the horizon :math:`H` (relative to the current root); None means no
            limit (the authors' code, where rollouts end at an infeasible action or a
            terminal state). At depth :math:`H - 1` a new action is always sampled.
        gamma: discount :math:`\\gamma \\in [0, 1]` (original: 0.9 object clearing and the
            synthetic chains, 0.99 conveyor packing).
        backup: update rule of :math:`\\hat Q`, see :class:`Backup`.
        feasibility_retries: proposals tried per new action when the problem offers a
            feasibility check (original: 50; 200 for PW on conveyor packing). If all fail
            the last, infeasible, proposal is executed (and earns the infeasible reward).
        root_commitment: once the current root has this many feasible actions, the root
            moves to its best-:math:`\\hat Q` feasible child (original: 10 robot domains,
            5 / 5 / 3 synthetic chains in 3 / 10 / 20-D). None disables it. If a child of
            the root is terminal the root stays and the threshold doubles (the original).
        final_action: which root action :meth:`MCTS.search` recommends.
        terminal_child_forces_new: sample a new action at a node that has a terminal
            child instead of re-evaluating (the authors' code). Re-evaluating an action
            whose child is terminal is always skipped.
        voo_uniform_until_feasible: with the ``voo`` sampler, draw new actions uniformly
            in the box until the node has a feasible action (the authors' VOO sampler).
        pw_k: progressive-widening coefficient :math:`k > 0` (not given in the paper).
        pw_alpha: progressive-widening exponent :math:`\\alpha \\in [0, 1]` (``standard``
            widening only).
        widening: the progressive-widening test, see :class:`Widening`: ``standard``
            (default) or ``authors`` (the original's linear, inverted test, with
            ``pw_k`` as its ``w``).
        ucb_c: UCB exploration constant :math:`c \\ge 0` (the authors' code used
            :math:`2c` with a swept :math:`c`).
        best_return_over: paths the reported best return is a maximum over, see
            :class:`BestReturnOver`.
        commit_min_reward: which root actions count towards ``root_commitment``: the
            feasible ones with a reward of at least this (the authors' code on the robot
            domains: 0.0, so at a kitchen place root only clearing places count). None
            counts every feasible action.
        commit_reset_on_goal: once a terminal leaf (the goal) has been found, a
            commitment returns the root to the original root and doubles the threshold,
            instead of moving down (the authors' code). Off: the root keeps moving down.
        commit_reset_trigger: what counts as "a goal" for ``commit_reset_on_goal``, see
            :class:`CommitReset` (default ``goal_found``; the authors' code:
            ``root_goal_child``).
        use_problem_metric: the per-node optimiser measures distances with the
            problem's ``action_metric()`` for the node's state (e.g. the authors'
            per-operator distance: places compare x, y only). Needs a sampler with a
            ``metric`` option (VOO); ignored for the others and for problems without
            the method. Off: Euclidean distance in the action box.
    """

    sampler: str = "voo"
    sampler_options: Mapping[str, Any] = field(default_factory=dict)
    selection: Selection | str = Selection.REEVALUATE
    reevaluations: float = 5
    kappa_r: float = 0.8
    depth_limit: int | None = None
    gamma: float = 0.9
    backup: Backup | str = Backup.MAX
    feasibility_retries: int = 50
    root_commitment: int | None = 10
    final_action: FinalAction | str = FinalAction.MAX_Q
    terminal_child_forces_new: bool = True
    voo_uniform_until_feasible: bool = True
    pw_k: float = 1.0
    pw_alpha: float = 0.5
    widening: Widening | str = Widening.STANDARD
    ucb_c: float = 1.0
    best_return_over: BestReturnOver | str = BestReturnOver.LEAVES
    commit_min_reward: float | None = None
    commit_reset_on_goal: bool = False
    commit_reset_trigger: CommitReset | str = CommitReset.GOAL_FOUND
    use_problem_metric: bool = False

    def __post_init__(self) -> None:
        sampler = str(self.sampler).strip().lower().replace("-", "_")
        valid = available_samplers()
        if sampler not in valid:
            raise ValueError(
                f"unknown sampler {self.sampler!r}; valid samplers are: {', '.join(valid)}"
            )
        object.__setattr__(self, "sampler", sampler)
        if not isinstance(self.sampler_options, Mapping):
            raise ValueError(
                f"sampler_options must be a mapping of option names to values, got {self.sampler_options!r}"
            )
        # A private copy (a plain dict, so that configs pickle for parallel sweeps).
        object.__setattr__(self, "sampler_options", dict(self.sampler_options))
        sel = V.choice(Selection, self.selection, "selection")
        object.__setattr__(self, "selection", sel)
        if (sel is Selection.HOO) != (sampler == "hoo"):
            raise ValueError(
                "selection='hoo' and sampler='hoo' go together (HOO chooses every action"
                f" itself); got sampler={sampler!r}, selection={sel.value!r}"
            )
        object.__setattr__(
            self, "reevaluations", V.number(self.reevaluations, "reevaluations", 0.0)
        )
        object.__setattr__(self, "kappa_r", V.number(self.kappa_r, "kappa_r", 0.0, 1.0))
        object.__setattr__(
            self, "depth_limit", V.optional_integer(self.depth_limit, "depth_limit", 1)
        )
        object.__setattr__(self, "gamma", V.number(self.gamma, "gamma", 0.0, 1.0))
        object.__setattr__(self, "backup", V.choice(Backup, self.backup, "backup"))
        object.__setattr__(
            self,
            "feasibility_retries",
            V.integer(self.feasibility_retries, "feasibility_retries", 1),
        )
        object.__setattr__(
            self,
            "root_commitment",
            V.optional_integer(self.root_commitment, "root_commitment", 1),
        )
        object.__setattr__(
            self, "final_action", V.choice(FinalAction, self.final_action, "final_action")
        )
        for name in (
            "terminal_child_forces_new",
            "voo_uniform_until_feasible",
            "commit_reset_on_goal",
            "use_problem_metric",
        ):
            object.__setattr__(self, name, V.flag(getattr(self, name), name))
        pw_k = V.number(self.pw_k, "pw_k", 0.0)
        if pw_k <= 0.0:
            raise ValueError(f"pw_k must be > 0, got {self.pw_k!r}")
        object.__setattr__(self, "pw_k", pw_k)
        object.__setattr__(self, "pw_alpha", V.number(self.pw_alpha, "pw_alpha", 0.0, 1.0))
        object.__setattr__(self, "widening", V.choice(Widening, self.widening, "widening"))
        object.__setattr__(
            self,
            "commit_reset_trigger",
            V.choice(CommitReset, self.commit_reset_trigger, "commit_reset_trigger"),
        )
        object.__setattr__(self, "ucb_c", V.number(self.ucb_c, "ucb_c", 0.0))
        object.__setattr__(
            self,
            "best_return_over",
            V.choice(BestReturnOver, self.best_return_over, "best_return_over"),
        )
        if self.commit_min_reward is not None:
            object.__setattr__(
                self,
                "commit_min_reward",
                V.number(self.commit_min_reward, "commit_min_reward", -math.inf),
            )
        # Build the sampler's config once, so that bad options fail here, not mid-search.
        self.sampler_config()

    def sampler_config(self) -> OptimizerConfig | Any:
        """The per-node sampler's config object (None for ``uniform``)."""
        options = dict(self.sampler_options)
        if self.sampler == "uniform":
            if options:
                raise ValueError(f"sampler 'uniform' takes no options, got {sorted(options)}")
            return None
        if self.sampler == "hoo":
            from voot.tree.hoo import HOOConfig

            V.config_options(HOOConfig, options, "sampler 'hoo'")
            return HOOConfig(**options)
        from voot.optim.registry import make_config

        try:
            return make_config(self.sampler, **options)
        except ImportError as exc:  # registered, but its module is not written yet
            raise ValueError(f"sampler {self.sampler!r} is not available: {exc}") from None

    def replace(self, **changes: Any) -> MCTSConfig:
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        """Plain values (enums as strings), e.g. for a results table."""
        out: dict[str, Any] = {}
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, StrEnum):
                v = v.value
            elif isinstance(v, Mapping):
                v = dict(v)
            out[f.name] = v
        return out


#: Named planners: the paper's VOOT and its baselines, as :class:`MCTSConfig` overrides.
PLANNERS: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {
        "voot": {"sampler": "voo", "selection": "reevaluate"},
        "doot": {"sampler": "doo", "selection": "reevaluate"},
        "rand_doot": {"sampler": "rand_doo", "selection": "reevaluate"},
        "uniform_t": {"sampler": "uniform", "selection": "reevaluate"},
        "pw_uct": {"sampler": "uniform", "selection": "progressive_widening"},
        "voronoi_pw": {"sampler": "voo", "selection": "progressive_widening"},
        "hoot": {"sampler": "hoo", "selection": "hoo"},
    }
)


def available_planners() -> list[str]:
    """Names accepted by :func:`planner_config` and :func:`voot.tree.plan`."""
    return sorted(PLANNERS)


def normalize_planner(name: str) -> str:
    """Lower-case, ``-`` to ``_`` (``"RAND-DOOT"`` -> ``"rand_doot"``); check it exists."""
    return V.registered_name(name, PLANNERS, "planner")


def planner_config(name: str = "voot", **overrides: Any) -> MCTSConfig:
    """The :class:`MCTSConfig` of a named planner, with some fields overridden.

    >>> planner_config("pw_uct", gamma=0.99).sampler
    'uniform'
    """
    base = dict(PLANNERS[normalize_planner(name)])
    V.config_options(MCTSConfig, overrides, f"planner {name!r}")
    base.update(overrides)
    return MCTSConfig(**base)
