"""The sim node's messages from its world: world and joint states, RViz markers, camera images, and the
expert's view of a world state. What every node reads from a world state is in ``semgoal_ros.messages``."""

from __future__ import annotations

import mujoco
import numpy as np
from builtin_interfaces.msg import Time
from geometry_msgs.msg import Point, TransformStamped, Vector3
from sensor_msgs.msg import CameraInfo, Image, JointState
from visualization_msgs.msg import Marker, MarkerArray

from semgoal_core.expert import WorldView
from semgoal_core.geometry import TABLE_CENTER, TABLE_HALF_SIZE, TABLE_TOP
from semgoal_core.vocabulary import BLOCK_COLOURS, BLOCK_HALF_SIZE, SCENES
from semgoal_msgs.msg import WorldState
from semgoal_ros.messages import block_poses, block_positions, doubles, hands, set_blocks
from semgoal_sim.camera import Frame
from semgoal_sim.world import FetchWorld, Snapshot


def stamp(seconds: float) -> Time:
    """A builtin_interfaces/Time of ``seconds`` (whole nanoseconds, so 0.04 s steps stay exact)."""
    nanoseconds = round(seconds * 1e9)
    return Time(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)


def world_state(world: FetchWorld, snapshot: Snapshot, task: str, episode: int, seed: int = 0,
                clock_s: float | None = None, arm: int = 0) -> WorldState:
    """``clock_s``: the sim clock for the stamp (:attr:`SimCore.clock_s`); else the episode's own time. ``snapshot``:
    arm ``arm``'s (:meth:`FetchWorld.snapshot`), its slice of the world: its hand, its observation, the others'
    hands."""
    msg = WorldState(step=snapshot.step, scene=world.scene.name, task=task, episode=episode, seed=seed)
    msg.header.frame_id = "world"
    msg.header.stamp = stamp(snapshot.time if clock_s is None else clock_s)
    set_blocks(msg, world.blocks, snapshot.block_positions, snapshot.block_quaternions, snapshot.block_velocities)
    g, v = snapshot.grip_position, snapshot.grip_velocity
    msg.gripper_position = Point(x=float(g[0]), y=float(g[1]), z=float(g[2]))
    msg.gripper_velocity = Vector3(x=float(v[0]), y=float(v[1]), z=float(v[2]))
    msg.finger_positions = snapshot.finger_positions.astype(float).tolist()
    msg.finger_velocities = snapshot.finger_velocities.astype(float).tolist()
    if world.scene.bin is not None:
        msg.has_bin = True
        msg.bin_position = Point(x=world.scene.bin.center[0], y=world.scene.bin.center[1], z=TABLE_TOP)
    msg.observation = doubles(world.observation(snapshot, arm))
    msg.other_grippers = [Point(x=float(p[0]), y=float(p[1]), z=float(p[2])) for p, _ in snapshot.other_hands]
    msg.other_finger_openings = [opening for _, opening in snapshot.other_hands]
    msg.arm_contacts = world.arm_contacts
    return msg


def world_view(msg: WorldState) -> WorldView:
    """What the scripted expert reads, from a world state message."""
    positions, present = block_positions(msg)
    scene = SCENES[msg.scene]
    g = msg.gripper_position
    return WorldView({n: p for n, p, here in zip(scene.objects, positions, present, strict=True) if here},
                     np.array([g.x, g.y, g.z]), float(sum(msg.finger_positions)), scene.bin)


def joint_state(world: FetchWorld, snapshot: Snapshot, clock_s: float | None = None) -> JointState:
    positions, velocities = world.robot_joint_state()
    msg = JointState(name=world.robot_joint_names, position=positions.tolist(), velocity=velocities.tolist())
    msg.header.stamp = stamp(snapshot.time if clock_s is None else clock_s)
    return msg


def _cube(marker_id: int, ns: str, position, size, rgba, shape: int = Marker.CUBE) -> Marker:
    marker = Marker(ns=ns, id=marker_id, type=shape, action=Marker.ADD)
    marker.header.frame_id = "world"
    marker.pose.position = Point(x=float(position[0]), y=float(position[1]), z=float(position[2]))
    marker.pose.orientation.w = 1.0
    marker.scale = Vector3(x=float(size[0]), y=float(size[1]), z=float(size[2]))
    marker.color.r, marker.color.g, marker.color.b, marker.color.a = (float(c) for c in rgba)
    return marker


GRIPPER_COLOUR = (0.2, 0.2, 0.25, 0.8)


def markers(msg: WorldState) -> MarkerArray:
    """Table, bin (with its backboard), blocks and the gripper for RViz, after a DELETEALL: a world reset to
    fewer blocks leaves none behind."""
    table = _cube(0, "table", (*TABLE_CENTER, TABLE_TOP / 2), (2 * TABLE_HALF_SIZE[0], 2 * TABLE_HALF_SIZE[1],
                                                                  TABLE_TOP), (0.9, 0.9, 0.9, 1.0))
    items = [Marker(action=Marker.DELETEALL), table]
    scene = SCENES[msg.scene]
    if scene.bin is not None:
        b, colour = scene.bin, (0.45, 0.33, 0.22, 0.6)
        items.append(_cube(0, "bin", (*b.center, TABLE_TOP + b.wall_height / 2),
                           (2 * b.inner_half_size[0], 2 * b.inner_half_size[1], b.wall_height), colour))
        back_y = b.center[1] + b.inner_half_size[1] + b.wall_thickness / 2
        items.append(_cube(1, "bin", (b.center[0], back_y, TABLE_TOP + b.back_wall_height / 2),
                           (2 * b.inner_half_size[0], b.wall_thickness, b.back_wall_height), colour))
    for i, (name, pose) in enumerate(zip(msg.block_names, block_poses(msg), strict=True)):
        items.append(_cube(i, "blocks", pose[:3], (2 * BLOCK_HALF_SIZE,) * 3, BLOCK_COLOURS[name]))
    for i, (grip, opening) in enumerate(hands(msg)):  # a second arm's hand too
        items.append(_cube(i, "gripper", tuple(grip), (0.02, 0.02 + opening, 0.02), GRIPPER_COLOUR, Marker.SPHERE))
    return MarkerArray(markers=items)


def image(frame: np.ndarray, step: int) -> Image:
    """An rgb8 sensor_msgs/Image of a rendered (height, width, 3) uint8 frame; frame_id names the camera."""
    msg = Image(height=frame.shape[0], width=frame.shape[1], encoding="rgb8", step=3 * frame.shape[1])
    msg.header.frame_id = f"sim_camera/step_{step}"
    msg.data = np.ascontiguousarray(frame, dtype=np.uint8).tobytes()
    return msg


WORLD_FRAME = "world"
CAMERA_FRAME = "camera_color_optical_frame"
"""The RGB-D camera's optical frame (REP 103: x right, y down, z ahead); colour and depth share it."""
GRIP_FRAME = "gripper_grip"
"""The grip site between the fingertips: where ``holding`` measures from."""
BASE_FRAME = "base_link"


def rgbd(frame: Frame, clock_s: float) -> tuple[Image, Image, CameraInfo]:
    """Colour (rgb8), depth (32FC1, metres along the optical axis, 0 = no return) and the intrinsics, one stamp."""
    header_stamp = stamp(clock_s)
    height, width = frame.depth.shape
    colour = Image(height=height, width=width, encoding="rgb8", step=3 * width)
    colour.data = np.ascontiguousarray(frame.rgb, dtype=np.uint8).tobytes()
    depth = Image(height=height, width=width, encoding="32FC1", step=4 * width,
                  is_bigendian=int(np.little_endian is False))
    depth.data = np.ascontiguousarray(frame.depth, dtype=np.float32).tobytes()
    k = frame.intrinsics
    info = CameraInfo(height=height, width=width, distortion_model="plumb_bob", d=[0.0] * 5,
                      k=[k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0],
                      r=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                      p=[k.fx, 0.0, k.cx, 0.0, 0.0, k.fy, k.cy, 0.0, 0.0, 0.0, 1.0, 0.0])
    for msg in (colour, depth, info):
        msg.header.stamp, msg.header.frame_id = header_stamp, CAMERA_FRAME
    return colour, depth, info


def transform(child: str, pose: np.ndarray, clock_s: float, parent: str = WORLD_FRAME) -> TransformStamped:
    """A TransformStamped of ``child`` in ``parent`` from a 4x4 pose."""
    msg = TransformStamped(child_frame_id=child)
    msg.header.stamp, msg.header.frame_id = stamp(clock_s), parent
    t = msg.transform.translation
    t.x, t.y, t.z = (float(v) for v in pose[:3, 3])
    quaternion = np.empty(4)
    mujoco.mju_mat2Quat(quaternion, np.ascontiguousarray(pose[:3, :3], dtype=np.float64).reshape(9))
    r = msg.transform.rotation
    r.w, r.x, r.y, r.z = (float(v) for v in quaternion)
    return msg

