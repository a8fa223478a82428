"""Checks every robot env's tests make (a helper module, not a test module).

The kitchen and the conveyor keep the same contract: a truncated episode has ended, a
restored snapshot steps bit for bit as before, the gymnasium checks pass, a step's
timings add up, and a probe sequence steps the same in any process. Each check is written once here, with the
values (env, seed, actions) left to the test.
"""

from __future__ import annotations

import pickle
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env, data_equivalence
from gymnasium.utils.env_match import check_environments_match

#: This folder, for a child process that imports this module (:data:`IMPORT_IN_CHILD`).
TESTS_DIR = str(Path(__file__).resolve().parent)
#: The lines a child process's script starts with to import :func:`step_probes`.
IMPORT_IN_CHILD = (
    f"import sys\nsys.path.insert(0, {TESTS_DIR!r})\nfrom env_fixtures import step_probes\n"
)


def assert_horizon_ends(env: Any, action: np.ndarray) -> None:
    """Step ``action`` as the horizon's last step: truncated, not terminated; the episode
    has then ended, so neither a step nor a pre-check is allowed."""
    _, _, term, trunc, _ = env.step(action)
    assert not term and trunc
    with pytest.raises(ValueError, match="ended"):
        env.step(action)
    with pytest.raises(ValueError, match="ended"):
        env.precheck(action)


def assert_restore_is_exact(
    env: Any, seed: int, actions: Callable[[Any], Sequence[np.ndarray]], before: int
) -> None:
    """A restored snapshot steps bit for bit as the first time.

    From a reset at ``seed``, step the first ``before`` of ``actions(env)``, take a
    snapshot, step the next action, move on by one more, restore the snapshot (equal
    again) and step the same action: the same step, to the bit. The snapshot pickles.
    """
    env.reset(seed=seed)
    acts = actions(env)
    for a in acts[:before]:
        env.step(a)
    s = env.get_state()
    first = env.step(acts[before])
    env.step(acts[before + 1])  # move on, then come back
    env.set_state(s)
    assert env.get_state() == s
    second = env.step(acts[before])
    assert data_equivalence(first, second, exact=True)
    assert pickle.loads(pickle.dumps(s)) == s


def check_gymnasium_api(env_id: str, num_steps: int, seed: int) -> None:
    """Gymnasium's env checker on ``env_id``, and two envs made by the ``module:id`` form
    step alike for ``num_steps`` steps from ``seed``."""
    check_env(gym.make(env_id).unwrapped, skip_render_check=True)
    a = gym.make(f"voot:{env_id}")
    b = gym.make(f"voot:{env_id}")
    check_environments_match(a, b, num_steps=num_steps, seed=seed)


def step_probes(env: Any, probes: Sequence[np.ndarray]) -> list[tuple[Any, ...]]:
    """Step every probe in turn, each from where the last feasible one left the env (an
    infeasible probe's step is undone); the steps, in order."""
    out = []
    for a in probes:
        state = env.get_state()
        step = env.step(a)
        out.append(step)
        if not step[4]["feasible"]:
            env.set_state(state)
    return out


def timed_step(env: Any, action: np.ndarray) -> Any:
    """``env.step(action)``, checking ``env.last_timing`` (read by
    ``voot.bench.measure.env_speed``): parts >= 0 that sum to <= its total, which is at
    most the step's wall time."""
    began = time.perf_counter()
    out = env.step(action)
    elapsed = time.perf_counter() - began
    tm = env.last_timing
    assert min(tm.ik, tm.collision, tm.planning) >= 0.0, tm
    assert tm.ik + tm.collision + tm.planning <= tm.total <= elapsed, tm
    return out
