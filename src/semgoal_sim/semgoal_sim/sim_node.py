"""sim_node: the MuJoCo Fetch block world on the ROS graph.

Publishes /joint_states, /semgoal/world_state and /semgoal/markers; takes /semgoal/arm_command; serves
/semgoal/reset_world and /semgoal/move_block. In ``lockstep`` mode one command for the step just
published advances one control step (as fast as the graph goes); in ``realtime`` mode a timer steps at
``rate_hz`` with the last good command. With ``arms`` 2 a second Fetch stands across the table: its slice of the
world (its hand, its observation) goes on /semgoal/robot2/world_state and it takes /semgoal/robot2/arm_command; in
lockstep a step waits for both arms' commands. With ``render`` on, an offscreen camera (OSMesa where there
is no GPU) publishes /semgoal/camera/image_raw at ``render_hz``: a picture for people.

With ``camera`` on, the RGB-D sensor (``semgoal_sim.camera``) publishes colour, depth and camera info
under /semgoal/rgbd/ every ``camera_every`` control steps, stamped with the step's sim time, right after
the step's world state; the camera's and the base's frames go on /tf_static (again when an episode's
look moves the camera), the grip site's on /tf each step.

/clock, /joint_states and the markers are built and published only while something listens (a quarter of the
node's work per step is theirs, and a lockstep graph seldom has a viewer); a viewer that joins gets the latest
markers at once.
"""

import functools
import time
from typing import Any

import numpy as np
from rclpy.clock import Clock as TimerClock
from rclpy.clock import ClockType
from rclpy.event_handler import PublisherEventCallbacks
from rclpy.node import Node
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, JointState
from tf2_msgs.msg import TFMessage
from visualization_msgs.msg import MarkerArray

from semgoal_core.arms import MAX_ARMS
from semgoal_core.names import Mode
from semgoal_core.tasks import TASKS
from semgoal_core.vocabulary import SCENES
from semgoal_msgs.msg import ArmCommand, OperatorEvent, WorldState
from semgoal_msgs.srv import MoveBlock, ResetWorld
from semgoal_ros import interfaces as topics
from semgoal_ros import messages
from semgoal_ros.diagnostics import OK, WARN, Counters, Diagnostics
from semgoal_ros.parameters import Param, ParameterValueError, apply_changes, declare
from semgoal_sim import conversions
from semgoal_sim.camera import CONDITIONS, SimCamera
from semgoal_sim.sim_core import SimCore, check_command

WATCHDOG_PERIODS = 5
"""Realtime: control periods without an arm command after which the arm stops moving (0.2 s at 25 Hz)."""

PARAMS = (
    Param("scene", "two_blocks", "the scene to simulate", choices=tuple(SCENES)),
    Param("task", "", f"the task whose start the world takes: {', '.join(TASKS)} (empty: the scene's first)"),
    Param("seed", 0, "initial-state seed of the task", low=0, high=2**31 - 1),
    Param("arms", 1, "robot arms at the table: 2 adds a second Fetch across it (topics under /semgoal/robot2/)",
          low=1, high=MAX_ARMS),
    Param("mode", Mode.LOCKSTEP.value, "lockstep: one step per arm command; realtime: a timer at rate_hz",
          choices=tuple(Mode)),
    Param("rate_hz", 25.0, "control rate in realtime mode (the Fetch benchmark's 25 Hz)", low=0.1, high=1000.0,
          runtime=True),
    Param("markers_every", 5, "publish the RViz markers every N control steps", low=1, high=10_000, runtime=True),
    Param("heartbeat_hz", 2.0, "lockstep: republish a world state that has not moved, for late joiners (0: off)",
          low=0.0, high=100.0),
    Param("render", False, "publish an offscreen camera image on /semgoal/camera/image_raw"),
    Param("render_hz", 5.0, "camera frames per second", low=0.1, high=60.0),
    Param("render_width", 480, "camera image width (px)", low=16, high=4096),
    Param("render_height", 360, "camera image height (px)", low=16, high=4096),
    Param("camera", False, "publish the RGB-D camera (/semgoal/rgbd/...) and the frames on /tf, /tf_static"),
    Param("camera_every", 1, "RGB-D frames every N control steps (1: every step, in lockstep)", low=1, high=10_000),
    Param("camera_width", 160, "RGB-D image width (px)", low=16, high=4096),
    Param("camera_height", 120, "RGB-D image height (px)", low=16, high=4096),
    Param("camera_randomise", 0.0, "strength of the per-episode look randomisation (1: training's range, 0: off)",
          low=0.0, high=2.0),
    Param("camera_condition", "nominal", "the look when not randomised", choices=tuple(CONDITIONS)),
    Param("camera_paused", False, "stop publishing RGB-D frames (a camera fault, for drills and tests)", runtime=True),
)


class SimNode(Node):
    def __init__(self, **options: Any) -> None:
        """``options``: rclpy ``Node``'s (a namespace, parameter overrides: ``graph_node`` composes nodes so)."""
        super().__init__("sim", **options)
        values = declare(self, PARAMS)
        self.mode, self.rate_hz, self.markers_every = values["mode"], values["rate_hz"], values["markers_every"]
        self.render_size = (values["render_width"], values["render_height"])
        try:
            self.core = SimCore(values["scene"], values["task"], values["seed"], values["arms"])
        except ValueError as error:
            raise ParameterValueError(f"sim: {error}") from None
        arms = range(values["arms"])
        self.held_commands = [np.zeros(4) for _ in arms]
        self.command_at = [time.monotonic() for _ in arms]
        """When each arm's last command came (realtime: the watchdog holds an arm still once it is too old)."""
        self.lockstep_commands: dict[int, np.ndarray] = {}
        """Lockstep: the arms' commands for the step just published, until every arm's has come."""
        self.world_pubs = [self.create_publisher(WorldState, topics.arm_topic(topics.WORLD_STATE, arm), topics.RECORDING)
                           for arm in arms]
        self.joint_pub = self.create_publisher(JointState, topics.JOINT_STATES, topics.RECORDING)
        self.state: WorldState | None = None
        """The first arm's world state last published."""
        self.marker_pub = self.create_publisher(MarkerArray, topics.MARKERS, topics.LATCHED,
                                                event_callbacks=PublisherEventCallbacks(matched=self.markers_matched))
        for arm in arms:
            self.create_subscription(ArmCommand, topics.arm_topic(topics.ARM_COMMAND, arm),
                                     functools.partial(self.command_callback, arm=arm), topics.STREAM)
        self.create_service(ResetWorld, topics.RESET_WORLD, self.reset_callback)
        self.create_service(MoveBlock, topics.MOVE_BLOCK, self.move_block_callback)
        self.clock_pub = self.create_publisher(Clock, topics.CLOCK, topics.CLOCK_QOS)
        self.events_pub = self.create_publisher(OperatorEvent, topics.OPERATOR_EVENTS, topics.EVENTS)
        self.renderer = None
        steady = TimerClock(clock_type=ClockType.STEADY_TIME)  # the sim's own timers never wait on its /clock
        if values["render"]:
            self.image_pub = self.create_publisher(Image, topics.CAMERA_IMAGE, topics.CAMERA)
            self.create_timer(1.0 / values["render_hz"], self.publish_image, clock=steady)
        self.camera = None
        if values["camera"]:
            self.camera = SimCamera(values["camera_width"], values["camera_height"], values["camera_randomise"],
                                    values["camera_condition"])
            self.camera_every, self.camera_paused = values["camera_every"], values["camera_paused"]
            self.rgbd_pubs = (self.create_publisher(Image, topics.RGBD_COLOUR, topics.RGBD),
                              self.create_publisher(Image, topics.RGBD_DEPTH, topics.RGBD),
                              self.create_publisher(CameraInfo, topics.RGBD_INFO, topics.RGBD))
            self.tf_pub = self.create_publisher(TFMessage, topics.TF, topics.TF_QOS)
            self.tf_static_pub = self.create_publisher(TFMessage, topics.TF_STATIC, topics.LATCHED)
            self.static_pose: np.ndarray | None = None
        self.timer = None
        if self.mode == Mode.REALTIME:
            self.timer = self.create_timer(1.0 / self.rate_hz, self.realtime_step, clock=steady)
        elif values["heartbeat_hz"] > 0:  # lockstep: a late joiner (or a lost command) would otherwise wait forever
            self.create_timer(1.0 / values["heartbeat_hz"], self.heartbeat, clock=steady)
        self.counters = Counters()
        self.last_step_at: float | None = None
        self.reported_ticks = (self.core.ticks, time.monotonic())
        self.diagnostics = Diagnostics(self, self.health)
        self.heartbeat_step = -1
        apply_changes(self, PARAMS, self.apply_parameter)
        self.publish_state()
        self.get_logger().info(f"{values['scene']} ready: task {self.core.task}, seed {self.core.seed}, {self.mode} mode")

    def apply_parameter(self, name: str, value) -> None:
        """Put a change made while running into effect: the realtime rate, the markers' period."""
        if name == "markers_every":
            self.markers_every = value
        elif name == "camera_paused":
            self.camera_paused = value
        elif name == "rate_hz":
            self.rate_hz = value
            if self.timer is not None:
                self.timer.timer_period_ns = int(1e9 / value)

    def health(self):
        """Steps per second since the last report, late realtime steps, dropped and clamped commands."""
        ticks, at = self.core.ticks, time.monotonic()
        rate = (ticks - self.reported_ticks[0]) / max(at - self.reported_ticks[1], 1e-9)
        late_share = self.counters["late steps"] / max(self.counters["realtime steps"], 1)
        self.reported_ticks = (ticks, at)
        level = WARN if self.mode == Mode.REALTIME and late_share > 0.1 else OK
        message = f"{rate:.1f} steps/s in {self.mode} mode" + (f", {late_share:.0%} of steps late" if level == WARN else "")
        return level, message, {"steps per second": round(rate, 1), "control step": self.core.world.step_count,
                                "episode": self.core.episode, "sim time s": round(self.core.clock_s, 2), **self.counters}

    def publish_state(self) -> WorldState:
        """The world state (each arm's slice on its topic); returns the first arm's."""
        snapshot = self.core.snapshot()
        clock_s = self.core.clock_s
        msg = conversions.world_state(self.core.world, snapshot, self.core.task, self.core.episode, self.core.seed,
                                      clock_s)
        self.state = msg
        if self.clock_pub.get_subscription_count():
            self.clock_pub.publish(Clock(clock=msg.header.stamp))
        self.world_pubs[0].publish(msg)
        for arm, publisher in enumerate(self.world_pubs[1:], start=1):
            publisher.publish(conversions.world_state(self.core.world, self.core.snapshot(arm), self.core.task,
                                                      self.core.episode, self.core.seed, clock_s, arm))
        if self.joint_pub.get_subscription_count():
            self.joint_pub.publish(conversions.joint_state(self.core.world, snapshot, clock_s))
        if snapshot.step % max(1, self.markers_every) == 0 and self.marker_pub.get_subscription_count():
            self.marker_pub.publish(conversions.markers(msg))
        if self.camera is not None:
            self.publish_camera(snapshot, clock_s)
        return msg

    def markers_matched(self, status) -> None:
        """A viewer joined the markers: it gets the latest world's within a second (the executor's event poll), not
        at the next period's step."""
        if status.current_count_change > 0 and self.state is not None:
            self.marker_pub.publish(conversions.markers(self.state))

    def publish_camera(self, snapshot, clock_s: float) -> None:
        """The grip site on /tf every step; an RGB-D frame every ``camera_every`` steps (and the camera's
        frame on /tf_static when it moved: a new episode's look)."""
        world = self.core.world
        self.tf_pub.publish(TFMessage(transforms=[conversions.transform(conversions.GRIP_FRAME, world.grip_pose(), clock_s)]))
        if snapshot.step % self.camera_every or self.camera_paused:
            return
        frame = self.camera.frame(world, self.core.episode, self.core.seed)
        if self.static_pose is None or not np.array_equal(frame.world_from_camera, self.static_pose):
            self.static_pose = frame.world_from_camera
            self.tf_static_pub.publish(TFMessage(transforms=[
                conversions.transform(conversions.BASE_FRAME, world.base_pose(), clock_s),
                conversions.transform(conversions.CAMERA_FRAME, frame.world_from_camera, clock_s)]))
        for publisher, msg in zip(self.rgbd_pubs, conversions.rgbd(frame, clock_s), strict=True):
            publisher.publish(msg)

    def publish_image(self) -> None:
        """Render the current world (a reset may have built another one) and publish the frame."""
        from semgoal_sim.render import FrameRenderer

        if self.renderer is None or self.renderer.world is not self.core.world:
            if self.renderer is not None:
                self.renderer.close()
            self.renderer = FrameRenderer(self.core.world, *self.render_size)
        self.image_pub.publish(conversions.image(self.renderer.frame(), self.core.world.step_count))

    def command_callback(self, msg: ArmCommand, arm: int = 0) -> None:
        values = [msg.displacement.x, msg.displacement.y, msg.displacement.z, msg.gripper]
        if self.mode == Mode.LOCKSTEP and msg.step != self.core.world.step_count:
            self.get_logger().warn(f"dropped a stale command for step {msg.step} (now at {self.core.world.step_count})",
                                   throttle_duration_sec=1.0)
            self.counters["stale commands dropped"] += 1
            return
        check = check_command(values)
        if check.warning:
            self.get_logger().warn(check.warning, throttle_duration_sec=1.0)
            self.counters["bad commands dropped" if check.action is None else "commands clamped"] += 1
        if check.action is None:
            return
        if self.mode == Mode.REALTIME:
            self.held_commands[arm], self.command_at[arm] = check.action, time.monotonic()
            return
        self.lockstep_commands[arm] = check.action
        if len(self.lockstep_commands) == len(self.held_commands):
            self.core.step_arms([self.lockstep_commands[a] for a in range(len(self.held_commands))])
            self.lockstep_commands.clear()
            self.publish_state()

    def heartbeat(self) -> None:
        """Republish the world state when lockstep has not moved since the last heartbeat."""
        if self.core.world.step_count == self.heartbeat_step:
            self.publish_state()
        self.heartbeat_step = self.core.world.step_count

    def realtime_step(self) -> None:
        """One step on the timer; a step more than half a period after its time counts as late."""
        now = time.monotonic()
        if self.last_step_at is not None and now - self.last_step_at > 1.5 / self.rate_hz:
            self.counters["late steps"] += 1
        self.last_step_at = now
        self.counters["realtime steps"] += 1
        for arm, held in enumerate(self.held_commands):
            if now - self.command_at[arm] > WATCHDOG_PERIODS / self.rate_hz and held[:3].any():
                # no command for a while (the policy died or stalls): stop moving, keep the fingers' command so
                # that a held block stays held
                self.held_commands[arm] = np.array([0.0, 0.0, 0.0, held[3]])
                self.counters["watchdog stops"] += 1
                self.get_logger().warn(f"no command for arm {arm + 1} for {WATCHDOG_PERIODS} periods: holding it still")
        self.core.step_arms(self.held_commands)
        self.publish_state()

    def report(self, kind: str, request: str, success: bool, message: str) -> None:
        """Log the answer to an operator's request and put it on the operator events (a recording keeps it)."""
        if success:
            self.get_logger().info(message)
        else:
            self.get_logger().warning(message)
        event = OperatorEvent(kind=kind, request=request, accepted=success, answer=message)
        event.header.stamp = conversions.stamp(self.core.clock_s)
        self.events_pub.publish(event)

    def reset_callback(self, request: ResetWorld.Request, response: ResetWorld.Response) -> ResetWorld.Response:
        response.success, response.message = self.core.reset(request.task, request.seed, request.positions)
        given = f" from {len(request.positions) // 3} positions" if len(request.positions) else ""
        self.report(OperatorEvent.KIND_RESET, f"{request.task} seed {request.seed}{given}", response.success, response.message)
        self.held_commands = [np.zeros(4) for _ in self.held_commands]
        self.command_at = [time.monotonic() for _ in self.command_at]
        self.lockstep_commands.clear()
        response.world = self.publish_state()
        response.state = messages.semantic_state(response.world, messages.semantic_vector(response.world))
        return response

    def move_block_callback(self, request: MoveBlock.Request, response: MoveBlock.Response) -> MoveBlock.Response:
        p = request.position
        response.success, response.message = self.core.move_block(request.block, np.array([p.x, p.y, p.z]))
        self.report(OperatorEvent.KIND_MOVE, f"{request.block} to ({p.x:.3f}, {p.y:.3f}, {p.z:.3f})",
                    response.success, response.message)
        response.world = self.publish_state()
        return response


def main(args: list[str] | None = None) -> None:
    topics.run_node(SimNode, args)
