"""Tests of voot.bench.measure.mesh_speed: the mesh cost benchmark (figures, not speed)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from voot.bench.measure import mesh_speed as S
from voot.envs.assets import meshes as M
from voot.envs.assets.meshes import SHAPE_KINDS, ShapeSpec


@pytest.fixture(autouse=True)
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.setenv("VOOT_CACHE", str(tmp_path / "mine"))
    return tmp_path / "mine"


def test_sizes_and_the_scene_cover_the_kinds() -> None:
    assert set(S.SIZES) == set(SHAPE_KINDS)
    assert len(S.SCENE) == 10 and len({s.kind for s in S.SCENE}) >= 9


def test_the_temporary_cache_is_used_and_the_setting_restored(cache: Path) -> None:
    with S.temporary_cache() as tmp:
        assert os.environ["VOOT_CACHE"] == tmp != str(cache)
        M.mesh_assets([ShapeSpec("box", (0.1, 0.1, 0.1))])
        assert any(Path(tmp, "meshes").iterdir())
    assert os.environ["VOOT_CACHE"] == str(cache)
    assert not Path(tmp).exists() and not cache.exists()  # nothing left, nothing of ours


def test_time_shapes_reports_every_figure() -> None:
    spec = ShapeSpec("mug", S.SIZES["mug"])
    (t,) = S.time_shapes([spec], repeats=1)
    assert set(t) == {"cold", "disk", "memory", "triangles", "parts", "bytes"}
    assert t["cold"] > t["memory"] >= 0 and t["disk"] > 0
    assert t["parts"] == len(M.build_shape(spec).parts)
    assert t["triangles"] == len(M.build_shape(spec).visual.faces)
    with pytest.raises(ValueError, match="repeats must be >= 1"):
        S.time_shapes([spec], repeats=0)


def test_time_scene_and_time_lookup() -> None:
    specs = [ShapeSpec("box", (0.1, 0.1, 0.1)), ShapeSpec("bottle", (0.07, 0.07, 0.25))]
    t = S.time_scene(specs, repeats=1)
    assert set(t) == {"cold", "disk", "memory", "robot_only"}
    assert all(v > 0 for v in t.values())
    assert "obj_1" in S.scene_xml(specs) and S.scene_xml(specs).count("<freejoint") == 2
    box = S.time_lookup(specs[0], calls=300)
    assert box["hit_share"] == 1.0 and box["mesh_us"] > 0 and box["side_us"] > 0
    assert 0.5 < S.time_lookup(specs[1], calls=300)["hit_share"] < 1.0
    with pytest.raises(ValueError, match="calls must be >= 1"):
        S.time_lookup(specs[0], calls=0)
