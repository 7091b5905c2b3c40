"""perception_node: the RGB-D camera in, the blocks it sees and the semantic state out (a drop-in for
predicate_node: the planner and the console do not know which one runs).

Takes colour, depth and camera info (synchronised by stamp), the camera's pose from /tf_static, and the
world state's proprioception and bookkeeping (grip site, fingers, scene, task, episode, step), never its
block poses. Publishes, per frame:
- /semgoal/perception/blocks (BlockEstimates): centre, velocity, covariance and status of every block;
- /semgoal/semantic_state (SemanticState): the predicates on the estimates, with a confidence per literal;
- /semgoal/perception/world_state (WorldState): the world state with the estimated blocks and the policy's
  observation rebuilt from them (what the policy reads with ``--policy-input camera``); with ``arms`` 2, the second
  arm's on /semgoal/robot2/perception/world_state, from its own slice of the world at the frame's instant.

A frame of the wrong size, encoding or stamp is refused and counted, never a crash. When no whole frame
has come for longer than ``stale_after_s`` while world states do, each world state gets a semantic state
from the tracks as they stand, marked stale with the reason (the planner pauses the plan until a current
one comes), and /diagnostics reports it.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np
from rclpy.node import Node
from sensor_msgs.msg import CameraInfo, Image
from tf2_msgs.msg import TFMessage

from semgoal_core.arms import MAX_ARMS, arm_observation
from semgoal_core.tasks import ALL_TASKS, get_task
from semgoal_core.vocabulary import LAYOUTS, SCENES
from semgoal_msgs.msg import BlockEstimate, BlockEstimates, SemanticState, WorldState
from semgoal_perception.estimator import BlockEstimator
from semgoal_perception.geometry import PinholeCamera
from semgoal_perception.perceiver import ArmState, Perceiver, Perception
from semgoal_ros import interfaces as topics
from semgoal_ros.diagnostics import OK, WARN, Counters, Diagnostics, Latencies
from semgoal_ros.messages import doubles, hands, semantic_message, set_blocks
from semgoal_ros.parameters import Param, ParameterValueError, declare

CAMERA_FRAME = "camera_color_optical_frame"
PARAMS = (
    Param("model_dir", "", "an exported block voter's folder (empty: the shipped one)"),
    Param("stale_after_s", 1.0, "no frame for this long (wall time) is reported on /diagnostics", low=0.05, high=60.0),
    Param("threads", 1, "torch threads for the voter", low=1, high=64),
    Param("arms", 1, "robot arms at the table: with 2 the second arm's world state as the camera sees it too "
          "(/semgoal/robot2/perception/world_state, for its policy)", low=1, high=MAX_ARMS),
)
STALE_WORLD_STATES = 3
"""World states that must come without a whole frame (besides ``stale_after_s`` of wall time) before the state
is stale: on a loaded machine a frame may follow its world state late, never by three."""
PENDING_KEPT = 16
"""Frames, camera infos and world states kept while their partners are on the way."""


def image_array(msg: Image, encoding: str, channels: int, dtype: np.dtype) -> np.ndarray:
    """The pixels of ``msg``; ValueError (with the reason) unless it has ``encoding`` and a consistent size."""
    if msg.encoding != encoding:
        raise ValueError(f"encoding {msg.encoding!r}, expected {encoding!r}")
    item = np.dtype(dtype).itemsize * channels
    if msg.width == 0 or msg.height == 0 or msg.step != msg.width * item or len(msg.data) != msg.height * msg.step:
        raise ValueError(f"{msg.width}x{msg.height} step {msg.step} with {len(msg.data)} bytes is not a whole {encoding} image")
    array = np.frombuffer(bytes(msg.data), dtype=np.dtype(dtype).newbyteorder(">" if msg.is_bigendian else "<"))
    return array.reshape(msg.height, msg.width, channels) if channels > 1 else array.reshape(msg.height, msg.width)


def pose_matrix(transform) -> np.ndarray:
    """4x4 of a geometry_msgs/Transform."""
    q = transform.rotation
    w, x, y, z = q.w, q.x, q.y, q.z
    norm = np.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / norm, x / norm, y / norm, z / norm
    pose = np.eye(4)
    pose[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                    [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    t = transform.translation
    pose[:3, 3] = (t.x, t.y, t.z)
    return pose


def stamp_key(header) -> int:
    return header.stamp.sec * 1_000_000_000 + header.stamp.nanosec


class PerceptionNode(Node):
    def __init__(self, **options: Any) -> None:
        """``options``: rclpy ``Node``'s (a namespace, parameter overrides: ``graph_node`` composes nodes so)."""
        super().__init__("perception", **options)
        values = declare(self, PARAMS)
        import torch

        from semgoal_ros.package_data import share_path

        torch.set_num_threads(values["threads"])
        folder = Path(values["model_dir"]) if values["model_dir"] else share_path("semgoal_perception", "models", "block_voter")
        try:
            self.perceiver = Perceiver(BlockEstimator.load(folder))
        except (FileNotFoundError, RuntimeError, KeyError) as error:
            raise ParameterValueError(f"perception: no usable block voter in {folder}: {error}") from None
        self.stale_after_s = values["stale_after_s"]
        self.semantic_pub = self.create_publisher(SemanticState, topics.SEMANTIC_STATE, topics.PER_STEP)
        self.blocks_pub = self.create_publisher(BlockEstimates, topics.BLOCK_ESTIMATES, topics.RECORDING)
        self.world_pub = self.create_publisher(WorldState, topics.PERCEIVED_WORLD, topics.RECORDING)
        self.create_subscription(Image, topics.RGBD_COLOUR, lambda m: self.pending_in("colour", m), topics.RGBD)
        self.create_subscription(Image, topics.RGBD_DEPTH, lambda m: self.pending_in("depth", m), topics.RGBD)
        self.create_subscription(CameraInfo, topics.RGBD_INFO, lambda m: self.pending_in("info", m), topics.RGBD)
        self.create_subscription(WorldState, topics.WORLD_STATE, lambda m: self.pending_in("world", m), topics.STREAM)
        self.create_subscription(TFMessage, topics.TF_STATIC, self.tf_static_callback, topics.LATCHED)
        self.pending: dict[int, dict[str, object]] = {}
        self.other_arms = [(self.create_publisher(WorldState, topics.arm_topic(topics.PERCEIVED_WORLD, arm), topics.RECORDING),
                            {}) for arm in range(1, values["arms"])]
        """Per other arm: its perceived world state's publisher, and its world states waiting for their frame."""
        for arm in range(1, values["arms"]):
            self.create_subscription(WorldState, topics.arm_topic(topics.WORLD_STATE, arm),
                                     lambda m, arm=arm: self.other_arm_in(arm, m), topics.STREAM)
        self.seen_at: dict[int, Perception] = {}
        """The last frames' perceptions by their stamp: an other arm's world state of that instant is seen by them."""
        self.camera_pose: np.ndarray | None = None
        self.last_frame_at: float | None = None
        self.worlds_unseen = 0
        """World states that came since the last whole frame."""
        self.counters, self.latency = Counters(), Latencies()
        self.diagnostics = Diagnostics(self, self.health)
        self.get_logger().info(f"block voter from {folder}")

    def health(self):
        if self.last_frame_at is None:
            return WARN, "no camera frame yet", dict(self.counters)
        age = time.monotonic() - self.last_frame_at
        values = {"last frame age s": round(age, 2), **self.latency.summary("frame"), **self.counters}
        if age > self.stale_after_s:
            return WARN, f"no camera frame for {age:.1f} s: the semantic state is stale", values
        return OK, "seeing", values

    def tf_static_callback(self, msg: TFMessage) -> None:
        for transform in msg.transforms:
            if transform.child_frame_id == CAMERA_FRAME:
                self.camera_pose = pose_matrix(transform.transform)

    def blind_for(self) -> float | None:
        """Seconds since the last whole frame, when that is longer than ``stale_after_s`` and
        :data:`STALE_WORLD_STATES` world states came since; else None."""
        if self.last_frame_at is None or self.perceiver.tracker is None or self.worlds_unseen < STALE_WORLD_STATES:
            return None
        age = time.monotonic() - self.last_frame_at
        return age if age > self.stale_after_s else None

    def pending_in(self, kind: str, msg) -> None:
        """Keep ``msg`` until the frame with its stamp is whole (colour, depth, info, world state), then see it."""
        if kind == "world":
            self.worlds_unseen += 1
            if (age := self.blind_for()) is not None:
                self.publish_stale(msg, f"no camera frame for {age:.1f} s")
        key = stamp_key(msg.header)
        parts = self.pending.setdefault(key, {})
        parts[kind] = msg
        if len(parts) == 4:
            del self.pending[key]
            self.see(parts)
        while len(self.pending) > PENDING_KEPT:
            del self.pending[min(self.pending)]
            self.counters["unmatched messages dropped"] += 1

    def see(self, parts: dict) -> None:
        started = time.perf_counter()
        world: WorldState = parts["world"]
        try:
            rgb = image_array(parts["colour"], "rgb8", 3, np.uint8)
            depth = image_array(parts["depth"], "32FC1", 1, np.float32)
            camera = self.pinhole(parts["info"], rgb.shape[:2], depth.shape)
            task = get_task(world.task) if world.task in ALL_TASKS else None
            if world.scene not in LAYOUTS or task is None or task.scene != world.scene:
                raise ValueError(f"world state of scene {world.scene!r}, task {world.task!r}: not a known task of the scene")
            self.perceiver.estimator.check_blocks(task.blocks)
        except ValueError as error:
            self.counters["frames refused"] += 1
            self.get_logger().warn(f"refused a camera frame: {error}", throttle_duration_sec=2.0)
            return
        self.last_frame_at, self.worlds_unseen = time.monotonic(), 0
        arm = self.arm_state(world)
        blocks = task.blocks
        seen = self.perceiver.perceive(rgb, depth, camera, arm, world.scene, blocks, (world.episode, world.seed), world.step,
                                       hands(world)[1:])
        latency_ms = 1e3 * (time.perf_counter() - started)
        self.latency.seconds.append(latency_ms / 1e3)
        self.semantic_pub.publish(self.semantic_state(world, seen))
        self.blocks_pub.publish(self.estimates(world, seen, latency_ms))
        self.world_pub.publish(self.perceived_world(world, seen, arm))
        self.counters["frames seen"] += 1
        if self.other_arms:
            key = stamp_key(world.header)
            self.seen_at[key] = seen
            while len(self.seen_at) > PENDING_KEPT:
                del self.seen_at[min(self.seen_at)]
            for publisher, waiting in self.other_arms:
                if (other := waiting.pop(key, None)) is not None:
                    publisher.publish(self.perceived_world(other, seen, self.arm_state(other)))

    def other_arm_in(self, arm: int, world: WorldState) -> None:
        """Another arm's slice of the world: as the camera sees it at that instant once its frame is seen (now, if it
        was); while the camera is blind, the tracks as they stand, marked by the first arm's stale semantic state."""
        publisher, waiting = self.other_arms[arm - 1]
        key = stamp_key(world.header)
        if (seen := self.seen_at.get(key)) is None and self.blind_for() is not None and self._same_episode(world):
            seen = self.perceiver.read_out(world.scene, get_task(world.task).blocks, self.arm_state(world),
                                           hands(world)[1:])
        if seen is not None:
            publisher.publish(self.perceived_world(world, seen, self.arm_state(world)))
            return
        waiting[key] = world
        while len(waiting) > PENDING_KEPT:
            del waiting[min(waiting)]
            self.counters["unmatched messages dropped"] += 1

    def _same_episode(self, world: WorldState) -> bool:
        """Whether ``world`` is of the episode the camera has tracks of (a new one it has not seen: nothing to hold)."""
        return (world.scene in LAYOUTS and world.task in ALL_TASKS and self.perceiver.episode is not None
                and self.perceiver.episode == (world.scene, get_task(world.task).blocks, (world.episode, world.seed)))

    def publish_stale(self, world: WorldState, reason: str) -> None:
        """The tracks as they stand, for a world state the camera did not see, marked stale with ``reason``."""
        if not self._same_episode(world):
            return
        blocks = get_task(world.task).blocks
        arm = self.arm_state(world)
        seen = self.perceiver.read_out(world.scene, blocks, arm, hands(world)[1:])
        state = self.semantic_state(world, seen)
        state.stale = reason
        self.semantic_pub.publish(state)
        self.world_pub.publish(self.perceived_world(world, seen, arm))
        self.counters["stale states"] += 1
        self.get_logger().warn(f"{reason}: the semantic state is stale", throttle_duration_sec=2.0)

    @staticmethod
    def arm_state(world: WorldState) -> ArmState:
        return ArmState(np.array([world.gripper_position.x, world.gripper_position.y, world.gripper_position.z]),
                        np.array([world.gripper_velocity.x, world.gripper_velocity.y, world.gripper_velocity.z]),
                        np.array(world.finger_positions), np.array(world.finger_velocities))

    def pinhole(self, info: CameraInfo, colour_shape: tuple, depth_shape: tuple) -> PinholeCamera:
        if self.camera_pose is None:
            raise ValueError(f"no pose of {CAMERA_FRAME} on /tf_static yet")
        if colour_shape != depth_shape or (info.height, info.width) != tuple(colour_shape):
            raise ValueError(f"colour {colour_shape}, depth {depth_shape} and camera info {(info.height, info.width)} differ in size")
        fx, fy, cx, cy = info.k[0], info.k[4], info.k[2], info.k[5]
        if not (np.isfinite([fx, fy, cx, cy]).all() and fx > 0 and fy > 0):
            raise ValueError(f"camera info intrinsics fx {fx}, fy {fy}, cx {cx}, cy {cy} are not a camera's")
        return PinholeCamera(fx, fy, cx, cy, self.camera_pose)

    @staticmethod
    def semantic_state(world: WorldState, seen: Perception) -> SemanticState:
        return semantic_message(world, seen.blocks, seen.vector, seen.fallen, seen.moving, seen.confidence)

    @staticmethod
    def estimates(world: WorldState, seen: Perception, latency_ms: float) -> BlockEstimates:
        msg = BlockEstimates(scene=world.scene, step=world.step, episode=world.episode, latency_ms=latency_ms)
        msg.header.stamp, msg.header.frame_id = world.header.stamp, "world"
        for name, track in zip(seen.blocks, seen.tracks, strict=True):
            estimate = BlockEstimate(name=name, status=int(track.status), pixels=track.pixels, unseen_frames=track.unseen,
                                     position_covariance=np.diag(track.sigma ** 2).reshape(9).tolist())
            estimate.position.x, estimate.position.y, estimate.position.z = (float(v) for v in track.position)
            estimate.velocity.x, estimate.velocity.y, estimate.velocity.z = (float(v) for v in track.velocity)
            msg.blocks.append(estimate)
        return msg

    @staticmethod
    def perceived_world(world: WorldState, seen: Perception, arm: ArmState) -> WorldState:
        """The world state as the camera sees it: the arms' own fields, the estimated blocks and the
        observation rebuilt from them."""
        msg = WorldState(header=world.header, step=world.step, scene=world.scene, task=world.task,
                         episode=world.episode, seed=world.seed, gripper_position=world.gripper_position,
                         gripper_velocity=world.gripper_velocity, finger_positions=world.finger_positions,
                         finger_velocities=world.finger_velocities, has_bin=world.has_bin, bin_position=world.bin_position,
                         other_grippers=world.other_grippers, other_finger_openings=world.other_finger_openings,
                         arm_contacts=world.arm_contacts)
        slots = [SCENES[world.scene].objects.index(name) for name in seen.blocks]
        unturned, unspun = np.tile([1.0, 0.0, 0.0, 0.0], (len(slots), 1)), np.zeros((len(slots), 3))
        set_blocks(msg, seen.blocks, seen.positions[slots], unturned, np.hstack([seen.velocities[slots], unspun]))
        msg.observation = doubles(arm_observation(
            world.scene, arm.grip_position, arm.grip_velocity, arm.finger_positions, arm.finger_velocities,
            seen.positions[seen.present], seen.velocities[seen.present], hands(world)[1:]))
        return msg


def main(args: list[str] | None = None) -> None:
    topics.run_node(PerceptionNode, args)
