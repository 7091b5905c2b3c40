"""predicate_node: world state in, semantic state out (latched), one per world state.

Every world state gets its semantic state, changed or not: the planner takes its control-step clock
from this stream, and in lockstep the policy follows its decision on each step, one step later. A change
is logged in the scene's readable form, and a block that falls off the table as a warning.
"""

from typing import Any

from rclpy.node import Node

from semgoal_core.vocabulary import LAYOUTS
from semgoal_msgs.msg import SemanticState, WorldState
from semgoal_ros import interfaces as topics
from semgoal_ros import messages


class PredicateNode(Node):
    def __init__(self, **options: Any) -> None:
        """``options``: rclpy ``Node``'s (a namespace, parameter overrides: ``graph_node`` composes nodes so)."""
        super().__init__("predicates", **options)
        self.publisher = self.create_publisher(SemanticState, topics.SEMANTIC_STATE, topics.PER_STEP)
        self.create_subscription(WorldState, topics.WORLD_STATE, self.world_callback, topics.STREAM)
        self.last_key: tuple | None = None
        self.fall_episode: tuple | None = None
        self.falls_reported: set[str] = set()

    def world_callback(self, msg: WorldState) -> None:
        if msg.scene not in LAYOUTS:
            self.get_logger().warn(f"ignored a world state of unknown scene {msg.scene!r}", throttle_duration_sec=5.0)
            return
        try:
            vector = messages.semantic_vector(msg)
            state = messages.semantic_state(msg, vector)
        except (ValueError, IndexError) as error:
            self.get_logger().warn(f"ignored a malformed world state: {error}", throttle_duration_sec=5.0)
            return
        self.publisher.publish(state)
        key = (msg.scene, msg.episode, tuple(vector))
        if key != self.last_key:
            self.last_key = key
            self.get_logger().info(f"{LAYOUTS[msg.scene].readable(vector)}  (step {msg.step})")
        self.report_falls(msg, state.fallen)

    def report_falls(self, msg: WorldState, fallen: list[str]) -> None:
        """Warn once per block and episode when a block lies below the table."""
        if (msg.scene, msg.episode) != self.fall_episode:
            self.fall_episode, self.falls_reported = (msg.scene, msg.episode), set()
        fell = [block for block in fallen if block not in self.falls_reported]
        if fell:
            self.falls_reported.update(fell)
            self.get_logger().warn(f"{', '.join(fell)} fell off the table, out of the arm's reach (step {msg.step})")


def main(args: list[str] | None = None) -> None:
    topics.run_node(PredicateNode, args)
