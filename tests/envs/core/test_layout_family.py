"""Tests of voot.envs.core.family: the generated families as one env a learner trains
across (one observation space, the layout chosen at reset, the split mode)."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import data_equivalence

import voot  # noqa: F401  (registers the ids)
from voot.envs.core.family import LayoutFamily
from voot.envs.core.generation import HELDOUT_LAYOUTS, PROTOCOL_SPLIT, TRAINING_LAYOUTS
from voot.envs.core.names import Difficulty
from voot.problems import problem_record

FAMILIES = ["voot/GeneratedKitchen-v0", "voot/GeneratedStorage-v0"]


def _make(env_id: str, **kwargs: Any) -> Any:
    return gym.make(env_id, **kwargs).unwrapped


@pytest.mark.parametrize("env_id", FAMILIES)
def test_one_observation_space_for_20_layouts_and_every_level(env_id: str) -> None:
    env = _make(env_id)
    space = env.observation_space
    parts = env.observation_layout()
    levels = {(k, Difficulty.EASY) for k in range(20)} | {(1, d) for d in Difficulty}
    for layout, level in sorted(levels):
        obs, info = env.reset(seed=0, options={"layout_seed": layout, "difficulty": level})
        assert (info["layout_seed"], info["difficulty"]) == (layout, level)
        assert env.observation_space == space and space.contains(obs)
        mask = obs[parts["mask"]]
        n = len(env.objects)
        assert mask.tolist() == [1.0] * n + [0.0] * (env.MAX_OBJECTS - n)
        # empty slots are zeros; the base and the task's numbers are the fixed env's
        objects = obs[parts["objects"]].reshape(env.MAX_OBJECTS, env.OBJECT_FIELDS)
        assert not objects[n:].any()
        raw = super(LayoutFamily, env)._observation()  # the scene env's own observation
        assert np.array_equal(obs[parts["base"]], raw[: env.HEAD])
        assert np.array_equal(obs[parts["task"]], raw[-env.TAIL :])
        assert np.array_equal(objects[:n].reshape(-1), raw[env.HEAD : -env.TAIL])


@pytest.mark.parametrize("env_id", FAMILIES)
def test_a_reset_onto_a_layout_is_the_env_made_on_it(env_id: str) -> None:
    """Bit-identical: the reset's observation and info, then every step of the witness
    and the snapshots on the way."""
    made = _make(env_id, layout_seed=3, difficulty="medium")
    switched = _make(env_id, layout_seed=0)
    a = made.reset(seed=7)
    b = switched.reset(seed=7, options={"layout_seed": 3, "difficulty": "medium"})
    assert data_equivalence(a, b, exact=True)
    assert switched.get_state() == made.get_state()
    rng = np.random.default_rng(0)
    for action in made.witness_actions():
        probe = rng.uniform(-1, 1, made.action_space.shape)
        for act in (probe, action):
            before = made.get_state()
            assert data_equivalence(made.step(act), switched.step(act), exact=True)
            if act is probe:  # back, as a search would
                made.set_state(before)
                switched.set_state(before)
    assert switched.get_state() == made.get_state() and made.task.done
    # a reset without options stays on the layout; a bad option is refused, unchanged
    assert switched.reset(seed=1)[1]["layout_seed"] == 3
    with pytest.raises(ValueError, match="reset takes the options layout_seed, difficulty"):
        switched.reset(options={"layout": 4})
    with pytest.raises(ValueError, match="valid levels are"):
        switched.reset(options={"difficulty": "hardest"})
    assert switched.layout_seed == 3


@pytest.mark.parametrize("env_id", FAMILIES)
def test_the_split_mode_draws_its_layouts_by_the_seed(env_id: str) -> None:
    assert problem_record(env_id).layout_split == PROTOCOL_SPLIT
    train = _make(env_id, split="training")
    assert train.layout_seed == TRAINING_LAYOUTS[0]
    drawn = [train.reset(seed=s)[1]["layout_seed"] for s in range(12)]
    drawn += [train.reset()[1]["layout_seed"] for _ in range(12)]  # the seed's stream
    assert set(drawn) <= set(TRAINING_LAYOUTS) and len(set(drawn)) > 5
    again = _make(env_id, split="training")
    assert [again.reset(seed=s)[1]["layout_seed"] for s in range(12)] == drawn[:12]
    # the episode is the one of an env made on the drawn layout (np_random untouched)
    obs, info = train.reset(seed=4)
    made = _make(env_id, layout_seed=info["layout_seed"])
    assert data_equivalence((obs, info), made.reset(seed=4), exact=True)
    heldout = _make(env_id, split="heldout")
    assert {heldout.reset(seed=s)[1]["layout_seed"] for s in range(8)} <= set(HELDOUT_LAYOUTS)
    with pytest.raises(ValueError, match="layout_seed 3 is not a training layout"):
        train.reset(options={"layout_seed": 3})
    with pytest.raises(ValueError, match="valid splits are: training, heldout"):
        _make(env_id, split="test")


def test_a_vector_env_trains_across_the_training_layouts() -> None:
    envs = gym.make_vec(
        "voot/GeneratedStorage-v0", num_envs=2, vectorization_mode="sync", split="training"
    )
    envs.action_space.seed(0)
    _, info = envs.reset(seed=0)
    layouts = set(info["layout_seed"].tolist())
    for _ in range(60):  # the horizon is 20: every env autoresets onto a new draw
        _, _, _, _, info = envs.step(envs.action_space.sample())
        layouts |= set(info["layout_seed"].tolist())
    assert layouts <= set(TRAINING_LAYOUTS) and len(layouts) > 2
    envs.close()


@pytest.mark.parametrize("env_id", FAMILIES)
def test_a_seeded_action_space_keeps_its_stream_across_layouts(env_id: str) -> None:
    # one space object for the env's life: seeding it once makes random actions
    # reproducible whatever layouts the resets go to
    def draws() -> list[np.ndarray]:
        env = _make(env_id)
        env.action_space.seed(5)
        spaces = {id(env.action_space), id(env.observation_space)}
        out = []
        for layout in (1, 2, 1):
            env.reset(seed=0, options={"layout_seed": layout})
            spaces |= {id(env.action_space), id(env.observation_space)}
            out.append(env.action_space.sample())
        assert len(spaces) == 2
        return out

    first, second = draws(), draws()
    assert all(np.array_equal(a, b) for a, b in zip(first, second, strict=True))
    assert not np.array_equal(first[0], first[2])  # one stream, not re-seeded per layout


# ----- a state knows its scene ----------------------------------------------------------
def _same_size_layout(env_id: str, first: int) -> tuple[Any, Any]:
    """Two envs of different layouts whose states have the same size (the same object
    count), found by the generator (not hard-coded)."""
    a = _make(env_id, layout_seed=first)
    for k in range(first + 1, first + 40):
        b = _make(env_id, layout_seed=k)
        if b._state_size == a._state_size and len(b.objects) == len(a.objects):
            return a, b
    raise AssertionError("no layout of the same size")  # pragma: no cover


@pytest.mark.parametrize("env_id", FAMILIES)
def test_a_state_of_another_layout_of_the_same_size_is_refused(env_id: str) -> None:
    """Before, only the signature and the vector's size were checked: another layout's
    state with as many objects was taken (and the next step read the wrong scene)."""
    import copy
    import pickle

    a, b = _same_size_layout(env_id, 1)
    a.reset(seed=0)
    b.reset(seed=0)
    theirs = a.get_state()
    before = b.get_state()
    obs = b._observation()
    with pytest.raises(ValueError, match="state belongs to another scene") as err:
        b.set_state(theirs)
    message = str(err.value)
    assert f"layout_seed={a.layout_seed}" in message and f"layout_seed={b.layout_seed}" in message
    assert b.get_state() == before and np.array_equal(b._observation(), obs)  # unchanged
    # the identity names what made the state
    ident = theirs.scene
    assert (ident.layout_seed, ident.difficulty) == (a.layout_seed, "easy")
    assert ident.version == f"generator-{a.GENERATOR_VERSION}" and ident.family == a.family
    # pickled and copied states keep working, in another env of the same layout too
    twin = _make(env_id, layout_seed=a.layout_seed)
    for state in (pickle.loads(pickle.dumps(theirs)), copy.deepcopy(theirs)):
        twin.set_state(state)
        assert twin.get_state() == theirs


def test_a_fixed_v1_state_is_refused_by_a_generated_room_of_its_size() -> None:
    fixed = _make("voot/ConveyorPacking-v1")
    for k in range(10, 60):  # a hard room of 20 boxes, as v1's belt (found, not hard-coded)
        room = _make("voot/GeneratedStorage-v0", layout_seed=k, difficulty="hard")
        if room._state_size == fixed._state_size:
            break
    else:  # pragma: no cover - the generator has hard rooms of 20 boxes
        raise AssertionError("no generated room of the v1 state size in hard layouts 10-59")
    fixed.reset(seed=0)
    room.reset(seed=0)
    before = room.get_state()
    with pytest.raises(ValueError, match=r"made by conveyor \(fixed scene"):
        room.set_state(fixed.get_state())
    assert room.get_state() == before


@pytest.mark.parametrize("env_id", FAMILIES)
def test_a_reset_onto_another_layout_changes_the_identity(env_id: str) -> None:
    env = _make(env_id, layout_seed=0)
    old = env.get_state()
    env.reset(seed=0, options={"layout_seed": 2, "difficulty": "medium"})
    assert (env.scene_identity.layout_seed, env.scene_identity.difficulty) == (2, "medium")
    with pytest.raises(ValueError, match="state belongs to another scene"):
        env.set_state(old)
    env.reset(seed=0, options={"layout_seed": 0, "difficulty": "easy"})
    env.set_state(old)  # the same layout again: the same identity


@pytest.mark.parametrize("env_id", ["voot/GeneratedKitchen-v0", "voot/GeneratedStorage-v0"])
def test_a_bad_mujoco_cache_capacity_is_refused_before_any_generation(
    env_id: str, tmp_path: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``$VOOT_MUJOCO_CACHE_MB`` (voot.envs.core.caches.generated_compile) is checked
    with the arguments: a bad value is refused naming it, nothing generated or cached."""
    cache = tmp_path / "cache"
    monkeypatch.setenv("VOOT_CACHE", str(cache))
    monkeypatch.setenv("VOOT_MUJOCO_CACHE_MB", "lots")
    with pytest.raises(ValueError, match="VOOT_MUJOCO_CACHE_MB='lots'"):
        gym.make(env_id, layout_seed=987)
    assert not cache.exists()
    import mujoco

    before = mujoco.mj_getCacheCapacity(mujoco.mj_getCache())
    monkeypatch.setenv("VOOT_MUJOCO_CACHE_MB", "0")
    try:
        assert gym.make(env_id, layout_seed=987).unwrapped.layout_seed == 987
    finally:
        mujoco.mj_setCacheCapacity(mujoco.mj_getCache(), before)
