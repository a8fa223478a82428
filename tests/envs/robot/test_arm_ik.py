"""Tests of voot.envs.robot.arm_ik: closed-form seeds, mink refinement, the daqp step."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from voot.envs.robot.arm_ik import ArmIK, FloatArray, IKConfig
from voot.envs.robot.rotations import rot_x, rot_y


@pytest.fixture(scope="module")
def ik() -> ArmIK:
    return ArmIK()


def test_seeds_are_exact_closed_form_solutions(ik: ArmIK) -> None:
    rng = np.random.default_rng(1)
    for _ in range(30):
        q = rng.uniform(ik.lower, ik.upper)
        p, r = ik.forward(q)
        seeds = ik.seeds(p, r)
        assert seeds
        for s in seeds:
            p2, r2 = ik.forward(s)
            np.testing.assert_allclose(p2, p, atol=1e-9)
            np.testing.assert_allclose(r2, r, atol=1e-9)


def test_solve_reaches_reachable_targets(ik: ArmIK) -> None:
    rng = np.random.default_rng(2)
    n_ok = 0
    for _ in range(40):
        q = rng.uniform(ik.lower, ik.upper)
        p, r = ik.forward(q)
        res = ik.solve(p, r)
        if res.success:
            n_ok += 1
            assert res.q is not None
            assert np.all(res.q >= ik.lower - 1e-12) and np.all(res.q <= ik.upper + 1e-12)
            p2, r2 = ik.forward(res.q)
            assert np.linalg.norm(p2 - p) <= ik.config.position_tolerance * 1.01
            assert np.linalg.norm(r2 - r) < 3 * ik.config.orientation_tolerance
    assert n_ok >= 36  # every target is reachable; a few may need more iterations


def test_solve_reports_out_of_reach(ik: ArmIK) -> None:
    res = ik.solve([1.5, 0.0, 0.8], np.eye(3))
    assert not res.success and res.reason == "out of reach" and res.q is None


def test_solve_is_deterministic(ik: ArmIK) -> None:
    r = rot_x(1.2)
    target = np.array([0.55, 0.1, 0.45])
    a, b = ik.solve(target, r), ik.solve(target, r)
    assert a.success and np.array_equal(a.q, b.q) and a.iterations == b.iterations


def test_refinement_uses_mink_when_the_seed_violates_limits(ik: ArmIK) -> None:
    # a close, low target: every closed-form seed breaks a limit, mink finds a solution
    ang = math.pi
    r = np.column_stack(
        [[1, 0, 0], [0, math.cos(ang), math.sin(ang)], [0, -math.sin(ang), math.cos(ang)]]
    )
    res = ik.solve([0.47, 0.0, 0.64], r)
    assert res.success and res.iterations >= 1


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"solver": "cvxopt-ish"}, "daqp"),
        ({"max_iterations": -1}, "max_iterations"),
        ({"position_tolerance": 0.0}, "position_tolerance"),
        ({"orientation_cost": -1.0}, "orientation_cost"),
        ({"damping": True}, "IKConfig.damping must be a finite number > 0, got True"),
        ({"orientation_cost": True}, "IKConfig.orientation_cost"),
    ],
)
def test_ik_config_validation(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        IKConfig(**kwargs)  # type: ignore[arg-type]


def test_closest_seed_is_the_sorted_violation_choice(ik: ArmIK) -> None:
    """_closest_seed picks what sorting by (_violation, index) picked."""
    rng = np.random.default_rng(4)
    for k in range(400):
        seeds = list(rng.uniform(-3.5, 3.5, (int(rng.integers(1, 9)), 7)))
        if k % 3 == 0:  # inside the limits, and duplicates (exact ties)
            seeds = [np.clip(q, ik.lower, ik.upper) for q in seeds] + [seeds[0]]
        if k % 5 == 0 and len(seeds) > 1:
            seeds[1] = seeds[0].copy()
        viol = [ik._violation(q) for q in seeds]
        order = sorted(range(len(seeds)), key=lambda i: (viol[i], i))
        assert ik._closest_seed(seeds) == (order[0], viol[order[0]] == 0.0)


def test_chosen_seed_is_the_closest_of_all_seeds(ik: ArmIK) -> None:
    """Stopping at the first seed inside the limits picks what choosing among all did."""
    rng = np.random.default_rng(6)
    outcomes = set()
    for _ in range(200):
        # targets of random joint values, some beyond the limits (seeds outside them)
        q = rng.uniform(ik.lower - 0.5, ik.upper + 0.5)
        p, r = ik.forward(q)
        seeds = ik.seeds(p, r)
        chosen = ik._chosen_seed(p, r)
        if not seeds:
            assert chosen is None
            continue
        first, inside = ik._closest_seed(seeds)
        assert chosen is not None
        assert chosen[0].tobytes() == seeds[first].tobytes() and chosen[1] == inside
        outcomes.add((inside, first > 0))
    # stopped early at a later seed, and fell back to choosing among all
    assert (True, True) in outcomes and any(not inside for inside, _ in outcomes)
    assert ik._chosen_seed(np.array([5.0, 0.0, 0.0]), np.eye(3)) is None  # out of reach


def test_ik_step_is_minks_solve_ik(ik: ArmIK) -> None:
    """ArmIK's step (its own daqp call) is mink.solve_ik's velocity, bit for bit, with the
    limits inactive and active (joints at a limit, far targets)."""
    import mink

    assert ik._qp_rows is not None  # the daqp path is the one under test
    generic = ArmIK()
    generic._qp_rows = None  # mink.build_ik and qpsolvers, as for another solver
    rng = np.random.default_rng(6)
    at_limit = 0
    for k in range(200):
        q = rng.uniform(ik.lower, ik.upper)
        if k % 2:
            q = np.clip(rng.uniform(ik.lower - 1.0, ik.upper + 1.0), ik.lower, ik.upper)
        spread = 0.15 if k % 3 else 0.8
        target = np.array([0.5, 0.0, 0.5]) + rng.uniform(-spread, spread, 3)
        rotation = rot_x(float(rng.uniform(-3, 3))) @ rot_y(float(rng.uniform(-1.5, 1.5)))
        ik.task.set_target(
            mink.SE3.from_rotation_and_translation(mink.SO3.from_matrix(rotation), target)
        )
        ik.configuration.update(q)
        ours = ik._ik_velocity()
        at_limit += bool(np.any(q == ik.lower) or np.any(q == ik.upper))
        ik.configuration.update(q)
        theirs = mink.solve_ik(
            ik.configuration,
            [ik.task],
            1.0,
            ik.config.solver,
            damping=ik.config.damping,
            limits=ik.limits,
        )
        assert ours.tobytes() == theirs.tobytes()
        generic.task.set_target(ik.task.transform_target_to_world)
        generic.configuration.update(q)
        assert generic._ik_velocity().tobytes() == theirs.tobytes()
    assert at_limit > 50
    # and with a joint at its limit and a far target (the limit rows active)
    q = np.clip(ik.upper + 0.5, ik.lower, ik.upper)
    far = mink.SE3.from_rotation_and_translation(
        mink.SO3.from_matrix(np.eye(3)), np.array([0.2, 0.5, 0.9])
    )
    for model in (ik, generic):
        model.task.set_target(far)
    ik.configuration.update(q)
    theirs = mink.solve_ik(
        ik.configuration, [ik.task], 1.0, "daqp", damping=ik.config.damping, limits=ik.limits
    )
    generic.configuration.update(q)
    assert generic._ik_velocity().tobytes() == theirs.tobytes()


def test_ik_config_defaults_and_the_task_weights(ik: ArmIK) -> None:
    """The project's settings (the v1 fingerprints depend on them): 1 mm, 0.01 rad, 10
    QPs, daqp; the position error weighted 1 against orientation_cost."""
    assert IKConfig() == IKConfig(1e-3, 1e-2, 10, "daqp", 1e-6, 0.5)
    assert ik.task.position_cost == 1.0 and ik.task.orientation_cost == 0.5


def test_an_exact_seed_inside_the_limits_needs_no_iteration(ik: ArmIK) -> None:
    rng = np.random.default_rng(7)
    exact = 0
    for _ in range(20):
        p, r = ik.forward(rng.uniform(ik.lower, ik.upper))
        chosen = ik._chosen_seed(p, r)
        assert chosen is not None
        res = ik.solve(p, r)
        if chosen[1]:  # a seed inside the limits: it is the answer, as it is
            exact += 1
            assert res.success and res.iterations == 0 and res.q is not None
            assert res.q.tobytes() == chosen[0].tobytes()
            assert res.position_error < 1e-9 and res.orientation_error < 1e-9
    assert exact >= 10


def _far_from_the_seeds(ik: ArmIK) -> tuple[FloatArray, FloatArray]:
    """A target of joint values beyond the limits: every closed-form seed breaks one, so
    the search starts from a clipped seed with both errors large."""
    q = np.random.default_rng(0).uniform(ik.lower - 0.6, ik.upper + 0.6)
    p, r = ik.forward(q)
    chosen = ik._chosen_seed(p, r)
    assert chosen is not None and not chosen[1]
    return p, r


def test_both_tolerances_must_hold(ik: ArmIK) -> None:
    p, r = _far_from_the_seeds(ik)
    inside = np.array([0.2, -0.4, 0.1, -1.2, 0.3, 0.5, -0.2])
    for tight in ({"position_tolerance": 1e-300}, {"orientation_tolerance": 1e-300}):
        strict = ArmIK(IKConfig(**tight))  # type: ignore[arg-type]
        res = strict.solve(p, r)
        assert not res.success and res.reason == "no convergence" and res.iterations == 10
    # the exact seed of a target inside the limits (position error 5e-16) fails a tight
    # position tolerance too, though its orientation error is within the default: mink
    # refines it
    pi, ri = strict.forward(inside)
    assert strict._chosen_seed(pi, ri)[1]  # type: ignore[index]
    res = ArmIK(IKConfig(position_tolerance=1e-300)).solve(pi, ri)
    assert res.iterations >= 1


def test_max_iterations_bounds_the_qps(ik: ArmIK, monkeypatch: pytest.MonkeyPatch) -> None:
    p, r = _far_from_the_seeds(ik)
    for n in (0, 1, 3):
        strict = ArmIK(IKConfig(position_tolerance=1e-300, max_iterations=n))
        calls: list[int] = []

        def counted(step: Any = strict._ik_velocity, calls: list[int] = calls) -> Any:
            calls.append(1)
            return step()

        monkeypatch.setattr(strict, "_ik_velocity", counted)
        res = strict.solve(p, r)
        assert len(calls) == n and res.iterations == n and not res.success
        assert res.q is not None
        if n:  # the errors reported are those of the q returned
            pe, oe = strict._errors(res.q)
            assert (res.position_error, res.orientation_error) == (pe, oe)
            assert pe > 1e-3 and oe > 1e-3  # both errors are in play
        else:  # no QP: the clipped seed, no errors measured
            assert res.position_error == math.inf


def test_errors_split_position_and_orientation(ik: ArmIK) -> None:
    """A target at the tool point, turned 0.5 rad about the approach axis: no position
    error, 0.5 rad of orientation error."""
    q = np.array([0.2, -0.4, 0.1, -1.2, 0.3, 0.5, -0.2])
    p, r = ik.forward(q)
    ik.solve(p, r @ rot_x(0.5))  # sets the task's target
    pe, oe = ik._errors(q)
    assert pe < 1e-12 and oe == pytest.approx(0.5)
    # and turned about another axis: the orientation error is still not position error
    ik.solve(p, r @ rot_y(0.3))
    pe, oe = ik._errors(q)
    assert pe < 1e-12 and oe == pytest.approx(0.3)


def test_a_failed_daqp_solve_raises(ik: ArmIK, monkeypatch: pytest.MonkeyPatch) -> None:
    import mink

    from voot.envs.robot import arm_ik

    solve = arm_ik.daqp.solve

    def failing(*args: object, **kwargs: object) -> object:
        x, fval, _, info = solve(*args, **kwargs)
        return x, fval, -1, info  # a solution vector, but infeasible

    monkeypatch.setattr(arm_ik.daqp, "solve", failing)
    ik.configuration.update(np.zeros(7))
    with pytest.raises(mink.NoSolutionFound):
        ik._daqp_velocity()
