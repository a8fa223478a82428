"""Typed names at the env seam: the values that were plain strings between an env and its
callers (difficulty levels; operators, pre-checks and units join them here).

Each is a :class:`enum.StrEnum`, so a member equals, hashes and serialises (JSON) as its
string value: stores, hashes and keyword arguments written with the strings keep working.
This module imports nothing heavy (no MuJoCo): problem records use it at ``import voot``.
"""

from __future__ import annotations

from enum import StrEnum


class Difficulty(StrEnum):
    """A level of a generated task family, from the easiest."""

    EASY = "easy"
    MEDIUM = "medium"
    HARD = "hard"
