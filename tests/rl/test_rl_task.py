"""voot.rl.task: the fixed-start RL task (no torch needed)."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import data_equivalence

import voot  # noqa: F401 - registers the ids
from voot.rl.task import EMPTY_PLAN_RETURN, PlanningTask, reward_parts


def kitchen(**kwargs: Any) -> gym.Env[Any, Any]:
    return gym.make("voot/KitchenClearing-v1", disable_env_checker=True, **kwargs)


def chain(dim: int = 3) -> gym.Env[Any, Any]:
    return gym.make("voot/ShekelChain-v0", dim=dim, disable_env_checker=True)


def same_state(a: Any, b: Any) -> bool:
    return np.array_equal(a.physics, b.physics) and a.task == b.task and a.rng_state == b.rng_state


def feasible_and_infeasible(task: PlanningTask) -> tuple[np.ndarray, np.ndarray]:
    """A feasible first action and an infeasible one, found by sampling from the start."""
    rng = np.random.default_rng(0)
    good = bad = None
    for _ in range(200):
        a = rng.uniform(-1, 1, 6)
        task.reset()
        _, _, _, _, info = task.step(a)
        if info["feasible"] and good is None:
            good = a
        if not info["feasible"] and bad is None:
            bad = a
        if good is not None and bad is not None:
            return good, bad
    raise AssertionError("no feasible and infeasible first actions found")


def test_reset_restores_the_initial_state_exactly() -> None:
    task = PlanningTask(kitchen(), seed=3, gamma=0.9)
    obs0, info0 = task.reset()
    state0 = task.unwrapped.get_state()  # type: ignore[attr-defined]
    good, _ = feasible_and_infeasible(task)
    task.reset()
    obs1, *_ = task.step(good)
    assert not np.array_equal(obs1, obs0)  # the feasible step moved something
    assert not same_state(task.unwrapped.get_state(), state0)  # type: ignore[attr-defined]
    obs, info = task.reset()
    assert np.array_equal(obs, obs0) and data_equivalence(info, info0, exact=True)
    assert same_state(task.unwrapped.get_state(), state0)  # type: ignore[attr-defined]
    # and the env then behaves exactly as from the start
    _, r_again, *_ = task.step(good)
    fresh = PlanningTask(kitchen(), seed=3, gamma=0.9)
    fresh.reset()
    _, r_fresh, *_ = fresh.step(good)
    assert r_again == r_fresh


def test_reset_restarts_the_wrappers_step_counters() -> None:
    task = PlanningTask(kitchen(max_episode_steps=2), seed=0, gamma=0.9)
    good, _ = feasible_and_infeasible(task)
    for _ in range(3):  # without the counter reset, TimeLimit would truncate at once
        task.reset()
        _, _, terminated, truncated, info = task.step(good)
        assert info["feasible"] and not terminated and not truncated


def test_an_infeasible_step_ends_the_episode() -> None:
    task = PlanningTask(kitchen(), seed=0, gamma=0.9)
    _, bad = feasible_and_infeasible(task)
    raw = kitchen()
    raw.reset(seed=0)
    *_, raw_term, raw_trunc, raw_info = raw.step(bad)
    assert not raw_info["feasible"] and not raw_term and not raw_trunc  # the env goes on
    task.reset()
    _, reward, terminated, truncated, info = task.step(bad)
    assert terminated and not truncated and reward == -2.0 and not info["feasible"]
    with pytest.raises(RuntimeError, match="reset"):
        task.step(bad)


def test_best_is_the_discounted_return_of_finished_episodes_bonus_excluded() -> None:
    task = PlanningTask(chain(3), seed=0, gamma=0.5)
    f = task.unwrapped.chain  # type: ignore[attr-defined]
    assert task.best_at(0) == (EMPTY_PLAN_RETURN, None)
    good = np.asarray(f.function.optimum_x, dtype=float)  # feasible: the optimum
    bad = task.action_space.low.copy()  # far corner: infeasible
    task.reset()
    _, r1, term1, *_ = task.step(good)
    _, _, term2, *_ = task.step(bad)
    assert not term1 and term2
    value_good = float(f.value(good))
    assert r1 == pytest.approx(value_good + f.bonus)  # the agent learns r + b
    expected = value_good + 0.5 * (float(f.value(bad)) - 2.0)  # the return excludes b
    assert task.best_return == pytest.approx(expected)
    assert task.n_steps == 2 and task.n_episodes == 1
    assert [(i.step, i.best) for i in task.improvements] == [(2, task.best_return)]
    assert task.best_at(1) == (EMPTY_PLAN_RETURN, None)  # unfinished at step 1
    # a worse episode changes nothing; an unfinished one does not count
    task.reset()
    task.step(bad)
    assert task.best_return == pytest.approx(expected) and len(task.improvements) == 1
    task.reset()
    task.step(good)
    task.step(good)
    assert task.best_return == pytest.approx(expected)


def test_first_finished_episode_replaces_the_empty_plan_even_if_lower() -> None:
    task = PlanningTask(chain(3), seed=0, gamma=0.9)
    task.reset()
    task.step(task.action_space.low.copy())
    assert task.best_return < EMPTY_PLAN_RETURN
    assert task.best_at(1)[0] == task.best_return


def test_objects_left_of_the_best_episode_and_initial() -> None:
    task = PlanningTask(kitchen(), seed=0, gamma=0.9)
    assert task.objects_initial == 7.0
    feasible_and_infeasible(task)  # finishes episodes at infeasible first actions
    assert task.best_objects_left == 7.0


def test_max_episode_steps_truncates() -> None:
    task = PlanningTask(chain(3), seed=0, gamma=0.9, max_episode_steps=2)
    good = np.asarray(task.unwrapped.chain.function.optimum_x, dtype=float)  # type: ignore[attr-defined]
    task.reset()
    assert task.step(good)[3] is False
    _, _, terminated, truncated, _ = task.step(good)
    assert truncated and not terminated and task.n_episodes == 1


def test_reward_parts_conventions() -> None:
    assert reward_parts(1.5, {"goal_bonus": 10.0}) == (1.5, 10.0)  # robot: bonus apart
    assert reward_parts(3.0, {"bonus": 1.0}) == (2.0, 1.0)  # chain: bonus included
    assert reward_parts(3.0, {}) == (3.0, 0.0)


def test_bad_arguments_and_envs() -> None:
    with pytest.raises(ValueError, match="gamma"):
        PlanningTask(chain(), seed=0, gamma=1.5)
    with pytest.raises(ValueError, match="seed"):
        PlanningTask(chain(), seed=-1, gamma=0.9)
    with pytest.raises(ValueError, match="max_episode_steps"):
        PlanningTask(chain(), seed=0, gamma=0.9, max_episode_steps=0)
    with pytest.raises(ValueError, match=r"get_state\(\)/set_state\(\)"):
        PlanningTask(gym.make("Pendulum-v1"), seed=0, gamma=0.9)
