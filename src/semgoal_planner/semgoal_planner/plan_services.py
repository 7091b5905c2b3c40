"""The planner node's services: GetPlan (the plan, the state it was decided on, the plan as text) and EditPlan
(an operator's edit applied once per request id, answered again when repeated, on record with its answer). A
mix-in of :class:`~semgoal_planner.planner_node.PlannerNode`."""

from __future__ import annotations

from semgoal_core.names import PlanStatus
from semgoal_msgs.msg import OperatorEvent
from semgoal_msgs.srv import EditPlan, GetPlan
from semgoal_planner.plan_messages import edit_text
from semgoal_ros import interfaces as topics
from semgoal_ros.messages import format_plan


class PlanServices:
    """GetPlan and EditPlan for the planner node."""

    def get_plan_callback(self, request: GetPlan.Request, response: GetPlan.Response) -> GetPlan.Response:
        response.plan = self.plan_now()
        if self.last_state is not None:
            response.state = self.last_state
        response.success = self.executive.status != PlanStatus.EMPTY
        response.message = format_plan(response.plan)
        return response

    def edit_plan_callback(self, request: EditPlan.Request, response: EditPlan.Response) -> EditPlan.Response:
        asked = (request.op, request.index, request.to_index, request.action, request.revision)
        try:
            answered = self.edit_answers.get(request.request_id, asked)
        except topics.ReusedRequestIdError as error:  # refused, the plan as it is
            response.success, response.message, response.plan = False, str(error), self.plan_now()
            self.operator_event(OperatorEvent.KIND_EDIT, edit_text(request), False, response.message, request.request_id)
            return response
        if answered is not None:  # sent again because our answer was lost: it was applied once already
            response.success, response.message, response.plan = answered
            return response
        response.success, response.message = self.executive.edit(
            request.op, int(request.index), int(request.to_index), request.action, int(request.revision))
        self.report(response.success, f"edit {request.op} {request.index} {request.action!r}: {response.message}")
        self.publish()
        response.plan = self.plan_now()
        self.operator_event(OperatorEvent.KIND_EDIT, edit_text(request), response.success, response.message,
                            request.request_id)
        self.edit_answers.remember(request.request_id, (response.success, response.message, response.plan), asked)
        return response
