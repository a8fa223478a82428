"""Tests of voot.record.reader: reading .rrd files back, and clear errors for bad ones."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("rerun")

import rerun as rr

from voot.record.reader import read_recording


@pytest.fixture(scope="module")
def small_rrd(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A recording with static and temporal data on two timelines, and a blueprint."""
    import rerun.blueprint as rrb

    path = tmp_path_factory.mktemp("rrd") / "small.rrd"
    rec = rr.RecordingStream("voot_test", recording_id="reader-test")
    rec.set_log_time_enabled(False)
    rec.save(path)
    rec.log("world/box", rr.Boxes3D(half_sizes=[[1, 2, 3]]), static=True)
    for i in range(5):
        rec.reset_time()
        rec.set_time("search", sequence=10 + i)
        rec.log("value", rr.Scalars(float(i * i)))
    rec.reset_time()
    for t in range(3):
        rec.set_time("plan", sequence=t)
        rec.log("pts", rr.Points2D(np.zeros((t + 1, 2))))
    rec.send_blueprint(rrb.Blueprint(rrb.TimeSeriesView(origin="/value")))
    rec.flush()
    rec.disconnect()
    return path


def test_entities_timelines_and_counts(small_rrd: Path) -> None:
    rec = read_recording(small_rrd)
    assert rec.application_id == "voot_test"
    assert rec.recording_id == "reader-test"
    assert rec.n_blueprints == 1
    assert set(rec.entities) == {"/world/box", "/value", "/pts"}
    box = rec.entity("world/box")
    assert box.is_static and box.static_rows == 1 and box.rows == {}
    assert "Boxes3D:half_sizes" in box.components
    assert rec.entity("/value").rows == {"search": 5}
    assert rec.entity("pts").rows == {"plan": 3}
    assert rec.timelines["search"].min == 10 and rec.timelines["search"].max == 14
    assert rec.timelines["plan"].rows == 3
    assert rec.n_chunks >= 3


def test_columns_and_latest_values(small_rrd: Path) -> None:
    rec = read_recording(small_rrd)
    values = rec.column("value", "Scalars:scalars", "search")
    assert values == [(10 + i, [float(i * i)]) for i in range(5)]
    assert rec.latest("value", "Scalars:scalars", "search") == [16.0]
    assert [len(v) for _, v in rec.column("pts", "Points2D:positions", "plan")] == [1, 2, 3]
    assert rec.latest("world/box", "Boxes3D:half_sizes") == [[1.0, 2.0, 3.0]]
    assert rec.column("value", "Scalars:scalars", "plan") == []
    with pytest.raises(KeyError, match="no entity '/nope'"):
        rec.entity("nope")
    with pytest.raises(KeyError, match="no component"):
        rec.column("value", "Points2D:positions", "search")
    with pytest.raises(KeyError, match="no rows"):
        rec.latest("value", "Scalars:scalars")


def test_truncated_file_is_a_clear_error(small_rrd: Path, tmp_path: Path) -> None:
    data = small_rrd.read_bytes()
    for cut, fraction in ((len(data) - 7, "end"), (len(data) // 2, "middle"), (12, "start")):
        bad = tmp_path / f"cut_{fraction}.rrd"
        bad.write_bytes(data[:cut])
        with pytest.raises(ValueError, match="truncated"):
            read_recording(bad)


def test_lenient_read_of_a_file_without_footer(small_rrd: Path, tmp_path: Path) -> None:
    data = small_rrd.read_bytes()
    bad = tmp_path / "no_footer.rrd"
    bad.write_bytes(data[: len(data) - 7])
    rec = read_recording(bad, strict=False)
    assert rec.entity("value").rows == {"search": 5}
    cut = tmp_path / "half.rrd"
    cut.write_bytes(data[: len(data) // 2])
    with pytest.raises(ValueError, match="truncated or corrupt"):
        read_recording(cut, strict=False)


def test_corrupt_or_missing_files(tmp_path: Path) -> None:
    junk = tmp_path / "junk.rrd"
    junk.write_bytes(b"this is not a rerun file" * 10)
    with pytest.raises(ValueError, match="not a readable rerun recording"):
        read_recording(junk)
    with pytest.raises(ValueError, match="no recording file"):
        read_recording(tmp_path / "missing.rrd")
    with pytest.raises(ValueError, match="no recording file"):
        read_recording(tmp_path)
