"""One typed record per planning problem: what voot knows about each gymnasium id.

Every family of environments declares, beside its env, one :class:`ProblemRecord` per id
it registers (``voot.envs.kitchen.problems``, ``voot.envs.conveyor.problems``,
``voot.envs.chains.problems``): the entry point and keywords gymnasium makes it with, its
short names, the paper's budget, the discount and root commitment the authors planned it
with, whether it plays the authors' two-stage tree rules, VOO's options there, whether it
takes generated layouts, at which difficulty levels and with which training / held-out
split, gymnasium's spec metadata (``max_episode_steps``, ``reward_threshold``), and, for
an old name kept as an alias, the id it was renamed to. :mod:`voot._registration` adds
the families' records at ``import voot`` (:func:`add_records`) and registers their ids
with gymnasium; the benchmark reads its planner settings from them
(:func:`voot.bench.protocol.problems.domain_options`), never from tables keyed by id.

This module and the records modules import nothing heavy (no MuJoCo, no env code): a
record is data, read at ``import voot`` and by every layer above.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any

from voot.envs.core.names import Difficulty
from voot.envs.core.splits import PROTOCOL_SPLIT, LayoutSplit

#: The shape of a gymnasium id voot registers: ``namespace/Name-vN``.
_ID = re.compile(r"^[A-Za-z0-9_]+/[A-Za-z0-9_]+-v\d+$")
#: The shape of an entry point: ``module.path:Class``.
_ENTRY = re.compile(r"^[A-Za-z_][\w.]*:[A-Za-z_]\w*$")


@dataclass(frozen=True)
class PaperSetup:
    """The paper's budget for a problem: simulations per run, seeds, planners compared."""

    simulations: int
    seeds: int
    planners: tuple[str, ...]


#: Planners of the paper's chain experiments (the six samplers).
CHAIN_PLANNERS: tuple[str, ...] = ("voot", "doot", "rand_doot", "pw_uct", "voronoi_pw", "hoot")
#: Planners of the paper's Figure 4.
ROBOT_PLANNERS: tuple[str, ...] = ("voot", "rand_doot", "pw_uct", "voronoi_pw", "doot")
#: Budget of a problem the paper does not run (and of any unrecorded environment).
DEFAULT_SETUP = PaperSetup(1_000, 20, ROBOT_PLANNERS)


@dataclass(frozen=True)
class ProblemRecord:
    """What voot knows about one gymnasium id (checked when built; immutable).

    Attributes:
        id: the gymnasium id (``voot/KitchenClearing-v1``).
        family: the family that declares it (``"kitchen"``, ``"conveyor"``, ``"chain"``),
            the name its envs carry (:attr:`voot.envs.core.env.ManipulationEnv.family`).
        entry_point: ``"module:Class"`` gymnasium makes the env from.
        kwargs: keyword arguments registered with the id (JSON values).
        aliases: short names (lower case, ``_`` for ``-``) that the benchmark accepts.
        paper_setup: the paper's simulations, seeds and planners for it.
        discount: the discount the authors planned it with (None: the planner's default,
            or what :attr:`tree_options` says).
        root_commitment: the root commitment threshold of the authors' tree rules
            (with :attr:`v1_rules`).
        v1_rules: whether it plays the authors' tree-side rules (commitment counting
            root actions with reward >= 0, the return to the root after a goal, the same
            feasibility retries for every planner).
        voo_options: the sampler options of the VOO planners on it (None: the default).
        voo_metric: whether VOO measures distances with the problem's own metric
            (``MCTSConfig.use_problem_metric``).
        pw_retries: the feasibility retries of the progressive-widening planners (None:
            the planner's default).
        layouts: whether the env is generated from a ``layout_seed`` keyword.
        difficulties: its difficulty levels (``difficulty`` keyword), easiest first.
        chain: the synthetic chain's function (:mod:`voot.tree.chains`) the env plays, if
            it is one: the authors' options on it depend on the dimension
            (:func:`voot.tree.chains.chain_planner_options`), and the benchmark also plans
            in it without the env (``"shekel_chain"``).
        layout_split: the training and held-out layout seeds of a generated family
            (with :attr:`layouts`).
        max_episode_steps: the domain's own episode limit (its config's ``horizon``),
            registered with gymnasium (``gym.make`` adds a ``TimeLimit`` at it); None:
            the domain has none.
        reward_threshold: the return at which gymnasium deems an episode solved; None
            where no return separates success from failure (docs/environments.md).
        renamed_to: for an old id kept as an alias, the id it was renamed to: making the
            old id warns once, naming the new one, and gives the new id's env.
        authors_domain: whether it is the paper's scene with the authors' domain options
            on (the storage rooms' exact footprint, their rooms and their rules:
            ``voot/ConveyorPacking-v3``), not the published protocol's v1 domain.
    """

    id: str
    family: str
    entry_point: str
    kwargs: Mapping[str, Any] = field(default_factory=dict)
    aliases: tuple[str, ...] = ()
    paper_setup: PaperSetup = DEFAULT_SETUP
    discount: float | None = None
    root_commitment: int | None = None
    v1_rules: bool = False
    voo_options: Mapping[str, Any] | None = None
    voo_metric: bool = False
    pw_retries: int | None = None
    layouts: bool = False
    difficulties: tuple[Difficulty, ...] = ()
    chain: str | None = None
    layout_split: LayoutSplit | None = None
    max_episode_steps: int | None = None
    reward_threshold: float | None = None
    renamed_to: str | None = None
    authors_domain: bool = False

    def __post_init__(self) -> None:
        if not _ID.match(self.id):
            raise ValueError(f"record id must look like 'namespace/Name-vN', got {self.id!r}")
        if not self.family.isidentifier():
            raise ValueError(f"{self.id}: family must be a plain name, got {self.family!r}")
        if not _ENTRY.match(self.entry_point):
            raise ValueError(
                f"{self.id}: entry_point must be 'module:Class', got {self.entry_point!r}"
            )
        try:
            json.dumps(dict(self.kwargs), allow_nan=False)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{self.id}: kwargs must be JSON values ({exc})") from None
        object.__setattr__(self, "kwargs", MappingProxyType(dict(self.kwargs)))
        for alias in self.aliases:
            if alias != alias.lower().replace("-", "_") or not alias.isidentifier():
                raise ValueError(f"{self.id}: alias {alias!r} must be lower case with '_'")
        if self.discount is not None and not 0.0 < self.discount <= 1.0:
            raise ValueError(f"{self.id}: discount must be in (0, 1], got {self.discount}")
        for name in ("root_commitment", "pw_retries", "max_episode_steps"):
            value = getattr(self, name)
            if value is not None and (type(value) is not int or value < 1):
                raise ValueError(f"{self.id}: {name} must be None or an int >= 1, got {value!r}")
        if self.v1_rules and self.root_commitment is None:
            raise ValueError(f"{self.id}: the v1 rules need a root_commitment")
        if self.voo_metric and self.voo_options is None:
            raise ValueError(f"{self.id}: voo_metric needs voo_options")
        if self.voo_options is not None:
            object.__setattr__(self, "voo_options", MappingProxyType(dict(self.voo_options)))
        if (self.difficulties or self.layout_split) and not self.layouts:
            raise ValueError(f"{self.id}: difficulty levels and splits need generated layouts")
        if self.renamed_to is not None and not _ID.match(self.renamed_to):
            raise ValueError(f"{self.id}: renamed_to must be an id, got {self.renamed_to!r}")
        levels = tuple(Difficulty(d) for d in self.difficulties)  # a ValueError names it
        object.__setattr__(self, "difficulties", levels)

    @property
    def short_name(self) -> str:
        """The first alias, else the id: how tables and figures name the problem."""
        return self.aliases[0] if self.aliases else self.id


_RECORDS: dict[str, ProblemRecord] = {}
_ALIASES: dict[str, str] = {}


def add_records(records: Iterable[ProblemRecord]) -> None:
    """Add a family's records (idempotent for the same records).

    Raises:
        ValueError: an id or alias already names another record.
    """
    for record in records:
        old = _RECORDS.get(record.id)
        if old is not None and old != record:
            raise ValueError(f"{record.id} is recorded twice, differently")
        for alias in record.aliases:
            if _ALIASES.get(alias, record.id) != record.id:
                raise ValueError(f"alias {alias!r} names both {_ALIASES[alias]} and {record.id}")
        _RECORDS[record.id] = record
        for alias in record.aliases:
            _ALIASES[alias] = record.id


def problem_records() -> tuple[ProblemRecord, ...]:
    """Every record, in the order the families added them."""
    return tuple(_RECORDS.values())


def aliases() -> Mapping[str, str]:
    """Every alias -> its id."""
    return MappingProxyType(_ALIASES)


def find_record(id_or_alias: str) -> ProblemRecord | None:
    """The record of a gymnasium id or alias (``"kitchen_v1"``, ``"Kitchen-V1"``), or None."""
    text = str(id_or_alias).strip()
    record = _RECORDS.get(text)
    if record is None:
        key = _ALIASES.get(text.lower().replace("-", "_"))
        record = _RECORDS.get(key) if key is not None else None
    return record


def problem_record(id_or_alias: str) -> ProblemRecord:
    """The record of a gymnasium id or alias.

    Raises:
        KeyError: nothing recorded under that name; lists the ids and aliases.
    """
    record = find_record(id_or_alias)
    if record is None:
        names = ", ".join([*_RECORDS, *_ALIASES])
        raise KeyError(f"no problem record for {id_or_alias!r}; recorded: {names}")
    return record


#: The entry point of an old id kept as an alias (:attr:`ProblemRecord.renamed_to`).
RENAMED_ENTRY_POINT = "voot._registration:make_renamed"


def robot_versions(
    v0: ProblemRecord,
    root_commitment: int,
    generated_entry_point: str,
    generated: tuple[str, str],
    max_episode_steps: int,
) -> tuple[ProblemRecord, ...]:
    """A robot family's records from its ``v0`` record (the paper's scene).

    ``-v1`` is the same entry point at its ``"v1"`` preset (the authors' two-stage
    protocol) with the authors' tree rules at ``root_commitment`` and VOO's per-operator
    distance. ``generated`` is the generated family's name and alias
    (``("GeneratedKitchen", "generated_kitchen")``): its id ``voot/<name>-v0`` is
    ``generated_entry_point`` (instances generated from ``layout_seed`` at every
    :class:`Difficulty`, the protocol's training / held-out split) with the v1 settings.
    Its first name, ``<family>-v2`` (alias ``<alias>_v2``), stays as an alias of it
    (:attr:`ProblemRecord.renamed_to`): the committed results name it. Every version
    truncates at ``max_episode_steps`` (the config's horizon); none has a
    ``reward_threshold`` (an episode succeeds when it terminates, whatever its return).
    """
    stem = v0.id.rsplit("-v", 1)[0]
    namespace = stem.split("/", 1)[0]
    v0 = replace(v0, max_episode_steps=max_episode_steps)
    v1 = replace(
        v0,
        id=f"{stem}-v1",
        kwargs={"preset": "v1"},
        aliases=tuple(f"{a}_v1" for a in v0.aliases),
        root_commitment=root_commitment,
        v1_rules=True,
        voo_metric=True,
        pw_retries=None,
    )
    name, alias = generated
    family = replace(
        v1,
        id=f"{namespace}/{name}-v0",
        entry_point=generated_entry_point,
        kwargs={},
        aliases=(alias,),
        layouts=True,
        difficulties=tuple(Difficulty),
        layout_split=PROTOCOL_SPLIT,
    )
    old = replace(
        family,
        id=f"{stem}-v2",
        entry_point=RENAMED_ENTRY_POINT,
        kwargs={"renamed_to": family.id},
        aliases=tuple(f"{a}_v2" for a in v0.aliases),
        renamed_to=family.id,
    )
    return v0, v1, family, old
