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

    def destroy_node(self) -> None:
        counts = self.recorder.close()
        self.get_logger().info(f"recorded {sum(counts.values())} messages to {self.path}")
        super().destroy_node()


def main(args: list[str] | None = None) -> None:
    topics.run_node(RecordNode, args)
