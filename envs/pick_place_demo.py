r"""A tiny MuJoCo pick-and-place problem to demonstrate (and test) recordings and videos.

Not a benchmark (those are :mod:`voot.envs`): a 6 m x 6 m walled room, a holonomic
robot (a cylinder base with an arm and a mesh head) and one box. Actions alternate:

``pick`` (:math:`x, y, \theta` of the base)
    feasible iff the base stands 0.25-0.6 m from the box and inside the room; the robot
    then holds the box. Reward :math:`1 - |d - 0.4|`. Info: ``base_pose``.
``place`` (:math:`x, y, \theta` of the box)
    feasible iff the spot is inside the room and within 1.5 m of the base; the box is
    put there. Reward :math:`\exp(-\lVert p - g \rVert)` with :math:`g` the goal (the
    green square); a placement on the goal ends the episode with a bonus of 2.
    Info: ``placement``.

Infeasible actions earn -2 and end the rollout (the paper's convention). Every step's
info carries ``next_operator``. States are teleports: ``qpos`` is set and
``mj_kinematics`` run, no dynamics. The problem holds ``model``/``data``, so
:class:`voot.record.SearchRecorder` draws the scene and :mod:`voot.record.video`
renders it.

``voot-bench record-demo --out DIR`` records VOOT and PW-UCT on it and draws their
Figure-5 panels and a GIF of VOOT's plan (:mod:`voot.bench.demos.record_demo`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from voot import validation as V
from voot.optim.base import Bounds, FloatArray
from voot.tree.problem import StepResult

DEMO_XML = """
<mujoco model="voot_record_demo">
  <visual><global offwidth="640" offheight="480"/></visual>
  <asset>
    <mesh name="head" vertex="0 0 0  0.12 0 0  0 0.12 0  0 0 0.12"/>
  </asset>
  <worldbody>
    <light pos="0 0 5" dir="0 0 -1" directional="true"/>
    <geom name="floor" type="plane" size="3 3 0.1" rgba="0.85 0.85 0.8 1"/>
    <geom name="goal" type="box" pos="1.8 1.8 0.002" size="0.35 0.35 0.002"
          rgba="0.3 0.8 0.3 1" contype="0" conaffinity="0"/>
    <geom name="wall_n" type="box" pos="0 3 0.25" size="3 0.05 0.25" rgba="0.6 0.6 0.6 1"/>
    <geom name="wall_s" type="box" pos="0 -3 0.25" size="3 0.05 0.25" rgba="0.6 0.6 0.6 1"/>
    <geom name="wall_e" type="box" pos="3 0 0.25" size="0.05 3 0.25" rgba="0.6 0.6 0.6 1"/>
    <geom name="wall_w" type="box" pos="-3 0 0.25" size="0.05 3 0.25" rgba="0.6 0.6 0.6 1"/>
    <body name="robot">
      <joint name="base_x" type="slide" axis="1 0 0"/>
      <joint name="base_y" type="slide" axis="0 1 0"/>
      <joint name="base_yaw" type="hinge" axis="0 0 1"/>
      <geom name="base" type="cylinder" size="0.25 0.15" pos="0 0 0.15" rgba="0.2 0.4 0.8 1"/>
      <geom name="arm" type="capsule" fromto="0 0 0.3 0.3 0 0.6" size="0.04" rgba="0.9 0.6 0.1 1"/>
      <geom name="hand" type="sphere" pos="0.3 0 0.6" size="0.06" rgba="0.9 0.6 0.1 1"/>
      <geom name="head" type="mesh" mesh="head" pos="0 0 0.3" rgba="0.9 0.9 0.9 1"/>
    </body>
    <body name="box" pos="-1.5 -1.0 0.1">
      <freejoint name="box_free"/>
      <geom name="box" type="box" size="0.1 0.1 0.1" rgba="0.8 0.2 0.2 1"/>
    </body>
  </worldbody>
</mujoco>
"""

#: A free-camera view of the whole room from the south, for videos.
DEMO_VIEW = {"lookat": (0.0, 0.0, 0.0), "distance": 7.5, "azimuth": 90.0, "elevation": -55.0}

#: Room half-size (m) inside which the base and the box must stay.
ROOM = 2.7
#: How far (m) from the base the box can be put down.
PLACE_REACH = 1.5
#: The goal square's centre and half-size.
GOAL = (1.8, 1.8)
GOAL_HALF = 0.35


class DemoPickPlace:
    """The demo problem (a :class:`~voot.tree.PlanningProblem`); see the module docstring.

    Args:
        horizon: the episode ends after this many actions.
    """

    def __init__(self, horizon: int = 6) -> None:
        import mujoco

        V.integer(horizon, "horizon", 1)
        self._mj = mujoco
        self.model = mujoco.MjModel.from_xml_string(DEMO_XML)
        self.data = mujoco.MjData(self.model)
        self.horizon = horizon
        self._box = int(self.model.joint("box_free").qposadr[0])
        self.bounds = Bounds([-3.0, -3.0, -math.pi], [3.0, 3.0, math.pi])
        self.t = 0
        self.holding = False
        mujoco.mj_kinematics(self.model, self.data)

    @property
    def operator(self) -> str:
        """The operator of the next action: ``pick`` or ``place``."""
        return "place" if self.holding else "pick"

    def snapshot(self) -> tuple[FloatArray, int, bool]:
        q = np.array(self.data.qpos)
        q.setflags(write=False)
        return q, self.t, self.holding

    def restore(self, snapshot: tuple[FloatArray, int, bool]) -> None:
        q, self.t, self.holding = snapshot
        self.data.qpos[:] = q
        self._mj.mj_kinematics(self.model, self.data)

    def action_bounds(self) -> Bounds:
        return self.bounds

    def _box_xy(self) -> FloatArray:
        return np.array(self.data.qpos[self._box : self._box + 2])

    def step(self, action: FloatArray) -> StepResult:
        a = np.asarray(action, dtype=np.float64)
        if a.shape != (3,) or not np.all(np.isfinite(a)):
            raise ValueError(f"action must be 3 finite numbers (x, y, theta), got {action!r}")
        x, y, th = (float(v) for v in a)
        inside = abs(x) <= ROOM and abs(y) <= ROOM
        q = self.data.qpos
        self.t += 1
        if not self.holding:
            d = float(np.hypot(*(self._box_xy() - (x, y))))
            feasible = inside and 0.25 <= d <= 0.6
            info: dict[str, Any] = {"base_pose": (x, y, th), "next_operator": "place"}
            if not feasible:
                return StepResult(-2.0, feasible=False, info={**info, "next_operator": "pick"})
            q[0:3] = (x, y, th)
            # Carried in the hand, 0.3 m ahead of the base.
            q[self._box : self._box + 3] = (x + 0.3 * math.cos(th), y + 0.3 * math.sin(th), 0.72)
            self.holding = True
            reward, bonus, done = 1.0 - abs(d - 0.4), 0.0, False
        else:
            d = float(np.hypot(x - q[0], y - q[1]))
            feasible = inside and d <= PLACE_REACH
            info = {"placement": (x, y, th), "next_operator": "pick"}
            if not feasible:
                return StepResult(-2.0, feasible=False, info={**info, "next_operator": "place"})
            q[self._box : self._box + 3] = (x, y, 0.1)
            q[self._box + 3 : self._box + 7] = (math.cos(th / 2), 0.0, 0.0, math.sin(th / 2))
            self.holding = False
            on_goal = abs(x - GOAL[0]) <= GOAL_HALF and abs(y - GOAL[1]) <= GOAL_HALF
            reward = math.exp(-math.hypot(x - GOAL[0], y - GOAL[1]))
            bonus, done = (2.0, True) if on_goal else (0.0, False)
        self._mj.mj_kinematics(self.model, self.data)
        return StepResult(
            reward, feasible=True, terminal=done or self.t >= self.horizon, bonus=bonus, info=info
        )
