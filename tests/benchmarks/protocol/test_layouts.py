"""Tests of voot.bench.protocol.layouts: the held-out sets, the protocol's overlap checks, the env
keyword helpers and the per-layout units of the intervals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from layout_fixtures import LAYOUT_ENV_ID, PLAIN_ENV_ID

from voot.bench.protocol.layouts import (
    HELDOUT_LAYOUTS,
    LAYOUT_KEY,
    LAYOUT_SETS,
    TRAINING_LAYOUTS,
    LayoutSet,
    check_layout_problem,
    check_layouts_disjoint,
    check_protocol,
    family_kwargs,
    layout_groups,
    layout_means,
    layout_medians,
    layout_of,
    layout_set,
    layouts_text,
    n_layouts,
    takes_layout_seed,
    with_layout,
)


def test_the_held_out_sets_are_fixed_and_disjoint() -> None:
    assert TRAINING_LAYOUTS == tuple(range(1000, 1020))
    assert HELDOUT_LAYOUTS == tuple(range(20))
    assert not set(TRAINING_LAYOUTS) & set(HELDOUT_LAYOUTS)
    assert set(LAYOUT_SETS) == {  # the generated families, by their names old and new
        "voot/GeneratedKitchen-v0",
        "voot/GeneratedStorage-v0",
        "voot/KitchenClearing-v2",
        "voot/ConveyorPacking-v2",
    }
    for split in LAYOUT_SETS.values():
        assert not set(split.training) & set(split.heldout)
    assert layout_set("voot/KitchenClearing-v2").heldout == HELDOUT_LAYOUTS
    with pytest.raises(ValueError, match="no held-out layout set; the generated families"):
        layout_set("voot/KitchenClearing-v1")


def test_a_layout_set_validates() -> None:
    split = LayoutSet((5, 6, 5), (1,))
    assert split.training == (5, 6)  # repeats dropped, order kept
    with pytest.raises(ValueError, match=r"layout seeds 3, 7 are both training"):
        LayoutSet((1, 3, 7), (3, 7, 9))
    with pytest.raises(ValueError, match="needs heldout layouts"):
        LayoutSet((1,), ())
    with pytest.raises(ValueError, match="training layouts must be integers >= 0"):
        LayoutSet((-1,), (2,))


def test_overlap_errors_name_the_seeds() -> None:
    check_layouts_disjoint(range(1000, 1020), range(20))
    with pytest.raises(ValueError, match=r"layout seeds 10-19 are both training .* test set"):
        check_layouts_disjoint(range(10, 30), range(20))
    # different layouts: the seeds may repeat (another layout is another problem)
    check_protocol([0, 1], [0, 1], [100, 101], [0, 1])
    with pytest.raises(ValueError, match="layout seeds 1 are both"):
        check_protocol([0], [0], [1, 2], [0, 1])
    # the same layouts in both phases (or none): the seeds must be disjoint
    with pytest.raises(ValueError, match="seeds 1 are both tuning and evaluation seeds"):
        check_protocol([0, 1], [1, 2], None, [0, 1])
    check_protocol([1000], [0], None, None)
    with pytest.raises(ValueError, match="need evaluation layouts"):
        check_protocol([0], [0], [100], [])
    with pytest.raises(ValueError, match="no tuning layouts"):
        check_protocol([0], [0], [], [1])
    with pytest.raises(ValueError, match="no tuning seeds"):
        check_protocol([], [0], [100], [1])


def test_env_keyword_helpers() -> None:
    assert with_layout({"difficulty": "easy"}, 3) == {"difficulty": "easy", LAYOUT_KEY: 3}
    assert with_layout({"difficulty": "easy"}, None) == {"difficulty": "easy"}
    assert family_kwargs({"difficulty": "easy", LAYOUT_KEY: 3}) == {"difficulty": "easy"}
    assert family_kwargs(None) == {}
    assert layout_of({"env_kwargs": {LAYOUT_KEY: 4}}) == 4
    assert layout_of({"env_kwargs": {}}) is None and layout_of({}) is None
    assert layouts_text([1002, 1000, 1001, 7]) == "7, 1000-1002"


def test_which_envs_take_a_layout_seed() -> None:
    assert takes_layout_seed(LAYOUT_ENV_ID)
    assert not takes_layout_seed(PLAIN_ENV_ID) and not takes_layout_seed("no/SuchEnv-v0")
    # a constructor that takes **kwargs may read it: the benefit of the doubt
    assert takes_layout_seed("voot/ShekelChain-v0")
    check_layout_problem(LAYOUT_ENV_ID)
    with pytest.raises(ValueError, match="takes no layout_seed keyword"):
        check_layout_problem(PLAIN_ENV_ID)


def test_layout_means_are_the_units() -> None:
    samples = np.array([[1.0, 2.0], [3.0, np.nan], [10.0, 10.0], [0.0, 0.0]])
    layouts = [5, 5, 2, None]
    groups = layout_groups(layouts)
    assert [g.tolist() for g in groups] == [[2], [0, 1], [3]]  # sorted layouts, then rows
    units = layout_means(samples, layouts)
    assert units.tolist() == [[10.0, 10.0], [2.0, 2.0], [0.0, 0.0]]  # NaN ignored per column
    # without layouts: the rows themselves
    assert np.array_equal(layout_means(samples, [None] * 4), samples, equal_nan=True)
    with pytest.raises(ValueError, match="3 layouts for 4 rows"):
        layout_means(samples, [1, 2, 3])
    # a layout whose runs are all unknown at a point stays unknown there
    assert np.isnan(layout_means(np.array([[np.nan], [np.nan]]), [1, 1])[0, 0])
    assert n_layouts(layouts) == 2 and n_layouts([None]) == 0


def test_layout_medians() -> None:
    values = np.array([1.0, 3.0, math.inf, math.inf, 7.0])
    assert layout_medians(values, [0, 0, 1, 1, 2]).tolist() == [2.0, math.inf, 7.0]
    assert layout_medians(values, None).tolist() == values.tolist()
