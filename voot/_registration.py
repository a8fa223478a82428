"""Gymnasium ids of voot's environments, registered when ``voot`` is imported.

Each family of environments declares one problem record per id beside its env
(:mod:`voot.problems`); :data:`FAMILIES` names the modules that hold them, one line per
family. Registration reads the records (data only) and stores entry-point strings, so it
costs little and imports no MuJoCo and no env code.
"""

from __future__ import annotations

import importlib

from voot.problems import ProblemRecord, add_records, problem_records

#: The records modules of the families, each with its ``RECORDS``: adding a family is
#: one line here and a folder of its own.
FAMILIES: tuple[str, ...] = (
    "voot.envs.chains.problems",
    "voot.envs.kitchen.problems",
    "voot.envs.conveyor.problems",
)


def _family_records(module: str) -> tuple[ProblemRecord, ...]:
    records: tuple[ProblemRecord, ...] = importlib.import_module(module).RECORDS
    return records


def register_envs() -> None:
    """Add every family's records (:func:`voot.problems.add_records`) and register their
    ids with gymnasium, each with its entry point and keywords (idempotent)."""
    for module in FAMILIES:
        add_records(_family_records(module))
    try:
        import gymnasium
    except ImportError:  # pragma: no cover - gymnasium is a core dependency
        return
    for record in problem_records():
        if record.id not in gymnasium.registry:
            gymnasium.register(
                id=record.id, entry_point=record.entry_point, kwargs=dict(record.kwargs)
            )
