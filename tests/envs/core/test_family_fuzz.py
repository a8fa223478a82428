"""A generative fuzz of the generated families' inputs (hypothesis): keyword arguments,
reset options and ``set_state`` snapshots.

The property, for every input drawn: either the call is refused with a ValueError before
anything changes (the env's state, the cache folder's files, the in-process memos), or it
is accepted and gives exactly what the canonical form of the same request gives (the
arguments as the checks return them: a Python ``int`` layout seed, a level by name...).
Few examples per run (the layouts are few and cached), no deadline: it runs in the suite.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import data_equivalence
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import voot  # noqa: F401  (registers the ids)
from voot.envs.conveyor.generated import instance as SI
from voot.envs.core.arguments import check_difficulty, check_layout_seed, check_render
from voot.envs.core.state import EnvState
from voot.envs.kitchen.generated import instance as KI

FAMILIES = ("voot/GeneratedStorage-v0", "voot/GeneratedKitchen-v0")
FUZZ = settings(
    max_examples=30,
    deadline=None,
    derandomize=True,  # the same examples every run (a failure reproduces)
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
_MISSING = object()


def _mostly(valid: st.SearchStrategy[Any], bad: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    """``valid`` four draws in five, else ``bad``: a whole request is then valid often
    enough that both sides of the property are exercised."""
    return st.sampled_from((True, True, True, True, False)).flatmap(lambda ok: valid if ok else bad)


#: Layout seeds: the valid few (cached after their first use) and every kind of wrong one.
layout_seeds = _mostly(
    st.sampled_from([_MISSING, None, 0, 1, np.int64(1), np.uint8(0)]),
    st.one_of(
        st.sampled_from([1.0, 1.5, np.float64(0.0), True, False, "1", "0", -1, 2**63, [1], b"1"]),
        st.floats(allow_nan=True, allow_infinity=True),
        st.text(max_size=3),
    ),
)
levels = _mostly(
    st.sampled_from([_MISSING, "easy", "medium"]),
    st.sampled_from(["Easy", "MEDIUM", " easy", "extreme", 1, None, b"easy"]),
)
splits = _mostly(
    st.sampled_from([_MISSING, None]), st.sampled_from(["heldout", "Heldout", "test", 0])
)
sizes = _mostly(
    st.sampled_from([_MISSING, (640, 480), [320, 240], (np.int64(64), 48)]),
    st.sampled_from([(640.5, 480), ("640", 480), (8, 8), 640, None]),
)
horizons = _mostly(
    st.sampled_from([_MISSING, 7, np.int64(7)]), st.sampled_from([7.0, True, 0, "7"])
)
extras = _mostly(
    st.sampled_from([{}, {"render_camera": "top_down"}]),
    st.sampled_from([{"bogus": 1}, {"render_camera": 3}, {"workspace": (0, 1, 0, 1)}]),
)


@pytest.fixture(scope="module")
def cache(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """One cache folder for the module (its layouts made once), and empty memos."""
    with pytest.MonkeyPatch.context() as mp:
        folder = tmp_path_factory.mktemp("fuzz-cache")
        mp.setenv("VOOT_CACHE", str(folder))
        SI.clear_memo()
        KI.clear_kitchen_cache()
        yield folder
    SI.clear_memo()
    KI.clear_kitchen_cache()


def _cache_view(folder: Path) -> tuple[Any, ...]:
    """The cache's files (name, size, modification time) and the memos' keys."""
    files = tuple(
        (str(p), p.stat().st_size, p.stat().st_mtime_ns)
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    )
    return files, tuple(SI.INSTANCES._items), tuple(KI.KITCHENS._items)


def _canonical(kwargs: dict[str, Any]) -> dict[str, Any]:
    """The request with every argument as its check returns it."""
    out = dict(kwargs)
    if out.get("layout_seed") is not None:
        out["layout_seed"] = check_layout_seed(out["layout_seed"])
    if "difficulty" in out:
        out["difficulty"] = str(check_difficulty(out["difficulty"]))
    if "render_size" in out:
        out["render_size"] = check_render(None, "perspective", out["render_size"])[2]
    if "horizon" in out:
        out["horizon"] = int(out["horizon"])
    return out


@pytest.mark.parametrize("family", FAMILIES)
@FUZZ
@given(
    seed=layout_seeds,
    level=levels,
    split=splits,
    size=sizes,
    horizon=horizons,
    extra=extras,
)
def test_make_refuses_before_anything_or_gives_the_canonical_env(
    cache: Path, family: str, seed: Any, level: Any, split: Any, size: Any, horizon: Any, extra: Any
) -> None:
    drawn = {"layout_seed": seed, "difficulty": level, "split": split, "render_size": size}
    drawn["horizon"] = horizon
    kwargs = {k: v for k, v in drawn.items() if v is not _MISSING}
    kwargs.update(extra)
    before = _cache_view(cache)
    try:
        env = gym.make(family, disable_env_checker=True, **kwargs).unwrapped
    except ValueError as exc:
        assert str(exc)  # a message
        assert _cache_view(cache) == before, f"refused {kwargs}, yet the cache changed"
        event("refused")
        return
    event("accepted")
    canonical = gym.make(family, disable_env_checker=True, **_canonical(kwargs)).unwrapped
    assert env.scene_identity == canonical.scene_identity
    assert env.config == canonical.config and env.split == canonical.split
    assert env.render_size == canonical.render_size and type(env.render_size[0]) is int
    assert data_equivalence(env.reset(seed=3), canonical.reset(seed=3), exact=True)
    assert env.get_state() == canonical.get_state()


@pytest.fixture(scope="module")
def envs(cache: Path) -> dict[str, Any]:
    return {f: gym.make(f, layout_seed=0, disable_env_checker=True).unwrapped for f in FAMILIES}


reset_seeds = _mostly(
    st.sampled_from([None, 0, 5, np.int64(5)]), st.sampled_from([5.0, True, -1, "5"])
)
option_keys = _mostly(st.just({}), st.sampled_from([{"bogus": 0}, {"seed": 1}]))


@pytest.mark.parametrize("family", FAMILIES)
@FUZZ
@given(
    seed=reset_seeds,
    layout=layout_seeds,
    level=levels,
    extra=option_keys,
    as_list=_mostly(st.just(False), st.just(True)),
)
def test_reset_refuses_before_anything_or_gives_the_canonical_reset(
    cache: Path,
    envs: dict[str, Any],
    family: str,
    seed: Any,
    layout: Any,
    level: Any,
    extra: dict[str, Any],
    as_list: bool,
) -> None:
    env = envs[family]
    env.reset(seed=1, options={"layout_seed": 0, "difficulty": "easy"})
    env.step(env.action_space.sample())
    before, views = env.get_state(), _cache_view(cache)
    options: Any = {
        k: v for k, v in {"layout_seed": layout, "difficulty": level}.items() if v is not _MISSING
    }
    options.update(extra)
    if as_list:
        options = list(options.items())
    try:
        got = env.reset(seed=seed, options=options)
    except ValueError:
        assert env.get_state() == before  # same layout, physics, task and generator
        assert _cache_view(cache) == views
        event("refused")
        return
    event("accepted")
    reference = gym.make(family, disable_env_checker=True, **_canonical(dict(options)))
    canonical_seed = None if seed is None else int(seed)
    want = reference.unwrapped.reset(seed=canonical_seed)
    assert env.scene_identity == reference.unwrapped.scene_identity
    if canonical_seed is not None:  # unseeded resets draw from the generators' own history
        assert data_equivalence(got, want, exact=True)
        assert env.get_state() == reference.unwrapped.get_state()


#: How a snapshot is damaged: (physics index or None, new value or kind of change).
damage = st.one_of(
    st.tuples(
        st.integers(0, 200),
        st.sampled_from([math.nan, math.inf, -math.inf, 1e300, -1e7, 2e6, 0.25, -3.0, 999_999.0]),
    ),
    st.tuples(
        st.none(),
        st.sampled_from(
            [
                "other-layout",
                "other-family",
                "no-scene",
                "float32",
                "list",
                "task-none",
                "rng-none",
                "not-a-state",
                "same",
            ]
        ),
    ),
)


@pytest.mark.parametrize("family", FAMILIES)
@FUZZ
@given(change=damage)
def test_set_state_refuses_before_anything_or_restores_exactly(
    envs: dict[str, Any], family: str, change: tuple[Any, Any]
) -> None:
    env = envs[family]
    other_family = envs[next(f for f in FAMILIES if f != family)]
    env.reset(seed=2, options={"layout_seed": 1, "difficulty": "easy"})
    other_layout = env.get_state()
    env.reset(seed=2, options={"layout_seed": 0, "difficulty": "easy"})
    start = env.get_state()
    env.step(env.action_space.sample())
    before = env.get_state()
    index, value = change
    fields = dict(vars(start))
    if index is not None:
        physics = np.array(start.physics)
        physics[index % physics.size] = value
        physics.setflags(write=False)
        fields["physics"] = physics
    elif value == "other-layout":
        fields["scene"] = other_layout.scene
    elif value == "other-family":
        fields["scene"] = other_family.get_state().scene
    elif value == "no-scene":
        fields["scene"] = None
    elif value == "float32":
        fields["physics"] = start.physics.astype(np.float32)
    elif value == "list":
        fields["physics"] = list(start.physics)
    elif value == "task-none":
        fields["task"] = None
    elif value == "rng-none":
        fields["rng_state"] = None
    state: Any = "a state" if value == "not-a-state" else EnvState(**fields)
    try:
        env.set_state(state)
    except ValueError:
        assert env.get_state() == before
        event("refused")
        return
    event("accepted")
    assert env.get_state() == state  # accepted: exactly the snapshot given
