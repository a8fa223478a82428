"""Gymnasium ids of voot's environments, registered when ``voot`` is imported.

Each family of environments declares one problem record per id beside its env
(:mod:`voot.problems`); :data:`FAMILIES` names the modules that hold them, one line per
family. Registration reads the records (data only) and stores entry-point strings, so it
costs little and imports no MuJoCo and no env code.

Each id is registered with its record's ``max_episode_steps`` and ``reward_threshold``.
An old id kept as an alias (:attr:`voot.problems.ProblemRecord.renamed_to`, such as
``voot/KitchenClearing-v2``, now ``voot/GeneratedKitchen-v0``) is made by
:func:`make_renamed`, which warns once and makes the new id's env.

Gymnasium tells a user of ``Name-vN`` that it "is out of date" whenever a higher
``Name-vM`` is registered. voot's versions are problems side by side, not revisions:
``-v0`` is the paper's scene as first released, ``-v1`` the authors' protocol on it, and
both are run and reported. Each voot spec is therefore filed in the registry under its
whole id as its name, without a version (``gym.spec("voot/KitchenClearing-v1").name ==
"KitchenClearing-v1"``, its ``version`` None; the registry's key stays the id, so
``gym.make`` and ``gym.spec`` find it as before, and a made env's ``spec`` is gymnasium's
usual one), and no voot id warns that another is newer.
"""

from __future__ import annotations

import importlib
import warnings
from typing import Any

from voot.problems import ProblemRecord, add_records, problem_record, problem_records

#: The records modules of the families, each with its ``RECORDS``: adding a family is
#: one line here and a folder of its own.
FAMILIES: tuple[str, ...] = (
    "voot.envs.chains.problems",
    "voot.envs.kitchen.problems",
    "voot.envs.conveyor.problems",
)

#: The old ids that have warned in this process (each warns once).
_WARNED: set[str] = set()


def _family_records(module: str) -> tuple[ProblemRecord, ...]:
    records: tuple[ProblemRecord, ...] = importlib.import_module(module).RECORDS
    return records


def register_envs() -> None:
    """Add every family's records (:func:`voot.problems.add_records`) and register their
    ids with gymnasium, each with its entry point, keywords and spec metadata
    (idempotent)."""
    for module in FAMILIES:
        add_records(_family_records(module))
    try:
        import gymnasium
    except ImportError:  # pragma: no cover - gymnasium is a core dependency
        return
    for record in problem_records():
        if record.id in gymnasium.registry:
            continue
        gymnasium.register(
            id=record.id,
            entry_point=record.entry_point,
            kwargs=dict(record.kwargs),
            max_episode_steps=record.max_episode_steps,
            reward_threshold=record.reward_threshold,
        )
        # a problem of its own, not a revision (module docstring): gymnasium's "out of
        # date" check compares the specs' names and versions
        spec = gymnasium.registry[record.id]
        spec.name, spec.version = record.id.split("/", 1)[1], None


def make_renamed(renamed_to: str, **kwargs: Any) -> Any:
    """The env of ``renamed_to`` (an id) made with ``kwargs``: the entry point of an old
    id kept as an alias. Warns once per old name and process (a ``FutureWarning`` naming
    the new id)."""
    from gymnasium.envs.registration import load_env_creator

    new = problem_record(renamed_to)
    old = [r.id for r in problem_records() if r.renamed_to == new.id]
    if new.id not in _WARNED:
        _WARNED.add(new.id)
        warnings.warn(
            f"{' and '.join(old)} is now {new.id} (alias {new.short_name}): the same env under"
            " a name of its own; the old name stays an alias",
            FutureWarning,
            stacklevel=3,
        )
    return load_env_creator(new.entry_point)(**kwargs)
