"""Property-based tests of the public entry points (hypothesis): generated bad and edge-case
inputs either work or raise a ValueError that names the argument, and leave the object as
it was.
"""

from __future__ import annotations

import math
from dataclasses import fields

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from voot.optim import make_optimizer
from voot.optim.base import Bounds
from voot.tree import MCTSConfig

#: Values of every kind a user might pass by mistake.
ANYTHING = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**6), max_value=10**6),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=8),
    st.lists(st.integers(-3, 3), max_size=3),
)
CONFIG_FIELDS = [f.name for f in fields(MCTSConfig) if f.name != "sampler_options"]


@settings(max_examples=300, deadline=None)
@given(name=st.sampled_from(CONFIG_FIELDS), value=ANYTHING)
def test_planner_config_fields_work_or_name_themselves(name: str, value: object) -> None:
    try:
        MCTSConfig(**{name: value})  # type: ignore[arg-type]
    except ValueError as exc:
        text = str(exc)
        assert name in text or "unknown" in text, (name, value, text)


@settings(max_examples=200, deadline=None)
@given(
    lower=st.lists(ANYTHING, min_size=0, max_size=3),
    upper=st.lists(ANYTHING, min_size=0, max_size=3),
)
def test_bounds_work_or_say_what_is_wrong(lower: list[object], upper: list[object]) -> None:
    try:
        b = Bounds(lower, upper)  # type: ignore[arg-type]
    except (ValueError, TypeError) as exc:
        assert isinstance(exc, ValueError), f"{type(exc).__name__}: {exc}"
        return
    assert np.all(np.isfinite(b.lower)) and np.all(b.lower < b.upper)


METHODS = ["voo", "doo", "rand_doo", "soo", "cmaes", "random"]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    method=st.sampled_from(METHODS),
    x=st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=1, max_size=3),
    value=st.floats(allow_nan=True, allow_infinity=True),
)
def test_a_refused_tell_leaves_the_optimiser_as_it_was(
    method: str, x: list[float], value: float
) -> None:
    opt = make_optimizer(method, [[-1.0, 1.0]] * 2, seed=0)
    for _ in range(3):
        p = opt.ask()
        opt.tell(p, -float(np.sum(p**2)))
    before = (opt.n_told, opt.xs.copy(), opt.values.copy(), opt.best_index)
    try:
        opt.tell(np.array(x), value)
    except ValueError:
        after = (opt.n_told, opt.xs.copy(), opt.values.copy(), opt.best_index)
        assert after[0] == before[0] and after[3] == before[3]
        assert np.array_equal(after[1], before[1]) and np.array_equal(after[2], before[2])
        return
    # accepted: a finite value at a point of the right shape
    assert len(x) == 2 and all(math.isfinite(v) for v in x)


@pytest.fixture(scope="module")
def kitchen() -> object:
    from voot.envs.kitchen.env import KitchenClearingEnv

    return KitchenClearingEnv(preset="v1")


@settings(
    max_examples=120, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(
    action=st.one_of(
        st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=0, max_size=8),
        st.lists(st.text(max_size=2), min_size=6, max_size=6),
    )
)
def test_env_actions_work_or_are_refused_without_a_trace(kitchen: object, action: list) -> None:
    env = kitchen
    env.reset(seed=0)  # type: ignore[attr-defined]
    before = env.get_state()  # type: ignore[attr-defined]
    for call in (env.precheck, env.step):  # type: ignore[attr-defined]
        env.set_state(before)  # type: ignore[attr-defined]
        try:
            call(action)
        except ValueError as exc:
            assert "action" in str(exc)
            assert env.get_state() == before  # type: ignore[attr-defined]


@settings(
    max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(
    flag=st.sampled_from(["--dims", "--seeds", "--budget", "--budget-scale", "--workers"]),
    value=st.text(alphabet="-0123456789.eafinx:", min_size=1, max_size=6),
)
def test_cli_arguments_give_an_error_message_not_a_traceback(
    flag: str, value: str, capsys: pytest.CaptureFixture[str]
) -> None:
    from voot.bench.cli.main import main

    argv = ["bbfo", "--functions", "shekel", "--methods", "voo", flag, value, "--dry-run"]
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse's own message for a malformed number
        code = int(exc.code or 0)
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert code in (0, 2), (argv, code, err)


@settings(
    max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(
    corrupt=st.sampled_from(["physics_nan", "physics_length", "task", "rng", "signature"]),
    where=st.integers(min_value=0, max_value=10**6),
    junk=ANYTHING,
)
def test_a_corrupted_snapshot_is_refused_and_changes_nothing(
    kitchen: object, corrupt: str, where: int, junk: object
) -> None:
    import dataclasses

    env = kitchen
    env.reset(seed=0)  # type: ignore[attr-defined]
    good = env.get_state()  # type: ignore[attr-defined]
    physics = np.array(good.physics)
    changes: dict[str, object] = {}
    if corrupt == "physics_nan":
        physics[where % physics.size] = np.nan
        changes["physics"] = physics
    elif corrupt == "physics_length":
        changes["physics"] = physics[: where % physics.size]
    elif corrupt == "task":
        changes["task"] = junk
    elif corrupt == "rng":
        changes["rng_state"] = {"bit_generator": "PCG64", "state": junk}
    else:
        changes["signature"] = int(where)
    bad = dataclasses.replace(good, **changes)
    if corrupt == "signature" and int(where) == good.signature:
        return
    before = env.get_state()  # type: ignore[attr-defined]
    with pytest.raises(ValueError):
        env.set_state(bad)  # type: ignore[attr-defined]
    assert env.get_state() == before  # type: ignore[attr-defined]
