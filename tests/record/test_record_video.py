"""Tests of voot.record.video: headless MuJoCo videos of plans (GIF; MP4 if available)."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")  # before mujoco is imported, if it is not yet

import importlib.util
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

from voot.envs.pick_place_demo import DemoPickPlace  # noqa: E402
from voot.record.video import collect_states, plan_frames, write_plan_video, write_video  # noqa: E402

#: A plan of the demo problem: pick next to the box, place it on the goal's edge.
PLAN = [np.array([-1.1, -1.0, np.pi]), np.array([-0.5, -0.6, 0.0])]


def _can_render() -> bool:
    from voot.envs.core.rendering import new_renderer

    try:  # new_renderer: an EGL context made at collection must not crash a later PPO test
        r = new_renderer(mujoco.MjModel.from_xml_string("<mujoco/>"), 8, 8)
    except Exception:
        return False
    r.close()
    return True


needs_gl = pytest.mark.skipif(not _can_render(), reason="no off-screen OpenGL (set MUJOCO_GL=egl)")


def test_states_from_actions_and_snapshots() -> None:
    problem = DemoPickPlace()
    start = problem.snapshot()
    states = collect_states(problem, actions=PLAN)
    assert len(states) == 3
    assert np.allclose(states[1][0][:2], PLAN[0][:2])  # the base moved to the pick pose
    assert np.allclose(states[2][0][3:5], PLAN[1][:2])  # the box was put down there
    end = problem.snapshot()
    problem.restore(start)
    again = collect_states(problem, snapshots=[start, end])
    assert np.array_equal(again[0][0], states[0][0]) and np.array_equal(again[1][0], states[2][0])
    with pytest.raises(ValueError, match="exactly one"):
        collect_states(problem, actions=PLAN, snapshots=[start])
    with pytest.raises(ValueError, match="exactly one"):
        collect_states(problem)
    with pytest.raises(ValueError, match="no MuJoCo"):
        collect_states(SimpleNamespace(), actions=PLAN)


@needs_gl
def test_gif_of_a_plan_with_interpolated_frames(tmp_path: Path) -> None:
    import imageio.v3 as iio

    problem = DemoPickPlace()
    start = problem.snapshot()
    frames = plan_frames(
        problem, PLAN, width=96, height=64, interpolate=2, view={"distance": 8.0, "elevation": -60}
    )
    assert len(frames) == 1 + 2 * 3
    assert all(f.shape == (64, 96, 3) and f.dtype == np.uint8 for f in frames)
    assert frames[0].std() > 0  # not a blank image
    assert not np.array_equal(frames[0], frames[3])  # the robot moved
    problem.restore(start)
    path = write_plan_video(
        tmp_path / "plan.gif", problem, actions=PLAN, width=96, height=64, fps=4, hold_last=2
    )
    back = iio.imread(path, index=None)
    assert back.shape == (3, 64, 96, 3)
    # Pillow folds the held copies of the last frame into a longer display time.
    from PIL import Image

    with Image.open(path) as gif:
        durations = []
        for k in range(gif.n_frames):
            gif.seek(k)
            durations.append(gif.info["duration"])
        assert gif.info.get("loop") == 0
    assert durations == [250, 250, 750]


@needs_gl
def test_gymnasium_mujoco_env_from_snapshots(tmp_path: Path) -> None:
    gym = pytest.importorskip("gymnasium")
    from voot.tree import MujocoGymProblem

    env = gym.make("InvertedPendulum-v5")
    problem = MujocoGymProblem(env, seed=0)
    snaps = [problem.snapshot()]
    for _ in range(3):
        problem.step(np.array([1.0]))
        snaps.append(problem.snapshot())
    frames = plan_frames(problem, snapshots=snaps, width=64, height=48)
    assert len(frames) == 4
    assert not np.array_equal(frames[0], frames[-1])
    env.close()


@needs_gl
def test_camera_and_size_errors() -> None:
    problem = DemoPickPlace()
    with pytest.raises(ValueError, match="no camera 'top'"):
        plan_frames(problem, PLAN, width=32, height=32, camera="top")
    with pytest.raises(ValueError, match="off-screen buffer"):
        plan_frames(problem, PLAN, width=4000, height=32)
    with pytest.raises(ValueError, match="unknown view key"):
        plan_frames(problem, PLAN, width=32, height=32, view={"zoom": 2})
    with pytest.raises(ValueError, match="interpolate"):
        plan_frames(problem, PLAN, interpolate=-1)


def test_env_without_mujoco_renders_itself() -> None:
    class Flat:
        render_mode = "rgb_array"

        def __init__(self) -> None:
            self.x = 0

        def step(self, a: object) -> None:
            self.x += 1

        def render(self) -> np.ndarray:
            return np.full((4, 5, 3), self.x, dtype=np.uint8)

    frames = plan_frames(Flat(), actions=[0, 0])
    assert [int(f[0, 0, 0]) for f in frames] == [0, 1, 2]
    with pytest.raises(ValueError, match="rgb_array"):
        plan_frames(SimpleNamespace(render_mode=None), actions=[0])


def test_write_video_checks(tmp_path: Path) -> None:
    frame = np.zeros((8, 8, 3), dtype=np.uint8)
    with pytest.raises(ValueError, match="unknown video format"):
        write_video(tmp_path / "a.avi", [frame])
    with pytest.raises(ValueError, match="no frames"):
        write_video(tmp_path / "a.gif", [])
    with pytest.raises(ValueError, match="fps"):
        write_video(tmp_path / "a.gif", [frame], fps=0)
    with pytest.raises(ValueError, match="frame 1"):
        write_video(tmp_path / "a.gif", [frame, np.zeros((4, 4, 3), dtype=np.uint8)])
    if importlib.util.find_spec("imageio_ffmpeg") is None:
        with pytest.raises(ValueError, match="imageio-ffmpeg"):
            write_video(tmp_path / "a.mp4", [frame])
    else:
        assert write_video(tmp_path / "a.mp4", [frame] * 3).stat().st_size > 0
