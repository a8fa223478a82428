"""voot.bench.report.stats against the published definitions (rliable's): hand-computed
examples, properties, the vectorised bootstrap against explicit resampling, bounds,
determinism and the input checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.stats
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from voot.bench.report import stats as S

FAST = S.Bootstrap(reps=800, seed=3)


def _scores(seed: int, runs: int = 6, tasks: int = 5, a: float = 2.0, b: float = 3.0):
    return np.random.default_rng(seed).beta(a, b, size=(runs, tasks))


# ----- point estimates by hand ----------------------------------------------------------
def test_iqm_of_known_arrays() -> None:
    # 8 scores: 2 cut from each end, the mean of 3, 4, 5, 6
    assert S.aggregate_iqm(np.arange(1.0, 9.0).reshape(2, 4)) == 4.5
    # 4 scores: 1 cut from each end; the outlier does not count
    assert S.aggregate_iqm([[1.0], [2.0], [3.0], [100.0]]) == 2.5
    # 10 scores: floor(2.5) = 2 cut from each end (scipy.stats.trim_mean's rule)
    assert S.aggregate_iqm(np.arange(10.0).reshape(5, 2)) == pytest.approx(
        np.mean([2, 3, 4, 5, 6, 7])
    )
    # fewer than 4 scores: nothing cut
    assert S.aggregate_iqm([[1.0, 2.0, 6.0]]) == 3.0


def test_mean_median_and_optimality_gap_by_hand() -> None:
    x = np.array([[0.0, 2.0, 10.0], [2.0, 2.0, 10.0]])  # task means 1, 2, 10
    assert S.aggregate_mean(x) == pytest.approx(13 / 3)
    assert S.aggregate_median(x) == 2.0
    assert S.optimality_gap([[0.5, 1.5], [1.0, 0.0]]) == pytest.approx(1 - (0.5 + 1 + 1 + 0) / 4)
    assert S.optimality_gap([[5.0, 20.0]], gamma=10.0) == pytest.approx(10 - 7.5)


def test_probability_of_improvement_of_known_samples() -> None:
    # 3 of the 4 pairs won: 3>1, 5>1, 5>4 (3<4)
    assert S.probability_of_improvement([[3.0], [5.0]], [[1.0], [4.0]]) == 0.75
    # ties count 1/2: (1/2 + 1 + 1/2 + 1) / 4
    assert S.probability_of_improvement([[2.0], [2.0]], [[2.0], [1.0]]) == 0.75
    # averaged over tasks: 0.75 on the first, 0 on the second
    x = [[3.0, 0.0], [5.0, 0.0]]
    y = [[1.0, 1.0], [4.0, 1.0]]
    assert S.probability_of_improvement(x, y) == 0.375
    # runs may differ in number: 2 x 3 pairs, 5 won
    assert S.probability_of_improvement([[2.0], [9.0]], [[1.0], [3.0], [0.0]]) == 5 / 6


def test_probability_of_improvement_is_the_mann_whitney_statistic() -> None:
    x, y = _scores(0, 7, 4), np.round(_scores(1, 5, 4), 1)
    per_task = [
        scipy.stats.mannwhitneyu(x[:, t], y[:, t], alternative="greater").statistic / (7 * 5)
        for t in range(4)
    ]
    assert S.probability_of_improvement(x, y) == pytest.approx(np.mean(per_task), abs=1e-12)


def test_profiles_at_known_thresholds() -> None:
    x = [[0.1, 0.5], [0.9, 0.3]]  # task means 0.5 and 0.4
    taus = [0.0, 0.3, 0.45, 0.5, 1.0]
    # strictly above: all 4; 0.5 and 0.9; 0.5 and 0.9; 0.9; none
    np.testing.assert_array_equal(S.run_score_profile(x, taus), [1.0, 0.5, 0.5, 0.25, 0.0])
    np.testing.assert_array_equal(S.average_score_profile(x, taus), [1.0, 1.0, 0.5, 0.0, 0.0])


# ----- properties -----------------------------------------------------------------------
_finite = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)
_arrays = hnp.arrays(
    np.float64, hnp.array_shapes(min_dims=2, max_dims=2, max_side=6), elements=_finite
)


@settings(max_examples=60, deadline=None)
@given(_arrays, st.randoms(use_true_random=False))
def test_iqm_lies_between_min_and_max_and_ignores_run_order(x: np.ndarray, rnd) -> None:
    iqm = S.aggregate_iqm(x)
    ulps = 4 * np.spacing(np.abs(x).max())  # a mean of equal values may round by an ulp
    assert x.min() - ulps <= iqm <= x.max() + ulps
    # each task's runs shuffled on their own, and the tasks shuffled: same IQM
    perm = np.random.default_rng(rnd.randrange(2**32))
    shuffled = np.stack([perm.permutation(col) for col in x.T], axis=1)[
        :, perm.permutation(x.shape[1])
    ]
    assert S.aggregate_iqm(shuffled) == pytest.approx(iqm, rel=1e-12, abs=1e-9)
    assert S.aggregate_median(shuffled) == pytest.approx(S.aggregate_median(x), rel=1e-12, abs=1e-9)


@settings(max_examples=40, deadline=None)
@given(
    st.integers(1, 5),
    st.integers(1, 5),
    st.integers(1, 4),
    st.data(),
)
def test_improvement_both_ways_sums_to_one(nx: int, ny: int, tasks: int, data) -> None:
    # distinct values: no ties
    values = data.draw(
        st.lists(_finite, min_size=(nx + ny) * tasks, max_size=(nx + ny) * tasks, unique=True)
    )
    v = np.array(values)
    x, y = v[: nx * tasks].reshape(nx, tasks), v[nx * tasks :].reshape(ny, tasks)
    assert S.probability_of_improvement(x, y) + S.probability_of_improvement(y, x) == pytest.approx(
        1.0
    )
    # with ties counted 1/2 it holds too, and a planner against itself is a coin flip
    rounded = np.round(x / 1e6)
    assert S.probability_of_improvement(rounded, y) + S.probability_of_improvement(
        y, rounded
    ) == pytest.approx(1.0)
    assert S.probability_of_improvement(x, x) == 0.5


@settings(max_examples=40, deadline=None)
@given(_arrays)
def test_profiles_fall_from_one_to_zero(x: np.ndarray) -> None:
    top = x.max() + 1e-9 * np.abs(x).max()  # a task's mean of equal scores may round up
    taus = np.linspace(x.min() - 1, top, 7)
    for profile in (S.run_score_profile(x, taus), S.average_score_profile(x, taus)):
        assert profile[0] == 1.0 and profile[-1] == 0.0
        assert np.all(np.diff(profile) <= 0)


# ----- the vectorised bootstrap is the stratified bootstrap -----------------------------
def _replicates(x: np.ndarray, indices: np.ndarray) -> list[np.ndarray]:
    """Each replicate materialised: each task's runs drawn by index (rliable's scheme)."""
    return [np.take_along_axis(x, idx, axis=0) for idx in indices]


def test_counts_count_the_drawn_runs() -> None:
    idx = S.draw_indices(np.random.default_rng(0), 4, 5, 3)
    counts = S.run_counts(idx)
    assert counts.shape == (4, 5, 3)
    for b in range(4):
        for t in range(3):
            np.testing.assert_array_equal(counts[b, :, t], np.bincount(idx[b, :, t], minlength=5))


def test_replicate_statistics_match_explicit_resampling() -> None:
    x = np.round(_scores(2, 9, 7), 2)  # ties included
    idx = S.draw_indices(np.random.default_rng(5), 60, *x.shape)
    counts = S.run_counts(idx)
    res = S._Resamples(x)
    cum = res.cumulative(counts)
    reps = _replicates(x, idx)
    expected = {
        S.Metric.MEAN: [S.aggregate_mean(r) for r in reps],
        S.Metric.MEDIAN: [S.aggregate_median(r) for r in reps],
        S.Metric.IQM: [S.aggregate_iqm(r) for r in reps],
        S.Metric.OPTIMALITY_GAP: [S.optimality_gap(r, 0.6) for r in reps],
    }
    for metric, values in expected.items():
        np.testing.assert_allclose(res.metric(metric, counts, cum, 0.6), values, rtol=0, atol=1e-12)
    taus = np.linspace(-0.1, 1.1, 25)
    np.testing.assert_allclose(
        res.run_profile(cum, taus), [S.run_score_profile(r, taus) for r in reps], atol=1e-12
    )
    np.testing.assert_allclose(
        res.task_profile(counts, taus), [S.average_score_profile(r, taus) for r in reps], atol=1e-12
    )


def test_improvement_interval_is_the_percentile_interval_of_resampled_pairs() -> None:
    x, y = np.round(_scores(3, 5, 4), 1), np.round(_scores(4, 6, 4), 1)
    bs = S.Bootstrap(reps=300, seed=9)
    got = S.improvement_interval(x, y, bs, names=("p", "q"))
    # the same stream, drawn as the module draws it: p's runs, then q's
    rng = S._generator(bs.seed, "P(X>Y)", "p", "q")
    ix = S.draw_indices(rng, bs.reps, *x.shape)
    iy = S.draw_indices(rng, bs.reps, *y.shape)
    values = [
        S.probability_of_improvement(rx, ry)
        for rx, ry in zip(_replicates(x, ix), _replicates(y, iy), strict=True)
    ]
    low, high = np.percentile(values, [2.5, 97.5])
    assert got.estimate == S.probability_of_improvement(x, y)
    assert got.low == pytest.approx(low, abs=1e-12) and got.high == pytest.approx(high, abs=1e-12)


def test_aggregate_interval_is_the_percentile_interval_of_the_replicates() -> None:
    x = _scores(6, 4, 3)
    bs = S.Bootstrap(reps=500, seed=1, confidence=0.9)
    got = S.aggregate_intervals({"a": x}, ["iqm", "mean"], bs)["a"]
    idx = S.draw_indices(S._generator(bs.seed, "a"), bs.reps, *x.shape)
    reps = _replicates(x, idx)
    for metric, f in ((S.Metric.IQM, S.aggregate_iqm), (S.Metric.MEAN, S.aggregate_mean)):
        low, high = np.percentile([f(r) for r in reps], [5.0, 95.0])
        assert got[metric].estimate == f(x)
        assert got[metric].low == pytest.approx(low, abs=1e-12)
        assert got[metric].high == pytest.approx(high, abs=1e-12)


# ----- determinism, independence, bounds ------------------------------------------------
def test_same_seed_gives_bit_identical_intervals() -> None:
    scores = {"a": _scores(0), "b": _scores(1)}
    metrics = list(S.Metric)
    assert S.aggregate_intervals(scores, metrics, FAST) == S.aggregate_intervals(
        scores, metrics, FAST
    )
    p1 = S.performance_profiles(scores, [0.2, 0.5], bootstrap=FAST)
    p2 = S.performance_profiles(scores, [0.2, 0.5], bootstrap=FAST)
    for k in scores:
        np.testing.assert_array_equal(p1[k].low, p2[k].low)
        np.testing.assert_array_equal(p1[k].high, p2[k].high)
    assert S.improvement_probabilities(scores, bootstrap=FAST) == S.improvement_probabilities(
        scores, bootstrap=FAST
    )
    other = S.aggregate_intervals(scores, metrics, S.Bootstrap(reps=FAST.reps, seed=FAST.seed + 1))
    assert (
        other["a"][S.Metric.IQM] != S.aggregate_intervals(scores, metrics, FAST)["a"][S.Metric.IQM]
    )


def test_a_planners_interval_does_not_depend_on_the_others() -> None:
    a, b = _scores(0), _scores(1)
    alone = S.aggregate_intervals({"a": a}, bootstrap=FAST)["a"]
    assert S.aggregate_intervals({"b": b, "a": a}, bootstrap=FAST)["a"] == alone
    c = _scores(2)
    pair = S.improvement_probabilities({"a": a, "b": b}, bootstrap=FAST)[("a", "b")]
    assert S.improvement_probabilities({"c": c, "b": b, "a": a}, bootstrap=FAST)[("a", "b")] == pair


def test_improvement_both_ways_uses_mirrored_replicates() -> None:
    out = S.improvement_probabilities({"a": _scores(0), "b": _scores(1, 8)}, bootstrap=FAST)
    ab, ba = out[("a", "b")], out[("b", "a")]
    assert ab.estimate + ba.estimate == pytest.approx(1.0)
    assert ab.low == pytest.approx(1 - ba.high, abs=1e-12)
    assert ab.high == pytest.approx(1 - ba.low, abs=1e-12)
    assert set(out) == {("a", "b"), ("b", "a")}


@pytest.mark.parametrize(
    "x",
    [
        np.ones((5, 4)),
        np.zeros((5, 4)),
        np.array([[0.0, 1.0]] * 3 + [[1.0, 0.0]] * 2),  # all at the bounds
        np.random.default_rng(0).beta(0.1, 0.1, size=(6, 5)),  # near the bounds
        np.random.default_rng(1).uniform(size=(3, 20)),
    ],
)
def test_intervals_of_scores_in_zero_one_stay_in_zero_one(x: np.ndarray) -> None:
    y = np.random.default_rng(2).beta(0.2, 0.2, size=(4, x.shape[1]))
    scores = {"x": x, "y": y}
    for iv in S.aggregate_intervals(scores, ["mean", "median", "iqm"], FAST)["x"].values():
        assert 0.0 <= iv.low <= iv.high <= 1.0 and 0.0 <= iv.estimate <= 1.0
    gap = S.aggregate_intervals(scores, ["optimality_gap"], FAST)["x"][S.Metric.OPTIMALITY_GAP]
    assert 0.0 <= gap.low <= gap.high <= 1.0
    for kind in S.ProfileKind:
        prof = S.performance_profiles(scores, np.linspace(-0.5, 1.5, 17), kind, FAST)["x"]
        assert np.all((prof.low >= 0) & (prof.low <= prof.high) & (prof.high <= 1))
    for iv in S.improvement_probabilities(scores, bootstrap=FAST).values():
        assert 0.0 <= iv.low <= iv.high <= 1.0


def test_constant_scores_and_a_single_run_give_zero_width_intervals() -> None:
    iv = S.aggregate_intervals({"a": np.full((4, 3), 0.7)}, ["iqm"], FAST)["a"][S.Metric.IQM]
    assert iv.low == pytest.approx(0.7) and iv.high == pytest.approx(0.7)
    one_run = np.array([[0.1, 0.4, 0.9]])
    for iv in S.aggregate_intervals({"a": one_run}, list(S.Metric), FAST)["a"].values():
        assert iv.low == pytest.approx(iv.estimate) and iv.high == pytest.approx(iv.estimate)


def test_intervals_narrow_with_more_runs() -> None:
    few = S.aggregate_intervals({"a": _scores(0, 4, 10)}, bootstrap=FAST)["a"][S.Metric.IQM]
    many = S.aggregate_intervals({"a": _scores(0, 64, 10)}, bootstrap=FAST)["a"][S.Metric.IQM]
    assert many.high - many.low < (few.high - few.low) / 2


def test_profile_result_carries_its_thresholds_and_kind() -> None:
    prof = S.performance_profiles({"a": _scores(0)}, [0.1, 0.9], "tasks", FAST)["a"]
    assert prof.kind is S.ProfileKind.TASKS
    np.testing.assert_array_equal(prof.taus, [0.1, 0.9])
    np.testing.assert_array_equal(prof.fraction, S.average_score_profile(_scores(0), [0.1, 0.9]))


# ----- bad input ------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("value", "message"),
    [
        (
            [1.0, 2.0],
            r"scores\['a'\] must be a 2-D array of shape \(runs, tasks\), got shape \(2,\)",
        ),
        (np.zeros((2, 2, 2)), r"must be a 2-D array .* got shape \(2, 2, 2\)"),
        (
            np.zeros((0, 3)),
            r"scores\['a'\] must have at least one run and one task, got shape \(0, 3\)",
        ),
        ([[1.0, math.nan], [0.0, 1.0]], r"scores\['a'\] must be finite, got nan at run 0, task 1"),
        ([[1.0, 0.0], [math.inf, 1.0]], r"must be finite, got inf at run 1, task 0"),
        ([["x", "y"]], r"scores\['a'\] must be numeric"),
        ([[True, False]], r"scores\['a'\] must be numeric"),
    ],
)
def test_bad_scores_are_named(value: object, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        S.aggregate_intervals({"a": value}, bootstrap=FAST)


def test_bad_collections_are_named() -> None:
    with pytest.raises(ValueError, match="at least one planner, got an empty mapping"):
        S.performance_profiles({}, [0.5])
    with pytest.raises(ValueError, match="scores must be a mapping"):
        S.aggregate_intervals([np.ones((2, 2))])  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"same number of tasks .* got a: 3, b: 2"):
        S.improvement_probabilities({"a": np.ones((2, 3)), "b": np.ones((2, 2))})
    with pytest.raises(ValueError, match=r"scores_x and scores_y .* got 3 and 2"):
        S.probability_of_improvement(np.ones((2, 3)), np.ones((2, 2)))
    with pytest.raises(ValueError, match=r"unknown planner\(s\) \['c'\]; valid planners are: a, b"):
        S.improvement_probabilities({"a": np.ones((2, 2)), "b": np.ones((2, 2))}, [("a", "c")])
    with pytest.raises(
        ValueError, match="unknown metric 'iqr'; valid metrics are: mean, median, iqm"
    ):
        S.aggregate_intervals({"a": np.ones((2, 2))}, ["iqr"])
    with pytest.raises(ValueError, match="metrics must name at least one metric"):
        S.aggregate_intervals({"a": np.ones((2, 2))}, [])
    with pytest.raises(ValueError, match="unknown profile kind 'episodes'"):
        S.performance_profiles({"a": np.ones((2, 2))}, [0.5], "episodes")
    with pytest.raises(ValueError, match="taus must be a non-empty 1-D array of finite numbers"):
        S.run_score_profile(np.ones((2, 2)), [[0.5]])
    with pytest.raises(ValueError, match="taus must be a non-empty 1-D array"):
        S.average_score_profile(np.ones((2, 2)), [math.nan])
    with pytest.raises(ValueError, match="gamma must be a finite number"):
        S.optimality_gap(np.ones((2, 2)), math.nan)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"reps": 0}, "reps must be an integer >= 1, got 0"),
        ({"reps": 10.0}, "reps must be an integer >= 1, got 10.0"),
        ({"confidence": 1.0}, r"confidence must be a finite number in \(0, 1\), got 1.0"),
        ({"confidence": 0}, r"confidence must be a finite number in \(0, 1\)"),
        ({"seed": -1}, "seed must be an integer >= 0, got -1"),
    ],
)
def test_bad_bootstrap_options_are_named(options: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        S.Bootstrap(**options)


def test_bootstrap_percentiles() -> None:
    # (1 - 0.95) / 2 as rliable's arch backend computes it, 2.5 up to rounding
    assert S.Bootstrap().percentiles == pytest.approx((2.5, 97.5))
    assert S.Bootstrap(confidence=0.9).percentiles == pytest.approx((5.0, 95.0))
