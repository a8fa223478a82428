"""Tests of voot.bench.sweep.plan: the planning grid, one run's row, determinism, resume."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from layout_fixtures import LAYOUT_ENV_ID
from store_fixtures import Interrupting, killed_and_resumed

from voot.bench.protocol import problems as P
from voot.bench.store.format import Row
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.backends import ProcessBackend, SerialBackend
from voot.bench.sweep.engine import run_sweep
from voot.bench.sweep.plan import (
    PlanSpec,
    build_plan_specs,
    record_paths,
    run_plan_spec,
    strip_timings,
    summarize_plan_specs,
)
from voot.bench.sweep.planners import EPSILONS, OMEGAS, REEVALUATIONS, planner_grid
from voot.bench.sweep.search import search_seed


def tiny(
    planners: Sequence[str] = ("voot", "pw_uct"), seeds: Sequence[int] = (0, 1), sims: int = 25
) -> list[PlanSpec]:
    return build_plan_specs(
        ["shekel_chain"], [3], planners, seeds, simulations=sims, grid="default"
    )


def test_paper_defaults_per_problem() -> None:
    specs = build_plan_specs(grid="default")
    assert {(s.problem, s.dim) for s in specs} == {("shekel_chain", 10), ("shekel_chain", 20)}
    assert {s.simulations for s in specs} == {10_000}
    assert {s.seed for s in specs} == set(range(20))
    assert {s.planner for s in specs} == set(P.CHAIN_PLANNERS)
    robots = build_plan_specs(["kitchen", "conveyor"], grid="default")
    kitchen = [s for s in robots if s.problem == "voot/KitchenClearing-v0"]
    conveyor = [s for s in robots if s.problem == "voot/ConveyorPacking-v0"]
    assert {s.simulations for s in kitchen} == {2000} and len({s.seed for s in kitchen}) == 20
    assert {s.simulations for s in conveyor} == {3000} and len({s.seed for s in conveyor}) == 50
    assert {s.planner for s in robots} == set(P.ROBOT_PLANNERS)
    assert all(s.dim is None for s in robots)
    text = summarize_plan_specs(robots)
    assert "kitchen 2000 simulations, 20 seeds: voot 20," in text


def test_grids() -> None:
    voot = planner_grid("VOOT", "chain")
    assert len(voot) == len(OMEGAS) * len(REEVALUATIONS["chain"])
    assert {g["omega"] for g in voot} == set(OMEGAS)
    assert {g["reevaluations"] for g in planner_grid("voot", "robot")} == set(
        REEVALUATIONS["robot"]
    )
    assert {g["epsilon"] for g in planner_grid("rand-doot", "robot")} == set(EPSILONS)
    assert set(planner_grid("pw_uct", "robot")[0]) == {"pw_k", "ucb_c"}
    assert set(planner_grid("voronoi_pw", "chain")[0]) == {"omega", "pw_k"}
    assert planner_grid("hoot", "chain", "default") == [{}]
    specs = build_plan_specs(["shekel_chain"], [3, 10], ["voot", "hoot"], [0, 1], simulations=5)
    assert len(specs) == 2 * (len(voot) + len(planner_grid("hoot", "chain"))) * 2
    assert len({s.run_id for s in specs}) == len(specs)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"problems": ["nope"]}, "unknown problem 'nope'; valid problems"),
        ({"planners": ["vooot"]}, "unknown planner 'vooot'; valid planners are: cem, ddpg, doot"),
        ({"dims": [5]}, "no reference threshold for the shekel chain in 5-D"),
        ({"dims": [0]}, "dims must be integers >= 1"),
        ({"seeds": [-1]}, "seeds must be integers >= 0"),
        ({"simulations": 0}, "simulations must be integers >= 1"),
        ({"grid": "huge"}, "unknown grid 'huge'"),
        ({"fixed": {"omegaa": 1}}, "unknown option.*omegaa.*or a planner parameter"),
        ({"planners": ["pw_uct"], "fixed": {"omega": 0.1}}, "takes no sampler option"),
        ({"fixed": {"depth_limit": 0}}, "depth_limit must be an integer >= 1"),
        ({"record": "run.txt"}, "must end in .rrd"),
        ({"record": "r.rrd", "seeds": range(60)}, "narrow the sweep"),
        ({"env_kwargs": {"x": object()}}, "JSON"),
        ({"planners": ["cem"], "fixed": {"omega": 0.1}}, r"unknown option\(s\) \['omega'\]"),
        ({"planners": ["mppi"], "fixed": {"noise": -1}}, "noise must be"),
        ({"planners": ["cem"], "record": "r.rrd"}, "keep none"),
    ],
)
def test_bad_plan_arguments(kwargs: dict[str, Any], match: str) -> None:
    good = dict(problems=["shekel_chain"], dims=[3], planners=["voot"], seeds=[0], grid="default")
    with pytest.raises(ValueError, match=match):
        build_plan_specs(**{**good, "simulations": 5, **kwargs})


def test_chain_row_contents() -> None:
    (spec,) = build_plan_specs(
        ["shekel_chain"], [3], ["voot"], [0], simulations=40, fixed={"omega": 0.3}
    )[:1]
    r = run_plan_spec(spec)
    assert r["status"] == "ok", r.get("error")
    assert r["kind"] == "plan" and r["run_id"] == spec.run_id and r["config"] == spec.config()
    best = np.array(r["best_so_far"])
    assert best.shape == (40,) and best[-1] == r["best_return"]
    elapsed = np.array(r["elapsed"])
    assert elapsed.shape == (40,) and np.all(np.diff(elapsed) >= 0) and elapsed[0] > 0
    assert "objects_left" not in r  # a chain reports no objects
    assert r["simulator_calls"] == r["n_steps"] + r["n_feasibility_checks"] > 0
    calls, cpu = np.array(r["calls_curve"]), np.array(r["cpu_elapsed"])
    assert calls.shape == cpu.shape == (40,)
    assert calls[-1] == r["n_steps"] + r["n_feasibility_checks"]
    assert calls[0] >= 1 and np.all(np.diff(calls) >= 1)  # every simulation steps at least once
    assert np.all(np.diff(cpu) >= 0) and cpu[-1] > 0
    assert r["planner_config"]["sampler_options"] == {"sampler": "centered_uniform", "omega": 0.3}
    assert r["planner_config"]["reevaluations"] == spec.params_dict["reevaluations"]
    assert r["plan_length"] == len(r["best_actions"]) == len(r["best_rewards"])
    assert r["problem_label"] == "shekel_chain-3D"


def test_common_random_numbers_across_settings() -> None:
    a, b = build_plan_specs(["shekel_chain"], [3], ["voot"], [4], simulations=5)[:2]
    assert a.params != b.params
    assert search_seed(a).entropy == search_seed(b).entropy
    c = build_plan_specs(["shekel_chain"], [3], ["voot"], [5], simulations=5)[0]
    assert search_seed(c).entropy != search_seed(a).entropy


def test_generic_env_path_through_the_chain_registration() -> None:
    (spec,) = build_plan_specs(
        ["voot/ShekelChain-v0"],
        None,
        ["voot"],
        [0],
        simulations=30,
        grid="default",
        env_kwargs={"dim": 3},
    )
    assert spec.dim is None and spec.label == "voot/ShekelChain-v0(dim=3)"
    r = run_plan_spec(spec)
    assert r["status"] == "ok", r.get("error")
    assert len(r["best_so_far"]) == 30
    assert r["simulator_calls"] == r["n_steps"]  # env.step calls (no feasibility check here)
    assert r["planner_config"]["reevaluations"] == 100  # the chain's settings, found by id


def test_failed_run_gives_a_failed_row() -> None:
    spec = PlanSpec("shekel_chain", 3, (), "voot", (("omega", 2.0),), 5, 0)
    r = run_plan_spec(spec)
    assert r["status"] == "failed" and r["error"].startswith("ValueError: omega")
    assert "Traceback" in r["traceback"] and r["best_so_far"] == []


def test_same_spec_same_row_across_processes() -> None:
    specs = tiny()
    here = {s.run_id: strip_timings(run_plan_spec(s)) for s in specs}
    rows = list(ProcessBackend(workers=2).map_unordered(run_plan_spec, specs))
    there = {r["run_id"]: strip_timings(r) for r in rows}
    assert there == here  # bit-identical curves, plans and counters


def test_interrupted_plan_sweep_resumes(tmp_path: Path) -> None:
    specs = tiny(sims=10)
    store = ResultStore(tmp_path / "r")
    with pytest.raises(KeyboardInterrupt):
        run_sweep(specs, store, Interrupting(after=3), progress=False)
    first = {p.name: p.read_bytes() for p in store.row_files()}
    assert len(first) == 3
    summary = run_sweep(specs, store, SerialBackend(), progress=False)
    assert summary.skipped == 3 and summary.ran == len(specs) - 3 and summary.failed == 0
    for name, data in first.items():
        assert (store.runs_path / name).read_bytes() == data
    rows = store.load(kind="plan", arrays=True)
    assert {r["run_id"] for r in rows} == {s.run_id for s in specs}
    assert all(isinstance(r["elapsed"], np.ndarray) for r in rows)


def test_killed_plan_process_resumes(tmp_path: Path) -> None:
    """SIGKILL a real `voot-bench plan` midway, rerun it, and check the store."""
    out = tmp_path / "r"
    argv = [
        "plan", "--out", str(out),
        "--problems", "shekel_chain", "--dims", "3", "--planners", "doot",
        "--seeds", "6", "--simulations", "400", "--grid", "default",
        "--workers", "1", "--no-progress",
    ]  # fmt: skip
    store, _ = killed_and_resumed(argv, out, rows=2)
    assert len(store.load(kind="plan")) == 6


def test_record_paths_and_recording(tmp_path: Path) -> None:
    specs = tiny(planners=["voot"], seeds=[0, 1], sims=5)
    paths = record_paths(specs, str(tmp_path / "run.rrd"))
    assert len(set(paths)) == 2 and all(
        p.endswith("-seed0.rrd") or p.endswith("-seed1.rrd") for p in paths
    )
    assert record_paths(specs[:1], "x/run.rrd") == ["x/run.rrd"]
    args: dict[str, Any] = {"simulations": 15, "grid": "default"}
    (spec,) = build_plan_specs(
        ["shekel_chain"], [3], ["voot"], [0], record=str(tmp_path / "one.rrd"), **args
    )
    (plain,) = build_plan_specs(["shekel_chain"], [3], ["voot"], [0], **args)
    assert spec.record == str(tmp_path / "one.rrd") and plain.record is None
    assert spec.run_id == plain.run_id  # the recording is not part of the run's identity
    r = run_plan_spec(spec)
    assert r["status"] == "ok", r.get("error")
    assert r["recorded"] == spec.record and (tmp_path / "one.rrd").stat().st_size > 0


def _mujoco_envs_available() -> bool:
    try:
        import voot.envs.kitchen  # noqa: F401
    except Exception:
        return False
    return True


#: The runs on the robot domains need the MuJoCo environments (the ``envs`` extra).
needs_envs = pytest.mark.skipif(
    not _mujoco_envs_available(), reason="the MuJoCo environments are not importable"
)


@needs_envs
def test_kitchen_run_records_objects() -> None:
    (spec,) = build_plan_specs(["kitchen"], None, ["voot"], [0], simulations=3, grid="default")
    r = run_plan_spec(spec)
    assert r["status"] == "ok", r.get("error")
    left = r["objects_left"]
    assert len(left) == 3 and all(v is not None for v in left)
    assert r["objects_initial"] >= max(left)
    assert r["simulator_calls"] >= r["n_steps"] > 0
    assert r["planner_config"]["gamma"] == 0.9
    assert r["planner_config"]["sampler_options"]["sampler"] == "uniform"


def test_plan_specs_are_registered_with_run_any() -> None:
    from voot.bench.sweep.engine import RUNNERS, run_any

    assert RUNNERS["plan"] is run_plan_spec
    spec = PlanSpec("shekel_chain", 3, (), "voot", (), 10, 0)
    assert run_any(spec)["best_so_far"] == run_plan_spec(spec)["best_so_far"]


def test_sampling_based_planners_in_the_sweep() -> None:
    assert planner_grid("random_shooting", "robot") == [{}]
    assert {g["init_std"] for g in planner_grid("CEM", "chain")} == {0.25, 0.5}
    assert set(planner_grid("mppi", "robot")[0]) == {"noise", "temperature"}
    assert len(planner_grid("predictive-sampling", "robot")) == 2
    specs = build_plan_specs(
        ["shekel_chain"], [3], ["cem", "RANDOM_SHOOTING"], [0], simulations=30, grid="default"
    )
    assert [s.planner for s in specs] == ["cem", "random_shooting"]
    for spec in specs:
        r = run_plan_spec(spec)
        assert r["status"] == "ok", r.get("error")
        assert len(r["best_so_far"]) == len(r["elapsed"]) == 30
        assert r["best_so_far"][-1] == r["best_return"]
        assert r["n_nodes"] == 0 and r["n_feasibility_checks"] == 0
        assert r["simulator_calls"] == r["n_steps"] >= 30
        assert r["calls_curve"][-1] == r["n_steps"] and len(r["calls_curve"]) == 30
        assert r["planner_config"]["planner"] == spec.planner
        assert r["planner_config"]["gamma"] == 0.9  # the chain's discount
        assert r["plan_length"] == len(r["best_actions"]) >= 1
    # the same spec gives the same row
    again = run_plan_spec(specs[0])
    assert strip_timings(again) == strip_timings(run_plan_spec(specs[0]))


@needs_envs
def test_kitchen_v1_run_with_a_sampling_based_planner() -> None:
    (spec,) = build_plan_specs(["kitchen_v1"], None, ["mppi"], [0], simulations=6, grid="default")
    r = run_plan_spec(spec)
    assert r["status"] == "ok", r.get("error")
    assert len(r["objects_left"]) == 6 and r["objects_initial"] >= max(r["objects_left"])
    assert r["simulator_calls"] >= r["n_steps"] >= 6
    assert r["planner_config"] == {**r["planner_config"], "planner": "mppi", "gamma": 0.9}
    assert min(r["best_rewards"]) >= -2.0


def test_one_horizon_for_tree_and_sampling_planners() -> None:
    """--horizon H: a tree's depth limit from the root (no commitment), a sequence length."""
    from voot.bench.sweep.plan import build_plan_specs
    from voot.bench.sweep.planners import run_config

    specs = build_plan_specs(
        ["shekel_chain"], [3], ["voot", "cem"], [0], simulations=5, grid="default", horizon=7
    )
    by = {s.planner: s for s in specs}
    assert by["voot"].params_dict == {"depth_limit": 7, "root_commitment": None}
    assert by["cem"].params_dict == {"horizon": 7}
    tree = run_config("shekel_chain", 3, "voot", by["voot"].params_dict)
    assert tree.depth_limit == 7 and tree.root_commitment is None
    assert run_config("shekel_chain", 3, "cem", by["cem"].params_dict).horizon == 7
    with pytest.raises(ValueError, match="horizon must be an integer >= 1"):
        build_plan_specs(["shekel_chain"], [3], ["voot"], [0], simulations=5, horizon=0)


def test_v1_calls_curve_counts_prechecks_beside_the_problems_own_count() -> None:
    """On a v1 robot domain ``simulator_calls`` counts executed steps only, while
    ``calls_curve`` counts steps and pre-checks; the new keys leave the curve as it was."""
    from dataclasses import replace

    (spec,) = build_plan_specs(["kitchen_v1"], None, ["voot"], [0], simulations=15, grid="default")
    r = run_plan_spec(spec)
    assert r["status"] == "ok", r.get("error")
    assert r["calls_curve"][-1] == r["n_steps"] + r["n_feasibility_checks"]
    assert r["n_feasibility_checks"] > 0 and r["simulator_calls"] == r["n_steps"]
    again = run_plan_spec(replace(spec))
    assert again["calls_curve"] == r["calls_curve"] and again["best_so_far"] == r["best_so_far"]


class NeverRuns:
    """A backend that fails the test if the sweep asks it to run anything."""

    name = "never"

    def map_unordered(self, fn: Callable[[Any], Row], items: Sequence[Any]) -> Iterator[Row]:
        assert not list(items), f"a finished sweep ran {len(list(items))} runs again"
        return iter(())


def test_interrupted_sweep_into_a_compact_store_resumes_and_then_runs_nothing(
    tmp_path: Path,
) -> None:
    from voot.bench.store.compact import CompactConfig

    specs = tiny(sims=40)
    full = ResultStore(tmp_path / "full")
    run_sweep(specs, full, SerialBackend(), progress=False)
    store = ResultStore(tmp_path / "compact", compact=CompactConfig(points=8))
    with pytest.raises(KeyboardInterrupt):
        run_sweep(specs, store, Interrupting(after=2), progress=False)
    first = {p.name: p.read_bytes() for p in store.row_files()}
    assert len(first) == 2 and all(b'"compact"' in data for data in first.values())
    # a later session (another process, another machine) opens it without any flag
    again = ResultStore(tmp_path / "compact", create=False)
    assert again.compact == CompactConfig(points=8)
    summary = run_sweep(specs, again, SerialBackend(), progress=False)
    assert summary.skipped == 2 and summary.ran == len(specs) - 2
    for name, data in first.items():
        assert (store.runs_path / name).read_bytes() == data
    done = run_sweep(specs, ResultStore(tmp_path / "compact"), NeverRuns(), progress=False)
    assert done.skipped == len(specs) and done.ran == 0
    by_id = {r["run_id"]: r for r in full.load()}
    for r in again.load():
        want = by_id[r["run_id"]]
        assert r["best_so_far"] == want["best_so_far"]  # exact
        assert r.get("objects_left") == want.get("objects_left")
        assert len(r["elapsed"]) == 40 and np.all(np.diff(r["elapsed"]) >= 0)  # timings differ
        assert set(r["interpolated"]) == {"elapsed", "cpu_elapsed", "calls_curve"}


def test_a_variant_is_in_the_config_and_run_id_only_when_set() -> None:
    from voot.bench.sweep.plan import PlanSpec

    plain = PlanSpec("voot/KitchenClearing-v1", None, (), "voot", (("omega", 0.3),), 10, 0)
    tagged = PlanSpec(
        "voot/KitchenClearing-v1", None, (), "voot", (("omega", 0.3),), 10, 0, variant="x"
    )
    assert "variant" not in plain.config() and tagged.config()["variant"] == "x"
    assert plain.run_id != tagged.run_id
    from voot.bench.sweep.search import search_seed

    # common random numbers: a variant searches with the plain run's seed
    assert search_seed(plain).entropy == search_seed(tagged).entropy
    assert search_seed(plain).spawn_key == search_seed(tagged).spawn_key


def test_the_layout_axis_expands_every_run_per_layout() -> None:
    args: dict[str, Any] = {"simulations": 5, "grid": "default"}
    plain = build_plan_specs([LAYOUT_ENV_ID], None, ["voot"], [0, 1], **args)
    axis = build_plan_specs([LAYOUT_ENV_ID], None, ["voot"], [0, 1], layout_seeds=[7, 3, 7], **args)
    assert len(plain) == 2 and len(axis) == 4  # repeated layouts are dropped
    assert [(s.layout, s.seed) for s in axis] == [(7, 0), (7, 1), (3, 0), (3, 1)]
    assert all(s.env_kwargs_dict == {"layout_seed": s.layout} for s in axis)
    assert all(s.layout is None for s in plain)
    assert len({s.run_id for s in axis}) == 4  # one id per (layout, seed)
    assert not {s.run_id for s in axis} & {s.run_id for s in plain}
    # without the axis the ids are those of the sweep before it existed
    assert plain == build_plan_specs([LAYOUT_ENV_ID], None, ["voot"], [0, 1], **args)
    assert axis[0].label == f"{LAYOUT_ENV_ID}(layout_seed=7)"
    assert axis[0].family_label == LAYOUT_ENV_ID
    # other env keywords stay beside the layout, and name the family
    hard = build_plan_specs(
        [LAYOUT_ENV_ID], None, ["voot"], [0], layout_seeds=[1],
        env_kwargs={"difficulty": "easy"}, **args,
    )  # fmt: skip
    assert hard[0].env_kwargs_dict == {"difficulty": "easy", "layout_seed": 1}
    assert hard[0].family_label == f"{LAYOUT_ENV_ID}(difficulty=easy)"
    text = summarize_plan_specs(axis)
    assert text == f"{LAYOUT_ENV_ID} 5 simulations, 2 layouts x 2 seeds: voot 4"
    paths = record_paths(axis, "x/run.rrd")
    assert paths[0].endswith("-layout7-seed0.rrd") and len(set(paths)) == 4


@pytest.mark.parametrize(
    ("problem", "kwargs", "match"),
    [
        ("shekel_chain", {}, "the shekel_chain has no layouts"),
        ("voot-test/PlainChain-v0", {}, "takes no layout_seed keyword"),
        (None, {"env_kwargs": {"layout_seed": 2}}, "both as an env keyword"),
        (None, {"layout_seeds": []}, "no layout seeds given"),
        (None, {"layout_seeds": [-1]}, "layout seeds must be integers >= 0"),
    ],
)
def test_bad_layout_axes(problem: str | None, kwargs: dict[str, Any], match: str) -> None:
    args: dict[str, Any] = {"layout_seeds": [0], "simulations": 5, "grid": "default", **kwargs}
    with pytest.raises(ValueError, match=match):
        build_plan_specs([problem or LAYOUT_ENV_ID], [3], ["voot"], [0], **args)


def test_a_layout_run_builds_its_layout() -> None:
    specs = build_plan_specs(
        [LAYOUT_ENV_ID], None, ["voot"], [0], layout_seeds=[0, 1], simulations=5, grid="default"
    )
    rows = [run_plan_spec(s) for s in specs]
    assert all(r["status"] == "ok" for r in rows), [r.get("error") for r in rows]
    assert [r["config"]["env_kwargs"] for r in rows] == [{"layout_seed": 0}, {"layout_seed": 1}]
    envs = [P.make_instance(s.problem, None, s.env_kwargs_dict, 0).env.unwrapped for s in specs]
    assert [e.layout_seed for e in envs] == [0, 1]
    assert envs[0].chain.threshold != envs[1].chain.threshold  # two layouts, two problems
