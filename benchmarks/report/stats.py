r"""Statistics for comparing planners across many tasks, as the field reports them.

The definitions are those of Agarwal et al., *Deep Reinforcement Learning at the Edge of
the Statistical Precipice* (NeurIPS 2021) and of their ``rliable`` package, which is how
algorithms are now compared across a suite of tasks with few runs each:

* aggregate metrics of a ``(runs, tasks)`` score array: the mean and the median of the
  per-task means, the **interquartile mean** (IQM, the mean of the middle 50% of all
  runs x tasks scores) and the optimality gap (:func:`aggregate_mean`,
  :func:`aggregate_median`, :func:`aggregate_iqm`, :func:`optimality_gap`);
* **performance profiles**: the fraction of runs (run-score distribution) or of tasks
  (average-score distribution) whose score is above each threshold tau
  (:func:`run_score_profile`, :func:`average_score_profile`);
* the **probability of improvement** ``P(X > Y)`` of one planner over another: per task the
  Mann-Whitney U statistic over all run pairs (ties count 1/2) divided by the number of
  pairs, averaged over tasks (:func:`probability_of_improvement`);
* 95% intervals on all of them by the **stratified bootstrap**: the runs of each task are
  resampled with replacement, tasks are kept, and the percentile interval of the
  resampled statistic is reported (:func:`aggregate_intervals`,
  :func:`performance_profiles`, :func:`improvement_probabilities`).

Scores come as a mapping ``planner -> array of shape (runs, tasks)``; every planner needs
the same tasks in the same column order (runs may differ in number). Choosing the tasks
(a family, a level, a layout), normalising scores to a common scale and matching budgets
(simulator calls or CPU time) are the caller's concern: this module takes arrays.

The bootstrap is deterministic: a :class:`Bootstrap` carries the seed, and each planner
(each pair, for ``P(X > Y)``) draws from its own stream derived from that seed and its
name, so a planner's interval does not move when others join the comparison, and the
same seed gives bit-identical intervals. The resampling is vectorised on multiplicities
(how often each run is drawn): one draw of ``(reps, runs, tasks)`` indices, counted, gives
every statistic above in ``O(reps x runs x tasks)`` without copying the scores per
replicate. Percentile intervals of a bounded statistic stay inside its bounds (scores in
[0, 1] give IQM and profile intervals in [0, 1], ``P(X > Y)`` intervals are in [0, 1]).

See the "Statistics across tasks" docs page for the maths and for why these, not t-intervals.
"""

from __future__ import annotations

import zlib
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
import scipy.stats
from numpy.typing import ArrayLike, NDArray

from voot import validation

#: The fraction cut from each end for the interquartile mean.
IQM_CUT = 0.25
#: Bootstrap replicates per chunk are chosen so that one chunk holds about this many
#: (replicate, run, task) cells: bounded memory whatever the reps.
_CHUNK_CELLS = 1 << 20

F64 = NDArray[np.float64]


class Metric(StrEnum):
    """The aggregate metrics of :func:`aggregate_intervals`."""

    MEAN = "mean"
    MEDIAN = "median"
    IQM = "iqm"
    OPTIMALITY_GAP = "optimality_gap"


class ProfileKind(StrEnum):
    """What a performance profile counts above each threshold."""

    #: The fraction of all runs x tasks scores above tau (rliable's default: smaller
    #: intervals, an unbiased estimate).
    RUNS = "runs"
    #: The fraction of tasks whose mean score over runs is above tau.
    TASKS = "tasks"


@dataclass(frozen=True)
class Bootstrap:
    """How intervals are estimated: stratified bootstrap, percentile intervals.

    ``reps`` defaults to 10,000 (rliable's default is 50,000 for aggregates and 2,000 for
    profiles): the Monte Carlo error of a 2.5% percentile from B replicates is about
    ``sqrt(0.025 * 0.975 / B)`` in probability, 0.0016 at 10,000 (0.0007 at 50,000),
    small beside the interval itself, and a leaderboard with a dozen planners, several
    task groups, profiles and all pairs of ``P(X > Y)`` stays at seconds. Pass
    ``reps=50_000`` to match rliable's precision.
    """

    #: Bootstrap replicates.
    reps: int = 10_000
    #: Coverage of the two-sided percentile interval.
    confidence: float = 0.95
    #: Seed of every stream (an integer >= 0).
    seed: int = 0

    def __post_init__(self) -> None:
        object.__setattr__(self, "reps", validation.integer(self.reps, "reps", 1))
        object.__setattr__(
            self,
            "confidence",
            validation.number(
                self.confidence, "confidence", 0.0, 1.0, open_low=True, open_high=True
            ),
        )
        object.__setattr__(self, "seed", validation.integer(self.seed, "seed", 0))

    @property
    def percentiles(self) -> tuple[float, float]:
        """The interval's ends as percentiles, e.g. (2.5, 97.5)."""
        tail = 100.0 * (1.0 - self.confidence) / 2.0
        return tail, 100.0 - tail


@dataclass(frozen=True)
class Interval:
    """A point estimate and its bootstrap interval ``[low, high]``."""

    estimate: float
    low: float
    high: float


@dataclass(frozen=True)
class Profile:
    """A performance profile: at each threshold ``taus[k]`` the fraction above it, with
    pointwise bootstrap bands ``low[k] .. high[k]``."""

    kind: ProfileKind
    taus: F64
    fraction: F64
    low: F64
    high: F64


# ----- input checks ---------------------------------------------------------------------
def score_array(value: ArrayLike, name: str = "scores") -> F64:
    """``value`` as a finite float64 array of shape ``(runs, tasks)``, both >= 1.

    Raises a ValueError naming ``name`` for a wrong shape, an empty array, NaN or
    infinities (with the first bad cell) and non-numeric entries.
    """
    arr = validation.real_array(value, name)
    if arr.ndim != 2:
        raise ValueError(
            f"{name} must be a 2-D array of shape (runs, tasks), got shape {arr.shape}"
        )
    if arr.size == 0:
        raise ValueError(f"{name} must have at least one run and one task, got shape {arr.shape}")
    bad = ~np.isfinite(arr)
    if bad.any():
        run, task = (int(i) for i in np.argwhere(bad)[0])
        raise ValueError(
            f"{name} must be finite, got {arr[run, task]} at run {run}, task {task}"
            f" ({int(bad.sum())} non-finite scores in all)"
        )
    return arr


def score_dict(scores: Mapping[str, ArrayLike]) -> dict[str, F64]:
    """Every planner's scores checked by :func:`score_array`, with the same task count."""
    if not isinstance(scores, Mapping):
        raise ValueError(
            f"scores must be a mapping planner -> array (runs, tasks), got {type(scores).__name__}"
        )
    if not scores:
        raise ValueError("scores must name at least one planner, got an empty mapping")
    out = {str(k): score_array(v, f"scores[{k!r}]") for k, v in scores.items()}
    tasks = {k: v.shape[1] for k, v in out.items()}
    if len(set(tasks.values())) > 1:
        listed = ", ".join(f"{k}: {n}" for k, n in tasks.items())
        raise ValueError(
            f"scores must have the same number of tasks (columns) for every planner, got {listed}"
        )
    return out


def _same_tasks(x: F64, y: F64) -> None:
    if x.shape[1] != y.shape[1]:
        raise ValueError(
            f"scores_x and scores_y must have the same number of tasks (columns),"
            f" got {x.shape[1]} and {y.shape[1]}"
        )


def thresholds(taus: ArrayLike) -> F64:
    """``taus`` as a non-empty, finite, 1-D float64 array."""
    arr = validation.real_array(taus, "taus")
    if arr.ndim != 1 or arr.size == 0 or not np.isfinite(arr).all():
        raise ValueError(f"taus must be a non-empty 1-D array of finite numbers, got {taus!r}")
    return arr


# ----- point estimates ------------------------------------------------------------------
def aggregate_mean(scores: ArrayLike) -> float:
    """The mean over tasks of the per-task mean score."""
    x = score_array(scores)
    return float(np.mean(np.mean(x, axis=0)))


def aggregate_median(scores: ArrayLike) -> float:
    """The median over tasks of the per-task mean score."""
    x = score_array(scores)
    return float(np.median(np.mean(x, axis=0)))


def aggregate_iqm(scores: ArrayLike) -> float:
    """The interquartile mean: the mean of the middle 50% of all runs x tasks scores.

    ``scipy.stats.trim_mean(scores, 0.25)`` over the flattened array: of N scores,
    ``floor(N / 4)`` are cut from each end of the sorted list.
    """
    x = score_array(scores)
    return float(scipy.stats.trim_mean(x, IQM_CUT, axis=None))


def optimality_gap(scores: ArrayLike, gamma: float = 1.0) -> float:
    """How far the scores fall short of ``gamma`` on average: ``gamma - mean(min(x, gamma))``.

    Scores above ``gamma`` (the level that counts as solved, 1 for normalised scores)
    earn nothing more.
    """
    x = score_array(scores)
    g = validation.number(gamma, "gamma")
    return float(g - np.mean(np.minimum(x, g)))


def run_score_profile(scores: ArrayLike, taus: ArrayLike) -> F64:
    """At each ``taus[k]``, the fraction of all runs x tasks scores strictly above it."""
    x = score_array(scores)
    t = thresholds(taus)
    return np.asarray([np.mean(x > tau) for tau in t])


def average_score_profile(scores: ArrayLike, taus: ArrayLike) -> F64:
    """At each ``taus[k]``, the fraction of tasks whose mean score is strictly above it."""
    x = score_array(scores)
    t = thresholds(taus)
    means = np.mean(x, axis=0)
    return np.asarray([np.mean(means > tau) for tau in t])


def _pair_wins(x: F64, y: F64) -> F64:
    """``(tasks, runs_x, runs_y)``: 1 where x's run beats y's on the task, 1/2 on a tie."""
    xt, yt = x.T[:, :, None], y.T[:, None, :]
    return (xt > yt).astype(np.float64) + 0.5 * (xt == yt)


def probability_of_improvement(scores_x: ArrayLike, scores_y: ArrayLike) -> float:
    """``P(X > Y)``: per task the probability that a run of X scores above a run of Y
    (the Mann-Whitney U statistic over the ``runs_x * runs_y`` pairs, ties counting 1/2,
    divided by the number of pairs), averaged over tasks."""
    x = score_array(scores_x, "scores_x")
    y = score_array(scores_y, "scores_y")
    _same_tasks(x, y)
    return float(np.mean(_pair_wins(x, y).mean(axis=(1, 2))))


# ----- the stratified bootstrap ---------------------------------------------------------
def _generator(seed: int, *names: str) -> np.random.Generator:
    """The stream of one planner (or pair): the seed with the names' CRC-32 as spawn key."""
    key = tuple(zlib.crc32(n.encode()) for n in names)
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=key))


def _chunk_sizes(reps: int, cells: int) -> Iterator[int]:
    """Replicates per chunk, so that a chunk holds about ``_CHUNK_CELLS`` cells."""
    step = max(1, _CHUNK_CELLS // cells)
    for start in range(0, reps, step):
        yield min(step, reps - start)


def draw_indices(rng: np.random.Generator, reps: int, runs: int, tasks: int) -> NDArray[np.int64]:
    """``(reps, runs, tasks)`` run indices: replicate ``b`` of the scores is
    ``scores[idx[b, n, m], m]``, i.e. each task's runs drawn with replacement."""
    return rng.integers(0, runs, size=(reps, runs, tasks))


def run_counts(indices: NDArray[np.int64]) -> F64:
    """How often each run is drawn per replicate and task: ``counts[b, i, m]`` is the
    number of ``n`` with ``indices[b, n, m] == i`` (same shape as ``indices``)."""
    reps, runs, tasks = indices.shape
    rep = np.arange(reps)[:, None, None]
    task = np.arange(tasks)[None, None, :]
    flat = ((rep * runs + indices) * tasks + task).ravel()
    counts = np.bincount(flat, minlength=reps * runs * tasks)
    return counts.reshape(reps, runs, tasks).astype(np.float64)


class _Resamples:
    """The statistics of bootstrap replicates of one score array, from run counts.

    Replicate ``b`` holds run ``i`` of task ``m`` ``counts[b, i, m]`` times; every statistic
    is a weighted one over the original scores, so no replicate is materialised.
    """

    def __init__(self, x: F64) -> None:
        self.x = x
        runs, tasks = x.shape
        self.n = runs * tasks
        flat = x.ravel()
        self.order = np.argsort(flat, kind="stable")
        self.sorted = flat[self.order]
        self.cut = int(IQM_CUT * self.n)  # scipy.stats.trim_mean's lowercut

    def task_means(self, counts: F64) -> F64:
        """``(reps, tasks)``: each task's mean over the resampled runs."""
        return np.einsum("bit,it->bt", counts, self.x) / self.x.shape[0]

    def cumulative(self, counts: F64) -> F64:
        """``(reps, n + 1)``: the replicate's count of scores <= each sorted score (0 first)."""
        w = counts.reshape(counts.shape[0], self.n)[:, self.order]
        out = np.zeros((w.shape[0], self.n + 1))
        np.cumsum(w, axis=1, out=out[:, 1:])
        return out

    def iqm(self, cum: F64) -> F64:
        """The trimmed mean of each replicate: sorted positions ``[cut, n - cut)`` kept."""
        lo, hi = self.cut, self.n - self.cut
        kept = np.clip(np.minimum(cum[:, 1:], hi) - np.maximum(cum[:, :-1], lo), 0.0, None)
        return (kept * self.sorted).sum(axis=1) / (hi - lo)

    def metric(self, metric: Metric, counts: F64, cum: F64 | None, gamma: float) -> F64:
        """``(reps,)``: ``metric`` of each replicate (``cum`` from :meth:`cumulative` for
        the IQM, unused otherwise)."""
        if metric is Metric.IQM:
            assert cum is not None
            return self.iqm(cum)
        if metric is Metric.OPTIMALITY_GAP:
            clipped = np.minimum(self.x, gamma)
            total = np.einsum("bit,it->b", counts, clipped)
            return gamma - total / self.n
        means = self.task_means(counts)
        if metric is Metric.MEAN:
            return means.mean(axis=1)
        return np.median(means, axis=1)

    def run_profile(self, cum: F64, taus: F64) -> F64:
        """``(reps, len(taus))``: the fraction of resampled scores above each tau."""
        below = np.searchsorted(self.sorted, taus, side="right")  # scores <= tau
        return (self.n - cum[:, below]) / self.n

    def task_profile(self, counts: F64, taus: F64) -> F64:
        """``(reps, len(taus))``: the fraction of resampled task means above each tau."""
        means = self.task_means(counts)
        return (means[:, :, None] > taus[None, None, :]).mean(axis=1)


def _percentile_interval(values: F64, bootstrap: Bootstrap) -> tuple[F64, F64]:
    """The percentile interval of each column of ``values`` (replicates x statistics).

    numpy's linear interpolation (as rliable's ``arch`` backend uses); clipped to the
    replicates' range, which it never leaves but for rounding, so that a bounded
    statistic's interval stays inside its bounds.
    """
    low, high = np.percentile(values, bootstrap.percentiles, axis=0)
    return (
        np.clip(low, values.min(axis=0), values.max(axis=0)),
        np.clip(high, values.min(axis=0), values.max(axis=0)),
    )


def _bootstrap_interval(
    x: F64, name: str, bootstrap: Bootstrap, statistics: Callable[[_Resamples, F64], F64]
) -> tuple[F64, F64]:
    """The percentile intervals of ``statistics(resamples, counts)`` (``(reps, k)``
    values per chunk of run counts) over ``bootstrap.reps`` replicates of ``x``, drawn
    from ``name``'s stream."""
    res = _Resamples(x)
    rng = _generator(bootstrap.seed, name)
    chunks = [
        statistics(res, run_counts(draw_indices(rng, size, *x.shape)))
        for size in _chunk_sizes(bootstrap.reps, x.size)
    ]
    return _percentile_interval(np.concatenate(chunks), bootstrap)


def _metrics(metrics: Iterable[Metric | str]) -> tuple[Metric, ...]:
    out = tuple(validation.choice(Metric, m, "metric", "metrics") for m in metrics)
    if not out:
        raise ValueError("metrics must name at least one metric, got none")
    return out


def _point(metric: Metric, x: F64, gamma: float) -> float:
    if metric is Metric.MEAN:
        return aggregate_mean(x)
    if metric is Metric.MEDIAN:
        return aggregate_median(x)
    if metric is Metric.IQM:
        return aggregate_iqm(x)
    return optimality_gap(x, gamma)


def aggregate_intervals(
    scores: Mapping[str, ArrayLike],
    metrics: Sequence[Metric | str] = (Metric.IQM,),
    bootstrap: Bootstrap | None = None,
    *,
    gamma: float = 1.0,
) -> dict[str, dict[Metric, Interval]]:
    """Each planner's aggregate metrics with stratified-bootstrap percentile intervals.

    Returns ``{planner: {metric: Interval}}``; all metrics of a planner use the same
    replicates (``gamma`` is the optimality gap's threshold).
    """
    data = score_dict(scores)
    wanted = _metrics(metrics)
    g = validation.number(gamma, "gamma")
    bs = bootstrap or Bootstrap()

    def replicates(res: _Resamples, counts: F64) -> F64:
        cum = res.cumulative(counts) if Metric.IQM in wanted else None
        return np.stack([res.metric(m, counts, cum, g) for m in wanted], axis=1)

    out: dict[str, dict[Metric, Interval]] = {}
    for name, x in data.items():
        low, high = _bootstrap_interval(x, name, bs, replicates)
        out[name] = {
            m: Interval(_point(m, x, g), float(low[k]), float(high[k]))
            for k, m in enumerate(wanted)
        }
    return out


def performance_profiles(
    scores: Mapping[str, ArrayLike],
    taus: ArrayLike,
    kind: ProfileKind | str = ProfileKind.RUNS,
    bootstrap: Bootstrap | None = None,
) -> dict[str, Profile]:
    """Each planner's performance profile at the thresholds ``taus``, with pointwise
    stratified-bootstrap percentile bands.

    ``kind="runs"``: the run-score distribution (fraction of runs x tasks above tau);
    ``kind="tasks"``: the average-score distribution (fraction of tasks whose mean over
    runs is above tau).
    """
    data = score_dict(scores)
    t = thresholds(taus)
    which = validation.choice(ProfileKind, kind, "profile kind", "profile kinds")
    bs = bootstrap or Bootstrap()

    def replicates(res: _Resamples, counts: F64) -> F64:
        if which is ProfileKind.RUNS:
            return res.run_profile(res.cumulative(counts), t)
        return res.task_profile(counts, t)

    out: dict[str, Profile] = {}
    for name, x in data.items():
        low, high = _bootstrap_interval(x, name, bs, replicates)
        point = (
            run_score_profile(x, t) if which is ProfileKind.RUNS else average_score_profile(x, t)
        )
        out[name] = Profile(which, t, point, low, high)
    return out


def improvement_interval(
    scores_x: ArrayLike,
    scores_y: ArrayLike,
    bootstrap: Bootstrap | None = None,
    *,
    names: tuple[str, str] = ("x", "y"),
) -> Interval:
    """``P(X > Y)`` (:func:`probability_of_improvement`) with a stratified-bootstrap
    percentile interval: X's and Y's runs resampled independently within each task.

    ``names`` key the random stream; it does not depend on their order, so ``P(Y > X)``
    uses the same replicates and its interval is the mirror image ``1 - [high, low]``.
    """
    x = score_array(scores_x, "scores_x")
    y = score_array(scores_y, "scores_y")
    _same_tasks(x, y)
    bs = bootstrap or Bootstrap()
    swap = names[1] < names[0]
    first, second = (y, x) if swap else (x, y)
    rng = _generator(bs.seed, "P(X>Y)", *sorted(names))
    wins = _pair_wins(x, y)
    tasks, pairs = x.shape[1], x.shape[0] * y.shape[0]
    chunks = []
    for size in _chunk_sizes(bs.reps, max(first.size, second.size, wins.size)):
        counts_first = run_counts(draw_indices(rng, size, *first.shape))
        counts_second = run_counts(draw_indices(rng, size, *second.shape))
        cx, cy = (counts_second, counts_first) if swap else (counts_first, counts_second)
        per_task = np.einsum("bjt,bjt->bt", np.einsum("bit,tij->bjt", cx, wins), cy) / pairs
        chunks.append(per_task.sum(axis=1, keepdims=True) / tasks)
    low, high = _percentile_interval(np.concatenate(chunks), bs)
    point = float(np.mean(wins.mean(axis=(1, 2))))
    return Interval(point, float(low[0]), float(high[0]))


def improvement_probabilities(
    scores: Mapping[str, ArrayLike],
    pairs: Iterable[tuple[str, str]] | None = None,
    bootstrap: Bootstrap | None = None,
) -> dict[tuple[str, str], Interval]:
    """``P(X > Y)`` with its interval for each ordered pair ``(X, Y)`` of planners
    (default: every ordered pair of distinct planners, in the mapping's order)."""
    data = score_dict(scores)
    if pairs is None:
        wanted = [(a, b) for a in data for b in data if a != b]
    else:
        wanted = [(str(a), str(b)) for a, b in pairs]
        unknown = sorted({n for pair in wanted for n in pair} - set(data))
        if unknown:
            raise ValueError(
                f"pairs name unknown planner(s) {unknown}; valid planners are: {', '.join(data)}"
            )
    return {
        (a, b): improvement_interval(data[a], data[b], bootstrap, names=(a, b)) for a, b in wanted
    }
