"""policy_node: world state and the active sub-goal in, one ArmCommand per world state out (lockstep) or
at ``rate_hz`` (realtime). Without an active sub-goal, or once it is confirmed (its literals held for
``SUBGOAL_CONFIRM_STEPS`` steps, the planner's rule), it holds still (realtime: zero
commands; lockstep: no command, so the world waits for the planner). It never publishes NaN or values
outside [-1, 1]."""

from __future__ import annotations

import time

import numpy as np
from rclpy.node import Node

from semgoal_msgs.msg import ArmCommand, SubGoal, WorldState
from semgoal_policy.controller import ACTION_MODES, HOLD, SubgoalController, VocabularyError
from semgoal_sim import conversions
from semgoal_sim import ros_interfaces as topics
from semgoal_sim.vocabulary import SCENES, Literal


class PolicyNode(Node):
    def __init__(self) -> None:
        super().__init__("policy")
        scene = self.declare_parameter("scene", "desk_cleanup").value
        model_dir = self.declare_parameter("model_dir", "").value
        self.mode = self.declare_parameter("mode", "lockstep").value
        rate_hz = self.declare_parameter("rate_hz", 25.0).value
        action_mode = self.declare_parameter("action_mode", "sample").value
        if scene not in SCENES or self.mode not in ("lockstep", "realtime") or action_mode not in ACTION_MODES:
            raise SystemExit(f"policy: bad parameters scene={scene!r} mode={self.mode!r} action_mode={action_mode!r}")
        self.controller = SubgoalController(scene, model_dir or None, action_mode)
        self.get_logger().info(f"actor for {scene}: {self.controller.meta.get('env_steps')} training steps, "
                               f"eval {self.controller.meta.get('final_eval', {}).get('per_kind')}")
        self.publisher = self.create_publisher(ArmCommand, topics.ARM_COMMAND, topics.STREAM)
        self.create_subscription(WorldState, topics.WORLD_STATE, self.world_callback, topics.STREAM)
        self.create_subscription(SubGoal, topics.SUBGOAL, self.subgoal_callback, topics.LATCHED)
        self.latest: WorldState | None = None
        self.answered_step, self.answered_at = -1, 0.0
        # realtime: act at rate_hz. lockstep: the world waits while no sub-goal is active (runs are
        # reproducible from the reset on); the timer only resends a command that may have been lost
        self.create_timer(1.0 / rate_hz if self.mode == "realtime" else 1.0, self.timer_callback)
        self.subgoal_text = ""
        self.nudging = False

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
            self.subgoal_text, self.nudging = text, False
            self.get_logger().info(f"sub-goal {text}")
            if self.mode == "lockstep":
                self.answered_step = -1
                self.answer_lockstep()

    def world_callback(self, msg: WorldState) -> None:
        self.latest = msg
        if self.mode == "lockstep":
            self.answer_lockstep()

    def timer_callback(self) -> None:
        if self.latest is None:
            return
        if self.mode == "realtime":
            self.publish_command(self.latest, self.decide(self.latest))
        elif time.monotonic() - self.answered_at > 1.0:
            self.answered_step = -1  # lockstep: the command for this step may have been lost; send it again
            self.answer_lockstep(stalled=True)

    def decide(self, msg: WorldState) -> np.ndarray | None:
        """The command for a world state; None once the sub-goal is confirmed (the planner names the next one)."""
        if self.controller.goal is not None and self.controller.confirmed(msg.step, conversions.semantic_vector(msg)):
            return None
        return self.controller.act(msg.observation, (msg.seed, msg.step))

    def answer_lockstep(self, stalled: bool = False) -> None:
        """One command per step while a sub-goal is active and not yet achieved; otherwise the world waits,
        so the next sub-goal starts from exactly the state where the last one was achieved.

        ``stalled``: no command went out for a second. If the sub-goal is confirmed here but the planner
        still names it (its confirmation began a step later, as messages raced), hold-still commands let
        the world tick on until the sub-goal changes, so the planner confirms too instead of both
        waiting for good (a graph stalled so once, in a long via-ROS evaluation under load)."""
        msg = self.latest
        if msg is None or self.controller.goal is None or msg.step == self.answered_step:
            return
        action = self.decide(msg)
        if action is None and stalled and not self.nudging:
            self.nudging = True
            self.get_logger().info(f"{self.subgoal_text} holds here but the planner still names it: "
                                   "holding still while the world ticks on")
        if action is not None or self.nudging:
            self.publish_command(msg, action)

    def publish_command(self, msg: WorldState, action: np.ndarray | None) -> None:
        action = HOLD if action is None else action
        command = ArmCommand(step=msg.step, gripper=float(action[3]))
        command.header.stamp = self.get_clock().now().to_msg()
        command.displacement.x, command.displacement.y, command.displacement.z = (float(v) for v in action[:3])
        self.publisher.publish(command)
        self.answered_step, self.answered_at = msg.step, time.monotonic()


def main(args: list[str] | None = None) -> None:
    topics.run_node(PolicyNode, args)
