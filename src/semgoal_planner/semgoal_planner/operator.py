"""The operator's commands: what `ros2 topic pub`, `ros2 service call` and `ros2 action send_goal` do natively.

    ./semgoal goal DC-3                        publish a goal (the planner plans and executes it)
    ./semgoal goal "in_bin(red) & in_bin(green)" --wait   execute it through the action, print progress
    ./semgoal goal DC-3 --wait --max-steps 600             ... and let it fail after 600 control steps
    ./semgoal goal DC-3 --wait --record run.mcap           ... recording the graph meanwhile (./semgoal replay)
    ./semgoal plan show
    ./semgoal plan insert 2 "pick(red)" | remove 2 | move 3 1 | replace 2 "put_in_bin(red)"
    ./semgoal plan remove 2 --revision 7       ... only if the plan is still at revision 7 (as plan show printed it)
    ./semgoal plan approve | pause | resume | replan | assign 2 human | claim 4 human:alice
"""

from __future__ import annotations

import argparse
import re
import signal
import sys

from semgoal_core.arguments import seconds
from semgoal_ros.client import GraphClient, GraphUnavailableError
from semgoal_ros.messages import format_plan


def _client() -> GraphClient:
    """A short-lived client for one command; Ctrl-C comes as a KeyboardInterrupt, so a command can cancel its goal."""
    return GraphClient("semgoal_operator", watch=False, handle_signals=False)


def goal_main(argv: list[str]) -> int:
    """`./semgoal goal TASK|LITERALS|SENTENCE [--wait [--max-steps N]]`: send a goal to planner_node. Exit 0
    sent (or, with --wait, achieved), 1 failed or no planner, 2 refused with the reason, 130 interrupted."""
    parser = argparse.ArgumentParser(prog="semgoal goal", description=goal_main.__doc__)
    parser.add_argument("goal", help="a task name (DC-3), literals joined by '&', or a sentence ('put red in the bin')")
    parser.add_argument("--wait", action="store_true", help="execute through the ExecuteGoal action and print progress")
    parser.add_argument("--max-steps", type=int, default=0,
                        help="with --wait: control steps the goal may take before it fails (default 0: no limit)")
    parser.add_argument("--timeout", type=seconds, default=300.0)
    parser.add_argument("--record", help="with --wait: record the graph while the goal runs into this MCAP file")
    args = parser.parse_args(argv)
    if args.max_steps < 0:
        parser.error(f"--max-steps must be 0 (no limit) or more, got {args.max_steps}")
    if args.max_steps and not args.wait:
        parser.error("--max-steps needs --wait: the budget travels with the ExecuteGoal action, not the goal topic")
    if args.record and not args.wait:
        parser.error("--record needs --wait: it records while the goal runs")
    client = _client()
    try:
        if args.wait:
            return _execute(client, args.goal, args.timeout, args.max_steps, args.record)
        refusal = _refusal(client, args.goal)
        if refusal:  # the topic has no answer: a goal the planner would refuse is not sent
            print(f"semgoal goal: refused: {refusal}", file=sys.stderr)
            return 2
        if not client.publish_goal(args.goal):
            print("semgoal goal: nobody subscribes to the goal topic: is planner_node running?", file=sys.stderr)
            return 1
        client.spin_until(lambda: False, 0.3)  # let DDS deliver before the node goes away
        print(f"published goal {args.goal!r}; see it with ./semgoal plan show")
        return 0
    except GraphUnavailableError as error:
        print(f"semgoal goal: {error}", file=sys.stderr)
        return 1
    finally:
        client.close()


def _refusal(client: GraphClient, text: str) -> str:
    """Why the planner would refuse ``text`` in the world it last observed ("" when it would plan it, or
    when no world state is known yet): the goal is parsed here as the planner parses it."""
    from semgoal_core.vocabulary import Literal
    from semgoal_planner.goals import GoalError, parse_goal

    state = client.get_plan().state
    if not state.scene:
        return ""
    true = [Literal(p.name, tuple(p.args)) for p in state.predicates if p.value]
    try:
        parse_goal(text, state.scene, tuple(state.objects), true)
    except GoalError as error:
        return str(error)
    return ""


def _execute(client: GraphClient, text: str, timeout: float, max_steps: int, record: str | None = None) -> int:
    with client.recording(record) as recorder:
        code = _follow(client, text, timeout, max_steps)
    if recorder is not None:
        print(f"recorded {sum(recorder.counts.values())} messages to {record}")
    return code


def _follow(client: GraphClient, text: str, timeout: float, max_steps: int) -> int:
    last = [None]

    def on_feedback(message) -> None:
        plan = message.feedback.plan
        key = (plan.revision, plan.current, plan.status)
        if key != last[0]:
            last[0] = key
            print(format_plan(plan), flush=True)

    caught: list[int] = []

    def stop_on_ctrl_c() -> None:  # between spins: an interrupt raised inside rclpy's C++ can lose its cause
        if caught:
            raise KeyboardInterrupt

    previous = signal.signal(signal.SIGINT, lambda number, _: caught.append(number))
    try:
        result = client.execute(text, on_feedback, timeout=timeout, max_steps=max_steps, while_running=stop_on_ctrl_c)
    except KeyboardInterrupt:
        print("semgoal goal: interrupted; the goal was cancelled", file=sys.stderr)
        return 130
    finally:
        signal.signal(signal.SIGINT, previous)
    print(f"{'success' if result.success else 'failure'}: {result.message} "
          f"({result.control_steps} control steps, {result.sim_time:.1f} s sim time, {result.replans} re-plans)")
    return 0 if result.success else 1


EDITS_WITH_INDEX = {"insert": ("index", "action"), "remove": ("index",), "move": ("index", "to_index"),
                    "replace": ("index", "action"), "assign": ("index", "action"), "claim": ("index", "action")}


def plan_main(argv: list[str]) -> int:
    """`./semgoal plan show | insert I ACTION | remove I | move I J | replace I ACTION | assign I robot|human[:NAME]
    | claim I human[:NAME] | approve | pause | resume | replan`: read or edit the plan through planner_node's services."""
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
    client = _client()
    try:
        if args.op == "show":
            response = client.get_plan()
            print(format_plan(response.plan))
            return 0 if response.success else 1
        edit = {"revision": args.revision}
        for name, value in zip(fields, args.args, strict=True):
            edit[name] = int(value) if name in ("index", "to_index") else value
        response = client.edit(args.op, **edit)
        print(("applied: " if response.success else "refused: ") + response.message)
        print(format_plan(response.plan))
        return 0 if response.success else 1
    except GraphUnavailableError as error:
        print(f"semgoal plan: {error}", file=sys.stderr)
        return 1
    finally:
        client.close()
