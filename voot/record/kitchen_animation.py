r"""A kitchen plan as frames: the robot driving, reaching and carrying between the states
the environment teleports to (the GIF of ``voot-bench demo``).

The frames are MuJoCo's off-screen renders of the env's visual geoms (groups 0-2), so a
generated kitchen's mesh objects (``voot/KitchenClearing-v2``) show as their visual
meshes, not as their hidden convex collision parts (group 3); the camera is fitted to a
generated house (:func:`kitchen_view`).

It reads the kitchen's task record (the held object and its grasp) and plans the drives
it shows with the env's base planner: an animation of this one environment, kept apart
from the demo application that uses it (:mod:`voot.bench.demos.kitchen_demo`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.tree.step_info import StepInfo

#: Free camera of the GIF: the kitchen and the hall seen from the west (the sink on the
#: left, the start on the right), the house's big rooms behind them.
KITCHEN_VIEW: dict[str, Any] = {
    "lookat": (0.6, -0.4, 0.0),
    "distance": 8.7,
    "azimuth": 0.0,
    "elevation": -60.0,
}

#: Distance of :func:`kitchen_view`'s eye from a generated house's centre, in multiples
#: of the house's longer side (the whole house fits a 4:3 frame at 60 degrees down).
GENERATED_VIEW_DISTANCE = 1.25

Frame = NDArray[np.uint8]


def kitchen_view(env: Any) -> dict[str, Any]:
    r"""The GIF's free camera for the kitchen ``env``.

    The paper's kitchen (v0, v1) gets :data:`KITCHEN_VIEW`. A generated kitchen
    (``voot/KitchenClearing-v2``, whose env carries its ``layout``) has its own size and
    room layout, so the camera is fitted to its house
    :math:`[x_0, x_1] \times [y_0, y_1]`: it looks at the house's centre from the west
    (azimuth 0, as :data:`KITCHEN_VIEW`, 60 degrees down) at
    :data:`GENERATED_VIEW_DISTANCE` :math:`\cdot \max(x_1 - x_0, y_1 - y_0)`.
    """
    layout = getattr(env, "layout", None)  # a generated kitchen's floor plan
    if layout is None:
        return dict(KITCHEN_VIEW)
    x0, x1, y0, y1 = (float(v) for v in layout.house)
    return {
        "lookat": (0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0),
        "distance": GENERATED_VIEW_DISTANCE * max(x1 - x0, y1 - y0),
        "azimuth": 0.0,
        "elevation": -60.0,
    }


def _resample(poses: NDArray[np.float64], spacing: float, max_frames: int) -> list[Any]:
    """Poses ``(k, 3)`` at about ``spacing`` metres along the polyline (at most ``max_frames``)."""
    p = np.asarray(poses, dtype=np.float64).reshape(-1, 3)
    if len(p) < 2:
        return [p[-1]] if len(p) else []
    seg = np.hypot(*np.diff(p[:, :2], axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n = int(min(max(math.ceil(s[-1] / spacing), 1), max_frames))
    targets = np.linspace(0.0, s[-1], n + 1)[1:]
    theta = np.unwrap(p[:, 2])
    out = np.column_stack(
        [
            np.interp(targets, s, p[:, 0]),
            np.interp(targets, s, p[:, 1]),
            np.interp(targets, s, theta),
        ]
    )
    return list(out)


def _drive(env: Any, start: Any, goal: Any) -> NDArray[np.float64]:
    """Waypoints ``(k, 3)`` of the robot's drive (arm tucked) from ``start`` to ``goal``.

    Shown only, not stepped: the environment plans no path before a pick. The robot's
    disc is planned among the objects but those it overlaps at either end (the one it
    just put down, the one it is about to grasp); a straight line if there is no path.
    """
    r = env.config.robot_radius
    boxes = env.object_boxes()
    touching = set(env.planner.colliding(start, r, boxes)) | set(
        env.planner.colliding(goal, r, boxes)
    )
    path = env.planner.plan(start, goal, r, [b for b in boxes if b.name not in touching])
    if path is None:
        return np.stack([np.asarray(start, dtype=np.float64), np.asarray(goal, dtype=np.float64)])
    return np.asarray(path.waypoints, dtype=np.float64)


def plan_animation(
    problem: Any,
    actions: Sequence[Any],
    *,
    size: tuple[int, int] = (320, 240),
    view: dict[str, Any] | None = None,
    label: str = "",
    spacing: float = 0.35,
    max_motion_frames: int = 10,
    arm_frames: int = 3,
    progress: Callable[[int, int], None] | None = None,
) -> list[Frame]:
    """Frames of a kitchen plan, stepped from the problem's current state.

    Between the states the environment teleports to, the robot is animated: before a
    pick it drives (arm tucked) along a base path to the pick pose (planned for the
    robot's disc among the objects; a straight line if there is none) and reaches;
    at a place it drives along the base path the environment planned, carrying the
    object rigidly, then tucks its arm. Infeasible actions change nothing and add no
    frame. If the plan clears the path, the robot finally drives to the sink. Each
    frame is captioned with ``label``, the step and the obstacles left. The problem is
    left at the end of the plan.

    Args:
        problem: an :class:`~voot.envs.core.problem.EnvProblem` over the kitchen.
        actions: the plan (planner actions, as in :attr:`PlanResult.actions`).
        size: ``(width, height)`` in pixels.
        view: the free camera (``lookat``, ``distance``, ``azimuth``, ``elevation``);
            default :func:`kitchen_view` (:data:`KITCHEN_VIEW` on the paper's kitchen,
            fitted to the house on a generated one).
        label: caption prefix.
        spacing: metres of base motion between frames.
        max_motion_frames: at most this many frames per base motion.
        arm_frames: frames of each arm motion.
        progress: called as ``progress(k, n)`` when ``k`` of the plan's ``n`` actions
            have their frames (from 0 to ``n``; rendering takes seconds).
    """
    from voot.envs.core.names import Operator
    from voot.envs.core.scene import set_object_pose
    from voot.envs.kitchen.problems import FAMILY
    from voot.envs.robot.model import TUCK, compose2d

    env = problem.unwrapped
    if getattr(env, "family", None) != FAMILY:
        raise ValueError(f"plan_animation needs the kitchen, got {type(env).__name__}")
    render = _KitchenRenderer(env, size, view if view is not None else kitchen_view(env))
    data, robot = env.data, env.robot
    n = len(actions)

    def caption(text: str) -> Callable[[], Frame]:
        return lambda: render.frame(f"{label}\n{text}" if label else text)

    try:
        left = len(env.task.on_path)
        frames = [caption(f"start: {left} obstacles on the path to the sink")()]
        for t, a in enumerate(actions, start=1):
            if progress is not None:
                progress(t - 1, n)
            before = env.get_state()
            task = env.task
            base0 = robot.base_pose(data)
            res = problem.step(np.asarray(a, dtype=np.float64))
            info = StepInfo.of(res.info)
            if not res.feasible:
                continue
            after = env.get_state()
            obj_name = str(info.object).removeprefix("obj_")
            text = caption(f"step {t}/{n}: {info.operator} {obj_name}, {info.objects_left} left")
            env.set_state(before)
            if info.operator == Operator.PICK:
                goal = np.asarray(info.base_pose)
                for w in _resample(_drive(env, base0, goal), spacing, max_motion_frames):
                    robot.set_base(data, w)
                    frames.append(text())
                robot.set_base(data, goal)
                grasp = np.array(after.task.grasp_q)
                for k in range(1, arm_frames + 1):
                    robot.set_arm(data, TUCK + (grasp - TUCK) * k / arm_frames)
                    frames.append(text())
            else:
                obj = env.objects[task.held]
                z = float(env.object_pose(task.held)[2])
                for w in _resample(info.base_path, spacing, max_motion_frames):
                    robot.set_base(data, w)
                    x, y, yaw = compose2d(w, task.held_rel)
                    set_object_pose(data, obj, (x, y, z, yaw))
                    frames.append(text())
                env.set_state(after)
                grasp = np.array(task.grasp_q)
                for k in range(arm_frames - 1, 0, -1):
                    robot.set_arm(data, TUCK + (grasp - TUCK) * k / arm_frames)
                    frames.append(text())
            env.set_state(after)
            frames.append(text())
        if progress is not None:
            progress(n, n)
        left = len(env.task.on_path)
        if left == 0:  # the path is clear: drive to the sink (shown only, not stepped)
            end = env.get_state()
            text = caption("path clear: to the sink")
            way = _drive(env, robot.base_pose(data), env.config.goal)
            for w in _resample(way, spacing, 2 * max_motion_frames):
                robot.set_base(data, w)
                frames.append(text())
            env.set_state(end)
        else:
            frames.append(caption(f"end of the plan: {left} obstacles left")())
    finally:
        render.close()
    return frames


class _KitchenRenderer:
    """Off-screen renders of the env's current state from a free camera, captioned."""

    def __init__(self, env: Any, size: tuple[int, int], view: dict[str, Any]) -> None:
        import mujoco

        from voot.envs.core.rendering import new_renderer
        from voot.record.video import FREE_CAMERA_KEYS

        w, h = (int(v) for v in size)
        if not (64 <= w <= 1280 and 48 <= h <= 960):
            raise ValueError(f"size must be (width, height) within 64..1280 x 48..960, got {size}")
        unknown = sorted(set(view) - set(FREE_CAMERA_KEYS))
        if unknown:
            raise ValueError(f"unknown view keys {unknown}; valid: {', '.join(FREE_CAMERA_KEYS)}")
        self.mj = mujoco
        self.env = env
        self.renderer = new_renderer(env.model, height=h, width=w)
        cam = mujoco.MjvCamera()
        mujoco.mjv_defaultFreeCamera(env.model, cam)
        for k, v in view.items():
            if k == "lookat":
                cam.lookat[:] = np.asarray(v, dtype=np.float64).reshape(3)
            else:
                setattr(cam, k, float(v))
        self.camera = cam
        self.font_size = max(9, h // 22)

    def frame(self, text: str = "") -> Frame:
        env, mj = self.env, self.mj
        mj.mj_kinematics(env.model, env.data)
        self.renderer.update_scene(env.data, camera=self.camera)
        env._decorate(self.renderer.scene)  # the path's corridor and the forbidden rooms
        img = np.array(self.renderer.render(), dtype=np.uint8)
        return _caption(img, text, self.font_size) if text else img

    def close(self) -> None:
        self.renderer.close()


def _caption(img: Frame, text: str, size: int) -> Frame:
    """``img`` with ``text`` in white on a dark band at the top."""
    from PIL import Image, ImageDraw, ImageFont

    pil = Image.fromarray(img)
    draw = ImageDraw.Draw(pil, "RGBA")
    font = ImageFont.load_default(size=size)
    lines = text.split("\n")
    band = (size + 3) * len(lines) + 4
    draw.rectangle((0, 0, pil.width, band), fill=(20, 20, 20, 170))
    for k, line in enumerate(lines):
        draw.text((4, 2 + k * (size + 3)), line, fill=(255, 255, 255, 255), font=font)
    return np.asarray(pil, dtype=np.uint8)
