"""Log a MuJoCo scene to rerun: geometry once (static), body poses per time step.

Every body with drawn geoms becomes one entity ``<root>/bodies/<body name>``; its geoms
are logged once, static, *in the body's frame*, batched by kind (``boxes`` for boxes and
planes, ``ellipsoids`` for spheres and ellipsoids, ``cylinders``, ``capsules``, and
``mesh`` for all its meshes merged, with per-vertex colours and normals, so the viewer
shades them). A body's pose is then one
:class:`rerun.Transform3D` per time step (MuJoCo's ``xpos``/``xquat``, world frame), so
the robot and the objects move along a plan. Bodies welded to the world (no joint
between them and the world, not mocap) never move: their pose is logged once, static.

Poses are computed on a private ``MjData``: :meth:`MujocoScene.log_poses` copies
``qpos`` and the mocap poses of the given data and runs ``mj_kinematics``, so the
caller's data (an environment's) is never touched. Height fields and SDF geoms are
skipped (counted in :attr:`MujocoScene.skipped`). Only the geom groups MuJoCo's viewer
shows by default are drawn (0, 1, 2): a mesh object of a generated scene
(:mod:`voot.envs.assets.meshes`) is drawn as its visual mesh (class ``decor``, group 1), not
as its convex collision parts (group 3) on top of it. MuJoCo is imported lazily.

:func:`model_camera_eye` turns one of the model's cameras into the 3-D view's first eye
(:class:`voot.record.blueprint.Eye3D`), so a recording opens on the view the scene was
designed with.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot.record.blueprint import Eye3D

#: MuJoCo's default geom colour: a geom with a material and this rgba takes the material's.
_DEFAULT_RGBA = (0.5, 0.5, 0.5, 1.0)

#: Half-size (m) drawn for an infinite plane (MuJoCo plane size 0).
INFINITE_PLANE_HALF_SIZE = 10.0

#: Thickness (m) of the slab drawn for a plane (its top face is the plane).
PLANE_THICKNESS = 0.002


def find_mujoco(obj: Any, max_depth: int = 6) -> tuple[Any, Any] | None:
    """The ``(MjModel, MjData)`` behind ``obj``, or None.

    Looks at ``obj`` itself and follows ``unwrapped``, ``env`` and ``problem``
    attributes (a planning-problem adapter, a gymnasium wrapper chain, a MuJoCo env)
    for a pair of attributes ``model`` / ``data`` of MuJoCo's types (checked by type
    name, so MuJoCo is not imported). A ``(model, data)`` tuple is returned as it is.
    """
    if isinstance(obj, tuple) and len(obj) == 2 and _is_mj(obj[0], "MjModel"):
        return obj[0], obj[1]
    seen: set[int] = set()
    todo = [(obj, 0)]
    while todo:
        o, depth = todo.pop(0)
        if o is None or id(o) in seen or depth > max_depth:
            continue
        seen.add(id(o))
        model = getattr(o, "model", None)
        data = getattr(o, "data", None)
        if _is_mj(model, "MjModel") and _is_mj(data, "MjData"):
            return model, data
        for name in ("unwrapped", "env", "problem"):
            try:
                nxt = getattr(o, name, None)
            except Exception:  # properties of half-built objects may raise
                nxt = None
            if nxt is not None and nxt is not o:
                todo.append((nxt, depth + 1))
    return None


def _is_mj(obj: Any, name: str) -> bool:
    return obj is not None and type(obj).__name__ == name and "mujoco" in type(obj).__module__


def _wxyz_to_xyzw(q: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.asarray(q, dtype=np.float64)[..., [1, 2, 3, 0]]


def _quat_rotate(q_wxyz: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotate vectors ``v`` (n, 3) by unit quaternions ``q`` (n, 4, wxyz)."""
    w = q_wxyz[..., :1]
    u = q_wxyz[..., 1:]
    t = 2.0 * np.cross(u, v)
    return np.asarray(v + w * t + np.cross(u, t), dtype=np.float64)


def vertex_normals(
    vertices: NDArray[np.float64], faces: NDArray[np.integer]
) -> NDArray[np.float32]:
    r"""Unit normals ``(n, 3)`` of a triangle mesh's vertices, for the viewer's shading.

    A vertex's normal is the normalised sum of the unit normals of the faces around it,
    each weighted by the face's angle at the vertex,
    :math:`n_v \propto \sum_{f \ni v} \alpha_{f,v}\, \hat n_f` (angle weights do not
    depend on how a polygon is cut into triangles: a cube's corner gets its diagonal),
    with the faces wound counter-clockwise seen from outside, as MuJoCo keeps them. A
    vertex on no face (or only on degenerate ones) gets the zero vector.
    """
    v = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    cross = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    area2 = np.linalg.norm(cross, axis=1, keepdims=True)
    unit = np.divide(cross, area2, out=np.zeros_like(cross), where=area2 > 0)
    out = np.zeros_like(v)
    for k in range(3):
        e1 = v[f[:, (k + 1) % 3]] - v[f[:, k]]
        e2 = v[f[:, (k + 2) % 3]] - v[f[:, k]]
        angle = np.arctan2(np.linalg.norm(np.cross(e1, e2), axis=1), np.einsum("ij,ij->i", e1, e2))
        np.add.at(out, f[:, k], unit * angle[:, None])
    length = np.linalg.norm(out, axis=1, keepdims=True)
    out = np.divide(out, length, out=np.zeros_like(out), where=length > 1e-12)
    return out.astype(np.float32)


def _entity_part(name: str) -> str:
    import rerun as rr

    return str(rr.escape_entity_path_part(name))


class MujocoScene:
    """Draws one ``MjModel`` in rerun.

    Args:
        model: the MuJoCo model.
        root: entity path under which everything is logged.
        geom_groups: geom groups to draw (None: all). Geoms with alpha 0 are skipped.

    Attributes:
        body_entities: entity path of every drawn body, by body id.
        moving: ids of drawn bodies that can move (their pose is logged per step).
        n_geoms: geoms drawn; ``skipped``: geoms of kinds that are not drawn.
    """

    def __init__(
        self, model: Any, root: str = "scene", geom_groups: Sequence[int] | None = (0, 1, 2)
    ) -> None:
        import mujoco

        if not _is_mj(model, "MjModel"):
            raise ValueError(f"model must be a mujoco.MjModel, got {type(model).__name__}")
        self._mj = mujoco
        self.model = model
        self.root = root.rstrip("/")
        self._data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, self._data)
        groups = None if geom_groups is None else {int(g) for g in geom_groups}
        rgba = np.array(model.geom_rgba, dtype=np.float64)
        matid = np.asarray(model.geom_matid)
        for g in range(model.ngeom):
            if matid[g] >= 0 and tuple(rgba[g]) == _DEFAULT_RGBA:
                rgba[g] = model.mat_rgba[matid[g]]
        drawn = rgba[:, 3] > 0
        if groups is not None:
            drawn &= np.isin(np.asarray(model.geom_group), sorted(groups))
        self._geoms = np.flatnonzero(drawn)
        self._rgba = rgba
        self.n_geoms = 0
        self.skipped = 0
        bodies = sorted({int(model.geom_bodyid[g]) for g in self._geoms})
        names = [model.body(b).name or f"body{b}" for b in range(model.nbody)]
        used: dict[str, int] = {}
        self.body_entities: dict[int, str] = {}
        for b in bodies:
            part = names[b]
            if part in used:  # MuJoCo allows unnamed bodies; keep paths unique
                part = f"{part}_{b}"
            used[part] = b
            self.body_entities[b] = f"{self.root}/bodies/{_entity_part(part)}"
        weld = np.asarray(model.body_weldid)
        self.moving: list[int] = [b for b in bodies if b != 0 and weld[b] != 0]

    # ----- geometry --------------------------------------------------------------------------
    def log_geometry(self, rec: Any) -> int:
        """Log every drawn geom (static) and the poses of the bodies that never move.

        Returns the number of geoms drawn.
        """
        import rerun as rr

        mj = self._mj
        m = self.model
        G = mj.mjtGeom
        kinds = {
            int(G.mjGEOM_PLANE): "plane",
            int(G.mjGEOM_BOX): "box",
            int(G.mjGEOM_SPHERE): "sphere",
            int(G.mjGEOM_ELLIPSOID): "ellipsoid",
            int(G.mjGEOM_CYLINDER): "cylinder",
            int(G.mjGEOM_CAPSULE): "capsule",
            int(G.mjGEOM_MESH): "mesh",
        }
        per_body: dict[int, dict[str, list[int]]] = {}
        for geom in self._geoms.tolist():
            kind = kinds.get(int(m.geom_type[geom]))
            if kind is None:
                self.skipped += 1
                continue
            per_body.setdefault(int(m.geom_bodyid[geom]), {}).setdefault(kind, []).append(geom)
        n = 0
        for b, groups in per_body.items():
            ent = self.body_entities[b]
            boxes = groups.get("box", []) + groups.get("plane", [])
            if boxes:
                half: list[Any] = []
                centers: list[Any] = []
                for g in boxes:
                    s = np.array(m.geom_size[g], dtype=np.float64)
                    p = np.array(m.geom_pos[g], dtype=np.float64)
                    if int(m.geom_type[g]) == int(G.mjGEOM_PLANE):
                        hx = s[0] if s[0] > 0 else INFINITE_PLANE_HALF_SIZE
                        hy = s[1] if s[1] > 0 else INFINITE_PLANE_HALF_SIZE
                        half.append([hx, hy, PLANE_THICKNESS / 2])
                        down = _quat_rotate(
                            np.array(m.geom_quat[g])[None], np.array([[0, 0, -PLANE_THICKNESS / 2]])
                        )[0]
                        centers.append(p + down)
                    else:
                        half.append(s)
                        centers.append(p)
                self._log_solids(
                    rec,
                    f"{ent}/boxes",
                    rr.Boxes3D,
                    boxes,
                    half_sizes=np.array(half),
                    centers=np.array(centers),
                )
            ell = groups.get("sphere", []) + groups.get("ellipsoid", [])
            if ell:
                radii = [
                    np.repeat(m.geom_size[g][0], 3)
                    if int(m.geom_type[g]) == int(G.mjGEOM_SPHERE)
                    else np.array(m.geom_size[g])
                    for g in ell
                ]
                self._log_solids(
                    rec,
                    f"{ent}/ellipsoids",
                    rr.Ellipsoids3D,
                    ell,
                    half_sizes=np.array(radii),
                    centers=np.array(m.geom_pos[ell]),
                )
            cyl = groups.get("cylinder", [])
            if cyl:
                self._log_solids(
                    rec,
                    f"{ent}/cylinders",
                    rr.Cylinders3D,
                    cyl,
                    lengths=2.0 * np.array(m.geom_size[cyl, 1]),
                    radii=np.array(m.geom_size[cyl, 0]),
                    centers=np.array(m.geom_pos[cyl]),
                )
            cap = groups.get("capsule", [])
            if cap:
                half_len = np.array(m.geom_size[cap, 1])
                axis = np.zeros((len(cap), 3))
                axis[:, 2] = half_len
                # rerun's capsule runs from its origin along +z; MuJoCo's is centred.
                start = np.array(m.geom_pos[cap]) - _quat_rotate(np.array(m.geom_quat[cap]), axis)
                self._log_solids(
                    rec,
                    f"{ent}/capsules",
                    rr.Capsules3D,
                    cap,
                    lengths=2.0 * half_len,
                    radii=np.array(m.geom_size[cap, 0]),
                    translations=start,
                )
            meshes = groups.get("mesh", [])
            if meshes:
                self._log_meshes(rec, f"{ent}/mesh", meshes)
            n += sum(len(v) for v in groups.values())
        for b in self.body_entities:
            if b != 0 and b not in self.moving:
                rec.log(self.body_entities[b], self._transform(b), static=True)
        self.n_geoms = n
        return n

    def _log_solids(
        self, rec: Any, entity: str, archetype: Any, geoms: list[int], **shape: Any
    ) -> None:
        """Log ``geoms`` as one static, solid rerun ``archetype`` (``rr.Boxes3D`` ...): its
        ``shape`` arguments (sizes, positions) and each geom's orientation and colour."""
        import rerun as rr

        rec.log(
            entity,
            archetype(
                **shape,
                quaternions=self._quats(geoms),
                colors=self._colors(geoms),
                fill_mode=rr.components.FillMode.Solid,
            ),
            static=True,
        )

    def _quats(self, geoms: list[int]) -> Any:
        import rerun as rr

        xyzw = _wxyz_to_xyzw(np.array(self.model.geom_quat[geoms]))
        return [rr.Quaternion(xyzw=q) for q in xyzw]

    def _colors(self, geoms: list[int]) -> NDArray[np.uint8]:
        return np.rint(np.clip(self._rgba[geoms], 0.0, 1.0) * 255).astype(np.uint8)

    def _log_meshes(self, rec: Any, entity: str, geoms: list[int]) -> None:
        import rerun as rr

        m = self.model
        verts, faces, colors = [], [], []
        offset = 0
        # MuJoCo keeps a mesh's vertices in the mesh's own frame (centred at its centroid,
        # along its principal axes); geom_pos / geom_quat place that frame in the body.
        for g in geoms:
            mesh = int(m.geom_dataid[g])
            va, vn = int(m.mesh_vertadr[mesh]), int(m.mesh_vertnum[mesh])
            fa, fn = int(m.mesh_faceadr[mesh]), int(m.mesh_facenum[mesh])
            v = np.array(m.mesh_vert[va : va + vn], dtype=np.float64)
            q = np.broadcast_to(np.array(m.geom_quat[g], dtype=np.float64), (vn, 4))
            verts.append(_quat_rotate(q, v) + np.array(m.geom_pos[g]))
            faces.append(np.array(m.mesh_face[fa : fa + fn], dtype=np.uint32) + offset)
            colors.append(np.repeat(self._colors([g]), vn, axis=0))
            offset += vn
        positions = np.concatenate(verts)
        triangles = np.concatenate(faces)
        rec.log(
            entity,
            rr.Mesh3D(
                vertex_positions=positions,
                triangle_indices=triangles,
                vertex_normals=vertex_normals(positions, triangles),
                vertex_colors=np.concatenate(colors),
            ),
            static=True,
        )

    # ----- poses -----------------------------------------------------------------------------
    def _transform(self, b: int) -> Any:
        import rerun as rr

        d = self._data
        return rr.Transform3D(
            translation=np.array(d.xpos[b]),
            quaternion=rr.Quaternion(xyzw=_wxyz_to_xyzw(np.array(d.xquat[b]))),
        )

    def set_state(self, data: Any) -> None:
        """Copy ``qpos`` and mocap poses of ``data`` (an ``MjData`` of the same model) and
        compute the body poses on the private data."""
        d = self._data
        if data is not None:
            d.qpos[:] = data.qpos
            if self.model.nmocap:
                d.mocap_pos[:] = data.mocap_pos
                d.mocap_quat[:] = data.mocap_quat
        self._mj.mj_kinematics(self.model, d)

    def body_poses(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Positions ``(n, 3)`` and quaternions ``(n, 4, wxyz)`` of the moving bodies now."""
        d = self._data
        return np.array(d.xpos[self.moving]), np.array(d.xquat[self.moving])

    def log_poses(self, rec: Any, data: Any = None) -> None:
        """Log the pose of every moving body in state ``data`` at the recording's current time.

        ``data`` is an ``MjData`` of the same model (None: the state last set).
        """
        self.set_state(data)
        for b in self.moving:
            rec.log(self.body_entities[b], self._transform(b))


def camera_names(model: Any) -> list[str]:
    """The names of ``model``'s cameras (unnamed ones left out), in id order."""
    return [n for n in (model.camera(i).name for i in range(model.ncam)) if n]


def model_camera_eye(model: Any, camera: str) -> Eye3D:
    """The 3-D view's eye at ``model``'s camera ``camera`` (its pose at the model's
    initial state).

    The eye stands where the camera is and looks along its optical axis at the point
    where that axis meets the floor (z = 0), the point it orbits around; a camera that
    does not look down looks at the point one scene extent (``model.stat.extent``) ahead.
    The eye keeps the world's +z up (the camera's roll is not kept). A name the model
    has no camera for is a ValueError listing the cameras.
    """
    import mujoco

    if not _is_mj(model, "MjModel"):
        raise ValueError(f"model must be a mujoco.MjModel, got {type(model).__name__}")
    cid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, str(camera))
    if cid < 0:
        raise ValueError(
            f"no camera {camera!r} in the model; cameras: {', '.join(camera_names(model)) or 'none'}"
        )
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    mujoco.mj_camlight(model, data)
    position = np.array(data.cam_xpos[cid], dtype=np.float64)
    # a MuJoCo camera looks along its frame's -z axis
    forward = -np.asarray(data.cam_xmat[cid], dtype=np.float64).reshape(3, 3)[:, 2]
    if forward[2] < -1e-9 and position[2] > 0.0:
        target = position + forward * (-position[2] / forward[2])
    else:
        target = position + forward * float(model.stat.extent)
    return Eye3D(tuple(position.tolist()), tuple(target.tolist()))


def log_mujoco_model(
    rec: Any,
    model: Any,
    data: Any = None,
    root: str = "scene",
    geom_groups: Sequence[int] | None = (0, 1, 2),
) -> MujocoScene:
    """Log ``model``'s geometry (static) and, if given, the poses in ``data`` now.

    Returns the :class:`MujocoScene`, whose :meth:`~MujocoScene.log_poses` logs later states.
    """
    scene = MujocoScene(model, root, geom_groups)
    scene.log_geometry(rec)
    if data is not None:
        scene.log_poses(rec, data)
    return scene
