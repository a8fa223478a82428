"""Tests of voot/GeneratedKitchen-v0 (voot.envs.kitchen.generated): generated, solvable kitchens."""

from __future__ import annotations

import copy
import itertools
import pickle
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env, data_equivalence
from process_fixtures import run_pickled

import voot  # noqa: F401  (registers the ids)
from voot.envs.core.scene import object_footprint
from voot.envs.core.units import normalize
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.generated import instance
from voot.envs.kitchen.generated.env import GeneratedKitchenEnv
from voot.envs.kitchen.generated.instance import clear_kitchen_cache, generated_kitchen
from voot.envs.kitchen.generated.layout import DIFFICULTIES
from voot.envs.kitchen.generated.witness import constructive_solution, placement_candidates
from voot.envs.motion.rects import rect_overlaps


def play(env: GeneratedKitchenEnv, actions: list[np.ndarray]) -> list[tuple]:  # type: ignore[type-arg]
    env.reset(seed=0)
    return [env.step(a) for a in actions]


@pytest.mark.parametrize("difficulty", list(DIFFICULTIES))
def test_the_witness_clears_the_path_under_the_v1_rules(difficulty: str) -> None:
    env = gym.make("voot/GeneratedKitchen-v0", layout_seed=1, difficulty=difficulty)
    u = env.unwrapped
    assert isinstance(u, GeneratedKitchenEnv)
    layout = u.layout
    cfg = u.config
    assert (cfg.start, cfg.goal, cfg.house, cfg.forbidden) == (
        layout.start,
        layout.goal,
        layout.house,
        layout.forbidden,
    )
    assert cfg.precheck == "kinematic" and cfg.nonclearing_penalty_infeasible
    assert u.initial_obstacles == layout.n_on_path
    steps = play(u, u.witness_actions())
    assert all(s[4]["feasible"] for s in steps)
    assert steps[-1][2] and not any(s[2] for s in steps[:-1])  # terminates at the last
    assert len(steps) == 2 * layout.n_on_path
    env.close()


def test_generation_counts_rejections_and_caches_the_kitchen() -> None:
    kitchen = generated_kitchen(0, "hard")
    assert kitchen.layout.attempt == len(kitchen.rejections) > 0
    assert [a for a, _ in kitchen.rejections] == list(range(kitchen.layout.attempt))
    assert generated_kitchen(0, "hard") is kitchen
    assert kitchen.tries >= len(kitchen.witness)


def test_the_cache_keeps_the_most_recent_kitchens(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(instance.KITCHENS, "size", 2)
    clear_kitchen_cache()
    a = generated_kitchen(0, "easy")
    generated_kitchen(1, "easy")
    assert generated_kitchen(0, "easy") is a  # used again: now the most recent
    generated_kitchen(2, "easy")  # forgets seed 1
    assert generated_kitchen(0, "easy") is a
    again = generated_kitchen(1, "easy")
    assert again.xml_sha256 == instance.KITCHENS.get_or_make((1, "easy"), list).xml_sha256
    assert len(instance.KITCHENS) == 2
    clear_kitchen_cache()
    b = generated_kitchen(0, "easy")
    assert b is not a and b.xml_sha256 == a.xml_sha256 and b.witness == a.witness


def test_seeds_give_different_scenes_and_the_env_copies_the_model() -> None:
    a, b = GeneratedKitchenEnv(layout_seed=0), GeneratedKitchenEnv(layout_seed=1)
    assert a.kitchen.xml_sha256 != b.kitchen.xml_sha256
    twin = GeneratedKitchenEnv(layout_seed=0)
    assert twin.kitchen is a.kitchen and twin.model is not a.model


def test_the_solver_gives_up_when_the_horizon_is_too_short() -> None:
    env = GeneratedKitchenEnv(layout_seed=0, horizon=3)
    assert constructive_solution(env) is None


def test_placement_candidates_avoid_the_path_and_the_forbidden_rooms() -> None:
    env = GeneratedKitchenEnv(layout_seed=2, difficulty="medium")
    env.reset()
    env.step(env.witness_actions()[0])
    cands = placement_candidates(env)
    assert cands
    held = env.objects[env.task.held]
    here = env.object_pose(env.task.held)
    dists = [np.hypot(x - here[0], y - here[1]) for x, y, _ in cands]
    assert all(b >= a - 1e-12 for a, b in itertools.pairwise(dists))  # nearest first
    clearing = env._clearing
    assert clearing is not None
    boxes = [object_footprint(held, x, y, np.radians(t)) for x, y, t in cands[:200]]
    assert not any(clearing.probe.hits(boxes))
    assert not any(rect_overlaps(b, env.config.forbidden) for b in boxes)


def test_layout_fields_and_bad_levels_are_errors() -> None:
    with pytest.raises(ValueError, match="start come from the generated layout"):
        GeneratedKitchenEnv(layout_seed=0, start=(1.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="valid levels are: easy, medium, hard"):
        GeneratedKitchenEnv(layout_seed=0, difficulty="brutal")
    with pytest.raises(ValueError, match="layout_seed"):
        GeneratedKitchenEnv(layout_seed=-3)


def test_gymnasium_checks_and_snapshots_are_bit_exact() -> None:
    env = gym.make("voot/GeneratedKitchen-v0", layout_seed=2, difficulty="medium")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped, skip_render_check=True)
    u = env.unwrapped
    witness = u.witness_actions()
    u.reset(seed=0)
    u.step(witness[0])
    state = u.get_state()
    first = [u.step(a) for a in witness[1:4]]
    for twin in (u, copy.deepcopy(u), pickle.loads(pickle.dumps(u))):
        twin.set_state(state)
        again = [twin.step(a) for a in witness[1:4]]
        assert data_equivalence(first, again, exact=True)


def test_the_same_seed_steps_the_same_in_another_process() -> None:
    env = GeneratedKitchenEnv(layout_seed=3, difficulty="medium")
    rng = np.random.default_rng(0)
    probes = [rng.uniform(-1, 1, 6) for _ in range(3)]
    local = play(env, [*env.witness_actions()[:3], *probes])
    code = (
        "import pickle, sys\n"
        "import numpy as np\n"
        "from voot.envs.kitchen.generated.env import GeneratedKitchenEnv\n"
        "probes = pickle.load(sys.stdin.buffer)\n"
        "env = GeneratedKitchenEnv(layout_seed=3, difficulty='medium')\n"
        "env.reset(seed=0)\n"
        "steps = [env.step(a) for a in [*env.witness_actions()[:3], *probes]]\n"
        "sys.stdout.buffer.write(pickle.dumps((env.kitchen.xml_sha256, env.kitchen.witness, steps)))\n"
    )
    digest, witness, steps = run_pickled(code, probes, timeout=300)
    assert digest == env.kitchen.xml_sha256 and witness == env.kitchen.witness
    assert data_equivalence(local, steps, exact=True)


def test_picks_grasp_the_mesh_and_a_miss_is_an_infeasible_pick() -> None:
    # the first obstacle of hard seed 2 is a jug: grasps beside its neck miss
    env = GeneratedKitchenEnv(layout_seed=2, difficulty="hard")
    env.reset()
    obj = env.task.on_path[0]
    assert env.layout.objects[obj].kind in ("jug", "bottle")
    pose = env.object_pose(obj)
    grasps = [
        env._grasp_pose(obj, pose, 0.0, np.array([2.0, hf, df]))
        for hf in np.linspace(0.5, 1.0, 6)
        for df in np.linspace(0.1, 0.9, 5)
    ]
    missed = [why for g, why in grasps if g is None]
    assert missed and set(missed) == {"grasp misses the object"}
    assert len(missed) < len(grasps)
    # the witness's first pick with the grasp moved to the neck's side, top height
    a = env.witness_actions()[0].copy()
    lo_hi = env.config.pick_ranges
    a[1] = 1.0  # height fraction 1
    a[2] = normalize([0.1], [lo_hi[2]])[0]  # depth fraction 0.1
    before = env.get_state()
    _, reward, _, _, info = env.step(a)
    assert not info["feasible"] and info["reason"] == "grasp misses the object"
    assert reward == env.config.infeasible_reward
    assert np.array_equal(env.get_state().physics, before.physics)
    # on a box the mesh grasp is the side grasp (to the STL's float32 rounding)
    box = next(i for i, o in enumerate(env.layout.objects) if o.kind == "box")
    params = np.array([2.0, 0.7, 0.4])
    mesh, _ = env._grasp_pose(box, env.object_pose(box), 1.0, params)
    side, _ = KitchenClearingEnv._grasp_pose(env, box, env.object_pose(box), 1.0, params)
    assert mesh is not None and side is not None
    assert np.allclose(mesh.position, side.position, rtol=0.0, atol=1e-6)
    assert np.array_equal(mesh.rotation, side.rotation)


def test_the_exact_footprint_option_reaches_the_generated_kitchens() -> None:
    """``base_model="footprint"`` passes through to a generated kitchen's config, and its
    witness still clears the path (its disc paths are footprint paths)."""
    env = gym.make("voot/GeneratedKitchen-v0", layout_seed=0, difficulty="medium",
                   base_model="footprint")  # fmt: skip
    u = env.unwrapped
    assert u.config.planner.footprint is not None
    env.reset(seed=0)
    terminated = False
    for a in u.witness_actions():
        _, _, terminated, _, info = env.step(a)
        assert info["feasible"], info["reason"]
    assert terminated
