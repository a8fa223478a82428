"""End-to-end tests of ``voot-bench plan`` on tiny grids: runs, resume, records, dry runs,
errors, tuning seeds and the estimate (with plot and select on its store)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from cli_fixtures import PLAN_TINY

from voot.bench.cli.main import main
from voot.bench.store.result_store import ResultStore


def test_plan_plot_select_end_to_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "plan"
    assert main(["plan", "--out", str(out), *PLAN_TINY]) == 0
    assert "4 runs: 0 already in the store, 4 ran (0 failed)" in capsys.readouterr().out
    assert main(["plan", "--out", str(out), *PLAN_TINY]) == 0  # resume: nothing to do
    assert "4 already in the store, 0 ran" in capsys.readouterr().out
    rows = ResultStore(out).load(kind="plan")
    assert len(rows) == 4 and all(len(r["best_so_far"]) == 12 for r in rows)

    png, secs, md = tmp_path / "f4.png", tmp_path / "f4s.png", tmp_path / "docs" / "plan.md"
    argv = ["plot", str(out), "--png", str(png), "--png-seconds", str(secs), "--markdown", str(md)]
    assert main([*argv, "--at", "5", "12"]) == 0
    printed = capsys.readouterr().out
    assert png.read_bytes()[:4] == b"\x89PNG" and secs.read_bytes()[:4] == b"\x89PNG"
    assert "| problem | simulations | voot | pw_uct |" in printed
    assert "| shekel_chain 3-D | 5 |" in printed and "| shekel_chain 3-D | 12 |" in printed
    assert md.read_text().startswith("### Best return")
    assert main(["plot", str(out), "--planners", "voot", "--problems", "shekel-chain"]) == 0
    assert "| problem | simulations | voot |\n" in capsys.readouterr().out

    assert main(["select", str(out)]) == 0
    assert "| shekel_chain | 3 | 12 | voot | default |" in capsys.readouterr().out

    # a store with both kinds needs --kind
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", str(out), *small, "--budget", "5", "--workers", "1"]) == 0
    capsys.readouterr()
    assert main(["plot", str(out)]) == 2
    assert "choose one with --kind" in capsys.readouterr().err
    assert main(["plot", str(out), "--kind", "plan"]) == 0
    assert main(["select", str(out), "--kind", "bbfo"]) == 0
    assert "| rastrigin | 3 | 5 | random |" in capsys.readouterr().out


def test_plan_and_plot_sampling_based_planners(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "mpc"
    argv = ["plan", "--out", str(out), *PLAN_TINY]
    i = argv.index("voot")
    argv[i : i + 2] = ["cem", "voot"]  # a sampling-based planner next to a tree planner
    assert main(argv) == 0
    rows = ResultStore(out).load(kind="plan")
    assert {r["config"]["planner"] for r in rows} == {"cem", "voot"}
    png = tmp_path / "mpc.png"
    assert main(["plot", str(out), "--png", str(png)]) == 0
    printed = capsys.readouterr().out
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert "| problem | simulations | voot | cem |" in printed
    assert "| shekel_chain 3-D | cem |" in printed  # the cost table
    assert main(["plot", str(out), "--planners", "CEM"]) == 0
    assert "| problem | simulations | cem |\n" in capsys.readouterr().out


def test_plan_records_a_run(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rrd = tmp_path / "run.rrd"
    argv = ["plan", "--out", str(tmp_path / "r"), *PLAN_TINY, "--record", str(rrd)]
    argv[argv.index("pw_uct")] = "voot"  # one planner ...
    argv[argv.index("--seeds") + 1] = "1"  # ... one seed: one run, recorded to run.rrd itself
    assert main(argv) == 0
    assert rrd.stat().st_size > 0
    assert ResultStore(tmp_path / "r").load()[0]["recorded"] == str(rrd)
    assert main(argv) == 0  # already done: not run (nor recorded) again
    assert "were not recorded again" in capsys.readouterr().err


def test_plan_records_a_generated_kitchen(tmp_path: Path) -> None:
    pytest.importorskip("rerun")
    pytest.importorskip("mujoco")
    from gymnasium import make

    from voot.record.reader import read_recording

    rrd = tmp_path / "run.rrd"
    argv = ["plan", "--out", str(tmp_path / "r"), "--problems", "kitchen_v2", "--planners"]
    argv += ["voot", "--simulations", "3", "--grid", "default", "--backend", "serial"]
    argv += ["--layout-seeds", "3:4", "--env-kwargs", "difficulty=medium", "--record", str(rrd)]
    assert main([*argv, "--no-progress"]) == 0
    (row,) = ResultStore(tmp_path / "r").load()
    assert row["config"]["env_kwargs"] == {"difficulty": "medium", "layout_seed": 3}
    env = make("voot/KitchenClearing-v2", layout_seed=3, difficulty="medium").unwrapped
    names = [o.name for o in env.objects]
    rec = read_recording(rrd)
    meshes = {e for e in rec.entities if e.startswith("/scene/bodies/obj_") and e.endswith("/mesh")}
    assert meshes == {f"/scene/bodies/{name}/mesh" for name in names}
    for name in names:  # each object's visual mesh, in the layout it was run on
        geom = env.model.geom(f"{name}_visual")
        n_visual = int(env.model.mesh_vertnum[int(geom.dataid[0])])
        assert len(rec.latest(f"scene/bodies/{name}/mesh", "Mesh3D:vertex_positions")) == n_visual


def test_plan_set_sampler_reaches_voo_and_plot_at_beyond_budget(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import json

    out = tmp_path / "p"
    base = ["plan", "--out", str(out), "--problems", "shekel_chain", "--dims", "3"]
    base += ["--planners", "voot", "--seeds", "1", "--simulations", "5", "--grid", "default"]
    assert main([*base, "--set", "sampler=gaussian", "--no-progress"]) == 0
    row = json.loads(next((out / "runs").glob("*.json")).read_text())
    assert row["planner_config"]["sampler"] == "voo"
    assert row["planner_config"]["sampler_options"]["sampler"] == "gaussian"
    capsys.readouterr()
    assert main(["plot", str(out), "--at", "50"]) == 2
    assert "beyond the runs' budget" in capsys.readouterr().err


def test_a_resumed_sweep_says_how_many_runs_are_stored(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = str(tmp_path / "p")
    base = ["plan", "--out", out, "--problems", "shekel_chain", "--dims", "3"]
    base += ["--planners", "voot", "--simulations", "5", "--grid", "default", "--no-progress"]
    assert main([*base, "--seeds", "1"]) == 0
    capsys.readouterr()
    assert main([*base, "--seeds", "2", "--dry-run"]) == 0
    assert "2 runs, 10 simulations; 1 already in the store" in capsys.readouterr().err


TUNE_TINY = (
    "--problems shekel_chain --dims 3 --planners voot --simulations 8 --workers 1 --no-progress"
).split()


def test_plan_with_tuning_seeds_end_to_end(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "plan"
    tuned = ["plan", "--out", str(out), *TUNE_TINY, "--tuning-seeds", "1000:1002", "--seeds", "0:2"]
    assert main([*tuned, "--dry-run"]) == 0
    printed = capsys.readouterr()
    assert "tuning: 12 runs (every setting) on seeds 1000-1001" in printed.err
    assert (
        "evaluation: 2 runs (the selected setting) on seeds 0-1, after the tuning runs"
        in printed.err
    )
    assert main([*tuned, "--estimate", "--probe-simulations", "3"]) == 0
    printed = capsys.readouterr().out
    assert (
        "| shekel_chain-3D | voot | 14 | 14 | 112 |" in printed
        and "probe: 3 simulations" in printed
    )
    assert "wall-hours on 1 worker" in printed
    # part of the tuning by hand (seed 1000): the tuned command reuses those very rows
    by_hand = ["plan", "--out", str(out), *TUNE_TINY, "--seeds", "1000:1001"]
    assert main(by_hand) == 0
    capsys.readouterr()
    assert main(tuned) == 0
    printed = capsys.readouterr()
    assert "12 runs: 6 already in the store, 6 ran (0 failed)" in printed.out
    assert "2 runs: 0 already in the store, 2 ran (0 failed)" in printed.out
    assert "settings selected on tuning seeds 1000-1001" in printed.err
    rows = ResultStore(out).load(kind="plan")
    assert len(rows) == 14
    from voot.bench.protocol.select import select_hyperparameters

    (sel,) = select_hyperparameters([r for r in rows if r["config"]["seed"] >= 1000])
    evaluation = [r for r in rows if r["config"]["seed"] < 1000]
    assert sorted(r["config"]["seed"] for r in evaluation) == [0, 1]
    assert all(r["config"]["params"] == sel.params for r in evaluation)
    assert main(tuned) == 0  # resume: nothing left
    assert "2 runs: 2 already in the store, 0 ran" in capsys.readouterr().out
    assert main([*tuned, "--estimate"]) == 0
    printed = capsys.readouterr().out
    assert "| shekel_chain-3D | voot | 14 | 0 | 0 |" in printed and "store: 14 rows" in printed

    # plot: the evaluation seeds with the tuned setting, one figure per axis
    figs, md = tmp_path / "figs", tmp_path / "plan.md"
    argv = ["plot", str(out), "--tuning-seeds", "1000:1002", "--axes-dir", str(figs)]
    assert main([*argv, "--markdown", str(md)]) == 0
    printed = capsys.readouterr().out
    for name in ("plan-simulations.png", "plan-calls.png", "plan-cpu-seconds.png"):
        assert (figs / name).read_bytes()[:4] == b"\x89PNG"
        assert f"`{name}`:" in printed
    text = md.read_text()
    assert "Settings selected on tuning seeds 1000-1001, disjoint from the evaluation seeds" in text
    assert f"| shekel_chain 3-D | voot | {sel.best.label} | 2 |" in text
    assert "### Simulator calls: executed steps and pre-checks" in text
    assert main(["plot", str(out)]) == 0  # without the option: the same-seed rule, all seeds
    assert f"| shekel_chain 3-D | voot | {sel.best.label} | 2 |" not in capsys.readouterr().out
    # the claims: a chain store has none of the paper's problems, every line says so
    assert main(["claims", str(out), "--tuning-seeds", "1000:1002"]) == 0
    printed = capsys.readouterr().out
    assert "| no data |" in printed and "reproduced: 0" in printed
    assert "disjoint from the evaluation seeds" in printed


def test_plan_tuning_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = str(tmp_path / "plan")
    base = ["plan", "--out", out, *TUNE_TINY, "--dry-run"]
    assert main([*base, "--tuning-seeds", "0:2", "--seeds", "1:3"]) == 2
    assert "seeds 1 are both tuning and evaluation seeds" in capsys.readouterr().err
    assert main([*base, "--tuning-seeds", "5:2", "--seeds", "0:2"]) == 2
    assert "--tuning-seeds: inverted or empty range" in capsys.readouterr().err
    assert main([*base, "--estimate", "--probe-simulations", "0"]) == 2
    assert "--probe-simulations must be >= 1" in capsys.readouterr().err
    assert main(["plot", out, "--tuning-seeds", "0:2"]) == 2  # no store there
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", out, *small, "--budget", "5", "--workers", "1"]) == 0
    capsys.readouterr()
    assert main(["plot", out, "--axes-dir", str(tmp_path / "f")]) == 2
    assert "apply to plan runs" in capsys.readouterr().err
    assert main(["claims", out]) == 2
    assert "no finished plan runs" in capsys.readouterr().err


LAYOUT_TINY = (
    "--problems voot-test/LayoutChain-v0 --planners voot pw_uct --simulations 6 --workers 1"
    " --no-progress"
).split()


def _unique_rows(out: Path) -> list[dict]:
    rows = ResultStore(out).load(kind="plan")
    assert len(rows) == len({r["run_id"] for r in rows})  # never a run twice
    return rows


def test_plan_layout_axis(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import layout_fixtures  # noqa: F401 - registers voot-test/LayoutChain-v0

    out = tmp_path / "axis"
    argv = ["plan", "--out", str(out), *LAYOUT_TINY, "--grid", "default"]
    assert main([*argv, "--layout-seeds", "3", "--dry-run"]) == 0
    printed = capsys.readouterr().out
    # one seed (0) per layout by default on a layout axis
    assert (
        "voot-test/LayoutChain-v0 6 simulations, 3 layouts x 1 seeds: voot 3, pw_uct 3" in printed
    )
    assert main([*argv, "--layout-seeds", "4", "9", "--seeds", "2"]) == 0
    assert "8 runs: 0 already in the store, 8 ran (0 failed)" in capsys.readouterr().out
    rows = _unique_rows(out)
    assert sorted({r["config"]["env_kwargs"]["layout_seed"] for r in rows}) == [4, 9]
    assert main([*argv, "--layout-seeds", "4,9", "--seeds", "2"]) == 0  # the same runs
    assert "8 already in the store, 0 ran" in capsys.readouterr().out
    assert main(["plot", str(out), "--png", str(tmp_path / "axis.png")]) == 0
    assert "| voot-test/LayoutChain-v0 | 6 |" in capsys.readouterr().out
    for bad, message in [
        (["--layout-seeds", "5:2"], "--layout-seeds: inverted or empty range"),
        (["--layout-seeds", "1", "x"], "--layout-seeds: 'x' is not an integer"),
        (["--tuning-layouts", "100:102"], "--tuning-layouts needs the evaluation layouts"),
        (["--heldout", "--layout-seeds", "3"], "--heldout sets the layouts itself"),
        (["--heldout"], "--heldout: voot-test/LayoutChain-v0 has no held-out layout set"),
    ]:
        assert main([*argv, *bad, "--dry-run"]) == 2, bad
        assert message in capsys.readouterr().err
    chain = ["plan", "--out", str(out), *TUNE_TINY, "--layout-seeds", "2", "--dry-run"]
    assert main(chain) == 2
    assert "the shekel_chain has no layouts" in capsys.readouterr().err


def test_plan_held_out_protocol_resumes(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Tuning on training layouts, evaluation on held-out ones: interrupted in the tuning,
    rerun, rerun again: every run once, nothing redone, the selection pooled per family."""
    import layout_fixtures

    from voot.bench.cli.main import EXIT_INTERRUPTED
    from voot.bench.protocol import layouts
    from voot.bench.sweep import backends as sweep

    class Interrupting:
        """A serial backend stopped (like Ctrl-C) after ``after`` rows."""

        name = "interrupting"

        def __init__(self, after: int) -> None:
            self.after = after

        def map_unordered(self, fn: Any, items: Any) -> Iterator[Any]:
            for i, item in enumerate(items):
                if i == self.after:
                    raise KeyboardInterrupt
                yield fn(item)

    monkeypatch.setitem(
        layouts.LAYOUT_SETS, layout_fixtures.LAYOUT_ENV_ID, layouts.LayoutSet((100, 101), (0, 1))
    )
    out = tmp_path / "heldout"
    argv = ["plan", "--out", str(out), *LAYOUT_TINY, "--heldout", "--seeds", "2"]
    assert main([*argv, "--dry-run"]) == 0
    err = capsys.readouterr().err
    # voot and pw_uct: 6 settings each, on 2 layouts x 2 seeds
    assert "tuning: 48 runs (every setting) on seeds 0-1 x layouts 100-101" in err
    assert "evaluation: 8 runs (the selected setting) on seeds 0-1 x layouts 0-1" in err
    real = sweep.make_backend
    monkeypatch.setattr(sweep, "make_backend", lambda *a, **k: Interrupting(after=5))
    assert main(argv) == EXIT_INTERRUPTED  # stopped in the middle of the tuning
    capsys.readouterr()
    assert len(_unique_rows(out)) == 5
    monkeypatch.setattr(sweep, "make_backend", real)
    assert main(argv) == 0
    printed = capsys.readouterr()
    assert "48 runs: 5 already in the store, 43 ran (0 failed)" in printed.out
    assert "8 runs: 0 already in the store, 8 ran (0 failed)" in printed.out
    assert "settings selected on training layouts 100-101 (seeds 0-1)" in printed.err
    rows = _unique_rows(out)
    assert len(rows) == 56
    from voot.bench.protocol.select import select_hyperparameters

    tuning = [r for r in rows if r["config"]["env_kwargs"]["layout_seed"] >= 100]
    evaluation = [r for r in rows if r["config"]["env_kwargs"]["layout_seed"] < 100]
    chosen = {s.method: s.params for s in select_hyperparameters(tuning)}
    assert all(s.best.n == 4 for s in select_hyperparameters(tuning))  # 2 layouts x 2 seeds
    assert all(r["config"]["params"] == chosen[r["config"]["planner"]] for r in evaluation)
    assert main(argv) == 0  # resume: nothing left
    printed = capsys.readouterr().out
    assert (
        "48 already in the store, 0 ran" in printed and "8 already in the store, 0 ran" in printed
    )
    assert len(_unique_rows(out)) == 56
    assert main(["plot", str(out), "--heldout", "--png", str(tmp_path / "h.png")]) == 0
    assert "Settings selected on training layouts 100-101" in capsys.readouterr().out
    # tuning on a held-out layout is refused, naming it
    bad = [
        "plan",
        "--out",
        str(out),
        *LAYOUT_TINY,
        "--tuning-layouts",
        "1:3",
        "--layout-seeds",
        "2",
    ]
    assert main([*bad, "--dry-run"]) == 2
    assert "layout seeds 1 are both training (tuning) and held-out" in capsys.readouterr().err
    # the same layouts in both phases: the seeds must differ
    same = ["plan", "--out", str(out), *LAYOUT_TINY, "--layout-seeds", "2", "--tuning-seeds", "0:2"]
    assert main([*same, "--seeds", "1:3", "--dry-run"]) == 2
    assert "seeds 1 are both tuning and evaluation seeds" in capsys.readouterr().err
    assert main([*same, "--seeds", "5:7", "--dry-run"]) == 0  # tuning on the same layouts
    assert "on seeds 0-1 x layouts 0-1; evaluation: 8 runs (the selected setting) on seeds 5-6" in (
        capsys.readouterr().err
    )


def test_problems_help_lists_the_recorded_names_by_meaning() -> None:
    from voot.bench.cli.main import build_parser
    from voot.bench.protocol.problems import names_text

    sub = build_parser()._subparsers._group_actions[0].choices["plan"]  # type: ignore[union-attr]
    text = next(a.help for a in sub._actions if a.dest == "problems")
    assert names_text() in text and "shekel_chain" in text
    assert "kitchen conveyor: the first release's rules (v0)" in text


def test_an_outside_planner_through_plan_plot_claims_and_the_held_out_protocol(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """An outside planner named module:attribute (planner_fixtures, on the tests' path):
    tuned on its own grid, evaluated, drawn, judged, and on held-out layouts, with its
    cost in every table."""
    import layout_fixtures

    from voot.bench.protocol import layouts

    outside = "planner_fixtures:rollouts"
    out = tmp_path / "plugin"
    tuned = [
        *("plan --out", str(out), "--problems shekel_chain --dims 3 --simulations 8"),
        *("--planners", outside, "voot --workers 1 --no-progress"),
        *("--tuning-seeds 100:102 --seeds 0:2",),
    ]
    argv = " ".join(tuned).split()
    assert main(argv) == 0
    printed = capsys.readouterr()
    assert f"| shekel_chain | 3 | 8 | {outside} | horizon=" in printed.err  # its selection
    rows = ResultStore(out).load(kind="plan")
    mine = [r for r in rows if r["config"]["planner"] == outside]
    assert len(mine) == 2 * 2 + 2  # its grid (horizon 2, 3) on the tuning seeds, then 2
    png = str(tmp_path / "p.png")
    assert main(["plot", str(out), "--tuning-seeds", "100:102", "--png", png]) == 0
    assert main(["plot", str(out), "--planners", outside, "--png", png]) == 0
    table = capsys.readouterr().out
    cost = [
        line for line in table.splitlines() if line.startswith(f"| shekel_chain 3-D | {outside}")
    ]
    assert cost and not any("nan" in line for line in cost)
    assert main(["claims", str(out)]) == 0
    capsys.readouterr()

    monkeypatch.setitem(
        layouts.LAYOUT_SETS, layout_fixtures.LAYOUT_ENV_ID, layouts.LayoutSet((100, 101), (0, 1))
    )
    held = tmp_path / "heldout"
    heldout = [
        *("plan --out", str(held), "--problems", layout_fixtures.LAYOUT_ENV_ID),
        *("--planners", outside, "--simulations 6 --workers 1 --no-progress --heldout"),
    ]
    assert main(" ".join(heldout).split()) == 0
    assert "settings selected on training layouts 100-101" in capsys.readouterr().err
    rows = ResultStore(held).load(kind="plan")
    assert {r["config"]["env_kwargs"]["layout_seed"] for r in rows} == {0, 1, 100, 101}
    assert main(["plot", str(held), "--heldout", "--png", str(tmp_path / "h.png")]) == 0


# ----- refused before the first run (issue 34) -----------------------------------------
_GENERATED = ["--planners", "voot", "--seeds", "1", "--simulations", "2", "--workers", "1"]


@pytest.mark.parametrize(
    ("extra", "needles"),
    [
        (["--env-kwargs", "layout_seed=-1"], ["--env-kwargs: layout_seed must be", "got -1"]),
        (["--env-kwargs", "layout_seed=1.5"], ["layout_seed must be an integer", "(float)"]),
        (["--env-kwargs", "layout_seed=1.0"], ["layout_seed must be an integer", "(float)"]),
        (["--env-kwargs", "layout_seed=true"], ["layout_seed must be an integer", "(bool)"]),
        (["--env-kwargs", "layout_seed=abc"], ["layout_seed must be an integer", "(str)"]),
        (["--env-kwargs", "layout_seed=null"], ["layout_seed must be an integer", "(NoneType)"]),
        (["--env-kwargs", "difficulty=extreme"], ["--env-kwargs", "valid levels are: easy"]),
        (["--layout-seeds", "9223372036854775808:9223372036854775809"], ["--layout-seeds"]),
    ],
)
def test_bad_env_arguments_are_refused_before_a_store_is_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: list[str], needles: list[str]
) -> None:
    from cli_fixtures import assert_refused

    argv = ["plan", "--out", str(tmp_path / "store"), "--problems", "generated_storage"]
    assert_refused([*argv, *_GENERATED, *extra], tmp_path, capsys, *needles)
    assert not (tmp_path / "store").exists()


def test_layout_seeds_on_a_problem_without_layouts_are_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from cli_fixtures import assert_refused

    argv = ["plan", "--out", str(tmp_path / "store"), "--problems", "conveyor_v1", *_GENERATED]
    line = assert_refused(
        [*argv, "--layout-seeds", "0:2"], tmp_path, capsys, "--layout-seeds", "takes no layout_seed"
    )
    assert "voot/GeneratedStorage-v0" in line  # names where layouts exist
    # the held-out protocol's tuning runs are checked as well
    assert_refused(
        [*argv, "--layout-seeds", "0:2", "--tuning-layouts", "5:6"], tmp_path, capsys, "--layout"
    )


def test_unwritable_outputs_are_refused_before_any_run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from cli_fixtures import assert_refused

    (tmp_path / "file").write_text("x")
    tiny = ["plan", *PLAN_TINY]
    assert_refused(
        [*tiny, "--out", str(tmp_path / "file" / "store")],
        tmp_path,
        capsys,
        "--out",
        "not a folder",
    )
    assert_refused([*tiny, "--out", str(tmp_path / "file")], tmp_path, capsys, "not a folder")
    rec = ["--planners", "voot", "--seeds", "1", "--out", str(tmp_path / "s")]
    assert_refused(
        [*tiny, *rec, "--record", str(tmp_path / "file" / "r.rrd")], tmp_path, capsys, "--record"
    )
    # a dry run is checked too: it is how a sweep is tried before it is run
    assert_refused(
        [*tiny, "--out", str(tmp_path / "file" / "s"), "--dry-run"], tmp_path, capsys, "--out"
    )


@pytest.mark.parametrize(
    ("extra", "needle"),
    [
        (["--workers", "0"], "--workers must be >= 1"),
        (["--workers", "-2"], "--workers must be >= 1"),
        (["--backend", "ray", "--max-tries", "0"], "--max-tries must be >= 1"),
    ],
)
@pytest.mark.parametrize("command", ["plan", "bbfo"])
def test_backend_options_are_refused_before_the_store_is_made(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: list[str], needle: str, command: str
) -> None:
    """The backend refused them only after the store's folder was made."""
    from cli_fixtures import assert_refused

    if command == "bbfo" and "--max-tries" in extra:
        return  # bbfo has no Ray retry option
    tiny = (
        ["plan", *PLAN_TINY]
        if command == "plan"
        else ["bbfo", "--functions", "shekel", "--dims", "3", "--methods", "voo", "--seeds", "1"]
    )
    if "--workers" in tiny:  # PLAN_TINY's own --workers 1 out
        i = tiny.index("--workers")
        tiny = tiny[:i] + tiny[i + 2 :]
    assert_refused([*tiny, *extra, "--out", str(tmp_path / "s")], tmp_path, capsys, needle)
    assert not (tmp_path / "s").exists()
