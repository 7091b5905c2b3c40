"""Topic names and QoS profiles shared by every semgoal node: the one place these choices live.

Latched state (world snapshot, semantic state, plan, active sub-goal) is reliable + transient_local with
depth 1, so a late joiner gets the last value at once. Streams (world state, arm commands) are keep-last.
Also the few ROS helpers every side shares: the nodes' ``main`` (:func:`run_node`) and, for clients (the
operator CLI, the graph client, the tests), spinning until a condition holds and sending an action goal.
"""

import time
from collections.abc import Callable

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

NAMESPACE = "/semgoal"
JOINT_STATES = "/joint_states"
WORLD_STATE = f"{NAMESPACE}/world_state"
SEMANTIC_STATE = f"{NAMESPACE}/semantic_state"
GOAL = f"{NAMESPACE}/goal"
PLAN = f"{NAMESPACE}/plan"
SUBGOAL = f"{NAMESPACE}/subgoal"
ARM_COMMAND = f"{NAMESPACE}/arm_command"
MARKERS = f"{NAMESPACE}/markers"
CAMERA_IMAGE = f"{NAMESPACE}/camera/image_raw"
RESET_WORLD = f"{NAMESPACE}/reset_world"
MOVE_BLOCK = f"{NAMESPACE}/move_block"
GET_PLAN = f"{NAMESPACE}/get_plan"
EDIT_PLAN = f"{NAMESPACE}/edit_plan"
EXECUTE_GOAL = f"{NAMESPACE}/execute_goal"

LATCHED = QoSProfile(
    depth=1,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
"""Last value kept for late joiners: semantic state, plan, sub-goal, markers."""

STREAM = QoSProfile(
    depth=10,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)
"""Per-step streams: world state, joint states, arm commands (reliable: lockstep must not lose a step)."""

CAMERA = QoSProfile(
    depth=1,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.BEST_EFFORT,
    durability=DurabilityPolicy.VOLATILE,
)
"""Rendered frames: only the newest matters, a dropped one is no loss (ROS's sensor-data profile)."""


def spin_node_until(node, condition: Callable[[], bool], timeout: float) -> bool:
    """Spin ``node`` until ``condition()`` holds; False after ``timeout`` seconds."""
    import rclpy

    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            return False
        rclpy.spin_once(node, timeout_sec=0.05)
    return True


GOAL_ANSWER_WAIT_S = 3.0
GOAL_SEND_ATTEMPTS = 3


def send_goal(action, goal, spin_until: Callable[[Callable[[], bool], float], bool], feedback_callback=None,
              attempts: int = GOAL_SEND_ATTEMPTS, wait_s: float = GOAL_ANSWER_WAIT_S):
    """Send an action goal; return its goal handle once the server answers, None after ``attempts`` tries.

    A goal is sent again when no answer comes within ``wait_s``: Fast DDS drops a server's answer when
    the server has not yet matched this client's reply reader ("failed to send response (timeout)", the
    service discovery race of ros2/ros2#1253), which a client created just before its first goal meets.
    A goal accepted but unanswered is superseded by the next (the planner runs one goal at a time), and
    its feedback, if any, carries its own goal id. ``spin_until(condition, seconds)`` spins the caller's
    node until ``condition()`` holds and says whether it did."""
    for _ in range(attempts):
        future = action.send_goal_async(goal, feedback_callback=feedback_callback)
        if spin_until(future.done, wait_s):
            return future.result()
    return None


def run_node(node_class: type, args: list[str] | None = None) -> None:
    """The executables' main: init, spin until Ctrl-C or shutdown, clean up (rclpy.init returns None on Jazzy)."""
    import rclpy
    from rclpy.executors import ExternalShutdownException

    rclpy.init(args=args)
    node = node_class()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception:
        if rclpy.ok():
            raise
        # SIGINT shut the context down while the executor built its wait set (rclpy raises RCLError there)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
