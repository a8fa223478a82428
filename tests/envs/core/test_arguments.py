"""Tests of voot.envs.core.arguments: the generated families' arguments, each checked by one
function, and checked before anything is generated or cached."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import voot  # noqa: F401  (registers the ids)
from voot.envs.conveyor.generated import instance as SI
from voot.envs.core.arguments import (
    LAYOUT_SEEDS,
    check_difficulty,
    check_layout_seed,
    check_render,
    check_split,
)
from voot.envs.core.names import Difficulty, Split
from voot.envs.kitchen.generated import instance as KI

FAMILIES = ("voot/GeneratedStorage-v0", "voot/GeneratedKitchen-v0")


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A fresh, empty cache folder and empty memos."""
    from voot.envs.assets import meshes

    monkeypatch.setenv("VOOT_CACHE", str(tmp_path / "cache"))
    SI.clear_memo()
    KI.clear_kitchen_cache()
    meshes.clear_memory_cache()
    yield tmp_path / "cache"
    SI.clear_memo()
    KI.clear_kitchen_cache()
    meshes.clear_memory_cache()


def _files(folder: Path) -> dict[str, bytes]:
    return {str(p): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("value", [0, 7, np.int64(3), np.uint8(2), 2**63 - 1])
def test_a_layout_seed_is_an_integer_of_numpy_or_python(value: object) -> None:
    got = check_layout_seed(value)
    assert type(got) is int and got == int(value)  # type: ignore[call-overload]


@pytest.mark.parametrize(
    "value", [1.5, 1.0, True, False, np.bool_(True), "1", np.float64(1.0), None, -1, 2**63, [1]]
)
def test_a_layout_seed_of_another_type_or_range_is_refused_naming_the_range(
    value: object,
) -> None:
    with pytest.raises(ValueError, match=r"layout_seed must be an integer in \[0, 92233"):
        check_layout_seed(value)


def test_one_range_for_every_family() -> None:
    assert LAYOUT_SEEDS == range(0, 2**63)
    for family in FAMILIES:
        with pytest.raises(ValueError, match=r"in \[0, 9223372036854775807\]"):
            gym.make(family, layout_seed=2**63)


def test_levels_and_splits_by_exact_name() -> None:
    assert check_difficulty("hard") is Difficulty.HARD
    assert check_difficulty(Difficulty.EASY) is Difficulty.EASY
    for bad in ("Hard", " hard", "extreme", 1, None, b"easy"):
        with pytest.raises(ValueError, match="valid levels are: easy, medium, hard"):
            check_difficulty(bad)
    with pytest.raises(ValueError, match=r"valid levels are: easy$"):
        check_difficulty("hard", (Difficulty.EASY,))
    assert check_split(None) is None and check_split("heldout") is Split.HELDOUT
    for bad in ("Training", 1, "train"):
        with pytest.raises(ValueError, match="valid splits are: training, heldout"):
            check_split(bad)


def test_render_arguments() -> None:
    assert check_render(None, "top_down", [320, np.int32(240)]) == (None, "top_down", (320, 240))
    bad_sizes = [(640.7, 480), ("640", 480), (True, 480), (640, 480, 3), 640, (8, 480), None]
    for size in bad_sizes:
        with pytest.raises(ValueError, match=r"render_size must be \(width, height\), two integ"):
            check_render(None, "perspective", size)
    assert check_render("rgb_array", "perspective", (16, 16))[0] == "rgb_array"
    # the ends of the ranges: 16..1280 x 16..960
    for w, h in ((16, 16), (1280, 960), (16, 960), (1280, 16)):
        assert check_render(None, "perspective", (w, h))[2] == (w, h)
    for w, h in ((15, 480), (1281, 480), (640, 15), (640, 961)):
        with pytest.raises(ValueError, match=r"within 16\.\.1280 x 16\.\.960"):
            check_render(None, "perspective", (w, h))
    for mode in ("human", ["rgb_array"]):
        with pytest.raises(ValueError, match="render_mode must be None or one of rgb_array"):
            check_render(mode, "perspective", (640, 480))
    for camera in (["top_down"], "side"):
        with pytest.raises(ValueError, match="render_camera must be one of perspective, top_d"):
            check_render(None, camera, (640, 480))


@pytest.mark.parametrize("family", FAMILIES)
def test_a_float_render_size_is_refused_not_truncated(family: str) -> None:
    # before: int(640.7) made a 640-pixel env
    with pytest.raises(ValueError, match="render_size"):
        gym.make(family, layout_seed=0, render_size=(640.7, 480))


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize(
    "kwargs",
    [
        {"layout_seed": 11, "render_size": (1, 1)},
        {"layout_seed": 11, "horizon": 1.5},
        {"layout_seed": 11, "difficulty": "Easy"},
        {"layout_seed": 11.0},
    ],
)
def test_a_refused_make_generates_and_writes_nothing(
    cache: Path, family: str, kwargs: dict[str, object]
) -> None:
    """Every argument is checked before a layout is generated or cached: before, a bad
    render size or config keyword was found only after layout 11 was generated, compiled
    and written to the cache."""
    with pytest.raises(ValueError):
        gym.make(family, **kwargs)
    assert _files(cache) == {}
    assert len(SI.INSTANCES) == 0 and len(KI.KITCHENS) == 0


@pytest.mark.parametrize("family", FAMILIES)
def test_a_warm_cache_serves_no_refused_seed(cache: Path, family: str) -> None:
    env = gym.make(family, layout_seed=1).unwrapped
    before = _files(cache)
    for value in (1.5, 1.0, True, "1", np.float64(1.0)):
        with pytest.raises(ValueError, match="layout_seed must be an integer"):
            gym.make(family, layout_seed=value)
        with pytest.raises(ValueError, match="layout_seed must be an integer"):
            env.reset(options={"layout_seed": value})
        assert env.layout_seed == 1
    assert _files(cache) == before
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a numpy integer is the same layout, no warning
        assert gym.make(family, layout_seed=np.int64(1)).unwrapped.layout_seed == 1
