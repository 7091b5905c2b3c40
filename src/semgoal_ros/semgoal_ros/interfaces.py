"""Topic names and QoS profiles shared by every semgoal node: the one place these choices live.

Latched state (plan, markers) is reliable + transient_local with depth 1, so a late joiner gets the last
value at once; the semantic state and the active sub-goal are latched too, with room for a few.
Streams (world state, arm commands) are keep-last. Also the few ROS helpers every side shares: the
nodes' ``main`` (:func:`run_node`) and, for clients (the operator CLI, the graph client, the tests),
spinning until a condition holds and sending a request again while no answer comes; for servers, the
memory of answers that makes such a repeat safe.
"""

import contextlib
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

from semgoal_core.arms import arm_namespace

NAMESPACE = "/semgoal"
CLOCK = "/clock"
JOINT_STATES = "/joint_states"
WORLD_STATE = f"{NAMESPACE}/world_state"
SEMANTIC_STATE = f"{NAMESPACE}/semantic_state"
GOAL = f"{NAMESPACE}/goal"
PLAN = f"{NAMESPACE}/plan"
SUBGOAL = f"{NAMESPACE}/subgoal"
ARM_COMMAND = f"{NAMESPACE}/arm_command"
MARKERS = f"{NAMESPACE}/markers"
PLAN_MARKERS = f"{NAMESPACE}/plan_markers"
CAMERA_IMAGE = f"{NAMESPACE}/camera/image_raw"
RGBD_COLOUR = f"{NAMESPACE}/rgbd/color/image_raw"
RGBD_DEPTH = f"{NAMESPACE}/rgbd/depth/image_raw"
RGBD_INFO = f"{NAMESPACE}/rgbd/color/camera_info"
TF = "/tf"
TF_STATIC = "/tf_static"
BLOCK_ESTIMATES = f"{NAMESPACE}/perception/blocks"
PERCEIVED_WORLD = f"{NAMESPACE}/perception/world_state"
RESET_WORLD = f"{NAMESPACE}/reset_world"
MOVE_BLOCK = f"{NAMESPACE}/move_block"
GET_PLAN = f"{NAMESPACE}/get_plan"
EDIT_PLAN = f"{NAMESPACE}/edit_plan"
EXECUTE_GOAL = f"{NAMESPACE}/execute_goal"
OPERATOR_EVENTS = f"{NAMESPACE}/operator_events"


def arm_topic(topic: str, arm: int) -> str:
    """Arm ``arm``'s own version of a per-arm topic (world state, sub-goal, arm command): the topic itself for the first
    arm, under ``/semgoal/robot2/`` for the second (:func:`semgoal_core.arms.arm_namespace`)."""
    return topic if arm == 0 else topic.replace(f"{NAMESPACE}/", f"{NAMESPACE}/{arm_namespace(arm)}/", 1)


def action_status(action: str) -> str:
    """The status topic of an action (``rcl_action``'s name for it): where a client's goal handles learn their status."""
    return f"{action}/_action/status"

LATCHED = QoSProfile(
    depth=1,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
"""Last value kept for late joiners: plan, markers."""

PER_STEP = QoSProfile(
    depth=10,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)
"""The semantic state and the active sub-goal: latched (a late joiner gets the last at once), but with
room for a few, since every one counts: in lockstep the policy follows the planner's decision on the
step before the world's, so the world runs up to two steps ahead of the planner, and a state or a
decision replaced before it was read would change the episode."""

STREAM = QoSProfile(
    depth=10,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)
"""The readers of per-step streams: world state, joint states, arm commands (reliable: lockstep must not lose a step;
their writers keep :data:`RECORDING`'s history)."""

RECORDING = QoSProfile(
    depth=1000,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)
"""Both ends of a per-step stream that a recorder must get whole. The reader: a client that falls behind while four
busy nodes share two cores would keep only the last ten steps of a depth-10 reader. The writers (world states, joint
states, arm commands, estimates): a reliable reader is repaired from what its writer still keeps, and with ten kept a
recorder starved through ten steps of a lockstep episode lost them for good (a session recording once held an
episode's heartbeats and none of its steps)."""

EVENTS = QoSProfile(depth=100, history=HistoryPolicy.KEEP_LAST, reliability=ReliabilityPolicy.RELIABLE,
                    durability=DurabilityPolicy.TRANSIENT_LOCAL)
"""Operator events as published, the last hundred kept: a session recorder started with the graph may match the
planner only after the operator's first goal (discovery takes seconds on a busy machine), and must still
have it."""

EVENTS_LIVE = QoSProfile(depth=100, history=HistoryPolicy.KEEP_LAST, reliability=ReliabilityPolicy.RELIABLE,
                         durability=DurabilityPolicy.VOLATILE)
"""Operator events from the moment a reader joins: the console's study log, an episode's recording."""

CLOCK_QOS = QoSProfile(depth=1, history=HistoryPolicy.KEEP_LAST, reliability=ReliabilityPolicy.RELIABLE,
                       durability=DurabilityPolicy.VOLATILE)
"""The sim clock: only the newest tick matters (rclpy's own /clock reader is best effort, which a reliable
writer serves)."""

CAMERA = QoSProfile(
    depth=1,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.BEST_EFFORT,
    durability=DurabilityPolicy.VOLATILE,
)
"""Rendered frames: only the newest matters, a dropped one is no loss (ROS's sensor-data profile)."""

RGBD = QoSProfile(
    depth=5,
    history=HistoryPolicy.KEEP_LAST,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)
"""The RGB-D sensor: reliable, since in lockstep the perception's semantic state of each frame counts (a lost
frame would stall the planner's clock); a few kept for the reader's synchronisation of the three."""

TF_QOS = QoSProfile(depth=100, history=HistoryPolicy.KEEP_LAST, reliability=ReliabilityPolicy.RELIABLE,
                    durability=DurabilityPolicy.VOLATILE)
"""/tf as tf2's listeners expect it (reliable, volatile, depth 100); /tf_static is :data:`LATCHED`."""


def spin_executor_until(executor, condition: Callable[[], bool], timeout: float) -> bool:
    """Spin ``executor`` until ``condition()`` holds; False after ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            return False
        executor.spin_once(timeout_sec=0.05)
    return True


ANSWER_WAIT_S = 3.0
SEND_ATTEMPTS = 3


def send_until_answered(send: Callable[[], object], spin_until: Callable[[Callable[[], bool], float], bool],
                        attempts: int = SEND_ATTEMPTS, wait_s: float = ANSWER_WAIT_S):
    """Send a request (``send()`` returns its future) until it is answered; the answer, or None after
    ``attempts`` tries.

    A request is sent again when no answer comes within ``wait_s``: Fast DDS drops a server's answer when
    the server has not yet matched this client's reply reader ("failed to send response (timeout)", the
    service discovery race of ros2/ros2#1253), which a client created just before its first request
    meets. So only requests that are safe to repeat may go through here: reads, action goals (the planner
    runs one goal at a time: a goal accepted but unanswered is superseded by the next, and its feedback
    carries its own goal id), and edits that carry a request id (:class:`RecentAnswers`).
    ``spin_until(condition, seconds)`` spins the caller's node until ``condition()`` holds and says
    whether it did."""
    for _ in range(attempts):
        future = send()
        if spin_until(future.done, wait_s):
            return future.result()
    return None


def send_goal(action, goal, spin_until: Callable[[Callable[[], bool], float], bool], feedback_callback=None,
              attempts: int = SEND_ATTEMPTS, wait_s: float = ANSWER_WAIT_S):
    """Send an action goal (:func:`send_until_answered`); its goal handle, or None when never answered."""
    return send_until_answered(lambda: action.send_goal_async(goal, feedback_callback=feedback_callback),
                               spin_until, attempts, wait_s)


class ReusedRequestIdError(ValueError):
    """A request id that came with another request than the one it was first sent with."""


class RecentAnswers:
    """The answers to the latest requests by request id, so a request sent again because its answer was
    lost gets the same answer instead of being applied twice (an idempotency key). An id is bound to its
    request: the same id with another request raises :class:`ReusedRequestIdError`. Bounded: the oldest id is
    forgotten first."""

    def __init__(self, size: int = 32) -> None:
        self.size = size
        self.answers: dict[str, tuple[object, object]] = {}

    def get(self, request_id: str, request: object = None):
        """The answer given to ``request_id``, or None; ``request``: what the request asked (compared)."""
        if not request_id or request_id not in self.answers:
            return None
        asked, answer = self.answers[request_id]
        if asked != request:
            raise ReusedRequestIdError(f"request id {request_id!r} was used for another request; send a new id")
        return answer

    def remember(self, request_id: str, answer, request: object = None) -> None:
        if not request_id:
            return
        self.answers[request_id] = (request, answer)
        while len(self.answers) > self.size:
            del self.answers[next(iter(self.answers))]


def run_node(node_class: type, args: list[str] | None = None) -> None:
    """The executables' main: init, spin until Ctrl-C or shutdown, clean up (rclpy.init returns None on Jazzy).
    A node refusing a start-up parameter value exits with status 2 and the reason."""
    run_nodes([node_class], args)


def run_nodes(node_factories: list[Callable[[], Any]], args: list[str] | None = None) -> None:
    """:func:`run_node` for several nodes (each made by a factory of ``node_factories``: a node class, or one with its
    namespace and values bound) in one process, spun by one single-threaded executor: each is still a node
    of its own, with its own name and parameters. The executor is :class:`~semgoal_ros.executor.SteadyExecutor`, or
    rclpy's own where ``SEMGOAL_EXECUTOR=rclpy`` (to tell a fault of ours from rclpy's). SteadyExecutor hands the
    nodes' messages to each other over as objects where no one else listens (:mod:`semgoal_ros.in_process`), unless
    ``SEMGOAL_IN_PROCESS=0`` (every message through the middleware, to measure what that saves)."""
    import rclpy
    from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor

    from semgoal_ros.executor import SteadyExecutor
    from semgoal_ros.parameters import ParameterValueError

    rclpy.init(args=args)
    nodes = []
    try:
        nodes = [make_node() for make_node in node_factories]
    except (KeyboardInterrupt, ExternalShutdownException):
        _destroy(rclpy, nodes)
        return
    except ParameterValueError as error:  # a bad start-up value: one line that says which and why, exit 2
        rclpy.logging.get_logger("semgoal").error(str(error))
        _destroy(rclpy, nodes)
        raise SystemExit(2) from None
    except Exception:
        if rclpy.ok():
            raise
        return  # SIGINT shut the context down while the node built its servers (rcl: context invalid)
    executor = SingleThreadedExecutor() if os.environ.get("SEMGOAL_EXECUTOR") == "rclpy" else SteadyExecutor()
    for node in nodes:
        executor.add_node(node)
    if len(nodes) > 1 and isinstance(executor, SteadyExecutor) and os.environ.get(IN_PROCESS_VARIABLE) != "0":
        executor.route_in_process()
    try:
        with _profiled("+".join(node.get_name() for node in nodes)):
            executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception:
        if rclpy.ok():
            raise
        # SIGINT shut the context down while the executor built its wait set (rclpy raises RCLError there)
    finally:
        _destroy(rclpy, nodes)


IN_PROCESS_VARIABLE = "SEMGOAL_IN_PROCESS"
"""``0``: the nodes of one process send each other every message through the middleware (:func:`run_nodes`)."""
PROFILE_DIR_VARIABLE = "SEMGOAL_PROFILE_DIR"
"""Where set, each node process profiles its spinning (cProfile) into ``DIR/NODES-PID.prof`` as it stops: where a
control step's CPU goes, node by node (docs/measurements.md)."""


@contextlib.contextmanager
def _profiled(name: str) -> Iterator[None]:
    folder = os.environ.get(PROFILE_DIR_VARIABLE)
    if not folder:
        yield
        return
    import cProfile
    from pathlib import Path

    profiler = cProfile.Profile(time.thread_time)  # CPU, not the waits: where this thread spends it
    profiler.enable()
    try:
        yield
    finally:
        profiler.disable()
        Path(folder).mkdir(parents=True, exist_ok=True)
        profiler.dump_stats(Path(folder) / f"{name}-{os.getpid()}.prof")


EXIT_GRACE_S = 5
"""How long a node process may take to destroy its nodes and context on the way out."""


def _destroy(rclpy, nodes: list) -> None:
    """Destroy the nodes and shut the context down. Fast DDS can busy-wait for ever there, a core at 100 %, on a
    participant listener callback in flight (eProsima/Fast-DDS#6513; a CI run left such a policy node spinning for
    its last ten minutes): past :data:`EXIT_GRACE_S` the kernel ends the process, by SIGALRM's default action. Armed
    only where nothing else handles SIGALRM (not inside a test run's own process)."""
    armed = (threading.current_thread() is threading.main_thread() and hasattr(signal, "alarm")
             and signal.getsignal(signal.SIGALRM) == signal.SIG_DFL)
    if armed:
        signal.alarm(EXIT_GRACE_S)
    try:
        for node in nodes:
            node.destroy_node()
        _shutdown(rclpy)
    finally:
        if armed:
            signal.alarm(0)


def _shutdown(rclpy) -> None:
    """Shut the context down, unless SIGINT's handler is doing so at the same moment: rcl then refuses the
    second shutdown with an RCLError (a CI run saw it when Ctrl-C landed while a node was being built)."""
    with contextlib.suppress(RuntimeError):
        rclpy.try_shutdown()
