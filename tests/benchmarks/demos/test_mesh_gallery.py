"""Tests of voot.bench.demos.mesh_gallery: the docs picture's scene (compiled, not rendered)."""

from __future__ import annotations

import itertools
from pathlib import Path

import mujoco
import pytest

from voot.bench.demos import mesh_gallery as G
from voot.envs.assets import meshes as M
from voot.envs.assets.meshes import SHAPE_KINDS
from voot.envs.core.scene import movable_objects


def test_the_gallery_holds_every_kind_in_each_variant(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("VOOT_CACHE", str(tmp_path))
    M.clear_memory_cache()
    xml, specs = G.gallery((0, 4))
    assert [s.kind for s in specs] == [*SHAPE_KINDS, *SHAPE_KINDS]
    assert {s.variant for s in specs} == {0, 4}
    model = mujoco.MjModel.from_xml_string(xml, assets=M.mesh_assets(specs))
    objs = movable_objects(model)
    assert len(objs) == 2 * len(SHAPE_KINDS)
    # side by side: no two footprints overlap
    row = sorted(objs[: len(SHAPE_KINDS)], key=lambda o: float(model.body_pos[o.body][0]))
    for a, b in itertools.pairwise(row):
        assert model.body_pos[a.body][0] + a.half[0] < model.body_pos[b.body][0] - b.half[0]
    M.clear_memory_cache()
