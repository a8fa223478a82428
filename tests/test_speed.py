"""Tests of the per-ask cost measurement (voot.bench.speed); no timing assertions."""

from __future__ import annotations

import numpy as np
import pytest

from voot.bench import speed
from voot.bench.speed import measure_ask_cost, shifted_sphere


def test_shifted_sphere() -> None:
    assert shifted_sphere(np.full(4, speed.SPHERE_SHIFT)) == 0.0
    assert shifted_sphere(np.zeros(2)) == pytest.approx(-2 * speed.SPHERE_SHIFT**2)


@pytest.mark.parametrize("method", ["voo", "random", "cmaes"])
def test_returns_seconds_per_ask(method: str) -> None:
    seconds = measure_ask_cost(method, 30, 3, 5, 0)
    assert isinstance(seconds, float) and 0.0 < seconds < 1.0


def test_asks_do_not_tell(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = {"ask": 0, "tell": 0}
    from voot.optim.voo import VOO

    ask, tell = VOO.ask, VOO.tell

    def counting_ask(self: VOO) -> np.ndarray:
        calls["ask"] += 1
        return ask(self)

    def counting_tell(self: VOO, x: np.ndarray, value: float) -> None:
        calls["tell"] += 1
        tell(self, x, value)

    monkeypatch.setattr(VOO, "ask", counting_ask)
    monkeypatch.setattr(VOO, "tell", counting_tell)
    measure_ask_cost("voo", 20, 2, 7, 0, sampler="gaussian")
    assert calls == {"ask": 27, "tell": 20}


@pytest.mark.parametrize(
    ("args", "match"),
    [
        (("voo", -1, 3, 5, 0), "n must be"),
        (("voo", 10, 0, 5, 0), "dim must be"),
        (("voo", 10, 3, 0, 0), "repeats must be"),
        (("voo", 10, 3, 2.5, 0), "repeats must be"),
        (("nelder_mead", 10, 3, 5, 0), "unknown method"),
    ],
)
def test_bad_arguments(args: tuple, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        measure_ask_cost(*args)


def test_custom_timer() -> None:
    ticks = iter(range(100))
    seconds = measure_ask_cost("random", 3, 2, 4, 0, timer=lambda: float(next(ticks)))
    assert seconds == 0.25  # one tick between start and end, over 4 asks
