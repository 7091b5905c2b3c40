"""Topic names and QoS profiles shared by every semgoal node: the one place these choices live.

Latched state (world snapshot, semantic state, plan, active sub-goal) is reliable + transient_local with
depth 1, so a late joiner gets the last value at once. Streams (world state, arm commands) are keep-last.
"""

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
