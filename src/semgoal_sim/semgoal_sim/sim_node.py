"""sim_node: the MuJoCo Fetch block world on the ROS graph.

Publishes /joint_states, /semgoal/world_state and /semgoal/markers; takes /semgoal/arm_command; serves
/semgoal/reset_world and /semgoal/move_block. In ``lockstep`` mode one command for the step just
published advances one control step (as fast as the graph goes); in ``realtime`` mode a timer steps at
``rate_hz`` with the last good command. With ``render`` on, an offscreen camera (OSMesa where there
is no GPU) publishes /semgoal/camera/image_raw at ``render_hz``.
"""

import numpy as np
from rcl_interfaces.msg import SetParametersResult
from rclpy.node import Node
from sensor_msgs.msg import Image, JointState
from visualization_msgs.msg import MarkerArray

from semgoal_msgs.msg import ArmCommand, WorldState
from semgoal_msgs.srv import MoveBlock, ResetWorld
from semgoal_ros import interfaces as topics
from semgoal_ros import messages
from semgoal_sim import conversions
from semgoal_sim.sim_core import SimCore, check_command

MODES = ("lockstep", "realtime")


class SimNode(Node):
    def __init__(self) -> None:
        super().__init__("sim")
        scene = self.declare_parameter("scene", "two_blocks").value
        task = self.declare_parameter("task", "").value
        seed = self.declare_parameter("seed", 0).value
        self.mode = self.declare_parameter("mode", "lockstep").value
        self.rate_hz = self.declare_parameter("rate_hz", 25.0).value
        self.markers_every = self.declare_parameter("markers_every", 5).value
        heartbeat_hz = self.declare_parameter("heartbeat_hz", 2.0).value
        render = self.declare_parameter("render", False).value
        render_hz = self.declare_parameter("render_hz", 5.0).value
        self.render_size = (self.declare_parameter("render_width", 480).value,
                            self.declare_parameter("render_height", 360).value)
        if self.mode not in MODES:
            raise ValueError(f"mode must be one of {MODES}, got {self.mode!r}")
        self.core = SimCore(scene, task, seed)
        self.held_command = np.zeros(4)
        self.world_pub = self.create_publisher(WorldState, topics.WORLD_STATE, topics.STREAM)
        self.joint_pub = self.create_publisher(JointState, topics.JOINT_STATES, topics.STREAM)
        self.marker_pub = self.create_publisher(MarkerArray, topics.MARKERS, topics.LATCHED)
        self.create_subscription(ArmCommand, topics.ARM_COMMAND, self.command_callback, topics.STREAM)
        self.create_service(ResetWorld, topics.RESET_WORLD, self.reset_callback)
        self.create_service(MoveBlock, topics.MOVE_BLOCK, self.move_block_callback)
        self.add_on_set_parameters_callback(self.parameters_callback)
        self.renderer = None
        if render:
            self.image_pub = self.create_publisher(Image, topics.CAMERA_IMAGE, topics.CAMERA)
            self.create_timer(1.0 / render_hz, self.publish_image)
        if self.mode == "realtime":
            self.timer = self.create_timer(1.0 / self.rate_hz, self.realtime_step)
        elif heartbeat_hz > 0:  # lockstep: a late joiner (or a lost command) would otherwise wait forever
            self.create_timer(1.0 / heartbeat_hz, self.heartbeat)
        self.heartbeat_step = -1
        self.publish_state()
        self.get_logger().info(f"{scene} ready: task {self.core.task}, seed {self.core.seed}, {self.mode} mode")

    def parameters_callback(self, params) -> SetParametersResult:
        for param in params:
            if param.name in ("scene", "mode", "render", "render_hz"):
                return SetParametersResult(successful=False, reason=f"{param.name} is fixed at start-up; restart the node")
        return SetParametersResult(successful=True)

    def publish_state(self) -> WorldState:
        snapshot = self.core.snapshot()
        msg = conversions.world_state(self.core.world, snapshot, self.core.task, self.core.episode, self.core.seed)
        self.world_pub.publish(msg)
        self.joint_pub.publish(conversions.joint_state(self.core.world, snapshot))
        if snapshot.step % max(1, self.markers_every) == 0:
            self.marker_pub.publish(conversions.markers(msg))
        return msg

    def publish_image(self) -> None:
        """Render the current world (a reset may have built another one) and publish the frame."""
        from semgoal_sim.render import FrameRenderer

        if self.renderer is None or self.renderer.world is not self.core.world:
            if self.renderer is not None:
                self.renderer.close()
            self.renderer = FrameRenderer(self.core.world, *self.render_size)
        self.image_pub.publish(conversions.image(self.renderer.frame(), self.core.world.step_count))

    def command_callback(self, msg: ArmCommand) -> None:
        values = [msg.displacement.x, msg.displacement.y, msg.displacement.z, msg.gripper]
        if self.mode == "lockstep" and msg.step != self.core.world.step_count:
            self.get_logger().warn(f"dropped a stale command for step {msg.step} (now at {self.core.world.step_count})",
                                   throttle_duration_sec=1.0)
            return
        check = check_command(values)
        if check.warning:
            self.get_logger().warn(check.warning, throttle_duration_sec=1.0)
        if check.action is None:
            return
        if self.mode == "realtime":
            self.held_command = check.action
            return
        self.core.step(check.action)
        self.publish_state()

    def heartbeat(self) -> None:
        """Republish the world state when lockstep has not moved since the last heartbeat."""
        if self.core.world.step_count == self.heartbeat_step:
            self.publish_state()
        self.heartbeat_step = self.core.world.step_count

    def realtime_step(self) -> None:
        self.core.step(self.held_command)
        self.publish_state()

    def report(self, success: bool, message: str) -> None:
        if success:
            self.get_logger().info(message)
        else:
            self.get_logger().warning(message)

    def reset_callback(self, request: ResetWorld.Request, response: ResetWorld.Response) -> ResetWorld.Response:
        response.success, response.message = self.core.reset(request.task, request.seed)
        self.report(response.success, response.message)
        self.held_command = np.zeros(4)
        response.world = self.publish_state()
        response.state = messages.semantic_state(response.world, messages.semantic_vector(response.world))
        return response

    def move_block_callback(self, request: MoveBlock.Request, response: MoveBlock.Response) -> MoveBlock.Response:
        p = request.position
        response.success, response.message = self.core.move_block(request.block, np.array([p.x, p.y, p.z]))
        self.report(response.success, response.message)
        response.world = self.publish_state()
        return response


def main(args: list[str] | None = None) -> None:
    topics.run_node(SimNode, args)
