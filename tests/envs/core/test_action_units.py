"""Normalised action units (voot.envs.core.units): the affine map and its float form."""

from __future__ import annotations

import numpy as np

from voot.envs.core.units import denormalize, denormalize_floats, normalize


def test_denormalize_and_normalize() -> None:
    ranges = ((-2.0, 6.0), (-4.0, 4.0), (0.0, 6.283185307179586))
    a = np.array([0.1, -0.7, 0.3])
    lo = np.array([r[0] for r in ranges])
    hi = np.array([r[1] for r in ranges])
    ref = lo + 0.5 * (a + 1.0) * (hi - lo)
    assert denormalize(a, ranges).tobytes() == ref.tobytes()
    assert denormalize(a, list(ranges)).tobytes() == ref.tobytes()
    assert np.allclose(normalize(ref, ranges), a)
    out = denormalize(a, ranges)
    out[0] = 9.0  # a fresh array: the cached ranges are not touched
    assert denormalize(a, ranges).tobytes() == ref.tobytes()


def test_denormalize_floats_is_denormalize() -> None:
    ranges = ((-0.3, 1.7), (0.5, 1.0), (-np.pi, np.pi))
    rng = np.random.default_rng(8)
    for a in [*rng.uniform(-1, 1, (500, 3)), np.array([-1.0, 1.0, 0.0])]:
        ref = denormalize(a, ranges).tolist()
        assert denormalize_floats(a.tolist(), ranges) == ref
        assert denormalize_floats(a.tolist(), [list(r) for r in ranges]) == ref  # unhashable
