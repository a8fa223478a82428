"""Tests of voot.bench.store.compact: exact step curves, reduced cost curves, validation."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from voot.bench.measure.store_speed import synthetic_plan_row
from voot.bench.store.compact import (
    COMPACT_KEY,
    INTERPOLATED_KEY,
    CompactConfig,
    check_compact,
    check_roundtrip,
    compact_row,
    decode_curve,
    encode_curve,
    expand_row,
    is_compact,
    kept_indices,
)
from voot.bench.store.format import make_row


def plan_row(n: int = 3000, seed: int = 0) -> dict:
    return synthetic_plan_row(seed, n, np.random.default_rng(seed))


def through_json(row: dict) -> dict:
    return json.loads(json.dumps(row))


def test_step_curves_come_back_bit_for_bit_and_cost_curves_keep_first_and_last() -> None:
    row = plan_row()
    small = through_json(compact_row(row, CompactConfig()))
    assert is_compact(small) and "best_so_far" not in small and "elapsed" not in small
    back = expand_row(small)
    for key in ("best_so_far", "objects_left"):
        assert back[key] == row[key]  # exact, through JSON
    for key in ("elapsed", "cpu_elapsed", "calls_curve"):
        assert len(back[key]) == len(row[key]) == 3000
        assert back[key][0] == row[key][0] and back[key][-1] == row[key][-1]
        assert np.all(np.diff(back[key]) >= 0)  # interpolation keeps them monotone
        at = small[COMPACT_KEY]["curves"][key]["at"]
        assert [back[key][i] for i in at] == [row[key][i] for i in at]
        assert len(at) <= 102
    assert back[INTERPOLATED_KEY] == ["calls_curve", "cpu_elapsed", "elapsed"]
    assert {k: v for k, v in back.items() if k != INTERPOLATED_KEY}.keys() == row.keys()
    check_roundtrip(row, small)
    assert len(json.dumps(small)) * 10 < len(json.dumps(row))


def test_interpolated_values_are_close_on_a_smooth_curve() -> None:
    elapsed = np.cumsum(np.full(3000, 0.01))
    entry = encode_curve("elapsed", elapsed.tolist(), CompactConfig())
    assert entry is not None and entry["codec"] == "sampled"
    assert np.allclose(decode_curve(entry), elapsed, rtol=0, atol=1e-12)


def test_nan_entries_stay_nan_and_short_or_nan_cost_curves_stay_exact() -> None:
    left = [None, None, 3.0, 3.0, None, 1.0]
    entry = encode_curve("objects_left", left, CompactConfig())
    assert entry is not None and entry["codec"] == "steps" and entry["at"] == [0, 2, 4, 5]
    out = decode_curve(entry)
    assert np.isnan(out[[0, 1, 4]]).all() and out[2] == out[3] == 3.0 and out[5] == 1.0
    short = encode_curve("elapsed", [0.1, 0.2, 0.3], CompactConfig(points=5))
    assert short is not None and short["codec"] == "steps"  # no longer than the points
    with_nan = encode_curve("elapsed", [0.1] * 50 + [math.nan] * 150, CompactConfig(points=10))
    assert with_nan is not None and with_nan["codec"] == "steps"
    row = make_row("plan", {"seed": 0}, status="ok", wall_time=0.0, best_so_far=[1.0, 1.0])
    row["objects_left"] = left
    back = expand_row(compact_row(row, CompactConfig()))
    assert back["objects_left"] == left and INTERPOLATED_KEY not in back


def test_kept_indices_are_sorted_unique_and_hold_both_ends() -> None:
    for spacing in ("log", "linear"):
        config = CompactConfig(points=100, spacing=spacing)
        for n in (1, 2, 7, 2000, 3000):
            idx = kept_indices(n, config)
            assert idx[0] == 0 and idx[-1] == n - 1
            assert np.all(np.diff(idx) > 0) and idx.size <= min(n, 102)
    log = kept_indices(3000, CompactConfig(spacing="log"))
    linear = kept_indices(3000, CompactConfig(spacing="linear"))
    assert (log < 30).sum() > (linear < 30).sum()  # log: dense at the start
    assert kept_indices(0, CompactConfig()).size == 0


def test_a_compact_row_is_left_as_it_is_and_a_full_row_expands_to_a_copy() -> None:
    small = compact_row(plan_row(100), CompactConfig(points=10))
    assert compact_row(small, CompactConfig(points=50)) == small
    full = plan_row(10)
    assert expand_row(full) == full and expand_row(full) is not full
    arrays = expand_row(small, arrays=True)
    assert isinstance(arrays["best_so_far"], np.ndarray)
    assert not arrays["best_so_far"].flags.writeable


def test_config_validation_names_the_valid_choices() -> None:
    with pytest.raises(ValueError, match="valid spacings are: log, linear"):
        CompactConfig(spacing="cubic")
    with pytest.raises(ValueError, match="points"):
        CompactConfig(points=1)
    assert CompactConfig.from_dict(CompactConfig(7, "linear").to_dict()) == CompactConfig(
        7, "linear"
    )
    with pytest.raises(ValueError, match="version"):
        CompactConfig.from_dict({"version": 99})
    with pytest.raises(ValueError, match="object"):
        CompactConfig.from_dict([1])


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda c: c["curves"]["elapsed"].update(codec="zip"), "valid codecs are: steps, sampled"),
        (lambda c: c["curves"]["elapsed"]["at"].pop(), "lists of one length"),
        (lambda c: c["curves"]["elapsed"].update(n=-1), "'n' must be an integer"),
        (lambda c: c["curves"]["best_so_far"]["at"].__setitem__(0, 1), "rise strictly from 0"),
        (lambda c: c["curves"]["elapsed"]["at"].__setitem__(-1, 3001), "rise strictly"),
        (lambda c: c["curves"]["elapsed"]["values"].__setitem__(0, "x"), "numbers or null"),
        (lambda c: c["curves"].pop("best_so_far"), "without its 'best_so_far'"),
        (lambda c: c.update(version=7), "version"),
        (lambda c: c.pop("curves"), "'curves' object"),
    ],
)
def test_corrupt_compact_data_is_refused_with_the_reason(change: object, message: str) -> None:
    small = through_json(compact_row(plan_row(), CompactConfig()))
    check_compact(small[COMPACT_KEY])
    change(small[COMPACT_KEY])  # type: ignore[operator]
    with pytest.raises(ValueError, match=message):
        check_compact(small[COMPACT_KEY])


def test_a_sampled_curve_must_keep_its_last_index() -> None:
    small = through_json(compact_row(plan_row(), CompactConfig()))
    entry = small[COMPACT_KEY]["curves"]["elapsed"]
    entry["at"], entry["values"] = entry["at"][:-1], entry["values"][:-1]
    with pytest.raises(ValueError, match="last index"):
        check_compact(small[COMPACT_KEY])


def test_roundtrip_check_catches_a_changed_curve() -> None:
    row = plan_row(500)
    small = through_json(compact_row(row, CompactConfig()))
    small[COMPACT_KEY]["curves"]["best_so_far"]["values"][-1] += 1.0
    with pytest.raises(ValueError, match="best_so_far"):
        check_roundtrip(row, small)
    other = through_json(compact_row(row, CompactConfig()))
    other["wall_time"] = -1.0
    with pytest.raises(ValueError, match="wall_time"):
        check_roundtrip(row, other)
