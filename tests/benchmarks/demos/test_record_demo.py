"""Tests of voot.bench.demos.record_demo: ``voot-bench record-demo``."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")
pytest.importorskip("rerun")


def test_demo_command_writes_recordings_and_figure(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    pytest.importorskip("rerun")
    pytest.importorskip("matplotlib")
    from voot.bench.cli.main import main
    from voot.record.reader import read_recording

    argv = ["record-demo", "--no-video", "--out"]
    assert main([*argv, str(tmp_path), "--simulations", "120"]) == 0
    for planner in ("voot", "pw_uct"):
        rec = read_recording(tmp_path / f"demo_{planner}.rrd")
        assert rec.entity("search/best_return").rows == {"search": 120}
    assert (tmp_path / "demo_figure5.png").stat().st_size > 5000
    assert "figure ->" in capsys.readouterr().out
    # Too short a search to reach a place node: said, not raised.
    assert main([*argv, str(tmp_path / "short"), "--simulations", "3"]) == 0
    assert "no figure" in capsys.readouterr().out
