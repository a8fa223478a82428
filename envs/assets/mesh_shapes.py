"""Object shapes built with trimesh from a spec: the mesh, its convex parts, its mass.

The v1 scenes are MuJoCo primitives; generated scenes hold objects of real
shapes: boxes, open crates and trays, bins, bowls, plates, mugs with a handle, buckets,
bottles and jugs. Each is built procedurally from a :class:`ShapeSpec` (kind, bounding-box
size, variant) by :func:`build_shape`, deterministically (same spec, same bytes, in any
process), as

* a **visual mesh**: a watertight :class:`trimesh.Trimesh` swept from a profile (a list
  of horizontal rings, bottom to top, outer wall then inner wall for the hollow kinds),
  with a handle as a second closed shell for mugs and jugs;
* **convex collision parts**: a convex decomposition by construction (the floor slab,
  one hull per angular sector and height band of a wall, one per band of a solid, a few
  along a handle), each the trimesh convex hull of the rings it spans, so the parts cover
  the shape (MuJoCo collides a mesh geom as its convex hull anyway: one non-convex mesh
  would fill the inside of a bowl);
* its **mass, centre of mass and inertia** from the visual mesh (trimesh
  ``mass_properties``) at a density per kind (:data:`DENSITY`).

The body origin is the bottom centre of the bounding box, which spans exactly
``size`` (the sweep is mapped onto it by a final per-axis affine map, which keeps the
parts convex). Their files, cache and MJCF are :mod:`voot.envs.assets.meshes`.
"""

from __future__ import annotations

import functools
import hashlib
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import trimesh
from numpy.typing import NDArray

from voot import validation as V

FloatArray = NDArray[np.float64]

__all__ = [
    "DENSITY",
    "GENERATOR_VERSION",
    "SHAPE_KINDS",
    "MeshShape",
    "ShapeSpec",
    "build_shape",
    "built_shape",
]

SHAPE_KINDS: tuple[str, ...] = (
    "box",
    "crate",
    "tray",
    "bin",
    "bowl",
    "plate",
    "mug",
    "bucket",
    "bottle",
    "jug",
)

#: Density (kg/m^3) of each kind's mesh volume: a cardboard box as a solid block (the v1
#: scenes' object density, 100), plastic crates, trays, bins and buckets (polyethylene,
#: 950), ceramic bowls, plates and mugs (2300), bottles and jugs full of water (1000).
DENSITY: dict[str, float] = {
    "box": 100.0,
    "crate": 950.0,
    "tray": 950.0,
    "bin": 950.0,
    "bowl": 2300.0,
    "plate": 2300.0,
    "mug": 2300.0,
    "bucket": 950.0,
    "bottle": 1000.0,
    "jug": 1000.0,
}

#: Version of the shape generator: part of every cache key, so a change of the shapes
#: (bump it) never reads an old cache entry.
GENERATOR_VERSION = 3

#: Vertices per ring of the round kinds (a multiple of 4: the rings reach the bounding box
#: exactly on the x and y axes).
_ROUND = 32
#: Angular sectors of a round wall's convex parts: the hull of a sector's inner arc bulges
#: into the cavity by ``r (1 - cos(pi / 12))``, 3.4 % of the radius.
_SECTORS = 12


@dataclass(frozen=True)
class ShapeSpec:
    """What object to build: its kind, bounding-box size and variant.

    Attributes:
        kind: One of :data:`SHAPE_KINDS`.
        size: Extents ``(x, y, z)`` of the bounding box in metres, in the body frame
            (z up). The body origin is the centre of the box's bottom face.
        variant: Deterministic variation of the shape (taper, wall thickness, bevels,
            neck and handle proportions...); 0 is each kind's plain form.
    """

    kind: str
    size: tuple[float, float, float]
    variant: int = 0

    def __post_init__(self) -> None:
        V.one_of(self.kind, "kind", SHAPE_KINDS)
        if isinstance(self.size, str) or len(tuple(self.size)) != 3:
            raise ValueError(f"size must be 3 extents (x, y, z) in metres, got {self.size!r}")
        size = tuple(V.positive(v, f"size[{i}]") for i, v in enumerate(self.size))
        object.__setattr__(self, "size", size)
        object.__setattr__(self, "variant", V.integer(self.variant, "variant", 0))

    @property
    def key(self) -> str:
        """Hash of the spec and :data:`GENERATOR_VERSION` (cache key, asset names)."""
        text = (
            f"{GENERATOR_VERSION}|{self.kind}|{'|'.join(v.hex() for v in self.size)}|{self.variant}"
        )
        return hashlib.sha256(text.encode()).hexdigest()[:16]


@dataclass(frozen=True)
class MeshShape:
    """A built object shape (:func:`build_shape`).

    Attributes:
        spec: What was built.
        visual: The watertight visual mesh, body frame.
        parts: The convex collision parts, body frame (convex hulls; they cover the
            visual mesh up to the sagitta of the wall sectors).
        mass: Mass in kg (the visual mesh's volume times :data:`DENSITY` of the kind).
        center_of_mass: Centre of mass, body frame, ``(3,)``.
        inertia: Inertia tensor about the centre of mass, body axes, ``(3, 3)``.
    """

    spec: ShapeSpec
    visual: trimesh.Trimesh
    parts: tuple[trimesh.Trimesh, ...]
    mass: float
    center_of_mass: FloatArray
    inertia: FloatArray


# ----- building ---------------------------------------------------------------------------
def _rng(spec: ShapeSpec) -> np.random.Generator | None:
    """The variant's generator (None for variant 0: every parameter at its middle)."""
    if spec.variant == 0:
        return None
    return np.random.default_rng([SHAPE_KINDS.index(spec.kind), spec.variant])


def _pick(rng: np.random.Generator | None, lo: float, hi: float) -> float:
    """A shape parameter in ``[lo, hi]``: the middle for variant 0, else drawn."""
    return 0.5 * (lo + hi) if rng is None else float(rng.uniform(lo, hi))


def _unit_ring(shape: str, exponent: float = 2.0) -> FloatArray:
    """A closed ring of the unit square's or circle's boundary, counter-clockwise, ``(K, 2)``.

    ``rect``: the 4 corners. ``round``: a superellipse ``|x|^p + |y|^p = 1`` with
    ``p = exponent`` (2: a circle; larger: a rounded square), :data:`_ROUND` vertices, on
    the axes at indices ``0, K/4, K/2, 3K/4``.
    """
    if shape == "rect":
        return np.array([[1.0, -1.0], [1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0]])
    th = 2.0 * np.pi * np.arange(_ROUND) / _ROUND
    c, s = np.cos(th), np.sin(th)
    # exact axis points (cos(pi/2) is 6e-17, not 0)
    q = _ROUND // 4
    c[[q, 3 * q]] = 0.0
    s[[0, 2 * q]] = 0.0
    e = 2.0 / exponent
    return np.stack([np.sign(c) * np.abs(c) ** e, np.sign(s) * np.abs(s) ** e], axis=1)


def _rings(unit: FloatArray, profile: list[tuple[float, float, float]]) -> FloatArray:
    """Rings ``(P, K, 3)``: ``unit`` scaled by each profile point's ``(hx, hy)`` at its ``z``."""
    out = np.empty((len(profile), len(unit), 3))
    for i, (hx, hy, z) in enumerate(profile):
        out[i, :, 0] = unit[:, 0] * hx
        out[i, :, 1] = unit[:, 1] * hy
        out[i, :, 2] = z
    return out


def _sweep(rings: FloatArray) -> trimesh.Trimesh:
    """The closed surface through the rings ``(P, K, 3)``, both end rings capped.

    Consecutive rings are joined by quads (two triangles each); the first and last ring
    are closed by a fan (each ring must be convex). Orientation: if the enclosed volume
    comes out negative the faces are flipped, so the normals point outwards.
    """
    p, k = rings.shape[:2]
    idx = np.arange(p * k).reshape(p, k)
    a = idx[:-1, :]
    b = np.roll(idx[:-1, :], -1, axis=1)
    c = np.roll(idx[1:, :], -1, axis=1)
    d = idx[1:, :]
    quads = np.concatenate(
        [np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)]
    )
    j = np.arange(1, k - 1)
    first = np.stack([np.zeros_like(j), j + 1, j], -1)
    last = (p - 1) * k + np.stack([np.zeros_like(j), j, j + 1], -1)
    faces = np.concatenate([quads, first, last])
    mesh = trimesh.Trimesh(rings.reshape(-1, 3), faces, process=False)
    if mesh.volume < 0:
        mesh.invert()
    return mesh


def _hull(points: FloatArray) -> trimesh.Trimesh:
    """The convex hull of ``points`` as a closed mesh with outward normals.

    trimesh's hull (scipy's qhull) without its generic repair, a quarter of the cost: the
    faces are turned outwards here directly, each against the centroid of the hull's
    vertices (inside a convex hull).
    """
    hull = trimesh.convex.convex_hull(np.asarray(points, dtype=np.float64), repair=False)
    v = np.asarray(hull.vertices, dtype=np.float64)
    f = np.array(hull.faces, dtype=np.int64)
    tri = v[f]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    inward = np.einsum("ij,ij->i", normal, tri.mean(axis=1) - v.mean(axis=0)) < 0.0
    f[inward] = f[inward][:, ::-1]
    return trimesh.Trimesh(v, f, process=False)


@dataclass
class _Build:
    """A shape under construction: closed shells and convex parts, body frame."""

    shells: list[trimesh.Trimesh]
    parts: list[trimesh.Trimesh]


def _interp_half(profile: list[tuple[float, float, float]], z: float) -> tuple[float, float]:
    """Half widths ``(hx, hy)`` of an outer profile at height ``z`` (linear)."""
    zs = [p[2] for p in profile]
    return (
        float(np.interp(z, zs, [p[0] for p in profile])),
        float(np.interp(z, zs, [p[1] for p in profile])),
    )


def _solid(unit: FloatArray, outer: list[tuple[float, float, float]], bands: list[float]) -> _Build:
    """A solid of the swept profile ``outer`` (bottom to top), parts cut at ``bands``.

    Each band ``[z_i, z_{i+1}]`` is one convex part: the hull of the profile's rings inside
    it (exact for a straight or convex profile, a close cover otherwise).
    """
    rings = _rings(unit, outer)
    parts = []
    zs = np.array([p[2] for p in outer])
    for z0, z1 in itertools.pairwise(bands):
        inside = [(*_interp_half(outer, z0), z0)]
        inside += [outer[i] for i in np.flatnonzero((zs > z0) & (zs < z1))]
        inside.append((*_interp_half(outer, z1), z1))
        parts.append(_hull(_rings(unit, inside).reshape(-1, 3)))
    return _Build([_sweep(rings)], parts)


def _hollow(
    unit: FloatArray,
    outer: list[tuple[float, float, float]],
    wall: float,
    floor: float,
    bands: int,
    sectors: int,
) -> _Build:
    """An open-top vessel: the outer profile, a flat rim, the inner wall ``wall`` inside it.

    The inner wall runs at the outer profile's heights (from the rim down to the floor's
    top at ``floor``) with both half widths reduced by ``wall``. Parts: the floor slab
    (hull of the outer rings from 0 up to ``floor``) and, for each of ``bands`` equal height
    bands of the wall and each of ``sectors`` angular sectors, the hull of the outer and
    inner ring arcs in it.
    """
    height = outer[-1][2]
    zs = sorted({p[2] for p in outer if p[2] > floor} | {floor})
    inner = [(hx - wall, hy - wall, z) for z in reversed(zs) for hx, hy in [_interp_half(outer, z)]]
    rings = _rings(unit, outer + inner)
    shells = [_sweep(rings)]
    below = [q for q in outer if q[2] < floor]
    slab = _rings(unit, [*below, (*_interp_half(outer, floor), floor)])
    parts = [_hull(slab.reshape(-1, 3))]
    k = len(unit)
    edges = np.linspace(floor, height, bands + 1)
    for z0, z1 in itertools.pairwise(edges):
        levels = [z0, *(z for z in zs if z0 < z < z1), z1]
        prof = []
        for z in levels:
            hx, hy = _interp_half(outer, z)
            prof += [(hx, hy, z), (hx - wall, hy - wall, z)]
        band = _rings(unit, prof)
        for s in range(sectors):
            lo, hi = s * k // sectors, (s + 1) * k // sectors
            cols = [j % k for j in range(lo, hi + 1)]
            parts.append(_hull(band[:, cols, :].reshape(-1, 3)))
    return _Build(shells, parts)


def _handle(
    x_top: float, x_bottom: float, base: float, z_mid: float, reach: float, tube: float
) -> _Build:
    """A D-shaped handle on the +x side: a tube of radius ``tube`` swept along a path.

    The path starts inside the wall at ``(x_top, 0, z_mid + a)`` (``a = reach - tube``),
    runs out to ``x = base``, follows a half circle of radius ``a`` out to
    ``base + a`` and back to ``(base, 0, z_mid - a)``, and ends inside the wall at
    ``x_bottom``; the tube reaches ``base + reach``. A closed shell of its own that overlaps
    the body's wall (the overlap's volume, a few cubic millimetres, counts twice in the
    mass). Parts: the hulls of consecutive groups of its rings.
    """
    a = reach - tube
    pts = [np.array([x_top, 0.0, z_mid + a])]
    ts = [np.array([1.0, 0.0, 0.0])]
    for u in np.linspace(0.0, np.pi, 13):
        pts.append(np.array([base + a * math.sin(u), 0.0, z_mid + a * math.cos(u)]))
        ts.append(np.array([math.cos(u), 0.0, -math.sin(u)]))
    pts.append(np.array([x_bottom, 0.0, z_mid - a]))
    ts.append(np.array([-1.0, 0.0, 0.0]))
    k = 12
    psi = 2.0 * np.pi * np.arange(k) / k
    y = np.array([0.0, 1.0, 0.0])
    rings = np.empty((len(pts), k, 3))
    for i, (p, t) in enumerate(zip(pts, ts, strict=True)):
        n1 = np.cross(t, y)
        rings[i] = p + tube * (np.cos(psi)[:, None] * n1 + np.sin(psi)[:, None] * y)
    groups = [(0, 3), (2, 5), (4, 7), (6, 9), (8, 11), (10, 13), (12, 15)]
    parts = [_hull(rings[i0:i1].reshape(-1, 3)) for i0, i1 in groups]
    return _Build([_sweep(rings)], parts)


def _profile_box(spec: ShapeSpec) -> _Build:
    sx, sy, sz = spec.size
    hx, hy = sx / 2, sy / 2
    rng = _rng(spec)
    bevel = 0.0 if rng is None else _pick(rng, 0.0, 0.12) * min(sx, sy, sz)
    if bevel < 1e-4:
        outer = [(hx, hy, 0.0), (hx, hy, sz)]
    else:
        outer = [
            (hx - bevel, hy - bevel, 0.0),
            (hx, hy, bevel),
            (hx, hy, sz - bevel),
            (hx - bevel, hy - bevel, sz),
        ]
    return _solid(_unit_ring("rect"), outer, [0.0, sz] if bevel < 1e-4 else [p[2] for p in outer])


def _wall(spec: ShapeSpec, lo: float, hi: float, rng: np.random.Generator | None) -> float:
    """Wall thickness: ``lo..hi`` metres, at most a sixth of the smaller half width."""
    sx, sy, _ = spec.size
    return min(_pick(rng, lo, hi), min(sx, sy) / 12.0)


def _profile_crate(spec: ShapeSpec, shallow: bool) -> _Build:
    """An open-top rectangular box (crate; tray when ``shallow``: flared low walls)."""
    sx, sy, sz = spec.size
    rng = _rng(spec)
    wall = _wall(spec, 0.004, 0.01, rng)
    floor = min(_pick(rng, 0.005, 0.012), sz / 4.0)
    taper = _pick(rng, 0.0, 0.06) if not shallow else _pick(rng, 0.04, 0.15)
    hx, hy = sx / 2, sy / 2
    inset = taper * min(hx, hy, sz)
    outer = [(hx - inset, hy - inset, 0.0), (hx, hy, sz)]
    return _hollow(_unit_ring("rect"), outer, wall, floor, 1, 4)


def _profile_bin(spec: ShapeSpec) -> _Build:
    """A tapered open bin with rounded corners (a superellipse ring)."""
    sx, sy, sz = spec.size
    rng = _rng(spec)
    unit = _unit_ring("round", _pick(rng, 3.0, 6.0))
    taper = _pick(rng, 0.05, 0.15)
    wall = _wall(spec, 0.003, 0.006, rng)
    floor = min(_pick(rng, 0.004, 0.008), sz / 4.0)
    hx, hy = sx / 2, sy / 2
    outer = [(hx * (1 - taper), hy * (1 - taper), 0.0), (hx, hy, sz)]
    return _hollow(unit, outer, wall, floor, 2, 16)


def _profile_dish(spec: ShapeSpec, plate: bool) -> _Build:
    """A bowl (or plate): a foot ring and a curved wall flaring out to the rim."""
    sx, sy, sz = spec.size
    rng = _rng(spec)
    hx, hy = sx / 2, sy / 2
    foot = _pick(rng, 0.35, 0.55) if not plate else _pick(rng, 0.5, 0.7)
    foot_h = sz * (_pick(rng, 0.05, 0.1) if not plate else _pick(rng, 0.1, 0.2))
    power = _pick(rng, 0.5, 0.8) if not plate else _pick(rng, 0.25, 0.4)
    wall = _wall(spec, 0.003, 0.006, rng)
    wall = min(wall, 0.3 * sz)
    floor = foot_h + min(wall, 0.25 * sz)
    outer = [(foot * hx, foot * hy, 0.0), (foot * hx, foot * hy, foot_h)]
    for f in np.linspace(0.0, 1.0, 7)[1:]:
        r = foot + (1.0 - foot) * f**power
        outer.append((r * hx, r * hy, foot_h + f * (sz - foot_h)))
    return _hollow(_unit_ring("round"), outer, wall, floor, 2 if not plate else 1, _SECTORS)


def _profile_mug(spec: ShapeSpec) -> _Build:
    """A cylindrical (or slightly tapered) mug with a D handle on the +x side."""
    sx, sy, sz = spec.size
    rng = _rng(spec)
    reach = min(_pick(rng, 0.18, 0.26) * sx, 0.4 * sz)
    rx, ry = (sx - reach) / 2, sy / 2
    taper = _pick(rng, 0.0, 0.1)
    wall = min(_pick(rng, 0.003, 0.005), rx / 6, ry / 6)
    floor = min(_pick(rng, 0.006, 0.01), sz / 4)
    outer = [(rx * (1 - taper), ry * (1 - taper), 0.0), (rx, ry, sz)]
    body = _hollow(_unit_ring("round"), outer, wall, floor, 1, _SECTORS)
    tube = min(0.3 * reach, 0.08 * sz, 0.007)
    z_mid = _pick(rng, 0.5, 0.58) * sz
    a = reach - tube
    x_top = _interp_half(outer, z_mid + a)[0] - wall / 2
    x_bottom = _interp_half(outer, z_mid - a)[0] - wall / 2
    handle = _handle(x_top, x_bottom, rx, z_mid, reach, tube)
    return _Build(body.shells + handle.shells, body.parts + handle.parts)


def _profile_bucket(spec: ShapeSpec) -> _Build:
    """A tapered round bucket with a thickened rim."""
    sx, sy, sz = spec.size
    rng = _rng(spec)
    hx, hy = sx / 2, sy / 2
    taper = _pick(rng, 0.1, 0.2)
    wall = _wall(spec, 0.003, 0.005, rng)
    lip = min(_pick(rng, 0.004, 0.008), hx / 10, hy / 10)
    floor = min(_pick(rng, 0.005, 0.01), sz / 4)
    rim_h = min(0.06 * sz, 0.02)
    top = (1 - taper) + taper * (sz - rim_h) / sz
    outer = [
        (hx * (1 - taper) - lip, hy * (1 - taper) - lip, 0.0),
        (hx * top - lip, hy * top - lip, sz - rim_h),
        (hx, hy, sz - rim_h),
        (hx, hy, sz),
    ]
    return _hollow(_unit_ring("round"), outer, wall + lip, floor, 2, _SECTORS)


def _bottle_outer(
    spec: ShapeSpec, rng: np.random.Generator | None, rx: float, ry: float
) -> tuple[list[tuple[float, float, float]], list[float]]:
    """Outer profile (bevelled base, body, cosine shoulder, neck, lip) and part bands."""
    sz = spec.size[2]
    neck = _pick(rng, 0.3, 0.45)
    shoulder = _pick(rng, 0.55, 0.7) * sz
    neck_z = shoulder + _pick(rng, 0.15, 0.22) * sz
    bevel = min(0.03 * sz, 0.1 * min(rx, ry))
    outer = [(0.92 * rx, 0.92 * ry, 0.0), (rx, ry, bevel), (rx, ry, shoulder)]
    for f in np.linspace(0.0, 1.0, 6)[1:]:
        r = neck + (1.0 - neck) * 0.5 * (1.0 + math.cos(math.pi * f))
        outer.append((r * rx, r * ry, shoulder + f * (neck_z - shoulder)))
    outer.append((neck * rx, neck * ry, sz))
    mid = 0.5 * (shoulder + neck_z)
    return outer, [0.0, shoulder, mid, neck_z, sz]


def _profile_bottle(spec: ShapeSpec) -> _Build:
    """A round (or oval) bottle: body, shoulder, neck; a solid (full of water)."""
    sx, sy, _ = spec.size
    outer, bands = _bottle_outer(spec, _rng(spec), sx / 2, sy / 2)
    return _solid(_unit_ring("round"), outer, bands)


def _profile_jug(spec: ShapeSpec) -> _Build:
    """A wide bottle with a D handle on the +x side of its body.

    The handle spans ``z_mid - reach .. z_mid + reach`` between 8 % of the height and the
    shoulder (at least 55 % of it), so its reach is at most 23.5 % of the height: a low
    jug gets a small handle rather than one that reaches below its base.
    """
    sx, sy, sz = spec.size
    rng = _rng(spec)
    reach = min(_pick(rng, 0.2, 0.28) * sx, 0.235 * sz)
    rx, ry = (sx - reach) / 2, sy / 2
    outer, bands = _bottle_outer(spec, rng, rx, ry)
    body = _solid(_unit_ring("round"), outer, bands)
    tube = min(0.3 * reach, 0.06 * sz, 0.01)
    z_mid = max(min(0.45 * sz, bands[1] - reach), 0.08 * sz + reach)
    handle = _handle(rx - 2 * tube, rx - 2 * tube, rx, z_mid, reach, tube)
    return _Build(body.shells + handle.shells, body.parts + handle.parts)


_BUILDERS: dict[str, Callable[[ShapeSpec], _Build]] = {
    "box": _profile_box,
    "crate": lambda s: _profile_crate(s, shallow=False),
    "tray": lambda s: _profile_crate(s, shallow=True),
    "bin": _profile_bin,
    "bowl": lambda s: _profile_dish(s, plate=False),
    "plate": lambda s: _profile_dish(s, plate=True),
    "mug": _profile_mug,
    "bucket": _profile_bucket,
    "bottle": _profile_bottle,
    "jug": _profile_jug,
}


def _fit(mesh: trimesh.Trimesh, lo: FloatArray, scale: FloatArray, size: FloatArray) -> None:
    """Map ``mesh`` in place by ``v -> (v - lo) * scale - (size_x/2, size_y/2, 0)``."""
    v = (np.asarray(mesh.vertices) - lo) * scale - np.array([size[0] / 2, size[1] / 2, 0.0])
    mesh.vertices = v


def build_shape(spec: ShapeSpec) -> MeshShape:
    """Build the object ``spec`` describes (see the module docstring).

    Raises:
        ValueError: If the built visual mesh is not watertight (naming the spec); by
            construction it always is.
    """
    b = _BUILDERS[spec.kind](spec)
    visual = b.shells[0]
    if len(b.shells) > 1:
        joined = trimesh.util.concatenate(b.shells)
        assert isinstance(joined, trimesh.Trimesh)
        visual = joined
    size = np.array(spec.size)
    lo, hi = visual.bounds
    scale = size / (hi - lo)
    _fit(visual, lo, scale, size)
    for p in b.parts:
        _fit(p, lo, scale, size)
    if not visual.is_watertight or not visual.is_winding_consistent:
        raise ValueError(f"the mesh of {spec} is not watertight")
    visual.density = DENSITY[spec.kind]
    props = visual.mass_properties
    return MeshShape(
        spec=spec,
        visual=visual,
        parts=tuple(b.parts),
        mass=float(props["mass"]),
        center_of_mass=np.asarray(props["center_mass"], dtype=np.float64),
        inertia=np.asarray(props["inertia"], dtype=np.float64),
    )


@functools.lru_cache(maxsize=16)
def built_shape(spec: ShapeSpec) -> MeshShape:
    """:func:`build_shape`, remembered for the last few specs of this process.

    The mesh files and the grasp table of a spec (:mod:`voot.envs.robot.mesh_grasp`) are both
    made from its shape; this builds it once for both. The result is shared: do not
    change its meshes.
    """
    return build_shape(spec)
