"""Tests of voot.envs.motion.footprint.scene: the lazy scene is the eager one, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from voot.envs.motion.footprint.scene import PENDING, LazyScene, pack_static, unpack_static
from voot.envs.motion.footprint.search import FootprintSearch
from voot.envs.motion.footprint.shape import (
    Footprint,
    FootprintConfig,
    FootprintLattice,
    bound_boxes,
)
from voot.envs.motion.planar import Box2D

WS = (0.0, 4.0, 0.0, 3.0)
CFG = FootprintConfig(xy_step=0.1, headings=24)
ROBOT = Footprint((Box2D(0.0, 0.0, 0.3, 0.3, 0.0, "base"), Box2D(0.5, 0.1, 0.2, 0.25, 0.3, "load")))
STATIC = (Box2D(2.0, 0.4, 0.05, 0.4, 0.0, "wall"),)


def boxes(seed: int, n: int) -> tuple[Box2D, ...]:
    rng = np.random.default_rng(seed)
    return tuple(
        Box2D(float(rng.uniform(0.3, 3.7)), float(rng.uniform(0.3, 2.7)),
              float(rng.uniform(0.05, 0.3)), float(rng.uniform(0.05, 0.3)),
              float(rng.uniform(-3, 3)), f"b{seed}_{k}")
        for k in range(n)
    )  # fmt: skip


def test_a_clipped_window_is_the_full_windows_crop() -> None:
    lat = FootprintLattice(WS, CFG)
    box = boxes(0, 1)[0]
    full = lat.blocked_window(ROBOT, box)
    assert full is not None
    i0, i1, j0, j1, mask = full
    within = (i0 + 3, i1 - 2, j0 + 1, min(j1, j0 + 7))
    part = lat.blocked_window(ROBOT, box, within)
    assert part is not None
    c0, c1, d0, d1, sub = part
    assert (c0, c1, d0, d1) == within
    assert np.array_equal(sub, mask[:, c0 - i0 : c1 - i0, d0 - j0 : d1 - j0])
    assert lat.blocked_window(ROBOT, box, (0, 1, 0, 1)) is None  # far from the box


def known(scene: LazyScene) -> np.ndarray:
    """The poses whose byte is current: tested, and (compiled) in a tile not marked dirty."""
    view = np.frombuffer(scene.buffer, dtype=np.uint8).reshape(scene.lattice.shape)
    out = view != PENDING
    if scene.compiled:
        from voot.envs.motion.footprint.kernels import TILE_SHIFT

        _, nx, ny = scene.lattice.shape
        dirty = scene.kernel_data[-1]
        nty = -(-ny // (1 << TILE_SHIFT))
        ti = np.arange(nx)[:, None] >> TILE_SHIFT
        tj = np.arange(ny)[None, :] >> TILE_SHIFT
        out &= (dirty[ti * nty + tj] == 0)[None]
    return out.ravel()


@pytest.mark.parametrize("engine", ["compiled", "python"])
@pytest.mark.parametrize("tile", [1, 5, 32])
def test_the_lazy_scene_is_the_eager_free_lattice_through_updates(tile: int, engine: str) -> None:
    """Boxes added, removed, restored: every pose, once resolved, is the eager answer."""
    search = FootprintSearch(WS, STATIC, CFG)
    lat = FootprintLattice(WS, FootprintConfig(**{**CFG.__dict__, "engine": engine}))
    scene = LazyScene(lat, ROBOT, STATIC + bound_boxes(WS), tile, engine)
    view = np.frombuffer(scene.buffer, dtype=np.uint8)
    assert not known(scene).any()  # nothing tested yet
    a, b = boxes(1, 3), boxes(2, 2)
    rng = np.random.default_rng(0)
    for movable in (a, a + b, b, (), a[:1] + b, a + b):
        scene.update(movable)
        eager = search.free_grid(ROBOT, movable).astype(np.uint8).ravel()
        # the poses known after the update already agree
        current = known(scene)
        assert np.array_equal(view[current], eager[current])
        some = rng.choice(view.size, 50, replace=False)
        for index in some.tolist():
            assert scene.value(index) == eager[index]
        assert known(scene)[some].all()
        scene.resolve_all(np.arange(view.size, dtype=np.intp))
        assert np.array_equal(view, eager) and known(scene).all()
        assert 0 < eager.mean() < 1


def test_the_pose_test_is_the_windows_answer_at_sampled_poses() -> None:
    """pose_free (the compiled loops' test) against blocked_window, pose by pose."""
    from voot.envs.motion.footprint.kernels import pose_free

    lat = FootprintLattice(WS, CFG)
    scene = LazyScene(lat, ROBOT, STATIC + bound_boxes(WS), 8)
    movable = boxes(3, 6)
    scene.update(movable)
    blocked = lat.occupancy(ROBOT, STATIC + bound_boxes(WS) + movable).ravel()
    _, nx, ny = lat.shape
    for u in np.random.default_rng(1).choice(blocked.size, 3000, replace=False).tolist():
        assert pose_free(u, nx, ny, lat.xs, lat.ys, *scene.kernel_data[:5]) == (not blocked[u])


def test_tile_size_changes_no_path() -> None:
    """The search's answers do not depend on lazy_tile (0: the eager first version)."""
    gate = Box2D(2.0, 1.9, 0.05, 1.1, 0.0, "gate")  # closes the wall's gap: no path
    pair = (Box2D(1.3, 1.0, 0.2, 0.15, 0.4, "p"), Box2D(2.6, 2.2, 0.1, 0.3, -0.7, "q"))
    scenes = (pair, (gate,), pair[:1], (), (*pair, gate), pair)
    paths = []
    for tile in (0, 1, 7, 32):
        search = FootprintSearch(WS, STATIC, FootprintConfig(**{**CFG.__dict__, "lazy_tile": tile}))
        out = []
        for goal in ((3.0, 1.5, 0.5), (3.2, 2.3, 3.0), (3.3, 0.6, 1.57)):
            for mov in scenes:
                out.append(search.plan((0.6, 1.5, 0.0), goal, ROBOT, mov))
        paths.append(out)
    assert sum(p is not None for p in paths[0]) >= 6
    assert sum(p is None for p in paths[0]) >= 3
    for other in paths[1:]:
        for p, q in zip(paths[0], other, strict=True):
            assert (p is None and q is None) or np.array_equal(p, q)


def test_lazy_tile_is_validated() -> None:
    with pytest.raises(ValueError, match="lazy_tile"):
        FootprintConfig(lazy_tile=-1)
    with pytest.raises(ValueError, match="lazy_tile"):
        FootprintConfig(lazy_tile=257)
    with pytest.raises(ValueError, match="tile"):
        LazyScene(FootprintLattice(WS, CFG), ROBOT, STATIC, 0)


@pytest.mark.parametrize(
    "window", [None, (0, 5, 0, 31), (3, 9, 7, 8), (2, 40, 5, 29), (0, 1, 8, 16)]
)
def test_packed_static_unpacks_to_the_same_bytes(window: tuple[int, int, int, int] | None) -> None:
    """One bit per pose, whole or by window (any column offset), gives back the bytes."""
    free = np.random.default_rng(3).random((4, 41, 31)) < 0.6
    packed = pack_static(free)
    assert packed.nbytes == 4 * 41 * 4  # 31 columns in 4 bytes
    out = unpack_static(packed, 31, window)
    expected = free if window is None else free[:, window[0] : window[1], window[2] : window[3]]
    assert out.dtype == np.uint8 and np.array_equal(out, expected.astype(np.uint8))
