"""Tests of the per-ask cost measurement (voot.bench.measure.speed); no timing assertions."""

from __future__ import annotations

import numpy as np
import pytest

from voot.bench.measure import speed
from voot.bench.measure.speed import measure_ask_cost, shifted_sphere


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


# ----- VOO per ask + tell, per objective (voot-bench voo-speed) ----------------------------
def test_voo_cost_times_asks_and_tells_not_the_objective() -> None:
    # a clock that ticks once per reading: 2 ticks (ask) + 2 ticks (tell) per evaluation
    ticks = iter(range(1000))
    seconds, improved = speed.measure_voo_cost(
        "sphere", 20, 3, 7, 0, timer=lambda: float(next(ticks))
    )
    assert seconds == 2.0  # (1 tick for the ask + 1 for the tell) per evaluation
    assert 0 <= improved <= 7


def test_voo_cost_counts_improvements() -> None:
    # on the centred sphere VOO keeps improving early on; never more than every evaluation
    _, improved = speed.measure_voo_cost("sphere", 10, 2, 100, 0)
    assert 0 < improved < 100
    seconds, _ = speed.measure_voo_cost("shekel", 10, 3, 5, 1, sampler="gaussian")
    assert 0.0 < seconds < 1.0


@pytest.mark.parametrize(
    ("args", "match"),
    [
        (("cube", 10, 3, 5, 0), "valid objectives are: sphere, shifted_sphere, ackley"),
        (("sphere", -1, 3, 5, 0), "n must be"),
        (("sphere", 10, 0, 5, 0), "dim must be"),
        (("sphere", 10, 3, 0, 0), "repeats must be"),
    ],
)
def test_voo_cost_bad_arguments(args: tuple, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        speed.measure_voo_cost(*args)


def test_voo_speed_command(capsys: pytest.CaptureFixture[str]) -> None:
    from voot.bench.cli.main import main

    argv = ["measure", "voo-speed", "--objectives", "sphere", "shifted_sphere", "--n", "30"]
    assert main([*argv, "--dim", "3", "--repeats", "4", "--seeds", "2"]) == 0
    out = capsys.readouterr().out
    rows = [line for line in out.splitlines() if line.startswith("| sphere") or "shifted" in line]
    assert [r.split("|")[1:3] for r in rows] == [
        [" sphere ", " 0 "],
        [" sphere ", " 1 "],
        [" shifted_sphere ", " 0 "],
        [" shifted_sphere ", " 1 "],
    ]
    assert main(["measure", "voo-speed", "--repeats", "0"]) == 2
    assert "--repeats must be >= 1" in capsys.readouterr().err
