"""Tests of voot.record.recorder: recordings of searches, read back with rerun's reader."""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("rerun")
pytest.importorskip("mujoco")

import rerun as rr

from voot.envs.pick_place_demo import DemoPickPlace
from voot.record import (
    RecorderConfig,
    SearchRecorder,
    combine_callbacks,
    read_recording,
    record_plan,
)
from voot.record.recorder import watch_name
from voot.tree import MCTS, MCTSConfig, make_chain, plan
from voot.tree.null_problem import NullProblem


@pytest.fixture(autouse=True)
def strict_rerun() -> Iterator[None]:
    """Misuse of the rerun API raises instead of warning."""
    before = rr.strict_mode()
    rr.set_strict_mode(True)
    yield
    rr.set_strict_mode(before)


def _null_search(path: Path, n: int = 60, **options: object) -> tuple[MCTS, object]:
    problem = NullProblem(2)
    mcts = MCTS(problem, MCTSConfig(depth_limit=3), seed=0)
    with SearchRecorder(path, problem, **options) as recorder:  # type: ignore[arg-type]
        result = mcts.search(n, callback=recorder)
    return mcts, result


def test_scalars_samples_tree_and_plan_of_a_problem_without_scene(tmp_path: Path) -> None:
    path = tmp_path / "null.rrd"
    mcts, res = _null_search(path, 60, samples_every=10, flush_every=25)
    rec = read_recording(path)
    assert rec.application_id == "voot"
    assert rec.n_blueprints == 1
    assert set(rec.timelines) == {"search", "plan"}
    # One best-return and one tree-size value per simulation, equal to the search's own.
    best = rec.column("search/best_return", "Scalars:scalars", "search")
    assert [t for t, _ in best] == list(range(60))
    assert np.allclose([v[0] for _, v in best], mcts.best_return_curve)
    sizes = rec.column("search/n_nodes", "Scalars:scalars", "search")
    assert sizes[-1][1] == [len(mcts.nodes)]
    assert all(a[1][0] <= b[1][0] for a, b in itertools.pairwise(sizes))
    # No base poses nor placements: the root's samples in the 2-D fallback, every 10 sims.
    samples = rec.entity("samples/root")
    assert samples.rows == {"search": 6}
    pos = rec.column("samples/root", "Points2D:positions", "search")
    assert [t for t, _ in pos] == [9, 19, 29, 39, 49, 59]
    assert len(pos[-1][1]) == mcts.root.n_actions
    assert np.allclose(np.array(pos[-1][1]), np.array(mcts.root.actions)[:, :2])
    q = rec.latest("samples/root", "q_hat", "search")
    assert np.allclose(q, mcts.root.q)
    assert not any(e.startswith("/scene") for e in rec.entities)
    # The tree, once, at the last simulation, with every node and edge.
    tree = rec.entity("tree")
    assert tree.rows == {"search": 1}
    ids = rec.latest("tree", "GraphNodes:node_ids", "search")
    assert sorted(int(i) for i in ids) == list(range(len(mcts.nodes)))
    assert len(rec.latest("tree", "GraphEdges:edges", "search")) == len(mcts.nodes) - 1
    # The best plan: one reward per action, the return also at step 0.
    n_plan = len(res.actions)  # type: ignore[attr-defined]
    assert n_plan >= 1
    assert rec.entity("plan/reward").rows == {"plan": n_plan}
    assert rec.entity("plan/return").rows == {"plan": n_plan + 1}
    rewards = [v[0] for _, v in rec.column("plan/reward", "Scalars:scalars", "plan")]
    assert np.allclose(rewards, res.rewards)  # type: ignore[attr-defined]
    ret = rec.column("plan/return", "Scalars:scalars", "plan")[-1][1][0]
    assert ret == pytest.approx(res.best_return)  # type: ignore[attr-defined]
    last_action = rec.latest("plan/action", "BarChart:values", "plan")[0]
    assert np.allclose(last_action["buffer"], res.actions[-1])  # type: ignore[attr-defined]


def test_recording_does_not_change_the_search(tmp_path: Path) -> None:
    chain = make_chain("shekel", 3, threshold=0.5)
    ref = plan(chain, "voot", 80, seed=3)
    chain = make_chain("shekel", 3, threshold=0.5)
    res = record_plan(chain, tmp_path / "chain.rrd", "voot", 80, seed=3)
    assert np.array_equal(ref.best_return_curve, res.best_return_curve)
    assert ref.n_nodes == res.n_nodes
    rec = read_recording(tmp_path / "chain.rrd")
    assert rec.entity("search/best_return").rows == {"search": 80}


def test_scene_samples_and_plan_poses_of_the_mujoco_demo(tmp_path: Path) -> None:
    path = tmp_path / "demo.rrd"
    problem = DemoPickPlace()
    start = problem.snapshot()
    mcts = MCTS(problem, "voot", seed=0)
    recorder = SearchRecorder(path, problem, samples_every=25)
    res = mcts.search(150, callback=recorder)
    before = problem.snapshot()
    recorder.finish()
    after = problem.snapshot()
    # The replay of the plan leaves the problem where it was.
    assert np.array_equal(before[0], after[0]) and before[1:] == after[1:]
    rec = read_recording(path)
    # Geometry: static, one entity per body and kind; the world's floor, goal and walls.
    assert rec.entity("scene/bodies/world/boxes").static_rows == 1
    assert len(rec.latest("scene/bodies/world/boxes", "Boxes3D:half_sizes")) == 6
    for ent in ("robot/cylinders", "robot/capsules", "robot/ellipsoids", "robot/mesh", "box/boxes"):
        assert rec.entity(f"scene/bodies/{ent}").is_static
    # Poses: the root at search index 0, then every state of the best plan.
    n_plan = len(res.actions)
    assert n_plan >= 2
    for body in ("robot", "box"):
        info = rec.entity(f"scene/bodies/{body}")
        assert info.rows == {"plan": n_plan + 1, "search": 1}
    translations = rec.column("scene/bodies/robot", "Transform3D:translation", "plan")
    first_pick = np.asarray(res.actions[0])
    assert np.allclose(translations[1][1][0][:2], first_pick[:2], atol=1e-5)
    # Step 0 is the root's state.
    assert np.allclose(translations[0][1][0][:2], start[0][:2])
    # Samples: the root's base poses (pick) and the first place node's placements.
    root_poses = rec.column("scene/samples/root/base_poses", "Arrows3D:origins", "search")
    assert [t for t, _ in root_poses] == [24, 49, 74, 99, 124, 149]
    assert len(root_poses[-1][1]) == mcts.root.n_actions
    assert np.allclose(np.array(root_poses[-1][1])[:, :2], np.array(mcts.root.actions)[:, :2])
    place = recorder.watched()["first_place"]
    assert place.info["next_operator"] == "place"
    pts = rec.latest("scene/samples/first_place/placements", "Points3D:positions", "search")
    assert len(pts) == place.n_actions
    q = rec.latest("scene/samples/first_place/placements", "q_hat", "search")
    assert np.allclose(q, place.q)
    # Infeasible samples are grey, feasible ones are on the colour map.
    colors = np.array(
        rec.latest("scene/samples/root/base_poses", "Arrows3D:colors", "search"), dtype=np.uint64
    )
    grey = (170 << 24) | (170 << 16) | (170 << 8) | 255
    feasible = np.array(mcts.root.feasible)
    assert np.all(colors[~feasible] == grey)
    assert not np.any(colors[feasible] == grey)
    # The executed poses along the plan.
    assert rec.entity("scene/plan/base_pose").rows["plan"] == sum(1 for a in res.actions[::2])
    # The plan's rewards as one static bar chart (shown on the search timeline too).
    assert "/plan/rewards" in rec.entities
    assert not rec.entity("plan/rewards").rows  # static: on no timeline


def test_watch_entries_and_names(tmp_path: Path) -> None:
    assert watch_name("root") == "root"
    assert watch_name(3) == "node_3"
    assert watch_name("place") == "first_place"
    assert watch_name("a b/c") == "first_a_b_c"
    assert watch_name("best:place") == "best_place"
    path = tmp_path / "watch.rrd"
    mcts, _ = _null_search(path, 20, watch=(2, "nothing"), samples_every=5)
    rec = read_recording(path)
    assert "/samples/node_2" in rec.entities
    assert "/samples/root" not in rec.entities
    assert not any("nothing" in e for e in rec.entities)
    assert (
        len(rec.latest("samples/node_2", "Points2D:positions", "search")) == mcts.nodes[2].n_actions
    )


def test_best_path_watch_follows_the_best_plan(tmp_path: Path) -> None:
    problem = DemoPickPlace()
    mcts = MCTS(problem, "voot", seed=0)
    with SearchRecorder(
        tmp_path / "best.rrd", problem, watch=("best:place",), samples_every=20
    ) as r:
        mcts.search(100, callback=r)
        node = r.watched()["best_place"]
        assert node.info["next_operator"] == "place"
        assert node in [n for n, _ in mcts.best_plan()]
    rec = read_recording(tmp_path / "best.rrd")
    pts = rec.latest("scene/samples/best_place/placements", "Points3D:positions", "search")
    assert len(pts) == node.n_actions


def test_periodic_tree_and_node_cap(tmp_path: Path) -> None:
    path = tmp_path / "tree.rrd"
    mcts, _ = _null_search(path, 40, tree_every=10, tree_max_nodes=15)
    rec = read_recording(path)
    rows = rec.column("tree", "GraphNodes:node_ids", "search")
    assert [t for t, _ in rows] == [9, 19, 29, 39]
    assert len(mcts.nodes) > 15
    best = {str(n.id) for n, _ in mcts.best_plan()} | {str(mcts.best_node().id)}
    last = set(rows[-1][1])
    assert best <= last
    assert len(last) <= 15 + len(best)


def test_finish_is_idempotent_and_the_recorder_is_single_use(tmp_path: Path) -> None:
    problem = NullProblem(2)
    mcts = MCTS(problem, MCTSConfig(depth_limit=2), seed=0)
    recorder = SearchRecorder(tmp_path / "once.rrd")
    mcts.search(5, callback=recorder)
    assert recorder.problem is problem  # taken from the tree
    assert recorder.finish() == tmp_path / "once.rrd"
    assert recorder.finish() == tmp_path / "once.rrd"
    with pytest.raises(RuntimeError, match="finished"):
        recorder(mcts, 5)
    assert read_recording(tmp_path / "once.rrd").entity("search/best_return").rows == {"search": 5}


def test_combine_callbacks_calls_all_and_stops_if_any_says_so(tmp_path: Path) -> None:
    calls: list[int] = []

    def count(_mcts: object, i: int) -> bool:
        calls.append(i)
        return i == 6

    problem = NullProblem(2)
    mcts = MCTS(problem, MCTSConfig(depth_limit=2), seed=0)
    with SearchRecorder(tmp_path / "c.rrd", problem) as recorder:
        res = mcts.search(50, callback=combine_callbacks(recorder, None, count))
    assert res.n_simulations == 7
    assert calls == list(range(7))
    assert read_recording(tmp_path / "c.rrd").entity("search/n_nodes").rows == {"search": 7}


def test_bad_arguments(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"\.rrd"):
        SearchRecorder(tmp_path / "run.txt")
    with pytest.raises(ValueError, match="unknown RecorderConfig option"):
        SearchRecorder(tmp_path / "a.rrd", samples_evry=3)
    with pytest.raises(ValueError, match="config must be a RecorderConfig"):
        SearchRecorder(tmp_path / "b.rrd", config={"samples_every": 3})  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="found no MuJoCo model"):
        SearchRecorder(tmp_path / "c.rrd", NullProblem(2), scene=object())


def test_scene_can_be_switched_off(tmp_path: Path) -> None:
    problem = DemoPickPlace()
    record_plan(
        problem, tmp_path / "noscene.rrd", "voot", 20, seed=0, config=RecorderConfig(scene=False)
    )
    rec = read_recording(tmp_path / "noscene.rrd")
    assert not any(e.startswith("/scene/bodies") for e in rec.entities)
    # Sampled poses are still drawn on the floor.
    assert "/scene/samples/root/base_poses" in rec.entities


def test_reroot_keeps_the_timeline_growing(tmp_path: Path) -> None:
    problem = NullProblem(2)
    mcts = MCTS(problem, MCTSConfig(depth_limit=3, root_commitment=None), seed=0)
    with SearchRecorder(tmp_path / "reroot.rrd", problem, samples_every=5) as recorder:
        mcts.search(10, callback=recorder)
        old_root = mcts.root
        mcts.reroot(mcts.root.best_edge())
        mcts.search(10, callback=recorder)
        assert recorder.watched()["root"] is mcts.root is not old_root
    rec = read_recording(tmp_path / "reroot.rrd")
    best = rec.column("search/best_return", "Scalars:scalars", "search")
    assert [t for t, _ in best] == list(range(20))
    roots = rec.column("samples/root", "Points2D:positions", "search")
    assert [t for t, _ in roots] == [4, 9, 14, 19]
    assert len(roots[-1][1]) == mcts.root.n_actions


def _blueprint_text(path: Path) -> str:
    from rerun.chunk import RrdReader

    reader = RrdReader(str(path))
    (store,) = reader.blueprints()
    return "\n".join(str(c.to_record_batch()) for c in reader.stream(store=store))


def test_a_custom_blueprint_replaces_the_default(tmp_path: Path) -> None:
    import rerun.blueprint as rrb

    custom = rrb.Blueprint(rrb.Spatial2DView(origin="/samples", name="custom-view-xyz"))
    record_plan(
        make_chain("shekel", 3, threshold=0.5), tmp_path / "c.rrd", "voot", 5, 0, blueprint=custom
    )
    record_plan(make_chain("shekel", 3, threshold=0.5), tmp_path / "d.rrd", "voot", 5, 0)
    assert "custom-view-xyz" in _blueprint_text(tmp_path / "c.rrd")
    default = _blueprint_text(tmp_path / "d.rrd")
    assert "custom-view-xyz" not in default and "Best return" in default


def _blueprint_eye(path: Path) -> tuple[list[float], list[float], list[float]] | None:
    """The 3-D view's ``EyeControls3D`` (position, look target, up) in a file's blueprint."""
    from rerun.chunk import RrdReader

    reader = RrdReader(str(path))
    (store,) = reader.blueprints()
    for chunk in reader.stream(store=store):
        batch = chunk.to_record_batch()
        names = batch.schema.names
        cols = {
            part: next((n for n in names if n.endswith(f"EyeControls3D:{part}")), None)
            for part in ("position", "look_target", "eye_up")
        }
        if all(cols.values()):
            pos, target, up = (batch.column(c).to_pylist()[-1][0] for c in cols.values())  # type: ignore[arg-type]
            return pos, target, up
    return None


def _env_problem(env_id: str) -> object:
    import gymnasium as gym

    from voot.envs.core.problem import EnvProblem

    return EnvProblem(gym.make(env_id, disable_env_checker=True), seed=0)


@pytest.mark.parametrize("env_id", ["voot/KitchenClearing-v1", "voot/ConveyorPacking-v1"])
def test_the_3d_view_opens_at_the_scenes_perspective_camera(tmp_path: Path, env_id: str) -> None:
    """Kitchen and conveyor recordings open with the eye at the scene's ``perspective``
    camera, above and beside the rooms, looking down at a point on the floor."""
    from voot.record.mujoco_scene import model_camera_eye

    problem: Any = _env_problem(env_id)
    model = problem.unwrapped.model
    record_plan(problem, tmp_path / "k.rrd", "voot", 3, seed=0)
    eye = _blueprint_eye(tmp_path / "k.rrd")
    assert eye is not None, "the blueprint sets no 3-D eye"
    pos, target, up = eye
    expected = model_camera_eye(model, "perspective")
    np.testing.assert_allclose(pos, expected.position, atol=1e-5)
    np.testing.assert_allclose(target, expected.look_target, atol=1e-5)
    assert up == [0.0, 0.0, 1.0]
    # the eye is the MJCF camera's place; it looks down at the floor inside the rooms
    cam = model.camera("perspective").id
    np.testing.assert_allclose(pos, model.cam_pos[cam], atol=1e-5)
    assert pos[2] > 5.0 and target[2] == pytest.approx(0.0, abs=1e-5)
    cfg = problem.unwrapped.config
    region = cfg.house if "Kitchen" in env_id else cfg.workspace
    assert region[0] < target[0] < region[1] and region[2] < target[1] < region[3]
    assert not (region[0] < pos[0] < region[1] and region[2] < pos[1] < region[3])  # beside


def test_view_camera_options(tmp_path: Path) -> None:
    """None keeps rerun's automatic view; a model camera by name; an unknown name is an
    error naming the cameras; a scene without a perspective camera keeps rerun's view."""
    problem: Any = _env_problem("voot/KitchenClearing-v1")
    record_plan(problem, tmp_path / "a.rrd", "voot", 2, 0, config=RecorderConfig(view_camera=None))
    assert _blueprint_eye(tmp_path / "a.rrd") is None
    record_plan(
        problem, tmp_path / "t.rrd", "voot", 2, 0, config=RecorderConfig(view_camera="top_down")
    )
    eye = _blueprint_eye(tmp_path / "t.rrd")
    assert eye is not None and eye[1][:2] == pytest.approx(eye[0][:2])  # straight down
    with pytest.raises(ValueError, match="no camera 'nope' in the model; cameras: top_down"):
        SearchRecorder(tmp_path / "n.rrd", problem, config=RecorderConfig(view_camera="nope"))
    # the demo scene has no camera: "auto" leaves rerun's view
    record_plan(DemoPickPlace(), tmp_path / "d.rrd", "voot", 2, 0)
    assert _blueprint_eye(tmp_path / "d.rrd") is None
