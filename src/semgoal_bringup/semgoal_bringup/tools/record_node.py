"""record_node: every topic of the graph into one MCAP file until the node stops (``./semgoal up --record FILE``,
``ros2 launch semgoal_bringup semgoal.launch.py record:=FILE``); ``./semgoal replay FILE`` reads its last episode."""

from rclpy.node import Node

from semgoal_ros import interfaces as topics
from semgoal_ros.parameters import Param, declare
from semgoal_ros.recording import Recorder

PARAMS = (Param("path", "semgoal.mcap", "the MCAP file to write (its folder is created)"),)


class RecordNode(Node):
    def __init__(self) -> None:
        super().__init__("recorder")
        self.path = declare(self, PARAMS)["path"]
        self.recorder = Recorder(self, self.path, session=True)
        self.get_logger().info(f"recording to {self.path}")
        self.heard: set[str] = set()
        self.match_timer = self.create_timer(0.1, self.log_matches)

    def log_matches(self) -> None:
        """Say once per topic when its reader has matched a publisher: from then on the topic is recorded, with
        what the publisher keeps for late readers (discovery of a new process takes a moment)."""
        for subscription in self.recorder.subscriptions:
            if subscription.topic_name not in self.heard and subscription.get_publisher_count() > 0:
                self.heard.add(subscription.topic_name)
                self.get_logger().info(f"recording {subscription.topic_name}")

    def destroy_node(self) -> None:
        counts = self.recorder.close()
        self.get_logger().info(f"recorded {sum(counts.values())} messages to {self.path}")
        super().destroy_node()


def main(args: list[str] | None = None) -> None:
    topics.run_node(RecordNode, args)
