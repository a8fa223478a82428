"""Tests of voot.record.screenshot: screenshots of rerun's headless viewer."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("rerun")

from voot.record.screenshot import rerun_executable, viewer_screenshots


def test_the_viewer_binary_is_found() -> None:
    assert Path(rerun_executable()).name == "rerun"


def test_bad_arguments(tmp_path: Path) -> None:
    rrd = tmp_path / "run.rrd"
    with pytest.raises(ValueError, match="no recording"):
        viewer_screenshots(rrd, {None: tmp_path / "a.png"})
    rrd.write_bytes(b"")
    with pytest.raises(ValueError, match="at least one"):
        viewer_screenshots(rrd, {})
    with pytest.raises(ValueError, match="renderer"):
        viewer_screenshots(rrd, {None: tmp_path / "a.png"}, renderer="metal")
    with pytest.raises(ValueError, match="window_size"):
        viewer_screenshots(rrd, {None: tmp_path / "a.png"}, window_size=(10, 10))
    with pytest.raises(ValueError, match="timeline"):
        viewer_screenshots(rrd, {None: tmp_path / "a.png"}, sequence=3)


@pytest.mark.slow
def test_screenshot_of_a_demo_recording(tmp_path: Path) -> None:
    """Needs a graphics adapter (a GPU or Mesa's lavapipe); skipped without one."""
    pytest.importorskip("mujoco")
    from PIL import Image

    from voot.envs.pick_place_demo import DemoPickPlace
    from voot.record import record_plan

    rrd = tmp_path / "demo.rrd"
    record_plan(DemoPickPlace(), rrd, "voot", 40, seed=0)
    try:
        shots = viewer_screenshots(
            rrd,
            {None: tmp_path / "all.png", "Scene and sampled actions": tmp_path / "scene.png"},
            timeline="search",
            sequence=39,
            window_size=(800, 500),
        )
    except RuntimeError as exc:
        pytest.skip(f"the rerun viewer cannot run here: {exc}")
    full = Image.open(shots[None])
    scene = Image.open(shots["Scene and sampled actions"])
    assert full.width > scene.width > 100
    with pytest.raises(ValueError, match="no view"):
        viewer_screenshots(rrd, {"nothing": tmp_path / "x.png"}, window_size=(800, 500))
