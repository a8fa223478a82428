"""Tests of voot.bench.protocol.problems: names, paper settings, adapters, the env cache."""

from __future__ import annotations

import numpy as np
import pytest

from voot.bench.protocol import problems as P
from voot.tree.chains import SyntheticChain
from voot.tree.gym_adapters import GymProblem


def test_normalize_problem_names_and_aliases() -> None:
    assert P.normalize_problem("Shekel-Chain") == "shekel_chain"
    assert P.normalize_problem("kitchen") == "voot/KitchenClearing-v0"
    assert P.normalize_problem("conveyor") == "voot/ConveyorPacking-v0"
    assert P.normalize_problem("voot/ShekelChain-v0") == "voot/ShekelChain-v0"
    with pytest.raises(ValueError, match=r"unknown problem 'nope'; valid problems .*shekel_chain"):
        P.normalize_problem("nope")


def test_labels_setups_and_families() -> None:
    assert P.problem_label("voot/KitchenClearing-v0") == "kitchen"
    assert P.problem_label("voot/ShekelChain-v0", {"dim": 3}) == "voot/ShekelChain-v0(dim=3)"
    assert P.paper_setup("voot/KitchenClearing-v0") == P.PaperSetup(2000, 20, P.ROBOT_PLANNERS)
    assert P.paper_setup("voot/ConveyorPacking-v0").simulations == 3000
    assert P.paper_setup("voot/ConveyorPacking-v0").seeds == 50
    assert P.paper_setup("shekel_chain").simulations == 10_000
    assert P.paper_setup("shekel_chain").planners == P.CHAIN_PLANNERS
    assert P.family("voot/ShekelChain-v0") == "chain"
    assert P.family("voot/KitchenClearing-v0") == "robot"


def test_domain_options_are_the_references() -> None:
    chain = P.domain_options("shekel_chain", 20, "voot")
    assert chain["reevaluations"] == 100 and chain["kappa_r"] == 1.0
    assert chain["root_commitment"] == 3 and chain["gamma"] == 0.9
    assert chain["sampler_options"] == {"sampler": "centered_uniform"}
    assert "sampler_options" not in P.domain_options("shekel_chain", 10, "pw_uct")
    via_gym = P.domain_options("voot/ShekelChain-v0", None, "voot", {"dim": 20})
    assert via_gym == chain
    conveyor = P.domain_options("voot/ConveyorPacking-v0", None, "voronoi_pw")
    assert conveyor["gamma"] == 0.99 and conveyor["feasibility_retries"] == 200
    assert conveyor["sampler_options"] == {"sampler": "uniform", "omega": 0.3}
    kitchen = P.domain_options("voot/KitchenClearing-v0", None, "pw_uct")
    assert kitchen == {"gamma": 0.9}
    assert P.domain_options("Other-v0", None, "voot") == {}


def test_v1_domain_options_are_the_authors_tree_rules() -> None:
    assert P.normalize_problem("kitchen_v1") == "voot/KitchenClearing-v1"
    assert P.normalize_problem("conveyor-v1") == "voot/ConveyorPacking-v1"
    for planner in ("voot", "doot", "rand_doot", "pw_uct", "voronoi_pw", "hoot", "uniform_t"):
        kitchen = P.domain_options("voot/KitchenClearing-v1", None, planner)
        conveyor = P.domain_options("voot/ConveyorPacking-v1", None, planner)
        # the same retries for every planner on both domains (the paper: 50)
        assert kitchen["feasibility_retries"] == conveyor["feasibility_retries"] == 50
        assert kitchen["commit_min_reward"] == conveyor["commit_min_reward"] == 0.0
        assert kitchen["commit_reset_on_goal"] and conveyor["commit_reset_on_goal"]
        assert kitchen["root_commitment"] == 10 and conveyor["root_commitment"] == 1
        assert kitchen["gamma"] == 0.9 and conveyor["gamma"] == 0.99
        uses_voo = planner in ("voot", "voronoi_pw")
        assert kitchen.get("use_problem_metric", False) == uses_voo
    assert P.paper_setup("voot/ConveyorPacking-v1").simulations == 3000


def test_the_generated_conveyor_takes_the_v1_conveyors_options() -> None:
    assert P.normalize_problem("conveyor_v2") == "voot/ConveyorPacking-v2"
    for planner in ("voot", "pw_uct", "doot"):
        v1 = P.domain_options("voot/ConveyorPacking-v1", None, planner)
        v2 = P.domain_options("voot/ConveyorPacking-v2", None, planner, {"layout_seed": 3})
        assert v2 == v1
    assert P.paper_setup("voot/ConveyorPacking-v2") == P.paper_setup("voot/ConveyorPacking-v1")


def test_env_kwargs_must_be_json() -> None:
    assert P.check_env_kwargs({"dim": 3}) == {"dim": 3}
    with pytest.raises(ValueError, match="JSON"):
        P.check_env_kwargs({"f": object()})


def test_chain_instance_and_missing_dim() -> None:
    inst = P.make_instance("shekel_chain", 3, None, seed=0)
    assert isinstance(inst.problem, SyntheticChain) and inst.env is None
    assert inst.objects_initial is None
    with pytest.raises(ValueError, match="needs a dimension"):
        P.make_instance("shekel_chain", None, None, seed=0)


def test_env_instance_is_cached_and_reset() -> None:
    P.clear_env_cache()
    a = P.make_instance("voot/ShekelChain-v0", None, {"dim": 3}, seed=1)
    assert isinstance(a.problem, GymProblem)
    a.problem.step(np.zeros(3))  # moves the env on ...
    b = P.make_instance("voot/ShekelChain-v0", None, {"dim": 3}, seed=2)
    assert b.env is a.env  # ... the same env is kept for the next run ...
    assert b.problem.snapshot()[0] == 0  # ... and reset to the initial state
    c = P.make_instance("voot/ShekelChain-v0", None, {"dim": 3}, seed=1, cache=False)
    assert c.env is not a.env
    for i in range(P.ENV_CACHE_SIZE + 1):  # bounded: the oldest is dropped
        P.cached_env("voot/ShekelChain-v0", {"dim": 3, "bonus": float(i)})
    assert len(P._ENV_CACHE) == P.ENV_CACHE_SIZE
    P.clear_env_cache()
    assert not P._ENV_CACHE


def test_adapt_env_refuses_envs_without_state() -> None:
    import gymnasium

    env = gymnasium.make("CartPole-v1", disable_env_checker=True)
    with pytest.raises(ValueError, match="neither get_state"):
        P.adapt_env(env)


def test_help_names_come_from_the_records_by_meaning() -> None:
    from voot.bench.protocol.problems import NAME_MEANINGS, name_kind, names_text, recorded_names
    from voot.problems import problem_records

    robots = [r for r in problem_records() if r.chain is None and r.renamed_to is None]
    text = names_text()
    listed = [word for group in text.split("; ") for word in group.split(":")[0].split()]
    for record in robots:
        # each alias once, in the group of its meaning
        assert listed.count(record.aliases[0]) == 1
        group = next(g for g in text.split("; ") if record.aliases[0] in g.split(":")[0].split())
        assert group.endswith(NAME_MEANINGS[name_kind(record)])
    assert recorded_names() == [
        r.aliases[0] for r in robots if r.v1_rules and not r.layouts and not r.authors_domain
    ]
    assert "conveyor" not in names_text("kitchen")
    assert "generated_kitchen" not in names_text("kitchen", ("protocol", "v0"))
    # former names are still accepted but never listed
    assert "kitchen_v2" not in listed and "conveyor_v2" not in listed


def test_the_docs_name_every_id_and_alias_as_the_records_do() -> None:
    """docs/getting-started.md, "Problem names": one row per robot alias with its id."""
    from pathlib import Path

    from voot.problems import problem_records

    page = (Path(__file__).resolve().parents[3] / "docs" / "getting-started.md").read_text()
    section = page.split("## Problem names", 1)[1].split("\n## ", 1)[0]
    for record in problem_records():
        for alias in record.aliases:
            assert f"| `{alias}` | `{record.id}` |" in section
