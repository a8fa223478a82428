"""voot/GeneratedStorage-v0: the v1 conveyor on generated, solvable storage rooms."""

from __future__ import annotations

import copy
import pickle
import textwrap
from collections.abc import Iterator
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from env_fixtures import IMPORT_IN_CHILD, step_probes
from gymnasium.utils.env_checker import check_env, data_equivalence
from process_fixtures import run_pickled

import voot  # noqa: F401  (registers the ids)
from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.generated import instance as SI
from voot.envs.conveyor.generated.env import ConveyorFamilyEnv, witness_return
from voot.envs.core.problem import EnvProblem


@pytest.fixture(autouse=True)
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    monkeypatch.setenv("VOOT_CACHE", str(tmp_path))
    SI.clear_memo()
    yield tmp_path
    SI.clear_memo()


def _make(seed: int = 0, difficulty: str = "easy", **kw: object) -> ConveyorFamilyEnv:
    env = gym.make("voot/GeneratedStorage-v0", layout_seed=seed, difficulty=difficulty, **kw)
    u = env.unwrapped
    assert isinstance(u, ConveyorFamilyEnv)
    return u


def test_check_env_and_the_v1_rules_on_the_layout() -> None:
    env = _make(1, "medium")
    check_env(env, skip_render_check=True)
    assert isinstance(env, ConveyorPackingEnv) and env.config.precheck == "kinematic"
    assert env.config.loading_region == env.layout.loading_region
    assert env.config.workspace == env.layout.workspace
    assert env.n == env.layout.n_boxes == len(env.objects)
    # the family's one space: 20 box slots and their mask, whatever the layout
    assert env.observation_space.shape == (4 + 5 * 20 + 2 + 20,)
    _, info = env.reset(seed=0)
    assert info["layout_seed"] == 1 and info["difficulty"] == "medium"
    assert info["objects_left"] == env.n
    assert (env.layout_seed, env.difficulty) == (1, "medium")


@pytest.mark.parametrize("difficulty", ["easy", "medium", "hard"])
def test_the_witness_solves_the_env_and_passes_the_precheck(difficulty: str) -> None:
    env = _make(2, difficulty)
    env.reset(seed=0)
    problem = EnvProblem(env)
    for a in env.witness_actions():
        assert problem.is_feasible(a)
        res = problem.step(a)
        assert res.feasible, res.info["reason"]
    assert res.terminal and env.objects_left == 0
    assert witness_return(env) == pytest.approx(env.witness.total_return)
    assert witness_return(env, 0.99) < witness_return(env)


def test_snapshots_are_bit_exact() -> None:
    env = _make(3, "hard")
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    for a in env.witness_actions()[:2]:
        env.step(a)
    state = env.get_state()
    probes = [rng.uniform(-1, 1, 9) for _ in range(6)] + env.witness_actions()[2:3]
    first = []
    for a in probes:
        env.set_state(state)
        first.append(env.step(a))
    env.step(env.witness_actions()[2])
    for a, expected in zip(probes, first, strict=True):
        env.set_state(state)
        assert data_equivalence(env.step(a), expected, exact=True)
    for twin in (copy.deepcopy(env), pickle.loads(pickle.dumps(env))):
        twin.set_state(state)
        assert data_equivalence(twin.step(probes[-1]), first[-1], exact=True)
        assert twin.layout == env.layout and twin.witness == env.witness


def test_deterministic_across_processes_with_and_without_the_cache(cache: Path) -> None:
    env = _make(5, "medium")
    env.reset(seed=0)
    rng = np.random.default_rng(4)
    probes = [rng.uniform(-1, 1, 9) for _ in range(8)] + env.witness_actions()
    local = step_probes(env, probes)
    script = IMPORT_IN_CHILD + textwrap.dedent(
        """
        import pickle
        import gymnasium as gym
        import voot
        probes = pickle.load(sys.stdin.buffer)
        env = gym.make("voot/GeneratedStorage-v0", layout_seed=5, difficulty="medium").unwrapped
        env.reset(seed=0)
        out = step_probes(env, probes)
        sys.stdout.buffer.write(pickle.dumps((repr(env.layout), out)))
        """
    )
    for cache_dir in (str(cache), str(cache / "other")):  # cached, then generated anew
        layout, remote = run_pickled(script, probes, env={"VOOT_CACHE": cache_dir})
        assert layout == repr(env.layout)
        assert data_equivalence(local, remote, exact=True)
    assert local[-1][2]  # the witness terminated the episode


def test_different_seeds_and_levels_differ() -> None:
    a, b, c = _make(0, "easy"), _make(1, "easy"), _make(0, "hard")
    assert a.layout != b.layout and a.layout != c.layout
    oa, ob = a.reset(seed=0)[0], b.reset(seed=0)[0]
    assert oa.shape != ob.shape or not np.array_equal(oa, ob)
    assert a.config.workspace != b.config.workspace or a.n != b.n


def test_options_and_bad_keywords() -> None:
    env = _make(0, "easy", horizon=5, infeasible_reward=-3.0)
    assert env.config.horizon == 5 and env.config.infeasible_reward == -3.0
    with pytest.raises(ValueError, match="come from the generated layout"):
        _make(0, "easy", n_objects=3)
    with pytest.raises(ValueError, match="takes no 'preset'"):
        _make(0, "easy", preset="v0")
    with pytest.raises(ValueError, match="easy, medium, hard"):
        _make(0, "impossible")
    with pytest.raises(ValueError, match="layout_seed"):
        _make(-1, "easy")


def test_the_exact_footprint_option() -> None:
    """``base_model="footprint"`` reaches the generated rooms as it does v1: off by
    default; the witness still packs every box with the same return (a disc path is a
    footprint path, and the exact search runs only where the disc finds none); and a root
    action the disc refuses executes with the footprint, the same way twice."""
    disc = _make(0, "easy")
    exact = _make(0, "easy", base_model="footprint")
    assert disc.config.planner.footprint is None
    assert exact.config.planner.footprint is not None
    assert exact.layout == disc.layout
    assert witness_return(exact) == witness_return(disc)
    for e in (disc, exact):
        e.reset(seed=0)
    d_snap, e_snap = disc.get_state(), exact.get_state()
    rng = np.random.default_rng(5)
    for _ in range(2000):
        a = rng.uniform(-1.0, 1.0, 9)
        if not disc.precheck(a)[0]:
            continue
        _, _, _, d_info = disc.transition(a)
        disc.set_state(d_snap)
        if d_info["feasible"]:
            continue
        r1, _, _, i1 = exact.transition(a)
        exact.set_state(e_snap)
        if not i1["feasible"]:
            continue
        r2, _, _, i2 = exact.transition(a)
        assert d_info["reason"].endswith("no base path")
        assert (r1, i1["base_path_lengths"]) == (r2, i2["base_path_lengths"])
        return
    pytest.fail("no root action refused by the disc passed with the footprint")
