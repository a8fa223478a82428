"""The generated families' shared parts (voot.envs.core.generation): the level table."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from voot.envs.core.generation import level_table
from voot.envs.core.names import Difficulty


@dataclass(frozen=True)
class _Level:
    size: int
    shape: str = "square"


def test_a_level_table_reads_one_value_per_level_easiest_first() -> None:
    levels = level_table(_Level, {"size": (1, 2, 3)})
    assert list(levels) == [Difficulty.EASY, Difficulty.MEDIUM, Difficulty.HARD]
    assert [lv.size for lv in levels.values()] == [1, 2, 3]
    assert {lv.shape for lv in levels.values()} == {"square"}  # a field left out: its default
    with pytest.raises(TypeError):
        levels[Difficulty.EASY] = _Level(0)  # type: ignore[index]
    with pytest.raises(ValueError, match="size: 2 values for the 3 levels"):
        level_table(_Level, {"size": (1, 2)})
