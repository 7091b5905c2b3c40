"""The operator's side of a running node graph: reset the world, send a goal, wait for the result.

Used by the demo (one episode, printed and recorded), by ``./semgoal eval --via-ros`` (many episodes on
one graph), by the graph benchmark and by the robustness tests. It initialises rclpy on the current
ROS_DOMAIN_ID when the caller's process has not.

Only callers that look at the per-step streams (world state, semantic state, sub-goal: the demo, the
tests) subscribe to them (``watch``). In lockstep every reader of those topics is one more process woken
on each step, on the path from one step to the next: without them the graph steps about 1.2 times as
fast (``./semgoal bench-graph``). A reset is confirmed through the planner's GetPlan instead, which
reports the episode and step of the semantic state it last decided on.
"""

from __future__ import annotations

import os
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass

READY_TIMEOUT_S = 60.0
EPISODE_TIMEOUT_S = 300.0
RESET_TIMEOUT_S = 5.0
POLL_S = 0.005


@dataclass(frozen=True)
class GoalResult:
    success: bool
    message: str
    replans: int
    control_steps: int
    sim_time: float
    wall_s: float


class GraphClient:
    """An rclpy node with the sim's reset and move services, the planner's ExecuteGoal, and the state streams."""

    def __init__(self, name: str = "semgoal_operator", watch: bool = True, lockstep: bool = True) -> None:
        import rclpy
        from rclpy.action import ActionClient

        from semgoal_msgs.action import ExecuteGoal
        from semgoal_msgs.msg import SemanticState, SubGoal, WorldState
        from semgoal_msgs.srv import EditPlan, GetPlan, MoveBlock, ResetWorld
        from semgoal_ros import interfaces as topics

        if not rclpy.ok():
            rclpy.init(domain_id=int(os.environ["ROS_DOMAIN_ID"]))
        self.rclpy, self.topics = rclpy, topics
        self.node = node = rclpy.create_node(name)
        self.world: WorldState | None = None
        self.semantic: SemanticState | None = None
        self.subgoal: SubGoal | None = None
        self.world_listeners: list[Callable] = []
        self.watch, self.lockstep = watch, lockstep
        if watch:
            node.create_subscription(WorldState, topics.WORLD_STATE, self._on_world, topics.STREAM)
            node.create_subscription(SemanticState, topics.SEMANTIC_STATE, self._on_semantic, topics.LATCHED)
            node.create_subscription(SubGoal, topics.SUBGOAL, self._on_subgoal, topics.LATCHED)
        self.reset_client = node.create_client(ResetWorld, topics.RESET_WORLD)
        self.move_client = node.create_client(MoveBlock, topics.MOVE_BLOCK)
        self.plan_client = node.create_client(GetPlan, topics.GET_PLAN)
        self.edit_client = node.create_client(EditPlan, topics.EDIT_PLAN)
        self.action = ActionClient(node, ExecuteGoal, topics.EXECUTE_GOAL)
        self.ExecuteGoal, self.ResetWorld, self.MoveBlock, self.GetPlan = ExecuteGoal, ResetWorld, MoveBlock, GetPlan
        self.EditPlan = EditPlan

    # -- streams -------------------------------------------------------------------------------------
    def _on_world(self, msg) -> None:
        self.world = msg
        for listener in self.world_listeners:
            listener(msg)

    def _on_semantic(self, msg) -> None:
        self.semantic = msg

    def _on_subgoal(self, msg) -> None:
        self.subgoal = msg

    def spin_until(self, condition: Callable[[], bool], timeout: float) -> bool:
        return self.topics.spin_node_until(self.node, condition, timeout)

    # -- calls ---------------------------------------------------------------------------------------
    def wait_ready(self, timeout: float = READY_TIMEOUT_S, policy: bool = True) -> bool:
        """Sim services, the planner's services and action, the predicates and (with ``policy``) the policy
        are up: world state is read by the predicates and the policy, the semantic state by the planner, the
        sub-goal by the policy, and each of them by this client too when it watches."""
        own = int(self.watch)
        world_readers, subgoal_readers = (2 + own, 1 + own) if policy else (1 + own, own)
        return self.spin_until(lambda: (self.reset_client.service_is_ready() and self.plan_client.service_is_ready()
                                        and self.action.server_is_ready()
                                        and self.node.count_subscribers(self.topics.WORLD_STATE) >= world_readers
                                        and self.node.count_subscribers(self.topics.SEMANTIC_STATE) >= 1 + own
                                        and self.node.count_subscribers(self.topics.SUBGOAL) >= subgoal_readers),
                               timeout)

    def call(self, client, request, timeout: float = 30.0):
        future = client.call_async(request)
        return future.result() if self.spin_until(future.done, timeout) else None

    def reset(self, task: str, seed: int, attempts: int = 2) -> tuple[bool, str]:
        """Reset the world to a task's start; returns once the planner has decided on the new world's
        first state, so a goal sent next is planned from it.

        In lockstep, should the new world have stepped first (a goal still under way when it was reset),
        the reset is made again; in realtime the world steps on the sim's clock from the start (the arm
        holding still without a goal), and any state of the new world will do."""
        message = "reset_world did not answer"
        for _ in range(attempts):
            reply = self.call(self.reset_client, self.ResetWorld.Request(task=task, seed=seed))
            if reply is None or not reply.success:
                return False, reply.message if reply else message
            state = self.planner_state(reply.world.episode)
            if state is None:
                message = f"the planner saw no state of episode {reply.world.episode} ({reply.message})"
            elif state.step == 0 or not self.lockstep:
                return True, reply.message
            else:
                message = f"the world was at step {state.step} before a goal was sent ({reply.message})"
        return False, f"{message}; tried {attempts} resets"

    def must_reset(self, task: str, seed: int) -> None:
        """:meth:`reset`, raising RuntimeError with the reason when it fails (for unattended runs)."""
        ok, message = self.reset(task, seed)
        if not ok:
            raise RuntimeError(f"reset to {task} seed {seed} failed: {message}")

    def planner_state(self, episode: int, timeout: float = RESET_TIMEOUT_S):
        """The semantic state the planner last decided on, once it is of world ``episode``; None if it
        does not come within ``timeout``."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            reply = self.call(self.plan_client, self.GetPlan.Request(), timeout=deadline - time.monotonic())
            if reply is not None and reply.state.scene and reply.state.episode == episode:
                return reply.state
            time.sleep(POLL_S)
        return None

    def move_block(self, block: str, x: float, y: float, z: float) -> tuple[bool, str]:
        request = self.MoveBlock.Request(block=block)
        request.position.x, request.position.y, request.position.z = float(x), float(y), float(z)
        reply = self.call(self.move_client, request)
        return (reply.success, reply.message) if reply else (False, "move_block did not answer")

    def edit(self, op: str, index: int = 0, action: str = "") -> tuple[bool, str]:
        """An operator's plan edit; (applied, the planner's message). Sent again while unanswered: the
        request id makes a repeat safe (the planner answers it without applying it twice)."""
        request = self.EditPlan.Request(op=op, index=index, action=action, request_id=uuid.uuid4().hex)
        reply = self.topics.send_until_answered(lambda: self.edit_client.call_async(request), self.spin_until)
        return (reply.success, reply.message) if reply else (False, "edit_plan did not answer")

    def execute(self, goal_text: str, feedback: Callable | None = None, timeout: float = EPISODE_TIMEOUT_S,
                max_steps: int = 0, while_running: Callable[[], None] | None = None) -> GoalResult:
        """Send a goal through ExecuteGoal and wait for its result; the planner fails it once ``max_steps``
        control steps are spent (0: no limit).

        ``while_running`` is called between spins (not inside a callback, so it may call services): the
        robustness tests intervene there."""
        goal = self.ExecuteGoal.Goal()
        goal.goal.task = goal_text
        goal.max_steps = max_steps
        started = time.perf_counter()
        handle = self.topics.send_goal(self.action, goal, self.spin_until, feedback)
        if handle is None or not handle.accepted:
            return GoalResult(False, "the planner did not accept the goal", 0, 0, 0.0, 0.0)
        result_future = handle.get_result_async()

        def done() -> bool:
            if while_running is not None:
                while_running()
            return result_future.done()

        if not self.spin_until(done, timeout):
            return GoalResult(False, f"no result within {timeout:.0f} s", 0, 0, 0.0, time.perf_counter() - started)
        result = result_future.result().result
        return GoalResult(bool(result.success), result.message, int(result.replans), int(result.control_steps),
                          float(result.sim_time), time.perf_counter() - started)

    def close(self) -> None:
        self.node.destroy_node()
        self.rclpy.try_shutdown()
