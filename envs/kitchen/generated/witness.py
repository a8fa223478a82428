"""Proof that a generated kitchen can be cleared: a scripted constructive solution.

Every generated instance of ``voot/GeneratedKitchen-v0`` must be solvable. The proof does
not use a planner: :func:`constructive_solution` clears the obstacles one by one, in the
env's handling order, through the env's own ``step``. For each obstacle it tries a fixed
grid of pick parameters (:data:`PICK_GRID`), and for each feasible pick a fixed grid of
placements off the fixed path's swept volume and outside the forbidden rooms, nearest
first (:func:`placement_candidates`), until one place clears the obstacle; an infeasible
try is undone with ``set_state``. The kitchen is accepted iff every obstacle gets cleared
(:mod:`voot.envs.kitchen.generated.instance` draws the next attempt otherwise), and the
feasible actions found are the **witness** plan: normalised actions that solve the
episode from ``reset()`` (a scripted solution, as :mod:`voot.envs.scripted` is for v1).
The check is sufficient, not necessary: a cleverer plan might clear a rejected kitchen.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from voot.envs.core.scene import object_footprint
from voot.envs.core.units import normalize
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.motion.rects import rect_inside, rect_overlaps

__all__ = [
    "PICKS_PER_OBJECT",
    "PICK_GRID",
    "PLACES_PER_PICK",
    "PLACE_HEADINGS",
    "PLACE_SPACING",
    "constructive_solution",
    "placement_candidates",
]

FloatArray = NDArray[np.float64]

#: The constructive solver's pick grid, in the order tried: grasp angle (deg), height
#: fraction, depth fraction, base distance fraction, base angle (deg), facing offset (deg).
PICK_GRID: tuple[tuple[float, ...], ...] = tuple(
    (angle, height, 0.5, dist, base_angle, 0.0)
    for dist in (0.6, 0.75, 0.88)
    for base_angle in range(0, 360, 30)
    for angle, height in ((135.0, 0.8), (90.0, 0.95), (120.0, 0.6))
)
#: Spacing (metres) and headings (deg) of the solver's placement grid.
PLACE_SPACING = 0.3
PLACE_HEADINGS = (0.0, 90.0, 45.0, 135.0)
#: Feasible picks tried per obstacle, and placements stepped per pick, before giving up.
PICKS_PER_OBJECT = 8
PLACES_PER_PICK = 60


def _pick_action(env: KitchenClearingEnv, p: Sequence[float]) -> FloatArray:
    q = [math.radians(p[0]), p[1], p[2], p[3], math.radians(p[4]), math.radians(p[5])]
    return normalize(q, env.config.pick_ranges)


def _place_action(env: KitchenClearingEnv, x: float, y: float, theta_deg: float) -> FloatArray:
    a = np.zeros(6)
    a[:3] = normalize([x, y, math.radians(theta_deg)], env.config.place_ranges)
    return a


def placement_candidates(env: KitchenClearingEnv) -> list[tuple[float, float, float]]:
    """The solver's placements of the held object: ``(x, y, theta_deg)``, nearest first.

    A grid of :data:`PLACE_SPACING` over the house with the headings
    :data:`PLACE_HEADINGS`, kept where the object's footprint is inside the house, out of
    the forbidden rooms and off the fixed path's swept volume, sorted by the distance
    from the object's current position (then by heading, in order).
    """
    cfg, t = env.config, env.task
    obj = env.objects[t.held]
    here = env.object_pose(t.held)
    x0, x1, y0, y1 = cfg.house
    xs = np.arange(x0 + PLACE_SPACING / 2, x1, PLACE_SPACING)
    ys = np.arange(y0 + PLACE_SPACING / 2, y1, PLACE_SPACING)
    cands: list[tuple[float, int, float, float, float]] = []
    boxes = []
    for k, theta in enumerate(PLACE_HEADINGS):
        for x in xs:
            for y in ys:
                box = object_footprint(obj, float(x), float(y), math.radians(theta))
                if not rect_inside(box, cfg.house) or rect_overlaps(box, cfg.forbidden):
                    continue
                d = math.hypot(float(x) - here[0], float(y) - here[1])
                cands.append((d, k, round(float(x), 4), round(float(y), 4), theta))
                boxes.append(box)
    clearing = env._clearing
    assert clearing is not None
    on = clearing.probe.hits(boxes)
    kept = sorted(c for c, hit in zip(cands, on, strict=True) if not hit)
    return [(x, y, theta) for _, _, x, y, theta in kept]


def _carry_stuck(env: KitchenClearingEnv) -> bool:
    """Is the carry disc of the object just picked blocked where the robot stands? (Then
    every place of it has no base path: the v1 rules allow such a pick, the solver skips
    it.)"""
    disc = env.held_disc()
    base = env.robot.base_pose(env.data)
    others = env.object_boxes(exclude=(env.task.held,))
    return bool(env.planner.colliding(disc.center(base), disc.radius, others))


def constructive_solution(
    env: KitchenClearingEnv,
) -> tuple[tuple[tuple[float, ...], ...], int] | None:
    """Clear the env's path with the fixed grids (module docstring), or None if stuck.

    Resets ``env`` and leaves it in the solved state. Returns the witness (the feasible
    actions, normalised) and the number of actions stepped (feasible or undone).
    """
    env.reset()
    plan: list[tuple[float, ...]] = []
    tries = 0
    while not env.task.done:
        if env.task.steps + 2 > env.config.horizon:
            return None
        obj = env.task.on_path[0]
        left = len(env.task.on_path)
        before_pick = env.get_state()
        picks = 0
        placed = False
        for p in PICK_GRID:
            a = _pick_action(env, p)
            ok, _ = env.precheck(a)
            if not ok:
                continue
            tries += 1
            _, _, _, _, info = env.step(a)
            if not info["feasible"] or _carry_stuck(env):
                env.set_state(before_pick)
                continue
            picks += 1
            after_pick = env.get_state()
            stepped = 0
            for x, y, theta in placement_candidates(env):
                b = _place_action(env, x, y, theta)
                ok, _ = env.precheck(b)
                if not ok:
                    continue
                tries += 1
                stepped += 1
                _, _, _, _, info = env.step(b)
                if info["feasible"] and info["objects_left"] < left and env.task.held == -1:
                    plan += [tuple(float(v) for v in a), tuple(float(v) for v in b)]
                    placed = True
                    break
                env.set_state(after_pick)
                if stepped >= PLACES_PER_PICK:
                    break
            if placed:
                break
            env.set_state(before_pick)
            if picks >= PICKS_PER_OBJECT:
                break
        if not placed:
            return None
        assert obj not in env.task.on_path
    return tuple(plan), tries
