"""The benchmark envs as planning problems (voot.envs.core.problem.EnvProblem)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import voot  # noqa: F401  (registers the ids)
from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.scripted import conveyor_actions
from voot.envs.core.problem import EnvProblem
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.generated.env import GeneratedKitchenEnv
from voot.envs.kitchen.scripted import kitchen_actions
from voot.tree.problem import FeasibilityCheck, PlanningProblem, StepResult


@pytest.fixture(scope="module")
def kitchen() -> KitchenClearingEnv:
    return KitchenClearingEnv()


def test_protocols_and_bounds(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(kitchen, seed=0)
    assert isinstance(p, PlanningProblem) and isinstance(p, FeasibilityCheck)
    assert p.action_bounds().dim == 6
    acts = kitchen_actions(kitchen)
    res = p.step(acts[0])
    assert isinstance(res, StepResult) and res.feasible and res.reward == 0.0
    # a place node: a 3-D box, padded to the env's 6-D action
    b = p.action_bounds()
    assert b.dim == 3 and np.all(b.lower == -1.0) and np.all(b.upper == 1.0)
    res = p.step(acts[1][:3])
    assert res.feasible and res.info["operator"] == "place" and res.bonus == 0.0
    with pytest.raises(ValueError, match="6 entries"):
        p.step(np.zeros(3))


def test_goal_bonus_is_separate(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(gym.make("voot/KitchenClearing-v0"), seed=0)
    acts = kitchen_actions(kitchen)
    for k, a in enumerate(acts):
        res = p.step(a if k % 2 == 0 else a[:3])
        assert res.feasible
    assert res.terminal and res.bonus == 2.0 and res.reward < 2.0


def test_snapshot_restore_and_feasibility_cache(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(kitchen, seed=0)
    assert p.last_check is None
    s0 = p.snapshot()
    a = kitchen_actions(kitchen)[0]
    assert p.is_feasible(a)
    assert p.snapshot() == s0  # the check does not advance the state
    check = p.last_check
    assert check is not None and check.feasible and len(check.info["base_pose"]) == 3
    cached = p.step(a)  # reuses the check's result
    assert cached is check
    s1 = p.snapshot()
    p.restore(s0)
    fresh = p.step(a)
    assert fresh.reward == cached.reward and p.snapshot() == s1
    # a different action after a check is stepped for real
    p.restore(s0)
    assert not p.is_feasible(np.full(6, -0.3))
    assert p.last_check is not None and not p.last_check.feasible
    assert p.last_check.info["base_pose"] is not None  # where the rejected pick stood
    assert p.snapshot() == s0
    res = p.step(a)
    assert res.feasible and p.snapshot() == s1


def test_paper_units(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(kitchen, seed=0, units="paper")
    b = p.action_bounds()
    assert b.lower[0] == pytest.approx(math.radians(45)) and b.upper[4] == pytest.approx(
        2 * math.pi
    )
    q = b.lower + 0.5 * (b.upper - b.lower)
    np.testing.assert_allclose(p.to_env_action(q), np.zeros(6), atol=1e-12)
    with pytest.raises(ValueError, match="units"):
        EnvProblem(kitchen, units="furlongs")


def test_conveyor_problem() -> None:
    env = ConveyorPackingEnv()
    p = EnvProblem(env, seed=0)
    assert p.action_bounds().dim == 9
    res = p.step(conveyor_actions(env)[0])
    assert res.feasible and 0.0 < res.reward <= 3.0
    assert EnvProblem(env, units="paper").action_bounds().dim == 9


def test_rejects_other_envs() -> None:
    with pytest.raises(ValueError, match=r"needs a voot robot env \(a ManipulationEnv"):
        EnvProblem(gym.make("voot/ShekelChain-v0"))


# ----- the lean check path ---------------------------------------------------------------
def _plain_check(p: EnvProblem, action: np.ndarray) -> tuple[StepResult, object, object]:
    """The check as it was: full step, snapshot, full restore (the reference)."""
    u = p.unwrapped
    before = u.get_state()
    obs, reward, terminated, truncated, info = u.step(p.to_env_action(action))
    after = u.get_state()
    u.set_state(before)
    res = StepResult(
        float(reward),
        bool(info["feasible"]),
        bool(terminated or truncated),
        float(info["goal_bonus"]),
        info,
    )
    return res, after, obs


def _same_info(a: dict, b: dict) -> bool:
    if a.keys() != b.keys():
        return False
    for k in a:
        x, y = a[k], b[k]
        if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
            if not np.array_equal(np.asarray(x), np.asarray(y)):
                return False
        elif isinstance(x, list) and x and isinstance(x[0], np.ndarray):
            if len(x) != len(y) or not all(np.array_equal(u, v) for u, v in zip(x, y, strict=True)):
                return False
        elif x != y:
            return False
    return True


def _robot_env_ids() -> list[str]:
    """Every registered id of the two robot domains (any version)."""
    ids = []
    for env_id, spec in gym.registry.items():
        u = spec.entry_point if isinstance(spec.entry_point, str) else ""
        if env_id.startswith("voot/") and ("kitchen" in u or "conveyor" in u):
            ids.append(env_id)
    return sorted(ids)


@pytest.mark.parametrize("env_id", _robot_env_ids())
def test_lean_check_matches_plain_step(env_id: str) -> None:
    """is_feasible + step give what step-record-restore gave, feasible or not.

    Also the check of the INFEASIBLE_CHANGES_TASK_ONLY contract of every registered
    version: the plain path takes a full snapshot after each step.
    """
    env = gym.make(env_id).unwrapped
    p = EnvProblem(env, seed=0)
    kinematic = env.config.precheck == "kinematic"
    if isinstance(env, GeneratedKitchenEnv):  # a generated kitchen: its witness plan
        scripted = env.witness_actions()
    elif isinstance(env, KitchenClearingEnv):
        scripted = kitchen_actions(env)
    else:
        scripted = conveyor_actions(env)
    rng = np.random.default_rng(3)
    for k, good in enumerate(scripted[:4]):
        dim = p.action_bounds().dim
        for action in [*rng.uniform(-1, 1, (25, dim)), np.asarray(good)[:dim]]:
            ref, ref_after, _ = _plain_check(p, action)
            before = p.snapshot()
            ok = p.is_feasible(action)
            check = p.last_check
            assert p.unwrapped.get_state() == before  # the check left the state alone
            if not ref.feasible:  # the contract: only the task record changed
                assert np.array_equal(ref_after.physics, before.physics)
                assert ref_after.rng_state == before.rng_state
            if kinematic:  # v1: a narrower pre-check; failing it means failing the step
                assert ok or not ref.feasible
                continue
            assert ok == ref.feasible
            assert (
                check is not None and check.reward == ref.reward and check.terminal == ref.terminal
            )
            assert _same_info(check.info, ref.info)
        # execute the scripted action: the cached result and the next snapshot are exact
        res = p.step(np.asarray(good)[:dim])
        assert res.feasible and (kinematic or res is check)
        assert p.snapshot() == ref_after == p.unwrapped.get_state(), k


def test_infeasible_check_is_undone_by_the_task_alone(kitchen: KitchenClearingEnv) -> None:
    """An infeasible step changes only the step count (what _jump relies on)."""
    p = EnvProblem(kitchen, seed=0, prescreen=False)  # the check steps
    before = p.snapshot()
    bad = np.full(6, 1.0)  # the far corner of the box: the robot leaves the house
    assert not p.is_feasible(bad)
    after = p._cache[4]  # type: ignore[index]
    assert after.physics is before.physics and after.rng_state is before.rng_state
    assert after.task.steps == before.task.steps + 1
    res = p.step(bad)
    assert not res.feasible and p.unwrapped.task.steps == before.task.steps + 1
    assert np.array_equal(p.unwrapped.get_state().physics, before.physics)


def test_gymnasium_step_is_transition_plus_observation() -> None:
    env = gym.make("voot/KitchenClearing-v0").unwrapped
    env.reset(seed=0)
    s = env.get_state()
    a = kitchen_actions(env)[0]
    obs, reward, terminated, truncated, info = env.step(a)
    env.set_state(s)
    r2, t2, tr2, info2 = env.transition(a)
    assert (reward, terminated, truncated) == (r2, t2, tr2) and _same_info(info, info2)
    assert np.array_equal(obs, env._observation())


# ----- the v0 curves, bit for bit ----------------------------------------------------------
V0_CURVES = Path(__file__).resolve().parents[2] / "data" / "v0_curves.json"


def _v0_runs() -> list[dict]:
    return json.loads(V0_CURVES.read_text())["runs"]


@pytest.mark.parametrize("run", _v0_runs(), ids=lambda r: f"{r['env_id']}-{r['planner']}")
def test_v0_curves_reproduce_bit_for_bit(run: dict) -> None:
    """The curves of the code at 6af33b5 (tests/data/v0_curves.json) come out exactly.

    They were generated by that commit's code (``voot.bench.measure.speedup.run_workload`` on a
    ``git archive`` of it), each with the domain options of voot.bench.protocol.problems.
    """
    from voot.bench.protocol.problems import domain_options
    from voot.tree import plan

    env = gym.make(run["env_id"], disable_env_checker=True)
    p = EnvProblem(env.unwrapped, seed=run["seed"])
    res = plan(
        p, run["planner"], run["simulations"], seed=run["seed"],
        **domain_options(run["env_id"], None, run["planner"]),
    )  # fmt: skip
    assert res.n_steps == run["n_steps"]
    assert res.n_feasibility_checks == run["n_feasibility_checks"]
    assert float(res.best_return).hex() == run["best_return"]
    assert [float(v).hex() for v in res.best_return_curve] == run["curve"]


def test_an_env_moved_behind_the_problem_is_noticed(kitchen: KitchenClearingEnv) -> None:
    p = EnvProblem(kitchen, seed=0)
    a = kitchen_actions(kitchen)[0]
    s0 = p.snapshot()
    assert p.is_feasible(a)
    kitchen.step(a)  # not through the problem
    assert p.snapshot() != s0 and p.snapshot() == kitchen.get_state()
    with pytest.raises(ValueError, match="3 entries"):
        p.step(a)  # not the check's cached result: stepped from the new state (a place)
    kitchen.reset(seed=0)
    assert p.snapshot() == s0


def test_simulator_calls_count_every_transition(kitchen: KitchenClearingEnv) -> None:
    """n_simulator_calls (the SimulatorCalls protocol): v0 checks step, a cached step does not."""
    from voot.tree.problem import SimulatorCalls

    p = EnvProblem(kitchen, seed=0)
    assert isinstance(p, SimulatorCalls) and p.n_simulator_calls == 0
    pick = kitchen_actions(kitchen)[0]
    assert p.is_feasible(pick)
    p.step(pick)  # reuses the check's result
    assert p.n_simulator_calls == 1
    p.step(np.full(3, 1.0))  # not checked first: runs the simulator
    assert p.n_simulator_calls == 2
    v1 = EnvProblem(gym.make("voot/KitchenClearing-v1").unwrapped, seed=0)
    assert v1.is_feasible(pick) and v1.n_simulator_calls == 0  # the kinematic pre-check
    v1.step(pick)
    assert v1.n_simulator_calls == 1


# ----- the pre-screen ------------------------------------------------------------------------
def test_prescreen_changes_no_answer_result_count_or_state() -> None:
    """EnvProblem(prescreen=True) against prescreen=False, check by check and step by step."""
    on = EnvProblem(gym.make("voot/KitchenClearing-v0").unwrapped, seed=0)
    off = EnvProblem(gym.make("voot/KitchenClearing-v0").unwrapped, seed=0, prescreen=False)
    assert on.prescreen and not off.prescreen
    rng = np.random.default_rng(6)
    screened = 0
    for good in kitchen_actions(on.unwrapped)[:4]:
        dim = on.action_bounds().dim
        before_on, before_off = on.snapshot(), off.snapshot()
        for action in rng.uniform(-1, 1, (40, dim)):
            assert on.is_feasible(action) == off.is_feasible(action)
            screened += on._pending
            a, b = on.last_check, off.last_check
            assert a is not None and b is not None
            assert (a.reward, a.feasible, a.terminal, a.bonus) == (
                b.reward, b.feasible, b.terminal, b.bonus,
            )  # fmt: skip
            assert _same_info(a.info, b.info)
            assert on.snapshot() == off.snapshot()
            assert on.n_simulator_calls == off.n_simulator_calls
        # execute the last (mostly rejected) proposal, as a search does after its retries
        ra, rb = on.step(action), off.step(action)
        assert (ra.reward, ra.feasible) == (rb.reward, rb.feasible) and _same_info(ra.info, rb.info)
        assert on.snapshot() == off.snapshot() and on.n_simulator_calls == off.n_simulator_calls
        on.restore(before_on)
        off.restore(before_off)
        on.step(np.asarray(good)[:dim]), off.step(np.asarray(good)[:dim])
        assert on.snapshot() == off.snapshot()
    assert screened > 60  # the pre-screen settled most checks


def test_a_screened_check_is_computed_where_it_was_made(kitchen: KitchenClearingEnv) -> None:
    """last_check of a screened check, read after the env moved on, is the check's own."""
    p = EnvProblem(kitchen, seed=0)
    bad = np.full(6, 1.0)  # the far corner of the box: settled by the pre-screen
    s0 = p.snapshot()
    ref, _, _ = _plain_check(p, bad)
    calls = p.n_simulator_calls
    assert not p.is_feasible(bad) and p._pending
    assert p.n_simulator_calls == calls + 1  # counted as the step it stands for
    pick = kitchen_actions(kitchen)[0]
    assert p.is_feasible(pick) is True  # last_check is now this one's
    p.step(pick)
    here = p.snapshot()
    p.restore(s0)
    assert not p.is_feasible(bad)
    p.restore(here)  # moved on before anyone read last_check
    check = p.last_check
    assert check is not None and not check.feasible
    assert check.reward == ref.reward and _same_info(check.info, ref.info)
    assert p.snapshot() == here == kitchen.get_state()  # computed without moving the env
    assert p.last_check is check  # computed once
    # the step of a screened action runs it, counted with its check
    p.restore(s0)
    assert not p.is_feasible(bad)
    calls = p.n_simulator_calls
    res = p.step(bad)
    assert not res.feasible and p.n_simulator_calls == calls and p.last_check is res
    assert kitchen.task.steps == s0.task.steps + 1


@pytest.mark.parametrize(
    "env_id", ["voot/KitchenClearing-v1", "voot/ConveyorPacking-v1", "voot/KitchenClearing-v0"]
)
def test_bad_actions_are_refused_before_any_count_cache_or_state_changes(env_id: str) -> None:
    """step and is_feasible: a (1, d) array was flattened and taken, bools, strings and
    complex numbers read as numbers, and a NaN action counted a simulator call (and
    dropped the cached check) before the env refused it."""
    env = gym.make(env_id, disable_env_checker=True)
    p = EnvProblem(env, seed=0)
    d = p.action_bounds().dim
    good = np.zeros(d)
    p.is_feasible(good)  # a cached check, which the next step(good) reuses
    before = p.snapshot()
    bits = (before.physics.tobytes(), before.task, env.unwrapped.np_random.bit_generator.state)
    calls = p.n_simulator_calls
    last = p.last_check
    for bad, match in [
        (np.zeros((1, d)), rf"action must have {d} entries at this state"),
        (np.array(0.5), rf"must have {d} entries"),
        (np.zeros(d + 1), rf"must have {d} entries"),
        (np.full(d, np.nan), "NaN or infinite entries"),
        (np.r_[np.zeros(d - 1), np.inf], rf"NaN or infinite entries at indices \[{d - 1}\]"),
        (np.zeros(d, dtype=bool), "must be numeric, real numbers"),
        (np.array(["0.1"] * d), "must be numeric"),
        (np.full(d, 0.5j), "must be numeric"),
        (None, "must be numeric"),
    ]:
        for entry in (p.step, p.is_feasible):
            with pytest.raises(ValueError, match=match):
                entry(bad)
            s = env.unwrapped.get_state()
            assert (
                s.physics.tobytes(),
                s.task,
                env.unwrapped.np_random.bit_generator.state,
            ) == bits
            assert p.n_simulator_calls == calls and p.last_check is last
    p.step(good)  # the cached check is still used: no new simulator call
    assert p.n_simulator_calls == calls + (0 if env_id.endswith("v0") else 1)


def _robot_ids() -> list[str]:
    from voot.problems import problem_records

    return [r.id for r in problem_records() if r.chain is None]


@pytest.mark.parametrize("env_id", _robot_ids())
def test_plan_leaves_the_env_where_it_found_it(env_id: str) -> None:
    """After plan(), the env is at the root again, so its plan replays on it exactly."""
    import warnings

    from voot.bench.protocol.problems import domain_options
    from voot.tree import plan

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        env = gym.make(env_id)
    problem = EnvProblem(env, seed=0)
    before = env.unwrapped.get_state()
    res = plan(problem, "voot", n_simulations=15, seed=0, **domain_options(env_id, None, "voot"))
    after = env.unwrapped.get_state()
    assert after.physics.tobytes() == before.physics.tobytes()
    assert after.task == before.task and after.rng_state == before.rng_state
    assert len(res.actions) >= 1
    rewards = []
    for action in res.actions:
        reward = env.step(problem.to_env_action(action))[1]
        rewards.append(reward)
    assert rewards == res.rewards.tolist()
    env.close()
