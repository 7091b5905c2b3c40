"""`./semgoal demo`: two real nodes in separate processes exchange a semgoal message over DDS.

Starts the interface loopback node, publishes a GoalRequest from this process and prints what comes
back. (The full hierarchy demo replaces this once sim, planner and policy exist.)
"""

import os
import random
import subprocess
import sys
import time
from pathlib import Path


def main(argv: list[str]) -> int:
    """Run the loopback demo in a fresh ROS domain; exit 0 when the message came back intact."""
    os.environ["ROS_DOMAIN_ID"] = str(random.randint(1, 100))  # per-run domain: parallel demos never meet
    root = Path(os.environ["SEMGOAL_ROOT"])
    echo = subprocess.Popen([str(root / "semgoal"), "run", "semgoal_bringup", "echo_node"])
    try:
        import rclpy

        from semgoal_bringup.echo_node import echo_topics
        from semgoal_msgs.msg import GoalRequest

        rclpy.init(domain_id=int(os.environ["ROS_DOMAIN_ID"]))
        node = rclpy.create_node("semgoal_demo")
        topic_in, topic_out = echo_topics(GoalRequest)
        received: list[GoalRequest] = []
        node.create_subscription(GoalRequest, topic_out, received.append, 10)
        publisher = node.create_publisher(GoalRequest, topic_in, 10)
        sent = GoalRequest(task="DC-3")
        deadline = time.monotonic() + 30
        while not received and time.monotonic() < deadline:
            if publisher.get_subscription_count() > 0:
                publisher.publish(sent)
            rclpy.spin_once(node, timeout_sec=0.2)
        node.destroy_node()
        rclpy.try_shutdown()
    finally:
        echo.terminate()
        echo.wait()
    if received and received[0] == sent:
        print(f"sent {sent} from semgoal_demo, received it back from semgoal_echo: success")
        return 0
    print("no echo received within 30 s: failure", file=sys.stderr)
    return 1
