r"""Layout seeds: generated scenes as a sweep axis, and the held-out test set.

A generated task family (``voot/GeneratedKitchen-v0``, ``voot/GeneratedStorage-v0``) builds
its scene from the gymnasium keyword ``layout_seed``: one id, many layouts. A planner
tuned and evaluated on one scene measures that scene; the protocol of a generated family
keeps the layouts it tunes on apart from the layouts it reports, as Procgen keeps its
training levels apart from its test levels.

**The axis.** ``voot-bench plan --layout-seeds 0:20`` adds ``layout_seed`` to every run's
``env_kwargs`` (:func:`with_layout`); a run's id hashes its config, so each layout's runs
have their own ids and rows, and a sweep without the axis has exactly the ids it always
had. A problem *family* is the problem with every env keyword except ``layout_seed``
(:func:`family_kwargs`): hyperparameters are selected per (family, planner) over all its
layouts (:func:`voot.bench.protocol.select.cell_of` leaves the layout out of the cell), and
figures and tables draw one curve per (family, planner), the mean over its (layout,
seed) runs.

**The held-out set.** :data:`TRAINING_LAYOUTS` (1000-1019) and :data:`HELDOUT_LAYOUTS`
(0-19), the same for every generated family, disjoint by construction: each family's
problem record carries its split (:attr:`voot.problems.ProblemRecord.layout_split`, from
:data:`voot.envs.core.generation.PROTOCOL_SPLIT`, which the envs' split mode reads too),
and :data:`LAYOUT_SETS` collects them. ``voot-bench plan --heldout`` runs the protocol (:mod:`voot.bench.protocol.tuning`):

1. every setting of every planner's grid on the tuning seeds x the training layouts;
2. per (family, planner) the setting with the best mean final return, pooled over every
   training layout and tuning seed (the paper's rule, :func:`voot.bench.protocol.select.select_hyperparameters`;
   with as many seeds per layout, the pooled mean is the mean of the per-layout means);
3. that setting alone on the evaluation seeds x the held-out layouts.

Tuning on a held-out layout would be tuning on the test set: :func:`check_protocol`
refuses overlapping layouts, naming them (and, when both phases use the same layouts,
overlapping seeds).

**Intervals.** Runs on one layout share it: they are not independent draws of the
family. The unit of the intervals is therefore the layout (:func:`layout_means`): a
planner's value on a family is the mean over its layouts of the per-layout mean over
seeds, and the 95% t-interval is over those per-layout means, with ``n_layouts - 1``
degrees of freedom. This is the standard analysis of a nested (seeds within layouts)
design, whose between-layout variance is what a user's new layout meets; it is exact for
a balanced design (as many seeds on every layout) and reduces to the per-seed interval of
the paper when each run has its own layout or none. Medians (simulations until every
object is handled) take the per-layout median as the unit the same way.
"""

from __future__ import annotations

import inspect
from collections.abc import Collection, Iterable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.envs.core.generation import HELDOUT_LAYOUTS, TRAINING_LAYOUTS
from voot.envs.core.generation import LayoutSplit as LayoutSet
from voot.problems import problem_records

__all__ = ["HELDOUT_LAYOUTS", "LAYOUT_KEY", "LAYOUT_SETS", "TRAINING_LAYOUTS", "LayoutSet"]

#: The gymnasium keyword of a generated env that picks its layout.
LAYOUT_KEY = "layout_seed"
#: Tuning layouts as the selection takes them: one collection for every problem, or one
#: per problem (gymnasium id).
TuningLayoutsArg = Collection[int] | Mapping[str, Collection[int]]


def layouts_text(layouts: Iterable[int]) -> str:
    """Seeds (layout seeds, or run seeds) as ranges: ``[1000, 1001, 1002, 7]`` ->
    ``"7, 1000-1002"``."""
    values = sorted(set(int(s) for s in layouts))
    parts: list[str] = []
    i = 0
    while i < len(values):
        j = i
        while j + 1 < len(values) and values[j + 1] == values[j] + 1:
            j += 1
        parts.append(str(values[i]) if i == j else f"{values[i]}-{values[j]}")
        i = j + 1
    return ", ".join(parts)


def check_layouts_disjoint(training: Iterable[int], heldout: Iterable[int]) -> None:
    """Raise ValueError if a layout seed is in both ``training`` and ``heldout``, naming it."""
    both = set(int(s) for s in training) & set(int(s) for s in heldout)
    if both:
        raise ValueError(
            f"layout seeds {layouts_text(both)} are both training (tuning) and held-out"
            " (evaluation) layouts: that would tune on the test set; the tuning layouts must"
            " be disjoint from the evaluation layouts (e.g. --tuning-layouts 1000:1020"
            " --layout-seeds 0:20, or --heldout)"
        )


def check_disjoint(tuning_seeds: Iterable[int], evaluation_seeds: Iterable[int]) -> None:
    """Raise ValueError if a seed is both a tuning and an evaluation seed, or none is tuned."""
    tuning = set(int(s) for s in tuning_seeds)
    if not tuning:
        raise ValueError("no tuning seeds given")
    both = tuning & set(int(s) for s in evaluation_seeds)
    if both:
        raise ValueError(
            f"seeds {layouts_text(both)} are both tuning and evaluation seeds: that would be"
            " tuning on the test set (a setting selected on a seed flatters its result"
            " there); tuning seeds must be disjoint from the evaluation seeds (e.g."
            " --tuning-seeds 1000:1005 --seeds 0:20)"
        )


#: The held-out split of every generated family (by gymnasium id, old names too), from
#: the problem records (:class:`LayoutSet` is
#: :class:`voot.envs.core.generation.LayoutSplit`).
LAYOUT_SETS: dict[str, LayoutSet] = {
    r.id: r.layout_split for r in problem_records() if r.layout_split is not None
}


def layout_set(problem: str) -> LayoutSet:
    """The training and held-out layouts of ``problem`` (a gymnasium id).

    Raises:
        ValueError: ``problem`` has no held-out set; lists the families that have one.
    """
    try:
        return LAYOUT_SETS[problem]
    except KeyError:
        raise ValueError(
            f"{problem} has no held-out layout set; the generated families with one are:"
            f" {', '.join(LAYOUT_SETS)} (or give --tuning-layouts and --layout-seeds)"
        ) from None


def check_protocol(
    tuning_seeds: Collection[int],
    evaluation_seeds: Collection[int],
    tuning_layouts: Collection[int] | None,
    evaluation_layouts: Collection[int] | None,
) -> None:
    """Refuse a protocol that would evaluate on what it tuned on.

    With tuning layouts, they must be disjoint from the evaluation layouts (the seeds
    may then repeat: a seed on another layout is another problem). Without (both phases
    on the same layouts, or none), the seeds must be disjoint
    (:func:`check_disjoint`).

    Raises:
        ValueError: naming the overlapping layout seeds or seeds.
    """
    if tuning_layouts is None:
        check_disjoint(tuning_seeds, evaluation_seeds)
        return
    if not tuning_layouts:
        raise ValueError("no tuning layouts given")
    if not tuning_seeds:
        raise ValueError("no tuning seeds given")
    if not evaluation_layouts:
        raise ValueError(
            "tuning layouts need evaluation layouts: give --layout-seeds (the held-out"
            f" layouts, e.g. {layouts_text(HELDOUT_LAYOUTS)}) or use --heldout"
        )
    check_layouts_disjoint(tuning_layouts, evaluation_layouts)


def with_layout(env_kwargs: Mapping[str, Any], layout: int | None) -> dict[str, Any]:
    """``env_kwargs`` with ``layout_seed`` set (unchanged if ``layout`` is None)."""
    out = dict(env_kwargs)
    if layout is not None:
        out[LAYOUT_KEY] = int(layout)
    return out


def family_kwargs(env_kwargs: Mapping[str, Any] | None) -> dict[str, Any]:
    """The env keywords that name the family: all but ``layout_seed``."""
    return {k: v for k, v in (env_kwargs or {}).items() if k != LAYOUT_KEY}


def layout_of(config: Mapping[str, Any]) -> int | None:
    """The layout seed of a run's config (a row's ``config`` or a spec's), None if none."""
    value = (config.get("env_kwargs") or {}).get(LAYOUT_KEY)
    return None if value is None else int(value)


def takes_layout_seed(problem: str) -> bool:
    """Whether the registered env ``problem`` may take ``layout_seed``, read from the
    signature of its entry point without making the env (which may generate a scene).

    True if the entry point (a class's ``__init__``, or a function) names ``layout_seed``
    or takes ``**kwargs`` (the benefit of the doubt: a constructor may read the keyword
    from them; a wrong keyword then fails the run with the env's own message); False if
    it takes neither, or the id is not registered.
    """
    import gymnasium
    from gymnasium.envs.registration import load_env_creator

    import voot  # noqa: F401 - registers the voot/... ids

    spec = gymnasium.registry.get(problem)
    if spec is None or spec.entry_point is None:
        return False
    if LAYOUT_KEY in (spec.kwargs or {}):
        return True
    entry = spec.entry_point
    creator = load_env_creator(entry) if isinstance(entry, str) else entry
    fn = creator.__init__ if inspect.isclass(creator) else creator
    try:
        params = inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return True  # no signature to read: let the run tell
    return LAYOUT_KEY in params or any(
        p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values()
    )


def check_layout_problem(problem: str) -> None:
    """Raise ValueError unless ``problem`` is an env that takes ``layout_seed``."""
    if not takes_layout_seed(problem):
        families = ", ".join(LAYOUT_SETS)
        raise ValueError(
            f"{problem} takes no {LAYOUT_KEY} keyword: layout seeds apply to the generated"
            f" families ({families}) or any env whose constructor takes {LAYOUT_KEY}"
        )


def layout_groups(layouts: Sequence[int | None]) -> list[NDArray[np.intp]]:
    """Row indices per layout, layouts in sorted order (rows without one: one group each)."""
    groups: dict[Any, list[int]] = {}
    for i, layout in enumerate(layouts):
        key: Any = ("row", i) if layout is None else ("layout", int(layout))
        groups.setdefault(key, []).append(i)
    order = sorted(groups, key=lambda k: (k[0] == "row", k[1]))
    return [np.asarray(groups[k], dtype=np.intp) for k in order]


def layout_means(
    samples: NDArray[np.float64], layouts: Sequence[int | None] | None
) -> NDArray[np.float64]:
    """Per-layout means of ``samples`` (one row per run, aligned with ``layouts``): the
    units of the intervals (module docstring).

    Rows of one layout are averaged column by column, ignoring NaN (a column where no run
    of the layout is known stays NaN); rows without a layout stay rows of their own.
    Without layouts (None, empty, or none set) ``samples`` is returned as it is.
    """
    arr = np.asarray(samples, dtype=np.float64)
    if not layouts or all(v is None for v in layouts):
        return arr
    if len(layouts) != arr.shape[0]:
        raise ValueError(f"{len(layouts)} layouts for {arr.shape[0]} rows of samples")
    parts = []
    for idx in layout_groups(layouts):
        block = arr[idx]
        known = ~np.isnan(block)
        n = known.sum(axis=0)
        total = np.where(known, block, 0.0).sum(axis=0)
        with np.errstate(invalid="ignore", divide="ignore"):
            parts.append(np.where(n > 0, total / np.maximum(n, 1), np.nan))
    return np.stack(parts) if parts else np.full((0, *arr.shape[1:]), np.nan)


def layout_medians(
    values: NDArray[np.float64], layouts: Sequence[int | None] | None
) -> NDArray[np.float64]:
    """Per-layout medians of one value per run (``inf`` allowed: a run that never got
    there), the units of a median's interval; ``values`` unchanged without layouts."""
    arr = np.asarray(values, dtype=np.float64)
    if not layouts or all(v is None for v in layouts):
        return arr
    if len(layouts) != arr.shape[0]:
        raise ValueError(f"{len(layouts)} layouts for {arr.shape[0]} values")
    return np.array([float(np.median(arr[idx])) for idx in layout_groups(layouts)])


def n_layouts(layouts: Sequence[int | None]) -> int:
    """How many distinct layouts (0 when no run has one)."""
    return len({int(v) for v in layouts if v is not None})
