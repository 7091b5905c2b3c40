"""The planner node's journal kept: the plan saved on every change, and taken up (or discarded, with the
reason) by a planner started again, once the first semantic state says which world it is in; an action goal
in flight when the old planner died is ended for its client. A mix-in of
:class:`~semgoal_planner.planner_node.PlannerNode`; the journal itself is :mod:`semgoal_planner.journal`."""

from __future__ import annotations

from action_msgs.msg import GoalInfo, GoalStatus, GoalStatusArray

from semgoal_msgs.msg import OperatorEvent, SemanticState
from semgoal_planner.journal import Record, Verdict, World, resume
from semgoal_planner.plan_messages import sim_time


class JournalKeeping:
    """The planner node's journal."""

    def take_up_journal(self, msg: SemanticState) -> None:
        """Carry on with the plan of the planner before this one when the world is the one it was for;
        else discard it, numbering plans on from its revision. An action goal it had in flight is ended for
        its client, with the reason, either way: its handle died with that planner."""
        record = self.journaled
        verdict, why = resume(record, World(msg.scene, tuple(msg.objects), int(msg.episode), sim_time(msg)))
        if verdict == Verdict.WAIT:
            return
        self.journaled, ok = None, verdict == Verdict.RESUME
        revision = int(record.executive.get("revision", 0))
        if ok:
            try:
                self.executive.restore(record.executive, f"planner restarted: resumed the plan at revision {revision}, "
                                                         f"step {record.executive.get('current', 0)} ({why})")
            except ValueError as error:
                ok, why = False, str(error)
        if not ok:
            self.executive.continue_revisions(revision)
            self.get_logger().warn(f"the planner's journal ({self.journal.path}) was discarded: {why}")
        outcome = (f"the plan resumed at revision {revision}" if ok
                   else f"the journal was discarded ({why}): send the goal again")
        self.operator_event(OperatorEvent.KIND_GOAL, record.executive.get("goal_text", ""), ok,
                            f"planner_node stopped and started again; {outcome}")
        if record.action_goal:
            self.end_journaled_action_goal(record, f"the ExecuteGoal was interrupted: planner_node stopped and "
                                                   f"started again; {outcome}")

    def end_journaled_action_goal(self, record: Record, reason: str) -> None:
        """Mark the old planner's action goal aborted on the action's status topic (a client's goal handle reads
        it) and say why on the operator events, under the goal's id."""
        status = GoalStatus(status=GoalStatus.STATUS_ABORTED,
                            goal_info=GoalInfo(stamp=self.get_clock().now().to_msg()))
        status.goal_info.goal_id.uuid = list(bytes.fromhex(record.action_goal))
        self.action_status_pub.publish(GoalStatusArray(status_list=[status]))
        self.operator_event(OperatorEvent.KIND_GOAL, record.executive.get("goal_text", ""), False, reason,
                            request_id=record.action_goal)
        self.get_logger().warn(f"action goal {record.action_goal}: {reason}")

    def save_journal(self) -> None:
        """Write the plan to the journal when it changed (a new revision, status or step, another action goal)."""
        if self.journal is None or self.last_state is None or self.journaled is not None:
            return
        action_goal = bytes(self.action_goal[0].goal_id.uuid).hex() if self.action_goal else ""
        ex, state = self.executive, self.last_state
        key = (ex.revision, ex.status, ex.current, tuple(ex.working.items()), action_goal, state.episode)
        if key == self.last_saved:
            return
        self.last_saved = key
        world = World(state.scene, tuple(state.objects), int(state.episode), sim_time(state))
        self.journal.save(Record(ex.snapshot(), world, action_goal))
