"""The shared env base (voot.envs.core.env): snapshots restored all or nothing, the
task-record check on restore, action validation, the footprints' memory."""

from __future__ import annotations

import dataclasses
import pickle
from typing import Any

import numpy as np
import pytest

from voot.envs.kitchen.env import KitchenClearingEnv


@pytest.fixture(scope="module")
def kitchen() -> KitchenClearingEnv:
    return KitchenClearingEnv()


def test_snapshots_share_the_unchanged_generator_state(kitchen: KitchenClearingEnv) -> None:
    kitchen.reset(seed=1)
    a, b = kitchen.get_state(), kitchen.get_state()
    assert a.rng_state is b.rng_state and a == b
    kitchen.np_random.random()  # someone draws: the next snapshot has its own state
    c = kitchen.get_state()
    assert c.rng_state is not a.rng_state and c.rng_state != a.rng_state
    kitchen.set_state(a)
    assert kitchen.np_random.bit_generator.state == a.rng_state
    assert kitchen.get_state().rng_state is a.rng_state
    # snapshots still pickle and compare by value
    assert pickle.loads(pickle.dumps(a)) == a
    # another bit generator: deep copies as before
    kitchen.np_random = np.random.Generator(np.random.MT19937(3))
    s1, s2 = kitchen.get_state(), kitchen.get_state()
    assert s1.rng_state is not s2.rng_state
    kitchen.np_random.random()
    kitchen.set_state(s1)
    assert kitchen.np_random.random() == np.random.Generator(np.random.MT19937(3)).random()
    kitchen.reset(seed=0)


def test_validate_action_fast_path(kitchen: KitchenClearingEnv) -> None:
    a = np.array([0.5, -1.0, 1.0, 0.0, -0.25, 0.75])
    out, clipped = kitchen._validate_action(a)
    assert not clipped and out.tobytes() == a.tobytes() and out is not a
    out, clipped = kitchen._validate_action(a * 1.5)
    assert clipped and out.max() == 1.0 and out.min() == -1.0
    for bad in (
        np.full(6, np.nan),
        np.array([0.5, np.nan, 0, 0, 0, 0]),
        np.array([0, 0, 0, 0, 0, np.inf]),
    ):
        with pytest.raises(ValueError, match="NaN"):
            kitchen._validate_action(bad)


# ----- set_state: the whole snapshot is checked, then applied (all or nothing) ----------
def _bad_snapshots(env: Any, other: Any) -> list[tuple[Any, str]]:
    from voot.envs.core.state import EnvState

    s = env.get_state()
    nan_physics = s.physics.copy()
    nan_physics[3] = np.nan
    inf_physics = s.physics.copy()
    inf_physics[-1] = -np.inf
    huge_physics = s.physics.copy()
    huge_physics[1] = 1e300  # finite, but the next step would overflow
    rng_missing = {k: v for k, v in s.rng_state.items() if k != "uinteger"}
    rng_overflow = {**s.rng_state, "state": {"state": -1, "inc": 5}}

    def with_(**fields: Any) -> Any:
        return EnvState(**{**vars(s), **fields})

    return [
        (with_(physics=nan_physics), r"state\.physics must be finite and within .*, got nan"),
        (with_(physics=inf_physics), r"state\.physics must be finite and within .*, got -inf"),
        (with_(physics=huge_physics), r"state\.physics must be finite and within .*, got 1e\+300"),
        (with_(scene=other.get_state().scene), "state belongs to another scene"),
        (with_(scene=None), "carries no scene identity"),
        (with_(physics=list(s.physics)), "state does not fit this environment"),
        (with_(task=other.get_state().task), rf"state\.task must be a {type(s.task).__name__}"),
        (with_(task=None), "got NoneType"),
        (with_(rng_state={"bit_generator": "MT19937"}), r"state\.rng_state is not a state"),
        (with_(rng_state=None), r"state\.rng_state is not a state"),
        (with_(rng_state=rng_missing), r"state\.rng_state is not a state"),
        (with_(rng_state=rng_overflow), r"state\.rng_state is not a state"),
    ]


@pytest.mark.parametrize("which", ["kitchen", "conveyor"])
def test_set_state_refuses_a_bad_snapshot_and_changes_nothing(which: str) -> None:
    from voot.envs.conveyor.env import ConveyorPackingEnv

    kitchen, conveyor = KitchenClearingEnv(), ConveyorPackingEnv()
    env, other = (kitchen, conveyor) if which == "kitchen" else (conveyor, kitchen)
    env.reset(seed=5)
    other.reset(seed=5)
    start = env.get_state()
    action = np.zeros(env.action_space.shape)
    env.step(action)  # the env is elsewhere, so that a half restore would show
    here = env.get_state()
    obs_here = env._observation()
    rng_here = env.np_random.bit_generator.state
    for bad, match in _bad_snapshots(env, other):
        with pytest.raises(ValueError, match=match):
            env.set_state(bad)
        assert env.get_state() == here
        assert env.np_random.bit_generator.state == rng_here
        assert np.array_equal(env._observation(), obs_here)
    env.set_state(start)  # a good snapshot still restores exactly
    assert env.get_state() == start


def test_a_fixed_scene_state_names_its_family_and_the_physics_bound() -> None:
    from voot.envs.conveyor.env import ConveyorPackingEnv
    from voot.envs.core.env import MAX_PHYSICS
    from voot.envs.core.state import EnvState

    for env, family in ((KitchenClearingEnv(), "kitchen"), (ConveyorPackingEnv(), "conveyor")):
        env.reset(seed=0)
        s = env.get_state()
        assert s.scene is env.scene_identity
        assert (s.scene.family, s.scene.version, s.scene.layout_seed) == (family, "", None)
        for value, ok in ((MAX_PHYSICS, True), (-MAX_PHYSICS, True), (MAX_PHYSICS * 1.001, False)):
            physics = s.physics.copy()
            physics[0] = value  # the time: any value within the bound is a state
            state = EnvState(**{**vars(s), "physics": physics})
            if ok:
                env.set_state(state)
                assert env.get_state() == state
            else:
                with pytest.raises(ValueError, match=r"within \+-1e\+06"):
                    env.set_state(state)
        env.set_state(s)


def test_plain_action_is_the_validated_action_or_none(kitchen: KitchenClearingEnv) -> None:
    a = np.linspace(-1.0, 1.0, kitchen.action_dim)
    assert kitchen._plain_action(a) is a
    assert np.array_equal(kitchen._validate_action(a)[0], a)
    for bad in (a * 2.0, np.full(kitchen.action_dim, np.nan), a[:3], a.astype(np.float32), list(a)):
        assert kitchen._plain_action(bad) is None  # left to the step (clipped or refused)


def test_object_boxes_follow_the_state(kitchen: KitchenClearingEnv) -> None:
    """The remembered footprints are those of the current qpos (and of the exclusion)."""
    kitchen.reset(seed=0)
    s = kitchen.get_state()
    boxes = kitchen.object_boxes()
    assert kitchen.object_boxes() == boxes and kitchen.object_boxes(exclude=(0,)) == boxes[1:]
    adr = kitchen.objects[0].qpos_adr
    kitchen.data.qpos[adr] += 0.25  # moved behind the env's back: a new footprint
    moved = kitchen.object_boxes()
    assert abs(moved[0].cx - (boxes[0].cx + 0.25)) < 1e-12 and moved[1:] == boxes[1:]
    kitchen.set_state(s)
    assert kitchen.object_boxes() == boxes


# ----- set_state: a task record no episode reaches is refused (issue 27) ---------------
def _impossible_tasks(which: str) -> tuple[Any, list[tuple[Any, Any, str]]]:
    """An env, and (snapshot, task record no episode of it reaches, error) triples."""
    from voot.envs.conveyor.env import ConveyorPackingEnv
    from voot.envs.kitchen.scripted import kitchen_actions

    R = dataclasses.replace
    if which == "conveyor":
        env = ConveyorPackingEnv()
        env.reset(seed=0)
        s = env.get_state()
        t = s.task
        return env, [
            (s, R(t, steps=-1), r"steps must be an int in 0\.\.20 \(the horizon\), got -1"),
            (s, R(t, steps=21), "got 21"),
            (s, R(t, steps=np.int64(2)), "steps must be an int"),
            (s, R(t, placed=env.n + 1), rf"placed must be an int in 0\.\.{env.n} \(the boxes\)"),
            (s, R(t, placed=-3), "placed must be"),
            (s, R(t, done=True), "done must be False when placed is 0, got True"),
            (s, R(t, placed=env.n), f"done must be True when placed is {env.n}, got False"),
        ]
    env = KitchenClearingEnv()
    env.reset(seed=0)
    pick = env.get_state()
    _, _, _, _, info = env.step(kitchen_actions(env)[0])
    assert info["feasible"] and env.task.operator == "place"
    place = env.get_state()
    p, q = pick.task, place.task
    n = len(env.objects)
    first, second = p.on_path[:2]
    return env, [
        (pick, R(p, operator="drop"), "operator must be 'pick' or 'place', got 'drop'"),
        (pick, R(p, held=2), r"held must be -1 before a pick \(nothing in the gripper\), got 2"),
        (place, R(q, held=n), rf"held must be an object index in 0\.\.{n - 1} before a place"),
        (place, R(q, held=-3), "before a place, got -3"),
        (place, R(q, held=True), "before a place, got True"),
        (place, R(q, grasp_q=()), "grasp_q must be 7 finite joint values at a place, got ()"),
        (place, R(q, grasp_q=(*q.grasp_q[:6], np.nan)), "grasp_q must be 7"),
        (place, R(q, held_rel=(0.0, np.inf, 0.0)), r"held_rel must be 3 finite numbers"),
        (place, R(q, held_rel=None), "held_rel must be"),
        (pick, R(p, on_path=(n,)), rf"on_path must be a tuple of object indices in 0\.\.{n - 1}"),
        (pick, R(p, on_path=[first]), "on_path must be a tuple"),
        (pick, R(p, on_path=(second, first)), "on_path must list distinct objects in the"),
        (pick, R(p, on_path=(first, first)), "handling order"),
        (pick, R(p, on_path=()), r"done must be True when on_path is \(\), got False"),
        (pick, R(p, done=True), "done must be False"),
        (pick, R(p, last_place_cleared=1), "last_place_cleared and done must be bools"),
        (pick, R(p, last_place_cleared=True), "last_place_cleared can be True only after"),
        (pick, R(p, held_rel=(0.1, 0.0, 0.0)), "held_rel and grasp_q must be .* before a pick"),
        (pick, R(p, held_rel="x"), "held_rel and grasp_q must be"),
        (pick, R(p, held_rel=np.zeros(3)), "held_rel and grasp_q must be"),
        (pick, R(p, grasp_q=q.grasp_q), "held_rel and grasp_q must be"),
        (pick, R(p, grasp_q=None), "held_rel and grasp_q must be"),
        (pick, R(p, steps=-1), r"steps must be an int in 0\.\.50 \(the horizon\), got -1"),
        (pick, R(p, steps=51), "got 51"),
    ]


@pytest.mark.parametrize("which", ["kitchen", "conveyor"])
def test_set_state_refuses_a_task_record_no_episode_reaches(which: str) -> None:
    """Checked on restore, before anything changes (the next step failed deep inside
    with an IndexError or a broadcast error, or handled the wrong object)."""
    env, cases = _impossible_tasks(which)
    here = env.get_state()
    obs_here = env._observation()
    for snapshot, task, match in cases:
        bad = snapshot.with_task(task)
        with pytest.raises(ValueError, match=match) as err:
            env.set_state(bad)
        assert "this environment can reach" in str(err.value)
        assert str(err.value).endswith("the env is unchanged")
        assert env.get_state() == here
        assert np.array_equal(env._observation(), obs_here)
        with pytest.raises(ValueError, match=match):  # refused again: not remembered
            env.set_state(bad)
    for snapshot, _, _ in cases:  # the records episodes reach still restore
        env.set_state(snapshot)
        assert env.get_state() == snapshot


def test_set_state_checks_each_task_record_once(kitchen: KitchenClearingEnv) -> None:
    """A search restores each snapshot many times: the record's check runs once."""
    kitchen.reset(seed=0)
    a = kitchen.get_state()
    kitchen.step(np.zeros(6))
    b = kitchen.get_state()
    seen: list[Any] = []
    check = kitchen._task_error

    def counting(task: Any) -> str | None:
        seen.append(task)
        return check(task)

    kitchen._task_error = counting  # type: ignore[method-assign]
    try:
        for _ in range(3):
            kitchen.set_state(a)
            kitchen.set_state(b)
        # an equal record that is another object is checked (the memo is by identity)
        kitchen.set_state(a.with_task(dataclasses.replace(a.task)))
    finally:
        del kitchen._task_error
    assert [t is a.task for t in seen] == [True, False, False]
    assert seen[1] is b.task and seen[2] == a.task
    kitchen.reset(seed=0)


# ----- bad input to the v1 envs' public entries (issue 26) ------------------------------
def _bits(env: Any) -> tuple[bytes, Any, Any]:
    """The env's state, bit for bit: physics bytes, task record, generator state."""
    s = env.unwrapped.get_state()
    return s.physics.tobytes(), s.task, env.unwrapped.np_random.bit_generator.state


def _bad_actions(d: int) -> list[tuple[Any, str]]:
    """Actions of a ``d``-D env that must be refused, and the error each gets."""
    numeric = "must be numeric, real numbers"
    return [
        (np.zeros(d, dtype=bool), numeric),
        (np.array(["0.1"] * d), numeric),  # numpy would parse the strings
        (["0.1"] * d, numeric),
        (np.full(d, 0.1, dtype=object), numeric),
        (np.full(d, 0.1 + 0.5j), numeric),  # numpy would drop the imaginary part
        (np.zeros(d, dtype=complex), numeric),
        (None, numeric),
        ({"a": 1}, numeric),
        ([0.0] * (d - 1) + [[0.0]], numeric),  # ragged
        (np.full(d, np.nan), "NaN or infinite entries"),
        (np.r_[np.zeros(d - 1), -np.inf], rf"NaN or infinite entries at indices \[{d - 1}\]"),
        (np.array(0.1), rf"shape \({d},\)"),
        (np.zeros((1, d)), rf"shape \({d},\)"),
        (np.zeros(d - 1), rf"shape \({d},\)"),
        (np.zeros(d + 1), rf"shape \({d},\)"),
    ]


@pytest.mark.parametrize("env_id", ["voot/KitchenClearing-v1", "voot/ConveyorPacking-v1"])
def test_v1_entries_refuse_bad_actions_before_any_change(env_id: str) -> None:
    """step, transition and precheck: a clear error naming the shape, nothing changed
    (bools, strings, objects and complex numbers used to be read as numbers)."""
    import gymnasium as gym

    env = gym.make(env_id, disable_env_checker=True)
    env.reset(seed=3)
    u: Any = env.unwrapped
    d = u.action_dim
    before = _bits(env)
    for action, match in _bad_actions(d):
        for entry in (env.step, u.transition, u.precheck):
            with pytest.raises(ValueError, match=match):
                entry(action)
            assert _bits(env) == before, (entry, action)
        assert u.certainly_infeasible(action) is False  # the pre-screen leaves them to the step
    # real numbers of any width still step, as float64 would
    ints = env.step(np.zeros(d, dtype=np.int32))[1:4]
    env.reset(seed=3)
    assert env.step(np.zeros(d))[1:4] == ints


@pytest.mark.parametrize("env_id", ["voot/KitchenClearing-v1", "voot/ConveyorPacking-v1"])
def test_v1_reset_refuses_bad_seeds_and_options_before_any_change(env_id: str) -> None:
    """The options used to be refused after the seed had reseeded the generator."""
    import gymnasium as gym

    env = gym.make(env_id, disable_env_checker=True)
    env.reset(seed=3)
    env.step(np.zeros(env.unwrapped.action_dim))  # away from the reset state
    before = _bits(env)
    for options, match in [
        ({"x": 1}, r"reset takes no options \(None or \{\}\), got \['x'\]"),
        ({1: 2}, "reset takes no options"),
        ("str", "got 'str'"),
        (3, "got 3"),
    ]:
        with pytest.raises(ValueError, match=match):
            env.reset(seed=5, options=options)
        assert _bits(env) == before
    for seed in (-1, 1.5, "7", True, [1, 2]):
        with pytest.raises(ValueError, match="seed must be an integer >= 0 or None"):
            env.reset(seed=seed)
        assert _bits(env) == before
    # numpy's integers are integers; an empty options mapping is no option
    env.reset(seed=np.int64(5), options={})
    after_np = _bits(env)
    assert after_np != before
    env.reset(seed=5)
    assert _bits(env) == after_np


def test_v1_set_state_of_the_other_domain_or_version() -> None:
    """Another domain's snapshot is refused whole; a v0 snapshot of the same domain is
    a state of the same scene and task record, so v1 restores it (the checks are of the
    scene and the record, not of the version that reached it), exactly."""
    import gymnasium as gym

    kitchen = gym.make("voot/KitchenClearing-v1", disable_env_checker=True).unwrapped
    conveyor = gym.make("voot/ConveyorPacking-v1", disable_env_checker=True).unwrapped
    v0 = gym.make("voot/KitchenClearing-v0", disable_env_checker=True).unwrapped
    for env, other in ((kitchen, conveyor), (conveyor, kitchen)):
        env.reset(seed=1)
        other.reset(seed=1)
        before = _bits(env)
        with pytest.raises(ValueError, match="state belongs to another scene"):
            env.set_state(other.get_state())
        assert _bits(env) == before
    kitchen.reset(seed=2)
    own = kitchen.get_state()
    v0.reset(seed=2)
    kitchen.step(np.zeros(6))
    kitchen.set_state(v0.get_state())
    assert kitchen.get_state() == own
