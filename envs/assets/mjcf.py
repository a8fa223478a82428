"""MJCF writers: the building blocks of every scene voot writes, and their shared constants.

The fixed scenes (``models/kitchen.xml``, ``models/conveyor.xml``: :mod:`.fixed_scenes`)
and the generated ones (:mod:`voot.envs.kitchen.generated.scene`,
:mod:`voot.envs.conveyor.generated.scene`) are written with these pieces, so they follow
the same conventions the environments read back (:mod:`voot.envs.core.scene`):

* **collision classes** (see ``robot.xml`` for the robot's bit): ``scene`` (static:
  walls, furniture; contype :data:`SCENE_BIT`, conaffinity robot | object), ``object``
  (movable bodies with a free joint named ``obj_*``; contype :data:`OBJECT_BIT`,
  conaffinity every bit) and ``decor`` (visual only; never collides). The floor never
  collides: the task planner is kinematic and only horizontal obstructions matter;
* the **header** (:func:`header`): compiler, options, visual settings, the materials,
  the classes and the ``robot.xml`` include;
* blocks standing on the floor (:class:`Rect`, :func:`wall`), movable boxes and chairs,
  tables, cameras, the sun, the floor, markers, the sink and the conveyor belt.

Every writer is a pure function of its numbers (formatted by :func:`fmt`: 4 decimals, no
trailing zeros), so a scene's text, and the hash the generated families key their caches
and witnesses by (:func:`mjcf_sha256`), is the same in every process. Pure Python and
numpy: no MuJoCo.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "BELT_FIRST_X",
    "BELT_SPACING",
    "BELT_TOP",
    "BELT_Y",
    "CONVEYOR_START",
    "CONVEYOR_WALL_HEIGHT",
    "COUNTER_DEPTH",
    "COUNTER_HEIGHT",
    "GOAL_RGBA",
    "KITCHEN_GOAL",
    "KITCHEN_START",
    "KITCHEN_WALL_HEIGHT",
    "OBJECT_BIT",
    "OBJECT_PREFIX",
    "ROBOT_BIT",
    "ROBOT_INCLUDE",
    "SCENE_BIT",
    "START_RGBA",
    "WALL_THICKNESS",
    "Rect",
    "belt_pose",
    "belt_xml",
    "box_object",
    "cameras",
    "chair_object",
    "collision_defaults",
    "floor_plane",
    "fmt",
    "header",
    "lookat_xyaxes",
    "marker",
    "mjcf_sha256",
    "sink",
    "sun_light",
    "table",
    "vec",
    "wall",
]

# ----- conventions -------------------------------------------------------------------------
#: Collision bit of the robot's geoms (contype 1, set in ``robot.xml``).
ROBOT_BIT = 1
#: Collision bit of static scene geoms (contype 2, class ``scene``).
SCENE_BIT = 2
#: Collision bit of movable objects (contype 4, class ``object``).
OBJECT_BIT = 4
#: Name prefix of the movable objects' bodies (and free joints).
OBJECT_PREFIX = "obj_"
#: The robot's file, included by every scene (shipped in ``voot.models``).
ROBOT_INCLUDE = "robot.xml"

#: The collision classes: name -> (contype, conaffinity, group, extra attributes).
_CLASSES: tuple[tuple[str, int, int, int, str], ...] = (
    ("scene", SCENE_BIT, ROBOT_BIT | OBJECT_BIT, 0, ""),
    ("object", OBJECT_BIT, ROBOT_BIT | SCENE_BIT | OBJECT_BIT, 0, ' density="100"'),
    ("decor", 0, 0, 1, ""),
)

# ----- shared dimensions (metres) ------------------------------------------------------------
#: Thickness of every wall (outer walls stand outside the interior bounds).
WALL_THICKNESS = 0.1
#: Height of the kitchens' walls (the paper's and the generated ones).
KITCHEN_WALL_HEIGHT = 1.1
#: Height of the storage rooms' walls (the paper's and the generated ones).
CONVEYOR_WALL_HEIGHT = 1.2
#: Depth and height of the kitchens' counters.
COUNTER_DEPTH = 0.65
COUNTER_HEIGHT = 0.86
#: Start and goal base poses of the paper's kitchen problem (the original's).
KITCHEN_START = (-1.5, -1.5, math.pi / 2)
KITCHEN_GOAL = (0.0, 2.5, math.pi / 2)
#: Start base pose of the conveyor problem (the original's): facing the belt.
CONVEYOR_START = (0.0, 1.05, 0.0)
#: The belt's queue: top height, the first box's x, the spacing and the y of the queue.
BELT_TOP = 0.06
BELT_FIRST_X = 2.3
BELT_SPACING = 1.1
BELT_Y = 1.05
#: Colours of the start and goal markers.
START_RGBA = "0.1 0.6 1 1"
GOAL_RGBA = "1 0.8 0.1 1"

_MATERIALS = """\
    <material name="wall" rgba="0.93 0.91 0.86 1"/>
    <material name="wood" rgba="0.62 0.44 0.28 1"/>
    <material name="dark_wood" rgba="0.40 0.27 0.17 1"/>
    <material name="counter" rgba="0.85 0.86 0.88 1"/>
    <material name="counter_top" rgba="0.30 0.31 0.33 1"/>
    <material name="steel" rgba="0.70 0.72 0.75 1" specular="0.8" shininess="0.8"/>
    <material name="fabric" rgba="0.35 0.45 0.60 1"/>
    <material name="bed" rgba="0.85 0.80 0.70 1"/>
    <material name="belt" rgba="0.15 0.15 0.16 1"/>
    <material name="rail" rgba="0.55 0.58 0.62 1"/>
    <material name="cardboard" rgba="0.78 0.60 0.38 1"/>
    <material name="big_box" rgba="0.80 0.25 0.20 1"/>
    <material name="chair" rgba="0.20 0.50 0.45 1"/>
    <material name="clutter" rgba="0.55 0.55 0.75 1"/>
"""


# ----- numbers ---------------------------------------------------------------------------------
def fmt(x: float) -> str:
    """Format a number compactly for XML (4 decimals, no trailing zeros)."""
    s = f"{x:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def vec(*xs: float) -> str:
    """Numbers as an MJCF vector (:func:`fmt` each, space separated)."""
    return " ".join(fmt(x) for x in xs)


def mjcf_sha256(xml: str) -> str:
    """SHA-256 of an MJCF text (the same scene gives the same digest in every process)."""
    return hashlib.sha256(xml.encode()).hexdigest()


def lookat_xyaxes(pos: tuple[float, float, float], target: tuple[float, float, float]) -> str:
    """MJCF ``xyaxes`` of a camera at ``pos`` looking at ``target`` with z up."""
    p = np.asarray(pos, dtype=float)
    t = np.asarray(target, dtype=float)
    fwd = t - p
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    return vec(*right, *up)


# ----- the header ------------------------------------------------------------------------------
def collision_defaults(indent: str = "    ", one_line: bool = False) -> str:
    """The ``<default class=...>`` entries of the collision classes (inside ``<default>``)."""
    out = []
    for name, contype, affinity, group, extra in _CLASSES:
        geom = f'<geom contype="{contype}" conaffinity="{affinity}" group="{group}"{extra}/>'
        if one_line:
            out.append(f'{indent}<default class="{name}">{geom}</default>\n')
        else:
            out.append(f'{indent}<default class="{name}">\n{indent}  {geom}\n{indent}</default>\n')
    return "".join(out)


def header(model: str, extent: float, center: tuple[float, float, float], assets: str = "") -> str:
    """A scene's opening: compiler, options, visual settings, the textures and materials
    (``assets``: more ``<asset>`` entries, after them), the collision classes and the
    robot's include. The caller writes the ``<worldbody>`` and closes ``</mujoco>``."""
    return f"""<mujoco model="{model}">
  <!-- Generated by models/generate_scenes.py: edit that script, not this file. -->
  <compiler angle="radian" autolimits="true"/>
  <option timestep="0.01"/>
  <statistic extent="{fmt(extent)}" center="{vec(*center)}"/>
  <visual>
    <global offwidth="1280" offheight="960" azimuth="-120" elevation="-45"/>
    <quality shadowsize="4096"/>
    <headlight ambient="0.30 0.30 0.30" diffuse="0.25 0.25 0.25" specular="0.05 0.05 0.05"/>
    <map znear="0.01" zfar="200"/>
  </visual>
  <asset>
    <texture name="sky" type="skybox" builtin="gradient" rgb1="0.78 0.84 0.92" rgb2="0.98 0.98 1.0" width="256" height="256"/>
    <texture name="floor_tex" type="2d" builtin="checker" rgb1="0.80 0.78 0.74" rgb2="0.72 0.70 0.66" width="512" height="512"/>
    <material name="floor" texture="floor_tex" texrepeat="1 1" texuniform="true" reflectance="0.05"/>
    <texture name="tile_tex" type="2d" builtin="checker" rgb1="0.92 0.92 0.90" rgb2="0.82 0.84 0.86" width="512" height="512"/>
    <material name="tile" texture="tile_tex" texrepeat="2 2" texuniform="true"/>
{_MATERIALS}{assets}  </asset>
  <default>
{collision_defaults()}  </default>
  <include file="{ROBOT_INCLUDE}"/>
"""


# ----- blocks and bodies -----------------------------------------------------------------------
@dataclass(frozen=True)
class Rect:
    """An axis-aligned block standing on the floor: x and y bounds and a height."""

    xmin: float
    xmax: float
    ymin: float
    ymax: float
    height: float

    def geom(self, name: str, cls: str, material: str, z0: float = 0.0) -> str:
        """The block as a box ``<geom>`` (no indent, no newline)."""
        cx, cy = 0.5 * (self.xmin + self.xmax), 0.5 * (self.ymin + self.ymax)
        hx, hy, hz = (
            0.5 * (self.xmax - self.xmin),
            0.5 * (self.ymax - self.ymin),
            0.5 * self.height,
        )
        return (
            f'<geom name="{name}" class="{cls}" type="box" material="{material}" '
            f'size="{vec(hx, hy, hz)}" pos="{vec(cx, cy, z0 + hz)}"/>'
        )

    def line(self, name: str, material: str, cls: str = "scene") -> str:
        """:meth:`geom` as a worldbody line (indented, newline)."""
        return "    " + self.geom(name, cls, material) + "\n"


def wall(name: str, x0: float, x1: float, y0: float, y1: float, height: float) -> str:
    """A static wall block (class ``scene``, material ``wall``) as a worldbody line."""
    return Rect(x0, x1, y0, y1, height).line(name, "wall")


def box_object(
    name: str,
    x: float,
    y: float,
    yaw: float,
    size: tuple[float, float, float],
    material: str,
    z: float = 0.0,
) -> str:
    """A movable box: body origin at the centre of its footprint on its support."""
    sx, sy, sz = size
    return (
        f'    <body name="{name}" pos="{vec(x, y, z)}" euler="0 0 {fmt(yaw)}">\n'
        f'      <freejoint name="{name}"/>\n'
        f'      <geom name="{name}" class="object" type="box" material="{material}" '
        f'size="{vec(sx / 2, sy / 2, sz / 2)}" pos="0 0 {fmt(sz / 2)}"/>\n'
        f"    </body>\n"
    )


def chair_object(name: str, x: float, y: float, yaw: float) -> str:
    """A movable kitchen chair (0.46 x 0.46 m, seat 0.47 m, back 0.9 m); back at -x."""
    h = 0.23
    leg = 0.02
    parts = [
        f'    <body name="{name}" pos="{vec(x, y, 0.0)}" euler="0 0 {fmt(yaw)}">',
        f'      <freejoint name="{name}"/>',
        f'      <geom name="{name}_seat" class="object" type="box" material="chair" '
        f'size="{vec(h, h, 0.02)}" pos="0 0 0.45"/>',
        f'      <geom name="{name}_back" class="object" type="box" material="chair" '
        f'size="{vec(0.02, h, 0.21)}" pos="{vec(-h + 0.02, 0, 0.68)}"/>',
    ]
    for i, (sx, sy) in enumerate(((1, 1), (1, -1), (-1, 1), (-1, -1))):
        parts.append(
            f'      <geom name="{name}_leg{i}" class="object" type="box" material="dark_wood" '
            f'size="{vec(leg, leg, 0.215)}" pos="{vec(sx * (h - leg), sy * (h - leg), 0.215)}"/>'
        )
    parts.append("    </body>\n")
    return "\n".join(parts)


def table(name: str, rect: Rect, material: str = "wood", leg: float = 0.03) -> str:
    """A static table: a top slab (collision) over four legs (collision)."""
    top = 0.04
    cx, cy = 0.5 * (rect.xmin + rect.xmax), 0.5 * (rect.ymin + rect.ymax)
    hx, hy = 0.5 * (rect.xmax - rect.xmin), 0.5 * (rect.ymax - rect.ymin)
    out = [
        f'    <geom name="{name}_top" class="scene" type="box" material="{material}" '
        f'size="{vec(hx, hy, top / 2)}" pos="{vec(cx, cy, rect.height - top / 2)}"/>'
    ]
    lz = 0.5 * (rect.height - top)
    for i, (sx, sy) in enumerate(((1, 1), (1, -1), (-1, 1), (-1, -1))):
        out.append(
            f'    <geom name="{name}_leg{i}" class="scene" type="box" material="dark_wood" '
            f'size="{vec(leg, leg, lz)}" pos="{vec(cx + sx * (hx - 2 * leg), cy + sy * (hy - 2 * leg), lz)}"/>'
        )
    return "\n".join(out) + "\n"


# ----- the world around them -------------------------------------------------------------------
def cameras(
    top_center: tuple[float, float],
    top_height: float,
    top_extent: float,
    persp_pos: tuple[float, float, float],
    persp_target: tuple[float, float, float],
    persp_fovy: float,
) -> str:
    """The ``top_down`` (orthographic) and ``perspective`` cameras every scene has."""
    return (
        f'    <camera name="top_down" pos="{vec(top_center[0], top_center[1], top_height)}" '
        f'xyaxes="1 0 0 0 1 0" projection="orthographic" fovy="{fmt(top_extent)}"/>\n'
        f'    <camera name="perspective" pos="{vec(*persp_pos)}" '
        f'xyaxes="{lookat_xyaxes(persp_pos, persp_target)}" fovy="{fmt(persp_fovy)}"/>\n'
    )


def sun_light(x: float, y: float, z: float) -> str:
    """The directional light that casts the scene's shadows, above ``(x, y)``."""
    return (
        f'    <light name="sun" pos="{vec(x, y, z)}" dir="0.3 0.4 -1" directional="true"'
        ' castshadow="true" diffuse="0.45 0.45 0.45"/>\n'
    )


def floor_plane(cx: float, cy: float, half_x: float, half_y: float) -> str:
    """The floor: a plane of class ``decor`` (it never collides)."""
    return (
        f'    <geom name="floor" class="decor" type="plane" size="{vec(half_x, half_y, 0.1)}"'
        f' pos="{vec(cx, cy, 0)}" material="floor"/>\n'
    )


def marker(name: str, x: float, y: float, rgba: str) -> str:
    """A flat disc on the floor (decoration) marking a base pose."""
    return (
        f'    <geom name="{name}" class="decor" type="cylinder" size="0.12 0.002"'
        f' pos="{vec(x, y, 0.003)}" rgba="{rgba}"/>\n'
    )


def sink(x: float, y: float, top: float) -> str:
    """A sink's basin and faucet (decoration) at ``(x, y)`` on a counter top at ``top``."""
    return (
        f'    <geom name="sink_basin" class="decor" type="box" size="0.32 0.22 0.005"'
        f' pos="{vec(x, y, top + 0.002)}" material="steel"/>\n'
        f'    <geom name="sink_faucet" class="decor" type="cylinder" size="0.02 0.12"'
        f' pos="{vec(x, y + 0.26, top + 0.12)}" material="steel"/>\n'
    )


def belt_pose(k: int) -> tuple[float, float, float, float]:
    """The ``(x, y, z, yaw)`` of the ``k``-th box's body in the belt's queue (``k = 0``:
    the first to be picked), in the scenes and while the env moves the queue on."""
    return (BELT_FIRST_X + BELT_SPACING * k, BELT_Y, BELT_TOP, 0.0)


def belt_xml() -> str:
    """The belt east of the conveyor's start: a raised frame (static) with a dark surface
    and rails (decoration); shared by ``conveyor.xml`` and the generated storage rooms."""
    belt_x0, belt_x1 = 1.5, 25.0
    bx, bhx = 0.5 * (belt_x0 + belt_x1), 0.5 * (belt_x1 - belt_x0)
    out = [
        f'    <geom name="belt_frame" class="scene" type="box" material="rail" size="{vec(bhx, 0.5, (BELT_TOP - 0.01) / 2)}" pos="{vec(bx, BELT_Y, (BELT_TOP - 0.01) / 2)}"/>\n',
        f'    <geom name="belt_surface" class="decor" type="box" material="belt" size="{vec(bhx, 0.45, 0.005)}" pos="{vec(bx, BELT_Y, BELT_TOP - 0.005)}"/>\n',
    ]
    for side, y in (("s", 0.53), ("n", 1.57)):
        out.append(
            f'    <geom name="belt_rail_{side}" class="decor" type="box" material="rail" size="{vec(bhx, 0.02, 0.04)}" pos="{vec(bx, y, BELT_TOP + 0.02)}"/>\n'
        )
    return "".join(out)
