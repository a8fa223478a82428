"""Tests of the gymnasium ids (voot._registration, from the families' problem records):
every id, its record, its spec metadata, the old names kept as aliases, vector envs of
every id, and copies of its env.

A copy of an env (``copy.deepcopy``, or ``pickle`` in this process or another) must step
as the env: from the same snapshot, the same action gives bit-identical observation,
reward, flags and info. Each env is copied mid-episode, its caches warm (the kitchen with
an object in the gripper, whose collision filter a check switches), then the original
and each copy replay the same probes: their next action from where they stand, then
every probe action from each snapshot of the walk that led there.
"""

from __future__ import annotations

import copy
import inspect
import pickle
import subprocess
import sys
import textwrap
import warnings
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import data_equivalence

import voot  # noqa: F401  (registers the ids)
from voot import _registration
from voot.problems import ProblemRecord, problem_record, problem_records

#: The current ids (the old names kept as aliases apart).
IDS = sorted(r.id for r in problem_records() if r.renamed_to is None)
#: The old names: old id -> new id.
RENAMED = {r.id: r.renamed_to for r in problem_records() if r.renamed_to is not None}


def test_every_id_is_registered_with_its_entry_point_kwargs_and_metadata() -> None:
    assert len(IDS) == 10
    assert RENAMED == {
        "voot/KitchenClearing-v2": "voot/GeneratedKitchen-v0",
        "voot/ConveyorPacking-v2": "voot/GeneratedStorage-v0",
    }
    for env_id in [*IDS, *RENAMED]:
        spec = gym.spec(env_id)
        record = problem_record(env_id)
        assert spec.entry_point == record.entry_point
        assert spec.kwargs == dict(record.kwargs)
        assert spec.max_episode_steps == record.max_episode_steps
        assert spec.reward_threshold == record.reward_threshold is None
        for alias in record.aliases:
            assert problem_record(alias) is record
            assert problem_record(alias.upper().replace("_", "-")) is record


@pytest.mark.parametrize("env_id", IDS)
def test_the_episode_limit_is_the_domains_and_check_env_is_clean(env_id: str) -> None:
    """``max_episode_steps`` is the config's horizon (the chains have none), gymnasium's
    checker finds nothing, and making the id warns of nothing (no "out of date").

    The chains keep two advice lines of the checker: their action box is the test
    function's (the paper's), and their observation (the feasible actions so far) has
    no upper bound."""
    from gymnasium.utils.env_checker import check_env

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = gym.make(env_id)
        check_env(env.unwrapped, skip_render_check=True)
    advice = ("we recommend using a symmetric and normalized space", "maximum value is infinity")
    chain = "Chain" in env_id
    assert [
        str(w.message) for w in caught if not (chain and any(a in str(w.message) for a in advice))
    ] == []
    limit = gym.spec(env_id).max_episode_steps
    config = getattr(env.unwrapped, "config", None)
    assert limit == (None if config is None else config.horizon)
    env.close()


def test_an_old_name_warns_once_naming_the_new_id_and_makes_its_env() -> None:
    _registration._WARNED.clear()
    for old, new in RENAMED.items():
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            envs = [gym.make(old, layout_seed=1), gym.make(old, layout_seed=1)]
        messages = [str(w.message) for w in caught]
        assert len(messages) == 1 and new in messages[0] and old in messages[0], messages
        assert caught[0].category is FutureWarning
        fresh = gym.make(new, layout_seed=1)
        assert type(envs[0].unwrapped) is type(fresh.unwrapped)
        assert envs[0].spec is not None and envs[0].spec.id == old
        assert data_equivalence(envs[0].reset(seed=0), fresh.reset(seed=0), exact=True)
        # the same planner settings (the committed results name the old id)
        a, b = problem_record(old), problem_record(new)
        assert a.discount == b.discount and a.root_commitment == b.root_commitment
        assert a.voo_options == b.voo_options and a.layout_split == b.layout_split
        assert problem_record(f"{a.aliases[0]}") is a
        for env in [*envs, fresh]:
            env.close()


def _kind(value: Any) -> Any:
    """How gymnasium's vector envs stack an info value (``VectorEnv._add_info``): an
    array by its shape and dtype, a number by its type, anything else as an object."""
    if isinstance(value, dict):
        return {k: _kind(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return ("array", value.shape, value.dtype.str)
    if type(value) in (int, float, bool) or isinstance(value, np.number):
        return ("number", type(value).__name__)
    return "object"


@pytest.mark.parametrize("env_id", IDS)
def test_every_info_has_the_same_keys_shapes_and_dtypes(env_id: str) -> None:
    """The reset's and every step's, feasible or not, at every node, to the end (the
    known solution of the robot envs, then random actions)."""
    env = gym.make(env_id)
    _, info = env.reset(seed=0)
    kinds = _kind(info)
    u = env.unwrapped
    actions = list(u.solution_actions()) if hasattr(u, "solution_actions") else []
    env.action_space.seed(1)
    actions += [env.action_space.sample() for _ in range(60)]
    ended = 0
    for a in actions:
        _, _, terminated, truncated, info = env.step(a)
        assert _kind(info) == kinds, env_id
        if terminated or truncated:
            ended += 1
            _, info = env.reset()
            assert _kind(info) == kinds
    assert ended >= 1
    env.close()


@pytest.mark.parametrize("mode", ["sync", "async"])
@pytest.mark.parametrize("env_id", IDS)
def test_a_vector_env_of_every_id_steps_through_episode_ends(env_id: str, mode: str) -> None:
    """200 random steps of 2 envs (gymnasium's default autoreset: the step after an
    episode's end resets that env)."""
    envs = gym.make_vec(env_id, num_envs=2, vectorization_mode=mode)
    envs.action_space.seed(0)
    obs, info = envs.reset(seed=0)
    assert obs.shape == (2, *envs.single_observation_space.shape)
    ended = np.zeros(2, dtype=bool)
    autoresets = 0
    for _ in range(200):
        obs, reward, terminated, truncated, info = envs.step(envs.action_space.sample())
        autoresets += int(ended.sum())
        assert (reward[ended] == 0.0).all()  # an autoreset step
        ended = terminated | truncated
        assert envs.single_observation_space.contains(obs[0])
        assert set(info) >= {"feasible", "_feasible"}
    assert autoresets >= 2, env_id
    envs.close()


def test_a_record_is_checked_when_built() -> None:
    entry = "voot.envs.kitchen.env:KitchenClearingEnv"
    with pytest.raises(ValueError, match="namespace/Name-vN"):
        ProblemRecord(id="Kitchen", family="kitchen", entry_point=entry)
    with pytest.raises(ValueError, match="module:Class"):
        ProblemRecord(id="x/Y-v0", family="kitchen", entry_point="kitchen")
    with pytest.raises(ValueError, match="root_commitment"):
        ProblemRecord(id="x/Y-v0", family="kitchen", entry_point=entry, v1_rules=True)
    with pytest.raises(ValueError, match="'hardest' is not a valid Difficulty"):
        ProblemRecord(
            id="x/Y-v0", family="k", entry_point=entry, layouts=True, difficulties=("hardest",)
        )
    with pytest.raises(ValueError, match="layouts"):
        ProblemRecord(id="x/Y-v0", family="k", entry_point=entry, difficulties=("easy",))
    with pytest.raises(KeyError, match="no problem record for 'nope'; recorded: voot/"):
        problem_record("nope")
    record = problem_record("kitchen_v2")
    assert record.layouts and record.difficulties == ("easy", "medium", "hard")
    with pytest.raises(TypeError):
        record.kwargs["preset"] = "v0"  # type: ignore[index]


def _walk(env_id: str) -> tuple[Any, list[Any], list[list[np.ndarray]]]:
    """``env_id`` made and walked a few steps; the snapshots on the way, the probes of
    each, and the walk's next action last (the first thing a replay takes)."""
    env = gym.make(env_id)
    env.reset(seed=3)
    u = env.unwrapped
    rng = np.random.default_rng(11)
    space = env.action_space
    lo, hi = space.low, space.high
    if env_id == "voot/GeneratedKitchen-v0":  # a generated kitchen: its witness plan
        script = u.witness_actions()[:4]
    elif env_id.startswith("voot/KitchenClearing"):
        from voot.envs.kitchen.scripted import kitchen_actions

        script = kitchen_actions(u)[:4]  # pick, place, pick: then an object is held
    elif hasattr(u, "witness_actions"):  # a generated layout: the packing that proves it
        script = u.witness_actions()[:3]
    elif env_id.startswith("voot/ConveyorPacking"):
        from voot.envs.conveyor.scripted import conveyor_actions

        script = conveyor_actions(u)[:3]
    else:
        script = [rng.uniform(lo, hi) for _ in range(4)]
    states, probes = [], []
    for a in script[:-1]:
        states.append(u.get_state())
        near = [np.clip(a + rng.normal(0.0, 0.05 * (hi - lo), a.shape), lo, hi) for _ in range(2)]
        probes.append([a, *near, rng.uniform(lo, hi)])
        env.step(a)
    probes.append([script[-1]])
    return env, states, probes


def _replay(env: Any, states: list[Any], probes: list[list[Any]]) -> list[Any]:
    """The steps of ``env``: the last probe from where it stands, then every probe of
    each snapshot from that snapshot (in the child process too: sent as source)."""
    out = [env.step(probes[-1][0])]
    for state, actions in zip(states, probes, strict=False):
        for a in actions:
            env.unwrapped.set_state(state)
            out.append(env.step(a))
    return out


def test_copies_of_every_env_step_as_the_env_also_in_another_process() -> None:
    cases, copies, blobs = {}, {}, {}
    for env_id in IDS:
        env, states, probes = _walk(env_id)
        blobs[env_id] = pickle.dumps(env)
        copies[env_id] = [copy.deepcopy(env), pickle.loads(blobs[env_id])]
        cases[env_id] = (env, states, probes)
    child = textwrap.dedent(inspect.getsource(_replay)) + textwrap.dedent(
        """
        import pickle, sys
        import voot
        cases = pickle.load(sys.stdin.buffer)
        out = {k: _replay(pickle.loads(blob), s, p) for k, (blob, s, p) in cases.items()}
        sys.stdout.buffer.write(pickle.dumps(out))
        """
    )
    payload = {k: (blobs[k], cases[k][1], cases[k][2]) for k in IDS}
    proc = subprocess.run(
        [sys.executable, "-c", f"from typing import Any\n{child}"],
        input=pickle.dumps(payload),
        capture_output=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr.decode()[-2000:]
    remote = pickle.loads(proc.stdout)
    for env_id in IDS:
        env, states, probes = cases[env_id]
        local = _replay(env, states, probes)
        for how, steps in [
            ("deepcopy", _replay(copies[env_id][0], states, probes)),
            ("pickle", _replay(copies[env_id][1], states, probes)),
            ("pickle, another process", remote[env_id]),
        ]:
            assert len(steps) == len(local)
            for k, (a, b) in enumerate(zip(local, steps, strict=True)):
                assert data_equivalence(a, b, exact=True), (env_id, how, k, a[1:], b[1:])
        if "Chain" not in env_id:  # the probes meet feasible and infeasible actions
            feasible = [s[4]["feasible"] for s in local]
            assert any(feasible) and not all(feasible), (env_id, feasible)


def test_a_copy_made_after_rendering_renders_the_same() -> None:
    """The renderer (an OpenGL context) is not copied: a copy opens its own."""
    env = gym.make("voot/KitchenClearing-v1", render_mode="rgb_array", render_size=(64, 48))
    env.reset(seed=0)
    image = env.render()
    for twin in (copy.deepcopy(env), pickle.loads(pickle.dumps(env))):
        assert twin.unwrapped._renderer is None
        assert np.array_equal(twin.render(), image)
        twin.close()
    env.close()
