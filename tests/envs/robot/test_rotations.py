"""Tests of voot.envs.robot.rotations: elementary rotations and XYX Euler angles."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voot.envs.robot.rotations import rot_x, rot_y, rot_z, xyx_euler


def test_xyx_euler_round_trip() -> None:
    rng = np.random.default_rng(0)
    for _ in range(200):
        a, b, c = rng.uniform(-3.0, 3.0, 3)
        r = rot_x(a) @ rot_y(b) @ rot_x(c)
        sols = xyx_euler(r)
        assert 1 <= len(sols) <= 2
        for s in sols:
            np.testing.assert_allclose(rot_x(s[0]) @ rot_y(s[1]) @ rot_x(s[2]), r, atol=1e-9)
    # singular: b = 0
    (s,) = xyx_euler(rot_x(0.3) @ rot_x(0.4))
    np.testing.assert_allclose(rot_x(s[0]) @ rot_y(s[1]) @ rot_x(s[2]), rot_x(0.7), atol=1e-9)


def test_elementary_rotations_are_proper_and_turn_the_right_way() -> None:
    for rot, axis in ((rot_x, 0), (rot_y, 1), (rot_z, 2)):
        r = rot(0.7)
        np.testing.assert_allclose(r.T @ r, np.eye(3), atol=1e-15)
        assert np.linalg.det(r) == pytest.approx(1.0)
        np.testing.assert_array_equal(r[:, axis], np.eye(3)[axis])  # the axis stays put
    # a quarter turn takes each axis to the next one (right-handed)
    quarter = math.pi / 2
    np.testing.assert_allclose(rot_z(quarter) @ [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(rot_x(quarter) @ [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(rot_y(quarter) @ [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], atol=1e-15)


def test_wrap_lands_in_minus_pi_to_pi_and_keeps_the_angle() -> None:
    from voot.envs.robot.rotations import _wrap

    assert _wrap(0.0) == 0.0 and _wrap(math.pi) == -math.pi and _wrap(-math.pi) == -math.pi
    assert _wrap(1.5 * math.pi) == pytest.approx(-0.5 * math.pi)
    assert _wrap(-1.5 * math.pi) == pytest.approx(0.5 * math.pi)
    for a in np.random.default_rng(0).uniform(-20.0, 20.0, 200):
        w = _wrap(float(a))
        assert -math.pi <= w < math.pi
        assert math.cos(w) == pytest.approx(math.cos(a)) and math.sin(w) == pytest.approx(
            math.sin(a), abs=1e-12
        )


def test_xyx_euler_tolerates_a_rounded_cosine_above_one() -> None:
    """R[0, 0] a rounding above 1 (or below -1) is b = 0 (pi), not a math domain error."""
    r = rot_x(0.7).copy()
    r[0, 0] = 1.0 + 2.0**-52
    (s,) = xyx_euler(r)
    assert s[1] == 0.0 and s[0] == pytest.approx(0.7)
    flipped = rot_x(0.2) @ rot_y(math.pi)
    flipped[0, 0] = -1.0 - 2.0**-52
    (s,) = xyx_euler(flipped)
    assert s[1] == math.pi
