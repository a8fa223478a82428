"""Tests of voot.planners: the planner contract, the metered problem, the measured run with
its checks, voot's planners through the interface, and the registry (entry points faked
through importlib.metadata, module:attribute on the tests' own module)."""

from __future__ import annotations

from importlib import metadata
from typing import Any

import numpy as np
import planner_fixtures as F
import pytest

from voot import planners as PL
from voot.tree.chains import make_chain
from voot.tree.config import planner_config
from voot.tree.mcts import MCTS
from voot.tree.problem import FeasibilityCheck
from voot.tree.shooting import ShootingPlanner, shooting_config

SEED = np.random.SeedSequence(7)


class Checked:
    """The 3-D Shekel chain with a pre-check that refuses actions with a negative first
    coordinate."""

    def __init__(self) -> None:
        self.chain = make_chain("shekel", 3)

    def __getattr__(self, name: str) -> Any:  # snapshot, restore, step, action_bounds
        return getattr(self.chain, name)

    def is_feasible(self, action: Any) -> bool:
        return bool(action[0] >= 0)


def _planner(fn: Any, name: str = "p") -> PL.Planner:
    return PL.as_planner(name, fn)


def test_a_run_is_measured_by_voot_around_the_problem() -> None:
    chain = make_chain("shekel", 3)
    out = PL.run_planner(_planner(F.rollouts), chain, 12, SEED, {"horizon": 2}, discount=0.9)
    assert len(out.best_so_far) == len(out.elapsed) == len(out.cpu_elapsed) == 12
    assert np.all(np.diff(out.best_so_far) >= 0)  # best so far
    assert np.all(np.diff(out.calls_curve) > 0) and out.calls_curve[-1] == out.n_steps
    assert np.all(np.diff(out.cpu_elapsed) >= 0) and np.all(np.diff(out.elapsed) >= 0)
    assert out.n_feasibility_checks == 0 and out.simulator_calls == out.n_steps
    # the replay: the plan's discounted rewards are the last best return
    ret = sum(r * 0.9**t for t, r in enumerate(out.rewards))
    assert ret == pytest.approx(out.best_so_far[-1])
    assert 1 <= len(out.actions) <= 2


def test_the_metered_problem_counts_steps_and_pre_checks() -> None:
    plain = PL.metered(make_chain("shekel", 3), discount=0.5)
    assert not isinstance(plain, FeasibilityCheck) and plain.discount == 0.5
    checked = Checked()
    meter = PL.metered(checked)
    assert isinstance(meter, FeasibilityCheck)
    assert meter.is_feasible(np.ones(3)) and not meter.is_feasible(-np.ones(3))
    meter.step(np.zeros(3))
    assert (meter.n_steps, meter.n_feasibility_checks, meter.calls) == (1, 2, 3)
    assert meter.chain is checked.chain  # anything else is the wrapped problem's


def test_voots_planners_through_the_interface_are_unchanged() -> None:
    """The tree and sampling-based planners run through run_planner give the curve and
    counts of their own search."""
    for name, make in [
        ("voot", lambda p, s: MCTS(p, planner_config("voot"), seed=s)),
        ("cem", lambda p, s: ShootingPlanner(p, shooting_config("cem", horizon=3), s)),
    ]:
        settings = {"horizon": 3} if name == "cem" else {}
        out = PL.run_planner(
            PL.builtin_planner(name), Checked(), 40, np.random.SeedSequence(3), settings
        )
        direct = make(Checked(), np.random.SeedSequence(3)).search(40)
        assert out.best_so_far == direct.best_return_curve.tolist()
        assert (out.n_steps, out.n_feasibility_checks) == (
            direct.n_steps,
            direct.n_feasibility_checks,
        )
        assert out.calls_curve[-1] == direct.n_steps + direct.n_feasibility_checks
        assert out.returned.n_nodes == direct.n_nodes
        assert [a.tolist() for a in out.actions] == [a.tolist() for a in direct.actions]
    assert PL.builtin_planner("voot").builtin


@pytest.mark.parametrize(
    ("planner", "message"),
    [
        (F.yields_nan, "yielded the best return nan after simulation 2 of 5"),
        (F.raises_midway, "raised RuntimeError in simulation 3 of 5: the planner's own bug"),
        (F.no_replay, "returned a plan that does not replay: its 0 actions return 0.0"),
        (F.too_few, "yielded 1 best returns for a budget of 5"),
    ],
)
def test_a_broken_run_names_the_planner_and_the_simulation(planner: Any, message: str) -> None:
    with pytest.raises(PL.PlannerError, match="planner 'bad'") as info:
        PL.run_planner(_planner(planner, "bad"), make_chain("shekel", 3), 5, SEED)
    assert message in str(info.value)


def test_a_plan_of_the_wrong_shape_does_not_replay() -> None:
    def wrong_plan(problem: Any, budget: int, seed: Any) -> Any:
        for _ in range(budget):
            yield 0.0
        return [np.zeros(7)]

    with pytest.raises(PL.PlannerError, match="does not replay: action 1 of 1 raised"):
        PL.run_planner(_planner(wrong_plan), make_chain("shekel", 3), 2, SEED)


def test_a_planner_is_a_function_a_class_or_a_planner() -> None:
    fn = PL.as_planner("f", F.rollouts)
    assert fn.settings_grid("chain") == [{"horizon": 2}, {"horizon": 3}]
    cls = PL.as_planner("c", F.Rollouts)
    assert (cls.version, cls.settings_grid("robot")) == ("2.0", [{"horizon": 1}, {"horizon": 2}])
    out = PL.run_planner(cls, make_chain("shekel", 3), 4, SEED, {"horizon": 1})
    assert len(out.actions) == 1 and len(out.best_so_far) == 4
    per_family = PL.Planner("g", F.rollouts, grid=lambda family: {"horizon": (len(family),)})
    assert per_family.settings_grid("robot") == [{"horizon": 5}]
    assert PL.as_planner("again", fn).name == "again"
    with pytest.raises(PL.PlannerError, match=r"'w' .* wrong signature \(problem: 'Any'\)"):
        PL.as_planner("w", F.wrong_signature)
    with pytest.raises(PL.PlannerError, match="'n' is a int, not a planner"):
        PL.as_planner("n", F.not_a_planner)


def test_settings_are_checked_against_the_planners_signature() -> None:
    fn = PL.as_planner("f", F.rollouts)
    fn.check_settings({"horizon": 2})
    with pytest.raises(ValueError, match=r"'f' does not take these settings \['width'\]"):
        fn.check_settings({"width": 2})
    with pytest.raises(ValueError, match="its settings are: horizon"):
        fn.check_settings({"width": 2})


def test_module_attribute_names_a_planner() -> None:
    p = PL.import_planner("planner_fixtures:rollouts")
    assert p.function is F.rollouts and p.name == "planner_fixtures:rollouts"
    for target, message in [
        ("no_such_module_xyz:p", "importing no_such_module_xyz failed: ModuleNotFoundError"),
        ("planner_fixtures:nope", "module planner_fixtures has no attribute nope"),
        ("planner_fixtures:", "expected module:attribute"),
        ("planner_fixtures:wrong_signature", "has the wrong signature"),
        ("planner_fixtures:Rollouts.grid", "is a dict, not a planner"),  # dotted attributes
    ]:
        with pytest.raises(PL.PlannerError, match=f"planner '{target}'") as info:
            PL.import_planner(target)
        assert message in str(info.value)


def _fake_entry_points(monkeypatch: pytest.MonkeyPatch, **targets: str) -> None:
    eps = [metadata.EntryPoint(n, v, PL.ENTRY_POINT_GROUP) for n, v in targets.items()]

    def entry_points(group: str) -> list[metadata.EntryPoint]:
        return [ep for ep in eps if ep.group == group]

    monkeypatch.setattr(metadata, "entry_points", entry_points)


def test_the_registry_finds_entry_points_and_module_attributes(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    _fake_entry_points(
        monkeypatch, fake="planner_fixtures:rollouts", broken="no_such_module_xyz:planner"
    )
    registry = PL.PlannerRegistry([PL.builtin_planner("voot")])
    assert registry.names() == ["voot", "fake", "broken"]
    assert "fake" in registry and "planner_fixtures:Rollouts" in registry
    assert "nothing" not in registry
    assert registry.get("fake").function is F.rollouts
    assert registry.get("planner_fixtures:Rollouts").version == "2.0"
    with pytest.raises(PL.PlannerError, match=r"planner 'broken' \(entry point no_such_module"):
        registry.get("broken")
    with pytest.raises(KeyError, match="unknown planner 'nothing'; valid planners are: broken"):
        registry.get("nothing")
    assert PL.PlannerRegistry(group=None).names() == []


def test_the_interface_needs_no_mujoco_and_no_bench() -> None:
    """voot.planners and voot's planners through it load no MuJoCo, no environment beyond
    what ``import voot`` registers, and no voot.bench."""
    import ast
    import subprocess
    import sys

    def loaded(imports: str) -> set[str]:
        code = f"import sys; {imports}; print(sorted(sys.modules))"
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        return set(ast.literal_eval(out.stdout))

    base = loaded("import voot")
    modules = loaded(
        "import voot.planners as p; p.builtin_planner('voot'); p.builtin_planner('cem')"
    )
    new = sorted(
        m
        for m in modules - base
        if m.split(".")[0] == "mujoco" or m.startswith(("voot.envs", "voot.bench"))
    )
    assert "voot.tree.mcts" in modules and new == []
