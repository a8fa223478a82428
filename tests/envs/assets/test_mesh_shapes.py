"""Tests of voot.envs.assets.mesh_shapes: the trimesh shapes, their convex parts and their mass."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from mesh_fixtures import SIZES

from voot.envs.assets import mesh_shapes as S
from voot.envs.assets.mesh_shapes import SHAPE_KINDS, ShapeSpec, build_shape


def inside_hull(hull: trimesh.Trimesh, points: np.ndarray, tol: float) -> np.ndarray:
    """Which ``points`` lie in the convex ``hull`` (within ``tol`` of its faces)."""
    normals = np.asarray(hull.face_normals)
    offsets = np.einsum("ij,ij->i", normals, np.asarray(hull.triangles)[:, 0, :])
    inside: np.ndarray = np.all(points @ normals.T - offsets <= tol, axis=1)
    return inside


@pytest.mark.parametrize("variant", [0, 1, 7])
@pytest.mark.parametrize("kind", SHAPE_KINDS)
def test_every_kind_is_watertight_convex_parts_and_spans_its_size(kind: str, variant: int) -> None:
    spec = ShapeSpec(kind, SIZES[kind], variant)
    shape = build_shape(spec)
    assert shape.visual.is_watertight and shape.visual.is_winding_consistent
    assert shape.visual.volume > 0
    lo, hi = shape.visual.bounds
    np.testing.assert_allclose(hi - lo, spec.size, rtol=0, atol=1e-12)
    np.testing.assert_allclose(lo, [-spec.size[0] / 2, -spec.size[1] / 2, 0.0], atol=1e-12)
    assert shape.parts and all(p.is_convex and p.volume > 0 for p in shape.parts)
    # the parts cover the shape: every vertex of the visual mesh is in some part
    verts = np.asarray(shape.visual.vertices)
    covered = np.zeros(len(verts), dtype=bool)
    for p in shape.parts:
        covered |= inside_hull(p, verts, 1e-9)
    assert covered.all(), f"{int((~covered).sum())} vertices of {spec} outside every part"


def test_the_hollow_kinds_are_hollow_and_the_solid_ones_solid() -> None:
    # a vessel's volume is a fraction of its hull's; a box fills its bounding box
    for kind in ("crate", "tray", "bin", "bowl", "mug", "bucket"):
        shape = build_shape(ShapeSpec(kind, SIZES[kind]))
        assert shape.visual.volume < 0.5 * shape.visual.convex_hull.volume, kind
    box = build_shape(ShapeSpec("box", (0.1, 0.2, 0.3)))
    assert box.visual.volume == pytest.approx(0.1 * 0.2 * 0.3, rel=1e-12)
    assert box.mass == pytest.approx(0.1 * 0.2 * 0.3 * S.DENSITY["box"], rel=1e-12)


def test_variants_differ_and_a_spec_builds_the_same_mesh_twice() -> None:
    a, b = (
        build_shape(ShapeSpec("bottle", SIZES["bottle"], 1)),
        build_shape(ShapeSpec("bottle", SIZES["bottle"], 2)),
    )
    assert not np.array_equal(a.visual.vertices, b.visual.vertices)
    again = build_shape(ShapeSpec("bottle", SIZES["bottle"], 1))
    assert np.array_equal(a.visual.vertices, again.visual.vertices)
    assert np.array_equal(a.visual.faces, again.visual.faces)


def test_mugs_and_jugs_have_the_handle_on_the_plus_x_side() -> None:
    for kind in ("mug", "jug"):
        shape = build_shape(ShapeSpec(kind, SIZES[kind]))
        assert shape.visual.body_count == 2  # body and handle shells
        # the handle sits at the +x end: the centre of mass is pulled that way, the
        # body's axis is on the -x side of the bounding box's centre
        assert shape.center_of_mass[0] < 0.0


def test_mass_and_inertia_are_trimesh_s_and_positive_definite() -> None:
    for kind in SHAPE_KINDS:
        shape = build_shape(ShapeSpec(kind, SIZES[kind], 3))
        props = shape.visual.mass_properties  # density set by build_shape
        assert shape.visual.density == S.DENSITY[kind]
        assert shape.mass == pytest.approx(shape.visual.volume * S.DENSITY[kind], rel=1e-12)
        assert shape.mass == props["mass"]
        np.testing.assert_array_equal(shape.inertia, props["inertia"])
        np.testing.assert_array_equal(shape.center_of_mass, props["center_mass"])
        np.testing.assert_allclose(shape.inertia, shape.inertia.T, atol=1e-15)
        eig = np.linalg.eigvalsh(shape.inertia)
        assert eig.min() > 0, kind
        # the principal moments of a real body satisfy the triangle inequality
        assert eig[0] + eig[1] >= eig[2] * (1 - 1e-9), kind


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    kind=st.sampled_from(SHAPE_KINDS),
    size=st.tuples(st.floats(0.03, 0.6), st.floats(0.03, 0.6), st.floats(0.02, 0.6)),
    variant=st.integers(0, 1000),
)
def test_any_size_gives_a_watertight_mesh_of_that_size(
    kind: str, size: tuple[float, float, float], variant: int
) -> None:
    spec = ShapeSpec(kind, size, variant)
    shape = build_shape(spec)
    assert shape.visual.is_watertight and shape.visual.volume > 0
    np.testing.assert_allclose(shape.visual.extents, size, rtol=1e-12, atol=1e-15)
    assert all(p.is_convex for p in shape.parts)
    assert shape.mass > 0 and np.linalg.eigvalsh(shape.inertia).min() > 0
    # it stands on its base (not on a handle): the vertices at z = 0 span at least 30 %
    # of the footprint both ways
    verts = np.asarray(shape.visual.vertices)
    base = verts[verts[:, 2] < 1e-12]
    assert np.ptp(base[:, 0]) >= 0.3 * size[0] and np.ptp(base[:, 1]) >= 0.3 * size[1]


# ----- specs ------------------------------------------------------------------------------
def test_specs_are_validated_with_clear_errors() -> None:
    with pytest.raises(ValueError, match=r"kind must be one of box, crate.*got 'teapot'"):
        ShapeSpec("teapot", (0.1, 0.1, 0.1))
    with pytest.raises(ValueError, match=r"size\[1\] must be"):
        ShapeSpec("box", (0.1, -0.1, 0.1))
    with pytest.raises(ValueError, match=r"size\[2\] must be"):
        ShapeSpec("box", (0.1, 0.1, math.nan))
    with pytest.raises(ValueError, match=r"size\[0\] must be"):
        ShapeSpec("box", (math.inf, 0.1, 0.1))
    with pytest.raises(ValueError, match=r"size must be 3 extents"):
        ShapeSpec("box", (0.1, 0.1))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"variant must be an integer >= 0"):
        ShapeSpec("box", (0.1, 0.1, 0.1), -1)
    with pytest.raises(ValueError, match=r"variant must be"):
        ShapeSpec("box", (0.1, 0.1, 0.1), True)  # type: ignore[arg-type]


def test_specs_are_canonical_values_so_equal_specs_share_a_key() -> None:
    a = ShapeSpec("mug", (np.float64(0.1), 0.08, 1), np.int64(2))  # type: ignore[arg-type]
    b = ShapeSpec("mug", (0.1, 0.08, 1.0), 2)
    assert a == b and hash(a) == hash(b) and a.key == b.key
    assert type(a.size[2]) is float and type(a.variant) is int
    assert ShapeSpec("mug", (0.1, 0.08, 1.0), 3).key != b.key
    assert ShapeSpec("bowl", (0.1, 0.08, 1.0), 2).key != b.key
