"""What a 3-D viewer draws of a scene: every visible geom of the MuJoCo model (table, bin, blocks and the
Fetch's meshes) at the pose the sim's published state puts it, and the meshes as STL. No rclpy.

The poses are MuJoCo's own: the robot's joint positions and the blocks' poses go into the model's state and
``mj_kinematics`` places every geom, so the picture is the simulated world, not a drawing of it.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import mujoco
import numpy as np

from semgoal_sim.scene import block_body_name, build_model

FLOOR_HALF_SIZE = 2.0
"""Half side (m) of the square drawn for an infinite floor plane."""
FLOOR_THICKNESS = 0.001


@dataclass(frozen=True)
class GeomView:
    """One drawable geom: ``shape`` is "box", "mesh", "sphere" or "cylinder"; ``size`` the full extents
    (box, m), the diameters and height (sphere, cylinder), or 1s (mesh, drawn at its own scale)."""

    name: str
    shape: str
    position: tuple[float, float, float]
    quaternion: tuple[float, float, float, float]  # w, x, y, z
    size: tuple[float, float, float]
    rgba: tuple[float, float, float, float]
    mesh: str = ""


class SceneView:
    """A scene's model, posed from published state (:meth:`pose`), read out as :class:`GeomView` s."""

    def __init__(self, scene: str, arms: int = 1) -> None:
        """``arms``: 2 for the second arm across the table, its joints named ``robot2/...``."""
        self.scene = scene
        self.model = model = build_model(scene, arms=arms)
        self.data = mujoco.MjData(model)
        mujoco.mj_forward(model, self.data)
        self._joint_qpos = {model.joint(j).name: model.jnt_qposadr[j] for j in range(model.njnt)
                            if int(model.jnt_type[j]) in _ONE_DOF_JOINTS}
        self._block_of_body = {model.body(block_body_name(b)).id: b for b in _scene_blocks(scene)}
        self._block_qpos = {b: model.joint(f"{block_body_name(b)}:joint").qposadr[0] for b in _scene_blocks(scene)}
        self._drawn = [g for g in range(model.ngeom) if model.body_mocapid[model.geom_bodyid[g]] < 0
                       and int(model.geom_type[g]) in _SHAPES]
        self.present: frozenset[str] = frozenset(self._block_qpos)
        self._stl: dict[str, bytes] = {}

    def pose(self, joints: Mapping[str, float], blocks: Mapping[str, tuple[Iterable[float], Iterable[float]]]) -> None:
        """Joint positions by MuJoCo joint name (unknown names are ignored) and block poses by name as
        (centre, w-x-y-z quaternion); blocks not given are not drawn (a scene reset with fewer blocks)."""
        qpos = self.data.qpos
        for name, value in joints.items():
            if name in self._joint_qpos and np.isfinite(value):
                qpos[self._joint_qpos[name]] = value
        for name, (position, quaternion) in blocks.items():
            if name in self._block_qpos:
                address = self._block_qpos[name]
                qpos[address:address + 3], qpos[address + 3:address + 7] = list(position), list(quaternion)
        self.present = frozenset(b for b in blocks if b in self._block_qpos)
        mujoco.mj_kinematics(self.model, self.data)

    def geoms(self) -> list[GeomView]:
        """Every drawn geom at its current pose (blocks only while present)."""
        model, data = self.model, self.data
        views = []
        for g in self._drawn:
            block = self._block_of_body.get(int(model.geom_bodyid[g]))
            if block is not None and block not in self.present:
                continue
            quaternion = np.empty(4)
            mujoco.mju_mat2Quat(quaternion, data.geom_xmat[g])
            shape, size, mesh = _shape_and_size(model, g)
            material = model.geom_matid[g]
            rgba = model.mat_rgba[material] if material >= 0 else model.geom_rgba[g]
            name = model.geom(g).name or model.body(model.geom_bodyid[g]).name
            views.append(GeomView(name, shape, tuple(map(float, data.geom_xpos[g])),
                                  tuple(map(float, quaternion)), size, tuple(map(float, rgba)), mesh))
        return views

    def meshes(self) -> list[str]:
        return [self.model.mesh(i).name for i in range(self.model.nmesh)]

    def mesh_stl(self, name: str) -> bytes:
        """The compiled mesh ``name`` as binary STL, in its geom's frame (KeyError if the model has none)."""
        if name not in self._stl:
            self._stl[name] = mesh_stl(self.model, name)
        return self._stl[name]


_ONE_DOF_JOINTS = {int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)}
_SHAPES = {int(kind) for kind in (mujoco.mjtGeom.mjGEOM_BOX, mujoco.mjtGeom.mjGEOM_MESH, mujoco.mjtGeom.mjGEOM_SPHERE,
                                  mujoco.mjtGeom.mjGEOM_CYLINDER, mujoco.mjtGeom.mjGEOM_PLANE)}


def _shape_and_size(model: mujoco.MjModel, g: int) -> tuple[str, tuple[float, float, float], str]:
    kind, half = model.geom_type[g], model.geom_size[g]
    if kind == mujoco.mjtGeom.mjGEOM_MESH:
        return "mesh", (1.0, 1.0, 1.0), model.mesh(model.geom_dataid[g]).name
    if kind == mujoco.mjtGeom.mjGEOM_PLANE:
        x, y = (h if h > 0 else FLOOR_HALF_SIZE for h in half[:2])
        return "box", (float(2 * x), float(2 * y), FLOOR_THICKNESS), ""
    if kind == mujoco.mjtGeom.mjGEOM_SPHERE:
        return "sphere", (float(2 * half[0]),) * 3, ""
    if kind == mujoco.mjtGeom.mjGEOM_CYLINDER:
        return "cylinder", (float(2 * half[0]), float(2 * half[0]), float(2 * half[1])), ""
    return "box", tuple(float(2 * h) for h in half), ""


def _scene_blocks(scene: str) -> tuple[str, ...]:
    from semgoal_core.vocabulary import SCENES

    return SCENES[scene].objects


def mesh_stl(model: mujoco.MjModel, name: str) -> bytes:
    """A compiled mesh as binary STL (80-byte header, triangle count, then normal, vertices and a zero
    attribute per triangle), in the frame of the geoms that use it (MuJoCo recentres meshes on compiling)."""
    mesh = model.mesh(name)
    first_vertex, first_face = int(mesh.vertadr[0]), int(mesh.faceadr[0])
    vertices = model.mesh_vert[first_vertex:first_vertex + int(mesh.vertnum[0])]
    faces = model.mesh_face[first_face:first_face + int(mesh.facenum[0])]
    triangles = vertices[faces].astype(np.float32)  # (F, 3, 3)
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0)
    records = np.zeros(len(faces), dtype=[("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])
    records["normal"], records["vertices"] = normals, triangles
    header = f"semgoal mesh {name}".encode().ljust(80, b" ")
    return header + np.uint32(len(faces)).tobytes() + records.tobytes()
