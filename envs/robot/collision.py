"""Collision checks of the robot and the object it holds, with MuJoCo.

:class:`CollisionChecker` poses the robot (and the object it holds) in a scratch copy of
the scene and runs MuJoCo's collision detection (``mj_kinematics`` + ``mj_collision``),
reporting which scene geoms or objects are hit (:class:`CollisionReport`). Contacts
between the gripper and the object being grasped are allowed (the grasp touches it);
contacts between two other parties (an object resting against a wall) are not computed
at all: the checker's model copy filters them out (:func:`_robot_pairs_model`). A pick is
feasible only if the arm reaches the grasp (:mod:`voot.envs.robot.arm_ik`) and the robot there
is free; a place, only if the robot and the held object are free at the placement.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

from voot.envs.core.scene import ObjectInfo, set_object_pose
from voot.envs.robot.model import FINGER_OPEN, Robot

FloatArray = NDArray[np.float64]

__all__ = ["CollisionChecker", "CollisionReport"]


@dataclass
class CollisionReport:
    """What a configuration of robot and held object collides with (names, sorted)."""

    hits: list[str] = field(default_factory=list)

    @property
    def free(self) -> bool:
        return not self.hits


#: A contact pair not looked up yet (the pair memo holds None for "not reported").
_UNKNOWN = object()


class CollisionChecker:
    """MuJoCo collision queries for the robot and the object it holds.

    Works on its own :class:`mujoco.MjData`: :meth:`check` copies the given ``qpos``,
    applies the changes, runs ``mj_kinematics`` and ``mj_collision`` and inspects the
    contacts. A contact counts if one of its geoms belongs to the robot or to the
    ``held`` object, except contacts between the gripper and ``held`` (the grasp itself).
    Contacts among other bodies (objects resting against each other) are ignored.

    Args:
        model: The scene.
        robot: Named access to the robot in ``model``.
        objects: The scene's movable objects.
    """

    def __init__(self, model: mujoco.MjModel, robot: Robot, objects: list[ObjectInfo]) -> None:
        self.model, self._held_affinity = _robot_pairs_model(model, robot, objects)
        self.data = mujoco.MjData(self.model)
        # views into the model's and data's buffers, fetched once (each attribute access
        # builds a new array object)
        self._affinity_view = self.model.geom_conaffinity
        self._qpos_view = self.data.qpos
        # (geom, geom, held) -> what the contact reports (a pure function of the three)
        self._pair_hit: dict[tuple[int, int, int], str | None] = {}
        # the last query, ``(held, qpos bytes)``, and its report (see check; None: a hit
        # found by collides, names not built)
        self._last: tuple[tuple[int, bytes], CollisionReport | None] | None = None
        self.robot = robot
        self.objects = objects
        n = model.ngeom
        self._is_robot = np.zeros(n, dtype=bool)
        self._is_robot[list(robot.geoms)] = True
        self._is_gripper = np.zeros(n, dtype=bool)
        self._is_gripper[list(robot.gripper_geoms)] = True
        self._owner = np.full(n, -1, dtype=np.intp)  # object index, or -1
        for i, o in enumerate(objects):
            self._owner[list(o.geoms)] = i
        # plain lists and slices for check(), whose contacts are few: indexing them from
        # Python is cheaper than numpy masks over a handful of rows
        self._robot_l: list[bool] = self._is_robot.tolist()
        self._gripper_l: list[bool] = self._is_gripper.tolist()
        self._owner_l: list[int] = self._owner.tolist()
        self._base_sl = _as_slice(robot.base_qadr)
        self._arm_sl = _as_slice(robot.arm_qadr)
        self._finger_sl = _as_slice(robot.finger_qadr)
        self._names = []
        for g in range(n):
            owner = int(self._owner[g])
            if owner >= 0:
                self._names.append(objects[owner].name)
            else:
                self._names.append(
                    mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
                )

    def __getstate__(self) -> dict[str, object]:
        """The checker without its two buffer views, for :mod:`pickle` and :mod:`copy`.

        The views alias the buffers of :attr:`model` and :attr:`data`; copied, they would
        be arrays of their own, so a copy's checks would write the configuration where
        MuJoCo never reads it (and report collisions of a stale one). They are fetched
        again from the copy's model and data (:meth:`__setstate__`).
        """
        state = self.__dict__.copy()
        del state["_affinity_view"], state["_qpos_view"]
        return state

    def __setstate__(self, state: dict[str, object]) -> None:
        self.__dict__.update(state)
        self._affinity_view = self.model.geom_conaffinity
        self._qpos_view = self.data.qpos

    def check(
        self,
        qpos: FloatArray,
        base_pose: ArrayLike,
        arm_q: ArrayLike,
        held: int | None = None,
        object_poses: Mapping[int, ArrayLike] | None = None,
    ) -> CollisionReport:
        """Collisions of the robot (and ``held``) in a hypothetical configuration.

        Args:
            qpos: The scene's current ``qpos`` (copied, not modified).
            base_pose: Base ``(x, y, theta)``.
            arm_q: The 7 arm joints.
            held: Index (into ``objects``) of the object in the gripper, if any; its
                contacts with the gripper are allowed and its other contacts count.
            object_poses: Object index -> ``(x, y, z, yaw)`` overrides (e.g. the held
                object at its placement, or objects placed earlier in the same action).

        Returns:
            The names of what is hit (scene geom names; object body names), sorted,
            without duplicates; prefixed ``"robot-"`` or ``"object-"`` by the party hit.
            Treat it as read-only: a query repeating the last one (the same ``held`` and
            the same ``qpos`` once the changes are applied, byte for byte) returns the
            last report itself. The report is a pure function of the two (kinematics and
            contacts depend on the positions alone), so the repeat is exact; it is what a
            pre-screen followed by the full step of the same action asks
            (:meth:`voot.envs.core.env.ManipulationEnv.certainly_infeasible`).
        """
        key = self._configure(qpos, base_pose, arm_q, held, object_poses)
        last = self._last
        if last is not None and last[0] == key and last[1] is not None:
            return last[1]
        self._contacts(held)
        report = self._report(held)
        self._last = (key, report)
        return report

    def collides(
        self,
        qpos: FloatArray,
        base_pose: ArrayLike,
        arm_q: ArrayLike,
        held: int | None = None,
        object_poses: Mapping[int, ArrayLike] | None = None,
    ) -> bool:
        """``not check(...).free`` (the same arguments), without naming what is hit.

        It stops at the first contact that counts, so a pre-screen that only needs the
        verdict pays for no names; a free configuration is remembered as the last query
        (its report is empty), so :meth:`check` of it right after costs nothing.
        """
        key = self._configure(qpos, base_pose, arm_q, held, object_poses)
        last = self._last
        if last is not None and last[0] == key:
            return last[1] is None or not last[1].free
        self._contacts(held)
        d = self.data
        ncon = d.ncon
        if ncon:
            held_i = -2 if held is None else held
            memo = self._pair_hit
            for a, b in d.contact.geom[:ncon].tolist():
                pair = (a, b, held_i)
                name = memo.get(pair, _UNKNOWN)
                if name is _UNKNOWN:
                    name = memo[pair] = self._hit_name(a, b, held_i)
                if name is not None:
                    self._last = (key, None)  # hit; the names are built if check() asks
                    return True
        self._last = (key, CollisionReport())
        return False

    def _configure(
        self,
        qpos: FloatArray,
        base_pose: ArrayLike,
        arm_q: ArrayLike,
        held: int | None,
        object_poses: Mapping[int, ArrayLike] | None,
    ) -> tuple[int, bytes]:
        """Write the configuration into :attr:`data`'s ``qpos``; the query's key.

        The key is ``held`` and the ``qpos`` bytes: what a report is a function of.
        """
        d = self.data
        q = self._qpos_view
        q[:] = qpos
        base_sl, arm_sl, finger_sl = self._base_sl, self._arm_sl, self._finger_sl
        if base_sl is not None and arm_sl is not None and finger_sl is not None:
            q[base_sl] = base_pose
            q[arm_sl] = arm_q
            q[finger_sl] = FINGER_OPEN
        else:  # pragma: no cover - robot.xml keeps each joint group contiguous
            self.robot.set_base(d, base_pose)
            self.robot.set_arm(d, arm_q)
        if object_poses:
            objects = self.objects
            for i, pose in object_poses.items():
                if type(pose) is tuple and len(pose) == 4:
                    # set_object_pose's numbers, written straight into the qpos view
                    x, y, z, yaw = pose
                    adr = objects[i].qpos_adr
                    q[adr : adr + 7] = (x, y, z, math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw))
                else:
                    set_object_pose(d, objects[i], pose)
        return (-2 if held is None else held, q.tobytes())

    def _contacts(self, held: int | None) -> None:
        """Kinematics and contacts of the configuration in :attr:`data` (``held``'s filter)."""
        m, d = self.model, self.data
        mujoco.mj_kinematics(m, d)
        restore = self._held_affinity.get(held) if held is not None else None
        if restore is not None:
            geoms, full, reduced = restore
            affinity = self._affinity_view
            affinity[geoms] = full
            mujoco.mj_collision(m, d)
            affinity[geoms] = reduced
        else:
            mujoco.mj_collision(m, d)

    def _report(self, held: int | None) -> CollisionReport:
        """The report of the contacts in :attr:`data`."""
        d = self.data
        ncon = d.ncon
        if ncon == 0:
            return CollisionReport()
        held_i = -2 if held is None else held
        memo = self._pair_hit
        hits: set[str] = set()
        for a, b in d.contact.geom[:ncon].tolist():
            key = (a, b, held_i)
            if key in memo:
                name = memo[key]
            else:
                name = memo[key] = self._hit_name(a, b, held_i)
            if name is not None:
                hits.add(name)
        if len(memo) > 200_000:  # pragma: no cover - bounded by ngeom^2 x objects
            memo.clear()
        return CollisionReport(sorted(hits))

    def _hit_name(self, a: int, b: int, held_i: int) -> str | None:
        """What a contact between geoms ``a`` and ``b`` reports (None: not reported)."""
        robot, owner, gripper, names = self._robot_l, self._owner_l, self._gripper_l, self._names
        hold_a, hold_b = owner[a] == held_i, owner[b] == held_i
        if not (robot[a] or robot[b] or hold_a or hold_b):
            return None  # between two other parties
        if (gripper[a] and hold_b) or (gripper[b] and hold_a):
            return None  # the grasp itself
        if not (robot[a] or hold_a):
            a, b = b, a  # a is ours (robot or held), b the other party
        who = "robot" if robot[a] else "object"
        return f"{who}-{names[b]}" if not robot[b] else f"{who}-robot"


def _robot_pairs_model(
    model: mujoco.MjModel, robot: Robot, objects: list[ObjectInfo]
) -> tuple[
    mujoco.MjModel, dict[int, tuple[slice | list[int], NDArray[np.int32], NDArray[np.int32]]]
]:
    """A copy of ``model`` whose collision filter keeps only the pairs a check reports.

    :meth:`CollisionChecker.check` reports contacts of the robot and of the held object
    only; MuJoCo would also compute every contact between two other parties (an object
    resting against a wall). In the copy, every non-robot geom's ``conaffinity`` keeps
    only the robot's ``contype`` bits, so such pairs are never tested, and the held
    object's geoms get their own ``conaffinity`` back for the duration of a check. Pairs
    with the robot keep their filter, and a pair of the held object and another geom is
    kept exactly when it was (verified here for every object against every geom;
    otherwise the original filter is used). Contacts are computed per pair, so the ones
    reported are the same. Returns the model and, per object index, its geoms with
    their original and reduced ``conaffinity``.
    """
    contype = model.geom_contype.astype(np.int64)
    affinity = model.geom_conaffinity.astype(np.int64)
    is_robot = np.zeros(model.ngeom, dtype=bool)
    is_robot[list(robot.geoms)] = True
    robot_bits = int(np.bitwise_or.reduce(contype[is_robot])) if is_robot.any() else 0
    if np.any(contype[~is_robot] & robot_bits):  # pragma: no cover - not in the scenes
        return model, {}
    reduced = np.where(is_robot, affinity, affinity & robot_bits)

    def pairs(ct: NDArray[np.int64], af: NDArray[np.int64]) -> NDArray[np.bool_]:
        return ((ct[:, None] & af[None, :]) | (ct[None, :] & af[:, None])) != 0

    original = pairs(contype, affinity)
    held: dict[int, tuple[slice | list[int], NDArray[np.int32], NDArray[np.int32]]] = {}
    for i, obj in enumerate(objects):
        geoms = list(obj.geoms)
        trial = reduced.copy()
        trial[geoms] = affinity[geoms]
        filtered = pairs(contype, trial)
        ours = is_robot.copy()
        ours[geoms] = True
        # every pair with the robot or this object is filtered as before
        if not np.array_equal(filtered[ours], original[ours]):  # pragma: no cover
            return model, {}
        run = _as_slice(np.asarray(geoms, dtype=np.intp))
        held[i] = (
            geoms if run is None else run,
            model.geom_conaffinity[geoms].copy(),
            reduced[geoms].astype(model.geom_conaffinity.dtype),
        )
    copy_ = copy.copy(model)
    copy_.geom_conaffinity[:] = reduced.astype(model.geom_conaffinity.dtype)
    return copy_, held


def _as_slice(index: NDArray[np.intp]) -> slice | None:
    """``index`` as an equivalent slice if it is a run of consecutive addresses."""
    lo = int(index[0])
    if index.tolist() == list(range(lo, lo + len(index))):
        return slice(lo, lo + len(index))
    return None
