"""The shared env base: scene, robot, checks, action validation, snapshots, rendering.

:class:`ManipulationEnv` is a :class:`gymnasium.Env` over one MuJoCo scene with the
mobile manipulator. It is a *kinematic task planner*: actions teleport the robot and
the objects to feasible configurations (an object being carried moves rigidly with the
gripper); MuJoCo is used for its kinematics, collision detection and rendering, never to
integrate dynamics (no ``mj_step``). The kitchen (:mod:`voot.envs.kitchen.env`) and the
conveyor (:mod:`voot.envs.conveyor.env`) subclass it with their task.

Actions are vectors in normalised units ``[-1, 1]^d`` mapped affinely to the paper's
parameter ranges (:func:`voot.envs.core.units.denormalize`). Out-of-range entries are
clipped to ``[-1, 1]`` (``info["action_clipped"]`` says so); a NaN or infinite entry, or
a wrong shape, raises :class:`ValueError`.

Every step's ``info`` carries the poses a recording draws (:mod:`voot.record.samples`):
``base_pose``, the robot base ``(x, y, theta)`` of the action, and ``placement``, the
placed object's ``(x, y, theta)`` (None for a pick). They are filled in for infeasible
actions too, since both follow from the state and the action alone.

Snapshots (:meth:`ManipulationEnv.get_state` / :meth:`~ManipulationEnv.set_state`) are
immutable :class:`~voot.envs.core.state.EnvState` values holding the physics
(``mujoco.mj_getState`` with the ``mjSTATE_INTEGRATION`` signature, recorded in the
snapshot), the task's progress (an immutable dataclass of the subclass, including the held
object and its grasp) and the state of the env's random generator. Restoring a snapshot and applying the same action
gives bit-identical observation, reward and info, also in another process: every check
(IK, collision, base planning) is a deterministic function of the state and the action.
No step draws from the env's generator, so consecutive snapshots share one copy of its
state (a plain dict that nobody may mutate) instead of deep-copying it every time.

:meth:`ManipulationEnv.transition` is the step without its observation: reward,
terminated, truncated and info, bit-identical to :meth:`~ManipulationEnv.step`'s. A
planner's feasibility checks (:class:`voot.envs.core.problem.EnvProblem`) never read the
observation, and building it (every object's pose) cost about a tenth of a check.

What the class is made of lives beside it, one concept a module: the snapshot and
task-record types with their checks (:mod:`voot.envs.core.state`), the action units
(:mod:`voot.envs.core.units`), the named versions of a config (:mod:`voot.envs.core.presets`)
and the rendering helpers (:mod:`voot.envs.core.rendering`).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping, Sequence
from typing import Any, ClassVar, Generic

import gymnasium as gym
import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot import validation as V
from voot.envs.core.arguments import check_render
from voot.envs.core.metrics import Distance
from voot.envs.core.names import Operator
from voot.envs.core.rendering import CAMERAS, RENDER_MODES, new_renderer
from voot.envs.core.scene import (
    load_model,
    model_digest,
    movable_objects,
    object_footprint,
    object_pose,
    static_footprints,
)
from voot.envs.core.state import EnvState, SceneIdentity, StepTiming, TaskT
from voot.envs.motion.planner import BasePlanner, BasePlannerConfig, Box2D
from voot.envs.robot.arm_ik import ArmIK, IKConfig
from voot.envs.robot.collision import CollisionChecker
from voot.envs.robot.model import TUCK, Robot
from voot.optim.base import Bounds

FloatArray = NDArray[np.float64]


#: The largest magnitude a snapshot's physics entry may have (metres, radians, their
#: rates, seconds): a state beyond it is no state a step reaches (the scenes span tens of
#: metres), and squaring 1e300 overflows in the next step's checks. ``set_state`` refuses it.
MAX_PHYSICS = 1e6


class ManipulationEnv(gym.Env[FloatArray, FloatArray], Generic[TaskT]):
    """Base of the benchmark environments (see the module docstring).

    Subclasses set :attr:`scene`, build their task in ``__init__`` after calling
    ``super().__init__``, and implement :meth:`_initial_task`, :meth:`_step_task`,
    :meth:`_observation` and :meth:`_info_reset`.

    Args:
        scene: Scene name in ``voot.models``, or a compiled model (a generated scene,
            such as a procedural layout's).
        workspace: The region the robot's base disc must stay in (planner workspace).
        ik: IK settings.
        planner: Base planner settings.
        render_mode: None or ``"rgb_array"``.
        render_camera: ``"perspective"`` or ``"top_down"``.
        render_size: ``(width, height)`` of rendered images.
    """

    metadata: dict[str, Any] = {"render_modes": list(RENDER_MODES), "render_fps": 2}  # noqa: RUF012
    #: The subclass's settings (a frozen dataclass with ``precheck`` and ``infeasible_reward``).
    config: Any
    #: The envs' contract that :class:`voot.envs.core.problem.EnvProblem` relies on to undo
    #: a rejected check cheaply: an infeasible action changes nothing but the task
    #: record (its step count); the physics and the generator are untouched (the envs
    #: move the robot and objects only once every check has passed). A subclass that
    #: breaks it must set this to False.
    INFEASIBLE_CHANGES_TASK_ONLY: ClassVar[bool] = True
    #: The family of the env (its problem records' ``family``, :mod:`voot.problems`).
    family: ClassVar[str] = ""
    #: Signature of the physics part of snapshots.
    STATE_SIGNATURE: ClassVar[int] = int(mujoco.mjtState.mjSTATE_INTEGRATION)

    def __init__(
        self,
        scene: str | mujoco.MjModel,
        workspace: tuple[float, float, float, float],
        ik: IKConfig,
        planner: BasePlannerConfig,
        render_mode: str | None = None,
        render_camera: str = "perspective",
        render_size: tuple[int, int] = (640, 480),
    ) -> None:
        render_mode, render_camera, (w, h) = check_render(render_mode, render_camera, render_size)
        self.render_mode = render_mode
        self.render_camera = render_camera
        self.render_size = (w, h)
        self.model = scene if isinstance(scene, mujoco.MjModel) else load_model(scene)
        self.data = mujoco.MjData(self.model)
        self.robot = Robot(self.model)
        self.objects = movable_objects(self.model)
        self.object_index = {o.name: i for i, o in enumerate(self.objects)}
        self.collision = CollisionChecker(self.model, self.robot, self.objects)
        self.ik = ArmIK(ik)
        self.static_boxes = static_footprints(self.model)
        self.workspace = workspace
        self.planner = BasePlanner(workspace, self.static_boxes, planner)
        self._state_size = int(mujoco.mj_stateSize(self.model, self.STATE_SIGNATURE))
        self._renderer: mujoco.Renderer | None = None
        self._box_cache: dict[int, tuple[bytes, Box2D]] = {}
        self._boxes_cache: dict[tuple[tuple[int, ...], bytes], tuple[Box2D, ...]] = {}
        # the generator state of the last snapshot, shared by the snapshots after it while
        # it does not change (see _rng_snapshot)
        self._rng_shared: Mapping[str, Any] | None = None
        # task records set_state has found possible, by id (records are immutable, and a
        # search restores each snapshot many times): _task_error runs once per record
        self._checked_tasks: dict[int, Any] = {}
        self.last_timing = StepTiming()
        self.task: TaskT = self._initial_task()
        #: The class of this env's task record: what a snapshot's ``task`` must be.
        self._task_type: type = type(self.task)
        #: What this env's snapshots belong to: ``set_state`` takes no other's.
        self.scene_identity: SceneIdentity = self._scene_identity()

    def __getstate__(self) -> dict[str, Any]:
        """The env for :mod:`pickle` and :func:`copy.deepcopy`: a copy steps as the env.

        From the same snapshot, a copy (in this process or unpickled in another) gives
        bit-identical observations, rewards and infos. Left out: the renderer (an OpenGL
        context, which neither pickles nor copies; the copy opens its own when it first
        renders) and the memo of checked task records (it only saves time). The
        collision checker re-aliases its buffer views itself
        (:meth:`voot.envs.robot.collision.CollisionChecker.__getstate__`).
        """
        state = self.__dict__.copy()
        state["_renderer"] = None
        state["_checked_tasks"] = {}
        return state

    # ----- to implement --------------------------------------------------------------------
    def _scene_identity(self) -> SceneIdentity:
        """The identity of this env's scene (a generated family adds its layout)."""
        return SceneIdentity(
            family=self.family or type(self).__name__,
            version="",
            layout_seed=None,
            difficulty=None,
            digest=model_digest(self.model),
        )

    def _initial_task(self) -> TaskT:
        raise NotImplementedError

    def _reset_physics(self) -> None:
        raise NotImplementedError

    def _observation(self) -> FloatArray:
        raise NotImplementedError

    def _info_reset(self) -> dict[str, Any]:
        raise NotImplementedError

    def _task_error(self, task: TaskT) -> str | None:
        """What makes ``task`` (a record of this env's class) impossible here, or None.

        :meth:`set_state` asks before it changes anything: a record no episode of this
        env can reach (an unknown operator, an object index out of range, a count past
        its bounds) would otherwise fail deep inside the next step, or index the wrong
        object silently (Python takes ``objects[-3]``). Subclasses check every field a
        step or an observation reads; the base class accepts any record.
        """
        return None

    def action_bounds(self) -> Bounds:
        """The current operator's action box in normalised units (planner's view)."""
        raise NotImplementedError

    def precheck(self, action: ArrayLike) -> tuple[bool, dict[str, Any]]:
        """The cheap kinematic check of ``action`` now, changing nothing (see subclasses)."""
        raise NotImplementedError

    def current_operator(self) -> Operator:
        """The operator of the current node: what the next action does (pick or place)."""
        raise NotImplementedError

    def operator_ranges(self, operator: Operator) -> Sequence[tuple[float, float]]:
        """The ranges of a planner's action parameters at an ``operator`` node, in action
        order: the paper's units of each normalised entry (the env action's first
        entries; a shorter action is padded with zeros)."""
        raise NotImplementedError

    def operator_distance(self, operator: Operator) -> Distance:
        """The authors' distance between two actions of ``operator`` in the paper's units
        (:mod:`voot.envs.core.metrics`; VOO's cells with ``use_problem_metric``)."""
        raise NotImplementedError

    def node_label(self, operator: Operator) -> str:
        """How reports name a node of ``operator`` (``"pick"``; the conveyor says how many
        boxes an action places)."""
        return str(operator)

    def solution_actions(self) -> list[FloatArray]:
        """A known solution from the start, as normalised actions: the scripted one of a
        fixed scene, or the witness a generated instance was proven solvable with."""
        raise NotImplementedError

    def planning_problem(self, env: Any = None) -> Any:
        """This env as a :mod:`voot.tree` planning problem (:class:`~voot.envs.core.problem.EnvProblem`).

        ``env`` is the env as made (``gym.make`` wrappers included); default: this one.
        """
        from voot.envs.core.problem import EnvProblem

        return EnvProblem(self if env is None else env)

    def certainly_infeasible(self, action: ArrayLike) -> bool:
        """Would :meth:`transition` certainly find ``action`` infeasible now? Changes nothing.

        An exact pre-screen for a pre-check that runs the whole step (v0's
        ``"full_step"``): True only if the step's ``info["feasible"]`` would be False;
        False when that is not settled cheaply (the step must run), when the action needs
        clipping or is malformed, or when the episode has ended (the step would raise).
        The step's conditions are a conjunction of pure functions of the state and the
        action, so any one of them that fails settles the answer whatever the step's
        order: a subclass tests the cheap ones (and those that spare the costly ones)
        first and builds no info, reason or next state. The base class settles nothing.
        """
        return False

    def certainly_infeasible_values(self, values: list[float]) -> bool:
        """:meth:`certainly_infeasible` of the action with entries ``values``.

        ``values`` is a full-length action as Python floats, every entry in ``[-1, 1]``
        (the caller checked: no clipping needed); subclasses answer from the floats
        without the array. The base class builds the array.
        """
        return self.certainly_infeasible(np.array(values, dtype=np.float64))

    def _plain_action(self, action: ArrayLike) -> FloatArray | None:
        """``action`` as :meth:`_validate_action` returns it when no clipping is needed.

        None for anything else (wrong shape, entries outside ``[-1, 1]``, NaN): the
        caller leaves those to the step, which clips or raises.
        """
        if type(action) is not np.ndarray or action.dtype != np.float64:
            return None
        if action.shape != self.action_space.shape:
            return None
        values = action.tolist()
        if min(values) >= -1.0 and max(values) <= 1.0 and math.isfinite(sum(values)):
            return action
        return None

    def transition(self, action: ArrayLike) -> tuple[float, bool, bool, dict[str, Any]]:
        """:meth:`step` without the observation: ``(reward, terminated, truncated, info)``.

        The state changes exactly as by :meth:`step`; the observation of the new state is
        ``self._observation()`` whenever it is wanted.
        """
        raise NotImplementedError

    def step(self, action: ArrayLike) -> tuple[FloatArray, float, bool, bool, dict[str, Any]]:
        """Gymnasium's step: :meth:`transition`, then the observation of the new state."""
        reward, terminated, truncated, info = self.transition(action)
        return self._observation(), reward, terminated, truncated, info

    # ----- actions -------------------------------------------------------------------------
    @property
    def action_dim(self) -> int:
        """Length of the action vector."""
        shape = self.action_space.shape
        assert shape is not None
        return int(shape[0])

    def _validate_action(self, action: ArrayLike) -> tuple[FloatArray, bool]:
        """The action as float64 clipped to the space, and whether clipping happened."""
        space = self.action_space
        assert isinstance(space, gym.spaces.Box)
        a = V.real_array(action, f"action (shape {space.shape}, normalised units in [-1, 1])")
        if a.shape != space.shape:
            raise ValueError(
                f"action must have shape {space.shape} (normalised units in [-1, 1]), got shape {a.shape}"
            )
        # fast path: every entry finite (a NaN or infinity makes the sum non-finite) and in
        # [-1, 1], so clipping would return the same numbers
        values = a.tolist()
        if min(values) >= -1.0 and max(values) <= 1.0 and math.isfinite(sum(values)):
            return a.copy(), False
        if not np.all(np.isfinite(a)):
            bad = np.flatnonzero(~np.isfinite(a)).tolist()
            raise ValueError(f"action has NaN or infinite entries at indices {bad}: {a.tolist()}")
        clipped = np.clip(a, -1.0, 1.0)
        return clipped, bool(np.any(clipped != a))

    # ----- objects -------------------------------------------------------------------------
    def object_pose(self, i: int) -> FloatArray:
        """``(x, y, z, yaw)`` of object ``i`` in the current state."""
        return object_pose(self.data, self.objects[i])

    def object_box(self, i: int) -> Box2D:
        """Footprint of object ``i`` in the current state.

        Cached per object and keyed by its 7 free-joint numbers, so the (immutable)
        footprint of an object that has not moved is reused: it is a pure function of
        them, and reusing it keeps the base planner's graph cache warm.
        """
        obj = self.objects[i]
        key = self.data.qpos[obj.qpos_adr : obj.qpos_adr + 7].tobytes()
        hit = self._box_cache.get(i)
        if hit is not None and hit[0] == key:
            return hit[1]
        x, y, _, yaw = self.object_pose(i)
        box = object_footprint(obj, float(x), float(y), float(yaw))
        self._box_cache[i] = (key, box)
        return box

    def object_boxes(self, exclude: Sequence[int] = ()) -> list[Box2D]:
        """Footprints of all objects but ``exclude``, in object order (a new list).

        The last few answers are remembered by ``exclude`` and the ``qpos`` bytes (the
        footprints are a function of the objects' free joints), so the checks of one
        state ask :meth:`object_box` once per object.
        """
        key = (tuple(exclude), self.data.qpos.tobytes())
        hit = self._boxes_cache.get(key)
        if hit is None:
            hit = tuple(self.object_box(i) for i in range(len(self.objects)) if i not in exclude)
            if len(self._boxes_cache) >= 8:
                self._boxes_cache.clear()
            self._boxes_cache[key] = hit
        return list(hit)

    # ----- snapshots -----------------------------------------------------------------------
    def get_state(self) -> EnvState[TaskT]:
        """An immutable snapshot: physics, task progress, RNG (see the module docstring)."""
        physics = np.empty(self._state_size)
        mujoco.mj_getState(self.model, self.data, physics, self.STATE_SIGNATURE)
        physics.setflags(write=False)
        return EnvState(
            physics, self.STATE_SIGNATURE, self.task, self._rng_snapshot(), self.scene_identity
        )

    def _rng_snapshot(self) -> Mapping[str, Any]:
        """The generator's state for a snapshot, shared with the last one if unchanged.

        ``bit_generator.state`` builds a fresh dict on every read; for the PCG64 family
        (gymnasium's default) it holds only strings and ints, so equality is cheap and
        exact, and one dict can stand for every snapshot taken while nobody draws from the
        generator (no step does). Other bit generators (whose states hold arrays) get a
        deep copy per snapshot, as before.
        """
        bg = self.np_random.bit_generator
        state = bg.state
        if not isinstance(bg, np.random.PCG64 | np.random.PCG64DXSM):
            return copy.deepcopy(state)
        shared = self._rng_shared
        if shared is not None and shared == state:
            return shared
        self._rng_shared = state
        return state

    def set_state(self, state: EnvState[TaskT]) -> None:
        """Return to the snapshot ``state`` exactly, or raise and change nothing.

        The whole snapshot is checked before anything is applied: an :class:`EnvState`
        of this env's scene (its :class:`~voot.envs.core.state.SceneIdentity` equal to
        :attr:`scene_identity`: the same family, version, layout, level and compiled
        scene; a state of another layout with as many objects is refused, the message
        naming both), physics of this env's signature and size, all finite and within
        :data:`MAX_PHYSICS` (a NaN would otherwise surface deep in the base planner, or
        as a NaN observation; a 1e300 overflows the next step), a task record of this
        env's class (not None, not the other environment's) whose contents this env can
        reach (:meth:`_task_error`: a known operator, object indices in range; checked
        once per record, which is immutable), and a generator state that this env's bit
        generator takes. The generator is set first, since only numpy can refuse a state
        (it reads a whole state before it sets one); the physics and the task, already
        checked, follow and cannot fail. A bad snapshot is a ValueError naming the field
        and leaves the env as it was. The checks cost about two microseconds (the search
        restores a snapshot at every new action).
        """
        if not isinstance(state, EnvState):
            raise ValueError(
                f"state must be an EnvState from get_state(), got {type(state).__name__}"
            )
        scene = state.scene
        if scene is not self.scene_identity and scene != self.scene_identity:
            raise ValueError(
                "state belongs to another scene: it was made by"
                f" {scene or 'no env (it carries no scene identity)'}, this env is"
                f" {self.scene_identity}; the env is unchanged"
            )
        physics = state.physics
        if (
            type(physics) is not np.ndarray
            or physics.dtype != np.float64
            or state.signature != self.STATE_SIGNATURE
            or physics.shape != (self._state_size,)
        ):
            size = getattr(physics, "size", None)
            raise ValueError(
                f"state does not fit this environment: signature {state.signature} and "
                f"{size} numbers ({type(physics).__name__}), expected signature"
                f" {self.STATE_SIGNATURE} and {self._state_size} numbers (a float64 array)"
            )
        within = np.abs(physics) <= MAX_PHYSICS  # False for NaN too
        if not within.all():
            bad = np.flatnonzero(~within)
            raise ValueError(
                f"state.physics must be finite and within +-{MAX_PHYSICS:g}, got"
                f" {float(physics[bad[0]])!r} at {bad.size} of its {physics.size} entries"
                f" (first: index {int(bad[0])}); the env is unchanged"
            )
        if type(state.task) is not self._task_type:
            raise ValueError(
                f"state.task must be a {self._task_type.__name__} (this environment's task"
                f" record), got {type(state.task).__name__}"
            )
        task = state.task
        checked = self._checked_tasks
        if checked.get(id(task)) is not task:
            problem = self._task_error(task)
            if problem is not None:
                raise ValueError(
                    f"state.task is not a {self._task_type.__name__} this environment can"
                    f" reach: {problem}; the env is unchanged"
                )
            if len(checked) >= 4096:
                checked.clear()
            checked[id(task)] = task  # held, so that its id is not reused while it is here
        bg = self.np_random.bit_generator
        shared = isinstance(bg, np.random.PCG64 | np.random.PCG64DXSM)
        try:
            rng_state = dict(state.rng_state) if shared else copy.deepcopy(dict(state.rng_state))
            bg.state = rng_state  # type: ignore[assignment]  # read, not kept
        except (TypeError, ValueError, KeyError, OverflowError) as exc:
            raise ValueError(
                f"state.rng_state is not a state of this env's {type(bg).__name__} generator"
                f" ({type(exc).__name__}: {exc}); the env is unchanged"
            ) from None
        if shared:
            self._rng_shared = state.rng_state
        mujoco.mj_setState(self.model, self.data, physics, self.STATE_SIGNATURE)
        self.task = task

    # ----- gymnasium API -------------------------------------------------------------------
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[FloatArray, dict[str, Any]]:
        """Back to the scene's initial configuration (deterministic; ``seed`` seeds np_random).

        ``seed`` is None or an integer >= 0 (numpy's integers too; not a bool); the fixed
        envs take no ``options`` (None or an empty mapping; the generated families take a
        layout, :class:`voot.envs.core.family.LayoutFamily`). Both are checked before
        anything changes: a refused call leaves the generator, physics and task as they
        were.
        """
        if options is not None and (not isinstance(options, Mapping) or options):
            shown = list(options) if isinstance(options, Mapping) else repr(options)
            raise ValueError(f"reset takes no options (None or {{}}), got {shown}")
        seed = V.optional_integer(seed, "seed", low=0)
        super().reset(seed=seed)
        self._reset_physics()
        self.task = self._initial_task()
        return self._observation(), self._info_reset()

    def _set_robot(self, base: ArrayLike, arm: ArrayLike | None = None) -> None:
        self.robot.set_base(self.data, base)
        self.robot.set_arm(self.data, TUCK if arm is None else arm)

    def render(self) -> NDArray[np.uint8] | None:  # type: ignore[override]
        """An RGB image ``(height, width, 3)`` from :attr:`render_camera` (rgb_array mode)."""
        if self.render_mode is None:
            gym.logger.warn("render() called without render_mode; pass render_mode='rgb_array'")
            return None
        return self.render_image(self.render_camera)

    def render_image(self, camera: str, size: tuple[int, int] | None = None) -> NDArray[np.uint8]:
        """Render the current state from ``camera`` (``perspective`` or ``top_down``)."""
        if camera not in CAMERAS:
            raise ValueError(f"camera must be one of {', '.join(CAMERAS)}; got {camera!r}")
        w, h = size if size is not None else self.render_size
        if self._renderer is None or (self._renderer.width, self._renderer.height) != (w, h):
            if self._renderer is not None:
                self._renderer.close()
            self._renderer = new_renderer(self.model, height=h, width=w)
        mujoco.mj_kinematics(self.model, self.data)
        mujoco.mj_camlight(self.model, self.data)  # cameras follow the kinematics
        self._renderer.update_scene(self.data, camera=camera)
        self._decorate(self._renderer.scene)
        img: NDArray[np.uint8] = self._renderer.render().copy()
        return img

    def _decorate(self, scene: mujoco.MjvScene) -> None:
        """Hook: add visual-only markers (paths, regions) to a render."""

    def close(self) -> None:
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
