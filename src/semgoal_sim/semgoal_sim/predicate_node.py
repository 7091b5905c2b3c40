"""predicate_node: world state in, semantic state out (latched), on change and at a low rate."""

from rclpy.node import Node

from semgoal_msgs.msg import SemanticState, WorldState
from semgoal_sim import conversions
from semgoal_sim import ros_interfaces as topics
from semgoal_sim.vocabulary import LAYOUTS


class PredicateNode(Node):
    def __init__(self) -> None:
        super().__init__("predicates")
        republish_hz = self.declare_parameter("republish_hz", 2.0).value
        self.publisher = self.create_publisher(SemanticState, topics.SEMANTIC_STATE, topics.LATCHED)
        self.create_subscription(WorldState, topics.WORLD_STATE, self.world_callback, topics.STREAM)
        self.last: SemanticState | None = None
        self.last_key: tuple | None = None
        if republish_hz > 0:
            self.create_timer(1.0 / republish_hz, self.republish)

    def world_callback(self, msg: WorldState) -> None:
        if msg.scene not in LAYOUTS:
            self.get_logger().warn(f"ignored a world state of unknown scene {msg.scene!r}", throttle_duration_sec=5.0)
            return
        try:
            vector = conversions.semantic_vector(msg)
        except (ValueError, IndexError) as error:
            self.get_logger().warn(f"ignored a malformed world state: {error}", throttle_duration_sec=5.0)
            return
        key = (msg.scene, msg.episode, tuple(vector))
        self.last = conversions.semantic_state(msg, vector)
        if key != self.last_key:  # publish on change; the timer republishes the rest
            self.last_key = key
            self.publisher.publish(self.last)
            self.get_logger().info(f"{LAYOUTS[msg.scene].readable(vector)}  (step {msg.step})")

    def republish(self) -> None:
        if self.last is not None:
            self.publisher.publish(self.last)


def main(args: list[str] | None = None) -> None:
    topics.run_node(PredicateNode, args)
