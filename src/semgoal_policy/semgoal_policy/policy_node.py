"""policy_node: world state and the active sub-goal in, one ArmCommand per world state out (lockstep) or
at ``rate_hz`` (realtime). It holds still when no sub-goal is active and never publishes NaN or values
outside [-1, 1]."""

from __future__ import annotations

import time

from rclpy.node import Node

from semgoal_msgs.msg import ArmCommand, SubGoal, WorldState
from semgoal_policy.controller import SubgoalController, VocabularyError
from semgoal_sim import ros_interfaces as topics
from semgoal_sim.vocabulary import SCENES, Literal


class PolicyNode(Node):
    def __init__(self) -> None:
        super().__init__("policy")
        scene = self.declare_parameter("scene", "desk_cleanup").value
        model_dir = self.declare_parameter("model_dir", "").value
        self.mode = self.declare_parameter("mode", "lockstep").value
        rate_hz = self.declare_parameter("rate_hz", 25.0).value
        idle_hz = self.declare_parameter("idle_hz", 50.0).value
        if scene not in SCENES or self.mode not in ("lockstep", "realtime"):
            raise SystemExit(f"policy: bad parameters scene={scene!r} mode={self.mode!r}")
        self.controller = SubgoalController(scene, model_dir or None)
        self.get_logger().info(f"actor for {scene}: {self.controller.meta.get('env_steps')} training steps, "
                               f"eval {self.controller.meta.get('final_eval', {}).get('per_kind')}")
        self.publisher = self.create_publisher(ArmCommand, topics.ARM_COMMAND, topics.STREAM)
        self.create_subscription(WorldState, topics.WORLD_STATE, self.world_callback, topics.STREAM)
        self.create_subscription(SubGoal, topics.SUBGOAL, self.subgoal_callback, topics.LATCHED)
        self.latest: WorldState | None = None
        self.answered_step = -1
        self.answered_at = 0.0
        # realtime: act at rate_hz; lockstep while idle: keep the clock going without spinning flat out
        self.create_timer(1.0 / (rate_hz if self.mode == "realtime" else idle_hz), self.timer_callback)
        self.subgoal_text = ""

    def subgoal_callback(self, msg: SubGoal) -> None:
        literals = [Literal(p.name, tuple(p.args), bool(p.value)) for p in msg.goal] if msg.status == "active" else []
        try:
            self.controller.set_subgoal(literals)
        except VocabularyError as error:
            self.controller.set_subgoal([])
            self.get_logger().warn(f"holding still: sub-goal {msg.action!r} is not valid here: {error}")
            return
        text = msg.action if literals else f"(none: {msg.status or 'no plan'})"
        if text != self.subgoal_text:
            self.subgoal_text = text
            self.get_logger().info(f"sub-goal {text}")

    def world_callback(self, msg: WorldState) -> None:
        self.latest = msg
        if self.mode == "lockstep" and self.controller.goal is not None:
            self.answer(msg)

    def timer_callback(self) -> None:
        if self.latest is None:
            return
        # lockstep: answer a step once, again after a second in case the command was lost
        stale = time.monotonic() - self.answered_at > 1.0
        if self.mode == "realtime" or self.latest.step != self.answered_step or stale:
            self.answer(self.latest)

    def answer(self, msg: WorldState) -> None:
        action = self.controller.act(msg.observation)
        command = ArmCommand(step=msg.step, gripper=float(action[3]))
        command.header.stamp = self.get_clock().now().to_msg()
        command.displacement.x, command.displacement.y, command.displacement.z = (float(v) for v in action[:3])
        self.publisher.publish(command)
        self.answered_step, self.answered_at = msg.step, time.monotonic()


def main(args: list[str] | None = None) -> None:
    topics.run_node(PolicyNode, args)
