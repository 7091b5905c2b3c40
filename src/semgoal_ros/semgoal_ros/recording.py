"""Every topic of the graph into an MCAP file that `ros2 bag info` / `ros2 bag play` and Foxglove open: CDR
payloads exactly as rclpy serialised them (raw subscriptions: nothing is decoded or re-encoded here) and a
``ros2msg`` schema per type, built from the installed ``.msg`` files. Written with the ``mcap`` library.

A :class:`Recorder` rides on a client's node (the demo's, the evaluation's), so it spins with it; spin until
:meth:`Recorder.matched` before the episode starts (``GraphClient.recording`` does both).
"""

from __future__ import annotations

import functools
import importlib
import json
import re
import shlex
import struct
import sys
import time
from pathlib import Path

from mcap.writer import CompressionType, Writer
from rclpy.qos import DurabilityPolicy, QoSProfile

from semgoal_core.provenance import provenance
from semgoal_ros import interfaces as topics
from semgoal_ros.package_data import share_path

SEPARATOR = "=" * 80
PRIMITIVES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32", "uint32",
              "int64", "uint64", "string", "wstring"}


ALWAYS_PUBLISHED = (topics.WORLD_STATE, topics.JOINT_STATES, topics.SEMANTIC_STATE, topics.SUBGOAL, topics.PLAN,
                    topics.ARM_COMMAND, topics.CLOCK)
"""Topics the four nodes publish in every episode (the camera, goals and markers come and go)."""


def recorded_topics(session: bool = False) -> list[tuple[str, str, QoSProfile]]:
    """(topic, type name, QoS of the recording reader) of everything the graph says; a ``session`` recording
    also takes the operator events the graph published before it matched (:data:`~semgoal_ros.interfaces.EVENTS`),
    an episode's only those from its start."""
    latched = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    return [
        (topics.WORLD_STATE, "semgoal_msgs/msg/WorldState", topics.RECORDING),
        (topics.JOINT_STATES, "sensor_msgs/msg/JointState", topics.RECORDING),
        (topics.SEMANTIC_STATE, "semgoal_msgs/msg/SemanticState", latched),
        (topics.SUBGOAL, "semgoal_msgs/msg/SubGoal", latched),
        (topics.PLAN, "semgoal_msgs/msg/Plan", latched),
        (topics.ARM_COMMAND, "semgoal_msgs/msg/ArmCommand", topics.RECORDING),
        (topics.GOAL, "semgoal_msgs/msg/GoalRequest", topics.RECORDING),
        (topics.OPERATOR_EVENTS, "semgoal_msgs/msg/OperatorEvent", topics.EVENTS if session else topics.EVENTS_LIVE),
        (topics.MARKERS, "visualization_msgs/msg/MarkerArray", latched),
        (topics.PLAN_MARKERS, "visualization_msgs/msg/MarkerArray", latched),
        (topics.CLOCK, "rosgraph_msgs/msg/Clock", topics.RECORDING),
        (topics.CAMERA_IMAGE, "sensor_msgs/msg/Image", topics.CAMERA),
        ("/diagnostics", "diagnostic_msgs/msg/DiagnosticArray", topics.RECORDING),
        (topics.RGBD_COLOUR, "sensor_msgs/msg/Image", topics.RECORDING),
        (topics.RGBD_DEPTH, "sensor_msgs/msg/Image", topics.RECORDING),
        (topics.RGBD_INFO, "sensor_msgs/msg/CameraInfo", topics.RECORDING),
        (topics.BLOCK_ESTIMATES, "semgoal_msgs/msg/BlockEstimates", topics.RECORDING),
        (topics.TF, "tf2_msgs/msg/TFMessage", topics.RECORDING),
        (topics.TF_STATIC, "tf2_msgs/msg/TFMessage", latched),
        # the second arm's slice, sub-goal and commands (a graph with robots 2)
        (topics.arm_topic(topics.WORLD_STATE, 1), "semgoal_msgs/msg/WorldState", topics.RECORDING),
        (topics.arm_topic(topics.SUBGOAL, 1), "semgoal_msgs/msg/SubGoal", latched),
        (topics.arm_topic(topics.ARM_COMMAND, 1), "semgoal_msgs/msg/ArmCommand", topics.RECORDING),
    ]


CAMERA_RECORD_PERIOD_S = 0.2
"""The RGB-D frames are recorded at 5 Hz of sim time (every fifth control step), not at the 25 Hz they come:
colour, depth and info of the same instants, a fifth of the file."""
DECIMATED = (topics.RGBD_COLOUR, topics.RGBD_DEPTH, topics.RGBD_INFO)


def stamp_of(cdr: bytes) -> float:
    """The header stamp (s) of a serialised message that starts with a std_msgs/Header: after the 4-byte CDR
    encapsulation (its second byte 1 for little-endian, 0 for big) come its int32 sec and uint32 nanosec."""
    sec, nanosec = struct.unpack_from("<iI" if cdr[1] else ">iI", cdr, 4)
    return sec + nanosec * 1e-9


def kept(topic: str, cdr: bytes) -> bool:
    """Whether a recording keeps this message (the camera's only at :data:`CAMERA_RECORD_PERIOD_S` instants)."""
    if topic not in DECIMATED:
        return True
    ticks = stamp_of(cdr) / CAMERA_RECORD_PERIOD_S
    return abs(ticks - round(ticks)) < 1e-6


@functools.cache
def message_definition(type_name: str) -> str:
    """The ``ros2msg`` schema text of ``pkg/msg/Type``: its .msg file, then every type it uses, each after a
    separator line and ``MSG: pkg/Type`` (the layout rosbag2 writes). Read once per process: a recorder per
    episode (``eval --via-ros --record``) reuses it."""
    package, _, name = type_name.split("/")
    text = _msg_file(package, name)
    seen, parts, queue = {f"{package}/{name}"}, [], _used_types(text, package)
    while queue:
        used = queue.pop(0)
        if used in seen:
            continue
        seen.add(used)
        used_package, used_name = used.split("/")
        used_text = _msg_file(used_package, used_name)
        parts.append(f"{SEPARATOR}\nMSG: {used}\n{used_text}")
        queue += _used_types(used_text, used_package)
    return "\n".join([text, *parts])


def message_type(type_name: str) -> type:
    """The Python class of ``pkg/msg/Type``."""
    package, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), name)


def _msg_file(package: str, name: str) -> str:
    return share_path(package, "msg", f"{name}.msg").read_text().rstrip("\n")


def _used_types(text: str, package: str) -> list[str]:
    """``pkg/Type`` of every non-primitive field of a .msg text (a bare ``Type`` is of the same package)."""
    used = []
    for line in text.splitlines():
        tokens = line.split("#", 1)[0].split()
        if len(tokens) < 2 or "=" in tokens[1]:  # blank, or a constant (always a primitive)
            continue
        base = re.sub(r"(\[.*\]|<=\d+)$", "", tokens[0])
        if base not in PRIMITIVES:
            used.append(base if "/" in base else f"{package}/{base}")
    return used


class Recorder:
    """Writes every message of :func:`recorded_topics` that ``node`` receives to ``path`` until :meth:`close`
    (``session``: the whole run of a graph, as ``record_node`` writes it)."""

    def __init__(self, node, path: Path | str, session: bool = False) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.file = self.path.open("wb")
        self.writer = Writer(self.file, compression=CompressionType.LZ4)
        self.writer.start(profile="ros2", library="semgoal")
        record = provenance(shlex.join(sys.argv))
        self.writer.add_metadata("provenance", {key: json.dumps(value) if isinstance(value, dict) else str(value)
                                                for key, value in record.items()})
        self.counts: dict[str, int] = {}
        self.subscriptions = []
        schemas: dict[str, int] = {}
        for topic, type_name, qos in recorded_topics(session):
            if type_name not in schemas:
                schemas[type_name] = self.writer.register_schema(type_name, "ros2msg", message_definition(type_name).encode())
            channel = self.writer.register_channel(topic, "cdr", schemas[type_name])
            self.counts[topic] = 0
            self.subscriptions.append(node.create_subscription(
                message_type(type_name), topic, lambda data, c=channel, t=topic: self._write(c, t, data), qos, raw=True))
        self.node = node

    def matched(self) -> bool:
        """Whether every publisher the graph knows on a recorded topic, and at least one on each topic that a
        running graph always publishes (:data:`ALWAYS_PUBLISHED`), has matched its recording reader: a reader
        created just before an episode would otherwise miss its first messages while discovery runs."""
        return all(sub.get_publisher_count() >= max(int(sub.topic_name in ALWAYS_PUBLISHED),
                                                     self.node.count_publishers(sub.topic_name))
                   for sub in self.subscriptions)

    def _write(self, channel: int, topic: str, data: bytes) -> None:
        if not kept(topic, data):
            return
        now = time.time_ns()
        self.writer.add_message(channel, log_time=now, data=data, publish_time=now, sequence=self.counts[topic])
        self.counts[topic] += 1

    def close(self) -> dict[str, int]:
        """Finish the file (once); the messages written per topic."""
        if not self.file.closed:
            for subscription in self.subscriptions:
                self.node.destroy_subscription(subscription)
            self.writer.finish()
            self.file.close()
        return self.counts
