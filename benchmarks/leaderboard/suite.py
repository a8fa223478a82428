"""The leaderboard's suite: one versioned file saying what every entry runs.

A suite (``suite_v1.toml`` beside this module) fixes the families (gymnasium ids of the
generated families) with each one's simulation budget, the difficulty levels, the
held-out layouts and seeds of the evaluation, the training layouts and seeds of the
tuning (disjoint from the held-out ones: :func:`voot.bench.protocol.layouts.check_protocol`),
and the entries of the first leaderboard (a planner, optionally a variant with fixed
options and its own grid). :func:`load_suite` reads it into a frozen :class:`Suite`
whose fields are validated (a bad file is an error naming the field and the valid
choices) and whose :attr:`Suite.digest` is the SHA-256 of the file's bytes: a result
card names the suite by version *and* digest, so a changed file cannot pass for v1.
"""

from __future__ import annotations

import hashlib
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from voot import validation as V

#: The suites shipped, by name (``--suite v1``), beside this module.
SUITES: Mapping[str, str] = {"v1": "suite_v1.toml"}
#: The suite ``voot-bench leaderboard`` runs by default.
DEFAULT_SUITE = "v1"
#: The difficulty levels a generated family takes.
LEVELS: tuple[str, ...] = ("easy", "medium", "hard")


class SuiteError(ValueError):
    """A suite file that is not a valid suite (the message names the file and field)."""


@dataclass(frozen=True)
class Family:
    """A generated family of the suite and its budget of simulations per run."""

    problem: str
    simulations: int


@dataclass(frozen=True)
class Entry:
    """A leaderboard entry: a planner, or a planner's variant (fixed options, own grid).

    Attributes:
        planner: any planner name :mod:`voot.planners` accepts (built-in, entry point,
            ``module:attr``).
        variant: the variant's name (empty: the planner as it is); rows carry it, tables
            show ``planner[variant]``.
        set: options set in every run of the entry (e.g. ``{"widening": "authors"}``).
        axes: the grid searched when tuning, replacing the planner's own (empty: its own).
    """

    planner: str
    variant: str = ""
    set: tuple[tuple[str, Any], ...] = ()
    axes: tuple[tuple[str, tuple[Any, ...]], ...] = ()

    @property
    def name(self) -> str:
        """The entry's name in tables: ``planner`` or ``planner[variant]``."""
        return f"{self.planner}[{self.variant}]" if self.variant else self.planner


@dataclass(frozen=True)
class Suite:
    """A versioned benchmark definition (see the module).

    Attributes:
        version: the suite's version (``1``: ``--suite v1``).
        description: one line.
        families: the generated families and their budgets.
        levels: the difficulty levels.
        heldout_layouts: the evaluation layouts (held out from tuning).
        seeds: the evaluation seeds (per layout).
        tuning_layouts: the training layouts settings are selected on.
        tuning_seeds: the tuning seeds (per training layout).
        tuning_level: the level the tuning runs at (its selection is used at every level).
        reuse_protocol: take the committed protocol's selection (made on the same
            training layouts) where it has one, instead of tuning again.
        entries: the first leaderboard's entries (``--planners`` may name others).
        digest: SHA-256 of the suite file's bytes.
        source: the file it was read from.
    """

    version: int
    description: str
    families: tuple[Family, ...]
    levels: tuple[str, ...]
    heldout_layouts: tuple[int, ...]
    seeds: tuple[int, ...]
    tuning_layouts: tuple[int, ...]
    tuning_seeds: tuple[int, ...]
    tuning_level: str
    reuse_protocol: bool
    entries: tuple[Entry, ...]
    digest: str = field(default="", compare=False)
    source: str = field(default="", compare=False)

    @property
    def name(self) -> str:
        return f"v{self.version}"

    @property
    def ref(self) -> str:
        """How ``--suite`` names it: a shipped suite's name, else its file."""
        for name in SUITES:
            if self.source and Path(self.source).resolve() == suite_path(name).resolve():
                return name
        return self.source or self.name

    def entry(self, name: str) -> Entry:
        """The suite's entry called ``name`` (``pw_uct[pw_authors]``), else the planner
        ``name`` as a plain entry (any planner :mod:`voot.planners` finds)."""
        for e in self.entries:
            if e.name == name:
                return e
        return Entry(str(name).strip())

    def family(self, problem: str) -> Family:
        for f in self.families:
            if f.problem == problem:
                return f
        raise KeyError(f"{problem} is not a family of suite {self.name}")


def _range(value: Any, name: str, source: str) -> tuple[int, ...]:
    """``"A:B"`` (A .. B-1) or a list of integers, as a tuple of integers >= 0."""
    try:
        if isinstance(value, str):
            start, sep, stop = value.partition(":")
            if not sep:
                raise ValueError(f"{value!r} is not START:STOP")
            out = list(range(int(start), int(stop)))
        else:
            out = V.integers(value, name, 0)
        if not out:
            raise ValueError("empty")
        if min(out) < 0:
            raise ValueError("below 0")
    except (TypeError, ValueError) as exc:
        raise SuiteError(
            f"{source}: {name} must be START:STOP or a list of integers >= 0 ({exc})"
        ) from None
    return tuple(out)


def _table(data: Mapping[str, Any], key: str, source: str) -> Mapping[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, Mapping):
        raise SuiteError(f"{source}: [{key}] must be a table")
    return value


def _known(data: Mapping[str, Any], valid: Sequence[str], where: str, source: str) -> None:
    unknown = sorted(set(data) - set(valid))
    if unknown:
        raise SuiteError(
            f"{source}: unknown key(s) {unknown} in {where}; valid keys are: {', '.join(valid)}"
        )


def _entry(item: Any, source: str) -> Entry:
    if not isinstance(item, Mapping) or not isinstance(item.get("planner"), str):
        raise SuiteError(f"{source}: every [[entries]] needs planner = NAME")
    _known(item, ("planner", "variant", "set", "axes"), "[[entries]]", source)
    fixed = item.get("set", {})
    axes = item.get("axes", {})
    if not isinstance(fixed, Mapping) or not isinstance(axes, Mapping):
        raise SuiteError(f"{source}: an entry's set and axes must be tables")
    for k, v in axes.items():
        if not isinstance(v, list) or not v:
            raise SuiteError(f"{source}: axis {k!r} of {item['planner']} must be a non-empty list")
    variant = str(item.get("variant", ""))
    if (fixed or axes) and not variant:
        raise SuiteError(
            f"{source}: the entry of {item['planner']} sets options or axes; give it a"
            " variant name (its rows and tables are then planner[variant])"
        )
    return Entry(
        item["planner"],
        variant,
        tuple(sorted(fixed.items())),
        tuple(sorted((k, tuple(v)) for k, v in axes.items())),
    )


def parse_suite(data: Mapping[str, Any], source: str = "suite") -> Suite:
    """A :class:`Suite` from the parsed TOML ``data`` (checks every field).

    Raises:
        SuiteError: a missing or invalid field, naming it and the valid choices.
    """
    top = (
        "version",
        "description",
        "levels",
        "heldout_layouts",
        "seeds",
        "tuning",
        "families",
        "entries",
    )
    _known(data, top, "the suite", source)
    try:
        version = V.integer(data.get("version"), "version", 1)
    except (TypeError, ValueError) as exc:
        raise SuiteError(f"{source}: {exc}") from None
    levels = tuple(data.get("levels", LEVELS))
    bad = [lv for lv in levels if lv not in LEVELS]
    if bad or not levels:
        raise SuiteError(f"{source}: levels {bad or '[]'}; valid levels are: {', '.join(LEVELS)}")
    fams = data.get("families")
    if not isinstance(fams, list) or not fams:
        raise SuiteError(f"{source}: at least one [[families]] (problem, simulations) is needed")
    families = []
    for f in fams:
        if not isinstance(f, Mapping):
            raise SuiteError(f"{source}: [[families]] entries must be tables")
        _known(f, ("problem", "simulations"), "[[families]]", source)
        try:
            families.append(
                Family(str(f["problem"]), V.integer(f.get("simulations"), "simulations", 1))
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise SuiteError(f"{source}: a family needs problem and simulations ({exc})") from None
    tuning = _table(data, "tuning", source)
    _known(tuning, ("layouts", "seeds", "level", "reuse_protocol"), "[tuning]", source)
    level = str(tuning.get("level", "medium"))
    if level not in LEVELS:
        raise SuiteError(f"{source}: tuning level {level!r}; valid levels are: {', '.join(LEVELS)}")
    heldout = _range(data.get("heldout_layouts"), "heldout_layouts", source)
    training = _range(tuning.get("layouts"), "tuning.layouts", source)
    from voot.bench.protocol.layouts import check_layouts_disjoint

    try:
        check_layouts_disjoint(training, heldout)
    except ValueError as exc:
        raise SuiteError(f"{source}: {exc}") from None
    entries = tuple(_entry(e, source) for e in data.get("entries", []))
    names = [e.name for e in entries]
    if len(set(names)) != len(names):
        raise SuiteError(
            f"{source}: entries repeat: {sorted(n for n in names if names.count(n) > 1)}"
        )
    return Suite(
        version=version,
        description=str(data.get("description", "")),
        families=tuple(families),
        levels=levels,
        heldout_layouts=heldout,
        seeds=_range(data.get("seeds", [0]), "seeds", source),
        tuning_layouts=training,
        tuning_seeds=_range(tuning.get("seeds", [0]), "tuning.seeds", source),
        tuning_level=level,
        reuse_protocol=bool(tuning.get("reuse_protocol", True)),
        entries=entries,
    )


def suite_path(name: str) -> Path:
    """The file of the shipped suite ``name`` (``v1``), or a path given as it is."""
    if name in SUITES:
        return Path(__file__).with_name(SUITES[name])
    path = Path(name)
    if path.suffix == ".toml" and path.is_file():
        return path
    raise SuiteError(
        f"unknown suite {name!r}; valid suites are: {', '.join(SUITES)}, or a suite file (.toml)"
    )


def load_suite(name: str = DEFAULT_SUITE) -> Suite:
    """The suite ``name`` (``v1``, or a ``.toml`` path), validated, with its digest."""
    path = suite_path(name)
    data = path.read_bytes()
    try:
        parsed = tomllib.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise SuiteError(f"{path}: not a TOML file ({exc})") from None
    suite = parse_suite(parsed, str(path))
    object.__setattr__(suite, "digest", hashlib.sha256(data).hexdigest())
    object.__setattr__(suite, "source", str(path))
    return suite
