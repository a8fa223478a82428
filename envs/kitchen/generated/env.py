"""``voot/KitchenClearing-v2``: the object-clearing task in kitchens generated from a seed.

``gym.make("voot/KitchenClearing-v2", layout_seed=s, difficulty=d)`` builds the kitchen
:func:`~voot.envs.kitchen.generated.layout.generate_kitchen_layout` draws for ``(s, d)``
(:data:`~voot.envs.kitchen.generated.layout.DIFFICULTIES`: ``"easy"``, ``"medium"``, ``"hard"``),
writes it as MJCF (:mod:`voot.envs.kitchen.generated.scene`) and plays the v1 rules in it
(:data:`~voot.envs.kitchen.config.KITCHEN_PRESETS` ``"v1"``: two-stage feasibility, the
non-clearing penalty, the pick's base path) with the layout's start, sink pose, house and
forbidden rooms. Everything else is :class:`~voot.envs.kitchen.env.KitchenClearingEnv`.

**Every instance is solvable**, proven by a planner-independent check before it is
accepted: a scripted constructive solver (:func:`constructive_solution`) clears the
obstacles one by one, in the env's handling order, through the env's own ``step``. For
each obstacle it tries a fixed grid of pick parameters (:data:`PICK_GRID`), and for each
feasible pick a fixed grid of placements off the fixed path's swept volume and outside
the forbidden rooms, nearest first (:func:`placement_candidates`), until one place
clears the obstacle; an infeasible try is undone with ``set_state``. An instance is
accepted iff every obstacle gets cleared (and the env sees exactly the obstacles the
generator drew on the path); otherwise it is rejected and the next attempt of the seed
is drawn (a derived random stream, so the outcome is deterministic), up to
:data:`MAX_ATTEMPTS`. The feasible actions found are the **witness** plan:
:meth:`GeneratedKitchenEnv.witness_actions`, normalised actions that solve the episode from
``reset()`` (a scripted solution, as :mod:`voot.envs.kitchen.scripted` is for v1).

Generated kitchens are kept per ``(layout_seed, difficulty, GENERATOR_VERSION)`` in
this process (:func:`generated_kitchen`, the last :data:`KITCHEN_CACHE_SIZE`): the
layout, its MJCF, the compiled model and the witness; an env of a kept kitchen copies the
model and costs what a v1 env costs.
"""

from __future__ import annotations

import copy
import math
import time
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import mujoco
import numpy as np
from numpy.typing import NDArray

from voot.envs.core.presets import env_config
from voot.envs.core.scene import object_footprint, rect_inside, rect_overlaps
from voot.envs.core.state import replace
from voot.envs.core.units import normalize
from voot.envs.kitchen.config import KITCHEN_PRESETS, KitchenConfig
from voot.envs.kitchen.env import KitchenClearingEnv
from voot.envs.kitchen.generated.layout import (
    GENERATOR_VERSION,
    KitchenLayout,
    LayoutError,
    difficulty_level,
    generate_kitchen_layout,
)
from voot.envs.kitchen.generated.scene import (
    compile_kitchen,
    kitchen_layout_xml,
    scene_digest,
    shape_spec,
)
from voot.envs.robot.grasp import GraspPose
from voot.envs.robot.mesh_grasp import MeshGraspSet, grasp_set, mesh_side_grasp

__all__ = [
    "KITCHEN_CACHE_SIZE",
    "MAX_ATTEMPTS",
    "PICK_GRID",
    "GeneratedKitchen",
    "GeneratedKitchenEnv",
    "clear_kitchen_cache",
    "constructive_solution",
    "generated_kitchen",
    "placement_candidates",
]

FloatArray = NDArray[np.float64]

#: Attempts of a seed before generation gives up (hard kitchens need about 10 on average,
#: most of them cheap layout draws that leave no room for an obstacle: see the docs).
MAX_ATTEMPTS = 60
#: The config fields a layout sets (an option naming one is an error).
LAYOUT_FIELDS = ("start", "goal", "house", "forbidden")
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


@dataclass(frozen=True, eq=False)
class GeneratedKitchen:
    """An accepted generated kitchen (see the module docstring).

    Attributes:
        layout: The floor plan.
        xml: Its MJCF.
        digest: SHA-256 of :attr:`xml`.
        model: The compiled model (an env loads a copy).
        witness: Normalised actions that clear every obstacle from ``reset()``.
        rejections: ``(attempt, reason)`` of each rejected attempt before this one.
        seconds: Wall time the generation took (attempts, checks and all).
        tries: Actions the constructive solver stepped for the accepted attempt.
    """

    layout: KitchenLayout
    xml: str
    digest: str
    model: mujoco.MjModel
    witness: tuple[tuple[float, ...], ...]
    rejections: tuple[tuple[int, str], ...]
    seconds: float
    tries: int


#: Generated kitchens kept per process (the least recently used one is forgotten past
#: this: a kitchen holds its compiled model, about 3 MB).
KITCHEN_CACHE_SIZE = 64
_KITCHENS: OrderedDict[tuple[int, str, int], GeneratedKitchen] = OrderedDict()


def clear_kitchen_cache() -> None:
    """Forget the generated kitchens kept in this process."""
    _KITCHENS.clear()


def generated_kitchen(layout_seed: int, difficulty: str) -> GeneratedKitchen:
    """The accepted kitchen of ``(layout_seed, difficulty)``, generated once per process.

    Draws attempts 0, 1, ... (:func:`generate_kitchen_layout`) until one passes the
    solvability check (:func:`constructive_solution`).

    Raises:
        ValueError: a bad seed or level.
        RuntimeError: no attempt of :data:`MAX_ATTEMPTS` passed.
    """
    difficulty_level(difficulty)
    key = (int(layout_seed), difficulty, GENERATOR_VERSION)
    hit = _KITCHENS.get(key)
    if hit is not None:
        _KITCHENS.move_to_end(key)
        return hit
    t0 = time.perf_counter()
    rejections: list[tuple[int, str]] = []
    for attempt in range(MAX_ATTEMPTS):
        try:
            layout = generate_kitchen_layout(layout_seed, difficulty, attempt)
        except LayoutError as exc:
            rejections.append((attempt, f"layout: {exc}"))
            continue
        xml = kitchen_layout_xml(layout)
        model = compile_kitchen(xml, layout)
        candidate = GeneratedKitchen(
            layout, xml, scene_digest(xml), model, (), tuple(rejections), 0.0, 0
        )
        try:
            env = GeneratedKitchenEnv(_kitchen=candidate)
        except ValueError as exc:
            rejections.append((attempt, f"env: {exc}"))
            continue
        if env.initial_obstacles != layout.n_on_path:
            rejections.append(
                (attempt, f"{env.initial_obstacles} obstacles on the path, drew {layout.n_on_path}")
            )
            continue
        solution = constructive_solution(env)
        env.close()
        if solution is None:
            rejections.append((attempt, "the constructive solver left an obstacle"))
            continue
        witness, tries = solution
        kitchen = replace(
            candidate,
            witness=witness,
            rejections=tuple(rejections),
            seconds=time.perf_counter() - t0,
            tries=tries,
        )
        _KITCHENS[key] = kitchen
        while len(_KITCHENS) > KITCHEN_CACHE_SIZE:
            _KITCHENS.popitem(last=False)
        return kitchen
    raise RuntimeError(
        f"no solvable kitchen for layout_seed={layout_seed}, difficulty={difficulty!r} in"
        f" {MAX_ATTEMPTS} attempts: {rejections}"
    )


class GeneratedKitchenEnv(KitchenClearingEnv):
    """The kitchen of ``(layout_seed, difficulty)`` under the v1 rules (module docstring).

    Args:
        layout_seed: The layout's seed (an int >= 0).
        difficulty: The level (:data:`~voot.envs.kitchen.generated.layout.DIFFICULTIES`).
        config: Settings; default: the v1 preset's. Its start, goal, house and forbidden
            rooms are replaced by the layout's.
        render_mode: None or ``"rgb_array"``.
        render_camera: ``"perspective"`` or ``"top_down"``.
        render_size: ``(width, height)`` of rendered images.
        **options: :class:`KitchenConfig` fields overriding the config's, except the
            layout's (``start``, ``goal``, ``house``, ``forbidden``). The witness and the
            solvability check hold for the v1 rules.
    """

    def __init__(
        self,
        layout_seed: int = 0,
        difficulty: str = "easy",
        config: KitchenConfig | None = None,
        render_mode: str | None = None,
        render_camera: str = "perspective",
        render_size: tuple[int, int] = (640, 480),
        _kitchen: GeneratedKitchen | None = None,
        **options: Any,
    ) -> None:
        bad = sorted(set(options) & set(LAYOUT_FIELDS))
        if bad:
            raise ValueError(
                f"{', '.join(bad)} come from the generated layout; choose the kitchen with"
                " layout_seed and difficulty instead"
            )
        kitchen = _kitchen if _kitchen is not None else generated_kitchen(layout_seed, difficulty)
        layout = kitchen.layout
        base = env_config(KitchenConfig, KITCHEN_PRESETS, config, "v1", options)
        cfg = replace(
            base,
            start=layout.start,
            goal=layout.goal,
            house=layout.house,
            forbidden=layout.forbidden,
        )
        self.kitchen = kitchen
        #: The objects' grasp tables (from their meshes), in object order.
        self._grasp_sets: tuple[MeshGraspSet, ...] = tuple(
            grasp_set(shape_spec(o)) for o in layout.objects
        )
        super().__init__(
            config=cfg,
            render_mode=render_mode,
            render_camera=render_camera,
            render_size=render_size,
        )

    @property
    def layout(self) -> KitchenLayout:
        """The generated floor plan."""
        return self.kitchen.layout

    def solution_actions(self) -> list[FloatArray]:
        """The witness (:meth:`witness_actions`): the known solution of a generated instance."""
        return self.witness_actions()

    def witness_actions(self) -> list[FloatArray]:
        """The constructive solver's plan: normalised actions that clear the path from
        ``reset()`` (proof of solvability; a scripted solution for tests). Named as the
        generated storage rooms' (:mod:`voot.bench.protocol.difficulty` reads either)."""
        return [np.array(a, dtype=np.float64) for a in self.kitchen.witness]

    def _grasp_pose(
        self, obj: int, pose: FloatArray, base_heading: float, params: FloatArray
    ) -> tuple[GraspPose | None, str]:
        """The grasp on the object's mesh (:func:`~voot.envs.robot.mesh_grasp.mesh_side_grasp`):
        the side grasp's parameters with the tool point on the real surface, or None and
        ``"grasp misses the object"`` where the ray passes beside it (a jug's handle side,
        a bottle's neck)."""
        return mesh_side_grasp(
            self._grasp_sets[obj],
            pose,
            base_heading,
            params[0],
            params[1],
            params[2],
            self.config.grasp_standoff,
        )

    def _scene_model(self) -> str | mujoco.MjModel:
        """A copy of the generated kitchen's compiled model (the env may change its
        collision filters)."""
        return copy.copy(self.kitchen.model)


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
