"""Interface loopback node: echoes every semgoal message type, answers every service, runs the action.

Used to check the interfaces across processes over real DDS (tests, `./semgoal demo` before the full
graph was there). Each message arriving on ``/semgoal/echo/in/<Type>`` is republished unchanged on
``/semgoal/echo/out/<Type>``; services answer with a message that names what they received.
"""

import time

from rclpy.action import ActionServer
from rclpy.node import Node

from semgoal_msgs import msg, srv
from semgoal_msgs.action import ExecuteGoal
from semgoal_ros import interfaces as topics

MESSAGE_TYPES = [msg.Predicate, msg.SemanticState, msg.WorldState, msg.ArmCommand,
                 msg.SubGoal, msg.Plan, msg.GoalRequest]


def echo_topics(message_type: type) -> tuple[str, str]:
    """Input and output topic of one message type."""
    name = message_type.__name__
    return f"/semgoal/echo/in/{name}", f"/semgoal/echo/out/{name}"


class EchoNode(Node):
    """Loops every semgoal interface back to its caller."""

    def __init__(self) -> None:
        super().__init__("semgoal_echo")
        self.feedback_count = self.declare_parameter("feedback_count", 3).value
        self._echo_subscriptions = []
        for message_type in MESSAGE_TYPES:
            topic_in, topic_out = echo_topics(message_type)
            publisher = self.create_publisher(message_type, topic_out, 10)
            self._echo_subscriptions.append(
                self.create_subscription(message_type, topic_in, publisher.publish, 10))
        self.create_service(srv.EditPlan, "/semgoal/echo/edit_plan", self.edit_plan_callback)
        self.create_service(srv.GetPlan, "/semgoal/echo/get_plan", self.get_plan_callback)
        self.create_service(srv.ResetWorld, "/semgoal/echo/reset_world", self.reset_world_callback)
        self.create_service(srv.MoveBlock, "/semgoal/echo/move_block", self.move_block_callback)
        self._action_server = ActionServer(self, ExecuteGoal, "/semgoal/echo/execute_goal", self.execute_callback)
        self.get_logger().info("echoing every semgoal interface under /semgoal/echo/")

    def edit_plan_callback(self, request: srv.EditPlan.Request, response: srv.EditPlan.Response):
        response.success = True
        response.message = f"{request.op} {request.index} {request.to_index} {request.action}"
        response.plan.revision = request.index + 1
        return response

    def get_plan_callback(self, request: srv.GetPlan.Request, response: srv.GetPlan.Response):
        response.success = True
        response.message = "echo plan"
        response.plan.status = "empty"
        return response

    def reset_world_callback(self, request: srv.ResetWorld.Request, response: srv.ResetWorld.Response):
        response.success = True
        response.message = f"reset {request.task} {request.seed}"
        response.world.task = request.task
        return response

    def move_block_callback(self, request: srv.MoveBlock.Request, response: srv.MoveBlock.Response):
        response.success = True
        response.message = f"moved {request.block}"
        response.world.gripper_position = request.position
        return response

    def execute_callback(self, goal_handle) -> ExecuteGoal.Result:
        request = goal_handle.request.goal
        for index in range(self.feedback_count):
            feedback = ExecuteGoal.Feedback()
            feedback.plan.goal = request.task or " & ".join(request.literals)
            feedback.plan.current = index
            goal_handle.publish_feedback(feedback)
            time.sleep(0.05)
        goal_handle.succeed()
        return ExecuteGoal.Result(success=True, message=f"echoed {request.task}", control_steps=self.feedback_count)


def main(args: list[str] | None = None) -> None:
    topics.run_node(EchoNode, args)
