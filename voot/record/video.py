"""A video of a plan, rendered headless by MuJoCo's renderer (GIF or MP4).

:func:`write_plan_video` takes an environment (or a planning problem over one) and the
plan as a list of actions (stepped from the current state) or of snapshots (restored
one by one), collects the MuJoCo state (``qpos`` and mocap poses) at every step, and
renders each with :class:`mujoco.Renderer` on a private ``MjData``, optionally with
``interpolate`` in-between frames per step (positions interpolated on the
configuration manifold with ``mj_differentiatePos``/``mj_integratePos``, so free and
ball joints turn along the shortest rotation). Environments without a MuJoCo model are
rendered by their own ``render()`` (``render_mode="rgb_array"``).

Headless rendering needs an off-screen OpenGL: rendering sets ``MUJOCO_GL=egl`` when it
is unset, which only takes effect if MuJoCo was not imported before (export it in
the shell to be sure). GIFs are written with Pillow through imageio; MP4 needs
imageio's ffmpeg plugin (``pip install imageio-ffmpeg``), a ValueError says so.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot import validation as V
from voot.record.mujoco_scene import find_mujoco

Frame = NDArray[np.uint8]

#: Keys of ``view=`` (MuJoCo free-camera fields; unset ones keep MuJoCo's defaults).
FREE_CAMERA_KEYS = ("lookat", "distance", "azimuth", "elevation")

#: Video formats by file suffix.
FORMATS = (".gif", ".mp4")


def _check_positive_int(value: object, name: str, low: int = 1) -> int:
    return V.integer(value, name, low)


def _state_of(
    model: Any, data: Any
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    return (
        np.array(data.qpos, dtype=np.float64),
        np.array(data.mocap_pos, dtype=np.float64).reshape(model.nmocap, 3),
        np.array(data.mocap_quat, dtype=np.float64).reshape(model.nmocap, 4),
    )


def _step(env: Any, action: Any) -> None:
    env.step(np.asarray(action, dtype=np.float64))


def _restore(env: Any, snapshot: Any) -> None:
    restore = getattr(env, "restore", None)
    if callable(restore):
        restore(snapshot)
        return
    target = getattr(env, "unwrapped", env)
    set_state = getattr(target, "set_state", None)
    if not callable(set_state):
        raise ValueError(
            f"{type(env).__name__} can take neither restore(snapshot) nor"
            " unwrapped.set_state(state); pass actions instead of snapshots"
        )
    set_state(snapshot)


def collect_states(
    env: Any,
    actions: Sequence[Any] | None = None,
    snapshots: Sequence[Any] | None = None,
) -> list[tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]]:
    """MuJoCo states ``(qpos, mocap_pos, mocap_quat)`` along a plan.

    With ``actions``: the current state, then the state after each action (the env is
    stepped; it is left at the plan's end). With ``snapshots``: the state after
    restoring each one. Exactly one of them must be given.
    """
    if (actions is None) == (snapshots is None):
        raise ValueError("give exactly one of actions= (stepped from now) or snapshots= (restored)")
    found = find_mujoco(env)
    if found is None:
        raise ValueError(f"found no MuJoCo model/data on {type(env).__name__}")
    model, data = found
    states = []
    if actions is not None:
        states.append(_state_of(model, data))
        for a in actions:
            _step(env, a)
            states.append(_state_of(model, data))
    else:
        assert snapshots is not None
        for s in snapshots:
            _restore(env, s)
            states.append(_state_of(model, data))
    return states


class _Frames:
    """Render MuJoCo states on a private ``MjData``."""

    def __init__(
        self,
        model: Any,
        width: int,
        height: int,
        camera: str | int | None,
        view: Mapping[str, Any] | None = None,
    ) -> None:
        os.environ.setdefault("MUJOCO_GL", "egl")  # effective only if mujoco is not imported yet
        import mujoco

        from voot.envs.core.rendering import new_renderer

        self.mj = mujoco
        self.model = model
        off_w, off_h = int(model.vis.global_.offwidth), int(model.vis.global_.offheight)
        if width > off_w or height > off_h:
            raise ValueError(
                f"{width}x{height} exceeds the model's off-screen buffer {off_w}x{off_h};"
                " raise <visual><global offwidth=... offheight=...> in the MJCF or render smaller"
            )
        try:
            self.renderer = new_renderer(model, height, width)
        except Exception as exc:
            raise RuntimeError(
                f"MuJoCo could not create an off-screen renderer ({exc}); on a machine without"
                " a display export MUJOCO_GL=egl (or osmesa) before Python imports mujoco"
            ) from exc
        self.data = mujoco.MjData(model)
        if camera is None:
            cam = mujoco.MjvCamera()
            mujoco.mjv_defaultFreeCamera(model, cam)
            for key, value in (view or {}).items():
                if key not in FREE_CAMERA_KEYS:
                    raise ValueError(
                        f"unknown view key {key!r}; valid keys are: {', '.join(FREE_CAMERA_KEYS)}"
                    )
                if key == "lookat":
                    cam.lookat[:] = np.asarray(value, dtype=np.float64).reshape(3)
                else:
                    setattr(cam, key, float(value))
            self.camera: Any = cam
        else:
            if view:
                raise ValueError("view= sets the free camera; it cannot be combined with camera=")
            if (
                isinstance(camera, str)
                and mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, camera) < 0
            ):
                names = [model.camera(i).name for i in range(model.ncam)]
                raise ValueError(f"no camera {camera!r} in the model; cameras: {names}")
            if isinstance(camera, int) and not -1 <= camera < model.ncam:
                raise ValueError(f"camera id {camera} out of range (-1 free, 0..{model.ncam - 1})")
            self.camera = camera

    def render(
        self, qpos: NDArray[np.float64], mpos: NDArray[np.float64], mquat: NDArray[np.float64]
    ) -> Frame:
        d = self.data
        d.qpos[:] = qpos
        if self.model.nmocap:
            d.mocap_pos[:] = mpos
            d.mocap_quat[:] = mquat
        self.mj.mj_forward(self.model, d)
        self.renderer.update_scene(d, camera=self.camera)
        return np.array(self.renderer.render(), dtype=np.uint8)

    def interpolate(
        self,
        a: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
        b: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
        s: float,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        m = self.model
        vel = np.zeros(m.nv)
        self.mj.mj_differentiatePos(m, vel, 1.0, a[0], b[0])
        q = a[0].copy()
        self.mj.mj_integratePos(m, q, vel, s)
        mpos = (1 - s) * a[1] + s * b[1]
        mq = (1 - s) * a[2] + s * b[2]
        if len(mq):
            mq /= np.linalg.norm(mq, axis=1, keepdims=True)
        return q, mpos, mq

    def close(self) -> None:
        self.renderer.close()


def plan_frames(
    env: Any,
    actions: Sequence[Any] | None = None,
    snapshots: Sequence[Any] | None = None,
    *,
    width: int = 480,
    height: int = 360,
    camera: str | int | None = None,
    view: Mapping[str, Any] | None = None,
    interpolate: int = 0,
) -> list[Frame]:
    """RGB frames ``(height, width, 3)`` of a plan (see the module docstring).

    Args:
        env: a gymnasium env, a planning problem over one, or anything holding a MuJoCo
            ``model``/``data``; without MuJoCo, ``env.render()`` gives the frames.
        actions: the plan as actions, stepped from the current state (or None).
        snapshots: the plan as snapshots, restored one by one (or None; give exactly
            one of ``actions`` and ``snapshots``).
        width: frame width in pixels (within the model's off-screen buffer).
        height: frame height in pixels.
        camera: a camera name or id of the model; None: a free camera.
        view: the free camera's ``lookat`` (3 numbers), ``distance`` (m), ``azimuth``
            and ``elevation`` (degrees); unset ones keep MuJoCo's defaults (which look at
            the whole model).
        interpolate: in-between frames per step (0: one frame per state).
    """
    _check_positive_int(width, "width")
    _check_positive_int(height, "height")
    _check_positive_int(interpolate, "interpolate", low=0)
    if find_mujoco(env) is None:
        return _env_frames(env, actions, snapshots)
    states = collect_states(env, actions, snapshots)
    model = find_mujoco(env)[0]  # type: ignore[index]
    r = _Frames(model, width, height, camera, view)
    try:
        frames = [r.render(*states[0])]
        for a, b in itertools.pairwise(states):
            for k in range(1, interpolate + 1):
                frames.append(r.render(*r.interpolate(a, b, k / (interpolate + 1))))
            frames.append(r.render(*b))
    finally:
        r.close()
    return frames


def _env_frames(
    env: Any, actions: Sequence[Any] | None, snapshots: Sequence[Any] | None
) -> list[Frame]:
    """Frames from ``env.render()`` (an env without a MuJoCo model)."""
    if (actions is None) == (snapshots is None):
        raise ValueError("give exactly one of actions= (stepped from now) or snapshots= (restored)")
    target = getattr(env, "env", env)  # a planning-problem adapter keeps its env here
    if getattr(target, "render_mode", None) != "rgb_array":
        raise ValueError(
            f"{type(env).__name__} has no MuJoCo model and does not render rgb_array frames"
            " (create it with render_mode='rgb_array')"
        )

    def grab() -> Frame:
        return np.asarray(target.render(), dtype=np.uint8)

    frames = []
    if actions is not None:
        frames.append(grab())
        for a in actions:
            _step(env, a)
            frames.append(grab())
    else:
        for s in snapshots or ():
            _restore(env, s)
            frames.append(grab())
    return frames


def write_video(
    path: str | os.PathLike[str], frames: Sequence[Frame], fps: float = 4.0, hold_last: int = 0
) -> Path:
    """Write ``frames`` to ``path`` (``.gif`` via Pillow, ``.mp4`` via imageio-ffmpeg).

    ``hold_last`` repeats the last frame that many more times (a pause before a GIF loops).
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(
            f"unknown video format {p.suffix!r}; valid suffixes are: {', '.join(FORMATS)}"
        )
    if not frames:
        raise ValueError("no frames to write")
    V.number(fps, "fps", 0.0, 120.0, open_low=True)
    _check_positive_int(hold_last, "hold_last", low=0)
    shape = np.asarray(frames[0]).shape
    for k, f in enumerate(frames):
        if np.asarray(f).shape != shape or len(shape) != 3 or shape[2] not in (3, 4):
            raise ValueError(
                f"frame {k} has shape {np.asarray(f).shape}; all must be (H, W, 3) like frame 0 {shape}"
            )
    seq = [np.asarray(f, dtype=np.uint8) for f in frames] + [
        np.asarray(frames[-1], dtype=np.uint8)
    ] * hold_last
    p.parent.mkdir(parents=True, exist_ok=True)
    import imageio.v3 as iio

    if suffix == ".gif":
        # Pillow's GIF writer: duration per frame in milliseconds, loop forever.
        iio.imwrite(
            p, np.stack(seq), extension=".gif", plugin="pillow", duration=1000.0 / fps, loop=0
        )
        return p
    try:
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        raise ValueError(
            "writing .mp4 needs imageio's ffmpeg plugin: pip install imageio-ffmpeg (or write a .gif)"
        ) from None
    even = [
        f[: f.shape[0] // 2 * 2, : f.shape[1] // 2 * 2, :3] for f in seq
    ]  # H.264 wants even sizes
    iio.imwrite(p, np.stack(even), extension=".mp4", plugin="FFMPEG", fps=fps)
    return p


def write_plan_video(
    path: str | os.PathLike[str],
    env: Any,
    actions: Sequence[Any] | None = None,
    snapshots: Sequence[Any] | None = None,
    *,
    fps: float = 4.0,
    width: int = 480,
    height: int = 360,
    camera: str | int | None = None,
    view: Mapping[str, Any] | None = None,
    interpolate: int = 0,
    hold_last: int = 4,
) -> Path:
    """Render a plan (see :func:`plan_frames`) and write it (see :func:`write_video`)."""
    frames = plan_frames(
        env,
        actions,
        snapshots,
        width=width,
        height=height,
        camera=camera,
        view=view,
        interpolate=interpolate,
    )
    return write_video(path, frames, fps=fps, hold_last=hold_last)
