"""Tests of voot.bench.demos.kitchen_demo: the kitchen demo (``voot-bench demo``)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("rerun")
pytest.importorskip("mujoco")
pytest.importorskip("matplotlib")

from voot.bench.cli.main import main
from voot.bench.demos.kitchen_demo import (
    DemoSummary,
    layout_kwargs,
    output_stem,
    planner_options,
    run,
)
from voot.record.reader import read_recording


@pytest.mark.parametrize("planner", ["voot", "pw_uct", "voronoi_pw", "rand_doot"])
def test_planner_options_are_the_benchmarks(planner: str) -> None:
    from voot.bench.protocol.problems import domain_options

    assert planner_options(planner) == domain_options("voot/KitchenClearing-v0", None, planner)


def test_tiny_run_writes_a_recording_that_reads_back(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    summary = run(tmp_path / "out", n_simulations=12, seed=0, video_size=(96, 72), fps=5)
    assert isinstance(summary, DemoSummary)
    assert summary.n_simulations == 12 and summary.obstacles == 7
    assert 0 <= summary.cleared <= 7 and summary.plan_length >= 1
    rec = read_recording(summary.recording)
    assert rec.entity("search/best_return").rows == {"search": 12}
    assert rec.entity("scene/plan/base_pose").rows["plan"] >= 1
    assert "/scene/samples/root/base_poses" in rec.entities  # the env's info keys, drawn
    assert rec.n_blueprints == 1 and summary.recording_entities == len(rec.entities)
    assert summary.video is not None and summary.video.stat().st_size > 1000
    assert summary.video_frames > summary.plan_length
    saved = json.loads((tmp_path / "out" / "kitchen_voot.json").read_text())
    assert saved["cleared"] == summary.cleared and saved["recording"] == str(summary.recording)
    assert "layout_seed" not in saved and "difficulty" not in saved  # the paper's kitchen
    captured = capsys.readouterr()
    assert f"cleared {summary.cleared} of 7 obstacles" in captured.out and "rerun " in captured.out
    # the GIF's progress, on stderr: every action of the plan counted, then the writing
    n = summary.plan_length
    for k in (0, n):
        assert f"GIF: rendering the plan's frames, {k} of {n} actions" in captured.err
    assert "GIF: writing" in captured.err and "GIF: written" in captured.err
    assert "GIF:" not in captured.out


def test_bad_input(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="n_simulations"):
        run(tmp_path, n_simulations=0)
    with pytest.raises(ValueError, match="seed"):
        run(tmp_path, n_simulations=1, seed=-1)
    with pytest.raises(ValueError, match="unknown planner"):
        run(tmp_path, n_simulations=1, planner="nope")
    (tmp_path / "file").write_text("x")
    with pytest.raises(ValueError, match="folder"):
        run(tmp_path / "file", n_simulations=1)
    assert main(["demo", "--out", str(tmp_path / "cli"), "--simulations", "0"]) == 2


def _visual_vertices(model: object, body: str) -> int:
    """Vertices of ``body``'s visual mesh (its ``<body>_visual`` geom) in ``model``."""
    geom = model.geom(f"{body}_visual")  # type: ignore[attr-defined]
    return int(model.mesh_vertnum[int(geom.dataid[0])])  # type: ignore[attr-defined]


def test_generated_kitchen_recording_shows_its_mesh_objects(tmp_path: Path) -> None:
    from voot.bench.demos.kitchen_demo import GENERATED_ID, make_problem

    summary = run(
        tmp_path / "v2",
        n_simulations=4,
        seed=0,
        video_size=(96, 72),
        fps=5,
        verbose=False,
        env_id=GENERATED_ID,
        layout_seed=3,
        difficulty="medium",
    )
    stem = "kitchen_v2_medium_3_voot"
    assert summary.recording == tmp_path / "v2" / f"{stem}.rrd"
    assert summary.video == tmp_path / "v2" / f"{stem}.gif" and summary.video_frames > 1
    saved = json.loads((tmp_path / "v2" / f"{stem}.json").read_text())
    assert (saved["layout_seed"], saved["difficulty"]) == (3, "medium")
    env = make_problem(0, GENERATED_ID, layout_kwargs(GENERATED_ID, 3, "medium")).unwrapped
    model = env.model
    objects = sorted(o.name for o in env.objects)
    assert objects and summary.obstacles >= 1
    rec = read_recording(summary.recording)
    for name in objects:
        mesh = f"scene/bodies/{name}/mesh"
        # the visual mesh exactly: not its convex collision parts (group 3), nor both
        n_visual = _visual_vertices(model, name)
        assert len(rec.latest(mesh, "Mesh3D:vertex_positions")) == n_visual
        assert len(rec.latest(mesh, "Mesh3D:vertex_normals")) == n_visual
        parts = [g for g in range(model.ngeom) if model.geom_bodyid[g] == model.body(name).id]
        assert len(parts) > 2  # the object has collision parts that are left out
        # the object moves with the plan: one pose per step of the best plan
        assert rec.entity(f"scene/bodies/{name}").rows["plan"] == summary.plan_length + 1
    # the generated walls and counters are drawn as boxes of the world body
    walls = rec.latest("scene/bodies/world/boxes", "Boxes3D:half_sizes")
    assert len(walls) >= len(env.layout.blocks)


@pytest.mark.parametrize("v2", ["voot/GeneratedKitchen-v0", "voot/KitchenClearing-v2"])
def test_layout_options(v2: str) -> None:
    # the generated family, by its name and by its former one
    assert layout_kwargs(v2) == {"layout_seed": 0, "difficulty": "easy"}
    assert layout_kwargs(v2, 7, "hard") == {"layout_seed": 7, "difficulty": "hard"}
    assert layout_kwargs("voot/KitchenClearing-v1") == {}
    with pytest.raises(ValueError, match="layout_seed and difficulty choose a generated"):
        layout_kwargs("voot/KitchenClearing-v1", 3, "easy")
    with pytest.raises(ValueError, match="GeneratedKitchen-v0"):
        layout_kwargs("voot/KitchenClearing-v0", difficulty="easy")
    with pytest.raises(ValueError, match="valid levels are: easy, medium, hard"):
        layout_kwargs(v2, 0, "extreme")
    with pytest.raises(ValueError, match="layout_seed must be"):
        layout_kwargs(v2, -1)
    with pytest.raises(ValueError, match="unknown kitchen"):
        layout_kwargs("voot/ConveyorPacking-v1")
    assert output_stem("voot") == "kitchen_voot"
    assert output_stem("pw_uct", layout_kwargs(v2, 5, "hard")) == "kitchen_v2_hard_5_pw_uct"
