"""The planner node's ExecuteGoal action: a goal waits for a state of the world it is for, runs while the
node's callbacks go on, sends feedback with every change of the plan, and ends with the reason and the world's
control steps. A mix-in of :class:`~semgoal_planner.planner_node.PlannerNode` (its state and publishers)."""

from __future__ import annotations

import time

from rclpy.action import CancelResponse
from rclpy.action.server import ServerGoalHandle
from rclpy.task import Future

from semgoal_core.layout import CONTROL_DT
from semgoal_core.names import PlanStatus
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import OperatorEvent
from semgoal_planner.goals import Goal
from semgoal_planner.plan_messages import goal_as_given

FINAL = (PlanStatus.SUCCEEDED, PlanStatus.FAILED)


class GoalAction:
    """ExecuteGoal for the planner node."""

    async def execute_callback(self, handle: ServerGoalHandle) -> ExecuteGoal.Result:
        """Start the goal, then wait (without a thread: the callbacks go on) until it ends; feedback
        goes out with every change of the plan (:meth:`publish`)."""
        result = ExecuteGoal.Result()
        episode = int(handle.request.episode)
        goal = self.read(handle.request.goal, episode)
        if isinstance(goal, Goal) and not self.has_state(episode):
            await self.state_of(episode, self.state_wait_s)
        if episode and not self.has_state(episode):
            ok, message = False, (f"no semantic state of world episode {episode} within {self.state_wait_s:g} s "
                                  f"(the latest is of episode {self.last_state.episode if self.last_state else '-'})")
            self.report(False, f"goal refused: {message}")
            self.operator_event(OperatorEvent.KIND_GOAL, goal_as_given(handle.request.goal), False, message)
        else:
            self.min_episode = episode
            ok, message = self.start_goal(handle.request.goal, goal, int(handle.request.max_steps))
        result.episode = self.last_state.episode if self.last_state else 0
        # a refused goal ran no steps: its result must not carry the previous goal's figures
        steps = self.executive.goal_steps if ok else 0
        if ok and self.executive.status not in FINAL:
            ended = Future(executor=self.executor)
            self.action_goal = (handle, ended)
            self.publish_feedback()
            # ``ended`` carries the goal's step count when it ended: a new goal may come before this resumes
            message, steps = await ended
        self.min_episode = 0  # only while this goal runs: a sim restarted later counts episodes from 1 again
        if handle.is_cancel_requested:
            handle.canceled()
            result.message = "cancelled"
            return self._fill(result, ok, steps)
        result.success = ok and self.executive.status == PlanStatus.SUCCEEDED
        result.message = message
        (handle.succeed if result.success else handle.abort)()
        return self._fill(result, ok, steps)

    def has_state(self, episode: int) -> bool:
        """Whether a semantic state has come (of world ``episode`` or a later one, when it is not 0)."""
        return self.last_state is not None and self.last_state.episode >= episode

    async def state_of(self, episode: int, timeout_s: float) -> None:
        """Wait up to ``timeout_s`` for a semantic state (of ``episode`` or later, when not 0), so that a goal
        sent right after the nodes start, or right after a reset, is planned on that world rather than refused
        or decided on the one before; after that the executive says what is missing."""
        if timeout_s <= 0:
            return
        self.get_logger().info(f"goal waits up to {timeout_s:g} s for a semantic state"
                               + (f" of world episode {episode}" if episode else ""))
        deadline = time.monotonic() + timeout_s  # states of older episodes come meanwhile: the wait is one
        while not self.has_state(episode) and (left := deadline - time.monotonic()) > 0:
            seen = Future(executor=self.executor)
            self.state_waiters.append(seen)
            timer = self.create_timer(left, lambda seen=seen: seen.done() or seen.set_result(False))
            await seen
            self.destroy_timer(timer)

    def cancel_callback(self, handle: ServerGoalHandle) -> CancelResponse:
        if self.action_goal is not None and self.action_goal[0] is handle:
            self.executive.cancel()
            self.publish()
        return CancelResponse.ACCEPT

    def end_action_goal(self, reason: str, steps: int | None = None) -> None:
        """Resolve the action goal with ``reason`` and its step count (default: the goal's now)."""
        if self.action_goal is not None:
            _, ended = self.action_goal
            self.action_goal = None
            ended.set_result((reason, self.executive.goal_steps if steps is None else steps))

    def publish_feedback(self) -> None:
        handle, _ = self.action_goal
        feedback = ExecuteGoal.Feedback(plan=self.plan_now(), control_steps=self.executive.goal_steps)
        if self.last_state is not None:
            feedback.state = self.last_state
        handle.publish_feedback(feedback)

    def _fill(self, result: ExecuteGoal.Result, started: bool, steps: int) -> ExecuteGoal.Result:
        result.replans = self.executive.replans if started else 0
        result.control_steps = steps
        result.sim_time = result.control_steps * CONTROL_DT
        return result
