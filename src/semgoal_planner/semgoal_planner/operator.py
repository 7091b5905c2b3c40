"""The operator's commands: what `ros2 topic pub`, `ros2 service call` and `ros2 action send_goal` do natively.

    ./semgoal goal DC-3                        publish a goal (the planner plans and executes it)
    ./semgoal goal "in_bin(red) & in_bin(green)" --wait   execute it through the action, print progress
    ./semgoal goal DC-3 --wait --max-steps 600             ... and let it fail after 600 control steps
    ./semgoal plan show
    ./semgoal plan insert 2 "pick(red)" | remove 2 | move 3 1 | replace 2 "put_in_bin(red)"
    ./semgoal plan remove 2 --revision 7       ... only if the plan is still at revision 7 (as plan show printed it)
    ./semgoal plan approve | pause | resume | replan | assign 2 human
"""

from __future__ import annotations

import argparse
import re
import sys
import time
import uuid
from functools import partial

WAIT_S = 10.0


class OperatorClient:
    """A short-lived rclpy node for one command."""

    def __init__(self) -> None:
        import rclpy
        from rclpy.signals import SignalHandlerOptions

        # Ctrl-C raises KeyboardInterrupt with the context still valid, so a command can clean up (cancel its goal)
        rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
        self.rclpy = rclpy
        self.node = rclpy.create_node("semgoal_operator")

    def close(self) -> None:
        self.node.destroy_node()
        self.rclpy.try_shutdown()

    def call(self, service_type, name: str, request, timeout: float = WAIT_S):
        """Call a service, sending the request again while no answer comes (the request must be safe to
        repeat: a read, or an edit with a request id)."""
        from semgoal_ros import interfaces as topics

        client = self.node.create_client(service_type, name)
        if not client.wait_for_service(timeout_sec=timeout):
            raise TimeoutError(f"no {name} service: is planner_node running (same ROS_DOMAIN_ID)?")
        response = topics.send_until_answered(lambda: client.call_async(request),
                                              partial(topics.spin_node_until, self.node))
        if response is None:
            raise TimeoutError(f"{name} did not answer after {topics.SEND_ATTEMPTS} tries")
        return response


def format_plan(plan) -> str:
    lines = [f"goal: {plan.goal or '(none)'}   status: {plan.status}   revision {plan.revision}   replans {plan.replans}"]
    for step in plan.steps:
        marker = ">" if step.index == plan.current and plan.status == "executing" else " "
        lines.append(f"{marker} {step.index:2d}. {step.action:28s} {step.status:8s} {step.assignee}")
    return "\n".join(lines)


def goal_main(argv: list[str]) -> int:
    """`./semgoal goal TASK|LITERALS|SENTENCE [--wait [--max-steps N]]`: send a goal to planner_node. Exit 0
    sent (or, with --wait, achieved), 1 failed or no planner, 2 refused with the reason."""
    parser = argparse.ArgumentParser(prog="semgoal goal", description=goal_main.__doc__)
    parser.add_argument("goal", help="a task name (DC-3), literals joined by '&', or a sentence ('put red in the bin')")
    parser.add_argument("--wait", action="store_true", help="execute through the ExecuteGoal action and print progress")
    parser.add_argument("--max-steps", type=int, default=0,
                        help="with --wait: control steps the goal may take before it fails (default 0: no limit)")
    parser.add_argument("--timeout", type=float, default=300.0)
    args = parser.parse_args(argv)
    if args.max_steps < 0:
        parser.error(f"--max-steps must be 0 (no limit) or more, got {args.max_steps}")
    if args.max_steps and not args.wait:
        parser.error("--max-steps needs --wait: the budget travels with the ExecuteGoal action, not the goal topic")
    from semgoal_msgs.msg import GoalRequest
    from semgoal_planner.goals import is_task_name, looks_like_literals
    from semgoal_ros import interfaces as topics

    if is_task_name(args.goal):
        request = GoalRequest(task=args.goal.strip())
    elif looks_like_literals(args.goal):
        request = GoalRequest(literals=[args.goal])
    else:
        request = GoalRequest(text=args.goal)
    client = OperatorClient()
    try:
        if args.wait:
            return _execute(client, request, args.timeout, args.max_steps)
        publisher = client.node.create_publisher(GoalRequest, topics.GOAL, 10)
        deadline = time.monotonic() + WAIT_S
        while publisher.get_subscription_count() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        if publisher.get_subscription_count() == 0:
            print(f"semgoal goal: nobody subscribes to {topics.GOAL}: is planner_node running?", file=sys.stderr)
            return 1
        refusal = _refusal(client, args.goal)
        if refusal:  # the topic has no answer: a goal the planner would refuse is not sent
            print(f"semgoal goal: refused: {refusal}", file=sys.stderr)
            return 2
        publisher.publish(request)
        time.sleep(0.3)  # let DDS deliver before the node goes away
        print(f"published goal {args.goal!r}; see it with ./semgoal plan show")
        return 0
    finally:
        client.close()


def _refusal(client: OperatorClient, text: str) -> str:
    """Why the planner would refuse ``text`` in the world it last observed ("" when it would plan it, or
    when no world state is known yet): the goal is parsed here as the planner parses it."""
    from semgoal_core.vocabulary import Literal
    from semgoal_msgs.srv import GetPlan
    from semgoal_planner.goals import GoalError, parse_goal
    from semgoal_ros import interfaces as topics

    state = client.call(GetPlan, topics.GET_PLAN, GetPlan.Request()).state
    if not state.scene:
        return ""
    true = [Literal(p.name, tuple(p.args)) for p in state.predicates if p.value]
    try:
        parse_goal(text, state.scene, tuple(state.objects), true)
    except GoalError as error:
        return str(error)
    return ""


def _execute(client: OperatorClient, request, timeout: float, max_steps: int) -> int:
    from rclpy.action import ActionClient

    from semgoal_msgs.action import ExecuteGoal
    from semgoal_ros import interfaces as topics

    action = ActionClient(client.node, ExecuteGoal, topics.EXECUTE_GOAL)
    if not action.wait_for_server(timeout_sec=WAIT_S):
        print("semgoal goal: no execute_goal action server: is planner_node running?", file=sys.stderr)
        return 1
    last = [None]

    def on_feedback(message) -> None:
        plan = message.feedback.plan
        key = (plan.revision, plan.current, plan.status)
        if key != last[0]:
            last[0] = key
            print(format_plan(plan), flush=True)

    goal, sent = ExecuteGoal.Goal(goal=request, max_steps=max_steps), []

    def send():
        sent.append(action.send_goal_async(goal, feedback_callback=on_feedback))
        return sent[-1]

    spin_until = partial(topics.spin_node_until, client.node)
    try:  # Ctrl-C, from the goal's sending on: the goal is the operator's to stop, not to leave running (issue 57)
        handle = topics.send_until_answered(send, spin_until)
        if handle is None or not handle.accepted:
            print("semgoal goal: the planner did not accept the goal", file=sys.stderr)
            return 1
        result_future = handle.get_result_async()
        deadline = time.monotonic() + timeout
        while not result_future.done() and time.monotonic() < deadline:  # slices: Ctrl-C lands between them
            client.rclpy.spin_until_future_complete(client.node, result_future, timeout_sec=0.1)
    except KeyboardInterrupt:
        _cancel_sent(client, sent)
        print("semgoal goal: interrupted; the goal was cancelled", file=sys.stderr)
        return 130
    if not result_future.done():
        handle.cancel_goal_async()
        print(f"semgoal goal: no result within {timeout:.0f} s; cancelled", file=sys.stderr)
        return 1
    result = result_future.result().result
    print(f"{'success' if result.success else 'failure'}: {result.message} "
          f"({result.control_steps} control steps, {result.sim_time:.1f} s sim time, {result.replans} re-plans)")
    return 0 if result.success else 1


def _cancel_sent(client: OperatorClient, sent: list) -> None:
    """Cancel every goal sent that the planner accepted (waiting briefly for answers still on their way)."""
    for future in sent:
        client.rclpy.spin_until_future_complete(client.node, future, timeout_sec=WAIT_S)
        handle = future.result() if future.done() else None
        if handle is not None and handle.accepted:
            client.rclpy.spin_until_future_complete(client.node, handle.cancel_goal_async(), timeout_sec=WAIT_S)


EDITS_WITH_INDEX = {"insert": ("index", "action"), "remove": ("index",), "move": ("index", "to_index"),
                    "replace": ("index", "action"), "assign": ("index", "action")}


def plan_main(argv: list[str]) -> int:
    """`./semgoal plan show | insert I ACTION | remove I | move I J | replace I ACTION | assign I robot|human
    | approve | pause | resume | replan`: read or edit the plan through planner_node's services."""
    parser = argparse.ArgumentParser(prog="semgoal plan", description=plan_main.__doc__)
    parser.add_argument("op", choices=["show", *EDITS_WITH_INDEX, "approve", "pause", "resume", "replan"])
    parser.add_argument("args", nargs="*")
    parser.add_argument("--revision", type=int, default=0,
                        help="refuse the edit unless the plan is still at this revision (plan show prints it); "
                             "0: edit the plan as it is now")
    args = parser.parse_args(argv)
    if not 0 <= args.revision < 2**32:
        parser.error(f"--revision must be 0 or a plan revision, got {args.revision}")
    fields = EDITS_WITH_INDEX.get(args.op, ())
    if args.op != "show" and len(args.args) != len(fields):
        parser.error(f"{args.op} takes {len(fields)} argument(s): {' '.join(f.upper() for f in fields) or '(none)'}")
    for name, value in zip(fields, args.args, strict=False):  # checked before anything is sent
        if name in ("index", "to_index") and not (re.fullmatch(r"[0-9]{1,10}", value) and int(value) < 2**32):
            parser.error(f"{name.upper()} must be a step number (0 to {2**32 - 1}), got {value!r}")
    from semgoal_msgs.srv import EditPlan, GetPlan
    from semgoal_ros import interfaces as topics

    client = OperatorClient()
    try:
        if args.op == "show":
            response = client.call(GetPlan, topics.GET_PLAN, GetPlan.Request())
            print(format_plan(response.plan))
            return 0 if response.success else 1
        # the request id makes a resend after a lost answer safe: the planner answers it without applying it again
        request = EditPlan.Request(op=args.op, revision=args.revision, request_id=uuid.uuid4().hex)
        for name, value in zip(fields, args.args, strict=True):
            if name in ("index", "to_index"):
                setattr(request, name, int(value))
            else:
                request.action = value
        response = client.call(EditPlan, topics.EDIT_PLAN, request)
        print(("applied: " if response.success else "refused: ") + response.message)
        print(format_plan(response.plan))
        return 0 if response.success else 1
    except TimeoutError as error:
        print(f"semgoal plan: {error}", file=sys.stderr)
        return 1
    finally:
        client.close()
