"""Tests of voot.record.figure5: Figure-5 panels drawn from recordings."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("rerun")
pytest.importorskip("matplotlib")
pytest.importorskip("mujoco")

from voot.envs.pick_place_demo import DemoPickPlace
from voot.record import RecorderConfig, record_plan
from voot.record.figure5 import node_samples, samples_figure, unpack_colors
from voot.tree import make_chain


def test_unpack_colors() -> None:
    rgba = unpack_colors([0xFF0000FF, 0x00FF0080])
    assert np.allclose(rgba, [[1, 0, 0, 1], [0, 1, 0, 128 / 255]])


def test_panels_from_two_recordings(tmp_path: Path) -> None:
    config = RecorderConfig(watch=("root", "place", "best:place"))
    paths = {}
    for planner in ("voot", "pw_uct"):
        paths[planner] = tmp_path / f"{planner}.rrd"
        res = record_plan(DemoPickPlace(), paths[planner], planner, 60, seed=1, config=config)
        assert res.n_simulations == 60
    xy, rgba, t = node_samples(paths["voot"], "scene/samples/root/base_poses")
    assert xy.shape[1] == 2 and rgba.shape == (len(xy), 4) and t == 59
    assert np.all(np.abs(xy) <= 3.0)
    best_xy, _, _ = node_samples(paths["voot"], "scene/samples/best_place/placements")
    assert len(best_xy) >= 1
    out = samples_figure(
        {"VOOT": paths["voot"], "PW-UCT": paths["pw_uct"]}, tmp_path / "fig" / "f5.png"
    )
    assert out.stat().st_size > 5000
    with pytest.raises(ValueError, match="no entity"):
        node_samples(paths["voot"], "scene/samples/nothing/placements")
    with pytest.raises(ValueError, match="at least one"):
        samples_figure({}, tmp_path / "x.png")


def test_two_dimensional_fallback(tmp_path: Path) -> None:
    path = tmp_path / "chain.rrd"
    record_plan(make_chain("shekel", 3, threshold=0.5), path, "voot", 30, seed=0)
    xy, rgba, t = node_samples(path, "samples/root")
    assert xy.shape == (len(rgba), 2) and t == 29


def test_several_entities_per_panel_and_a_background(tmp_path: Path) -> None:
    config = RecorderConfig(watch=("root", "place"))
    paths = {}
    for planner in ("voot", "pw_uct"):
        paths[planner] = tmp_path / f"{planner}.rrd"
        record_plan(DemoPickPlace(), paths[planner], planner, 60, seed=1, config=config)
    drawn: list[object] = []
    entities = ["scene/samples/root/base_poses", "scene/samples/first_place/placements"]
    out = samples_figure(
        {"A": paths["voot"], "B": paths["pw_uct"]},
        tmp_path / "two.png",
        {"A": entities, "B": entities[0]},
        background=drawn.append,
        title="custom",
    )
    assert out.stat().st_size > 5000 and len(drawn) == 2  # one background per panel
    with pytest.raises(ValueError, match=r"no entity for the panels \['B'\]"):
        samples_figure(
            {"A": paths["voot"], "B": paths["pw_uct"]}, tmp_path / "x.png", {"A": entities}
        )
    with pytest.raises(ValueError, match="empty list"):
        samples_figure({"A": paths["voot"]}, tmp_path / "x.png", {"A": []})


def test_notes_are_written_under_their_panels(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "chain.rrd"
    record_plan(make_chain("shekel", 3, threshold=0.5), path, "voot", 30, seed=0)
    import matplotlib.axes

    written: list[str] = []
    real_text = matplotlib.axes.Axes.text

    def text(self: object, x: float, y: float, s: str, *args: object, **kwargs: object) -> object:
        written.append(s)
        return real_text(self, x, y, s, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(matplotlib.axes.Axes, "text", text)
    out = samples_figure(
        {"A": path, "B": path}, tmp_path / "n.png", "samples/root", notes={"A": "3 feasible"}
    )
    assert out.stat().st_size > 5000 and written == ["3 feasible"]  # B has no note
