"""planner_node killed with SIGKILL mid-goal and started again on its journal: the same plan (revision, steps,
a person's assignment, status) comes back, a raw action client waiting on the lost goal learns that it ended
and why, an edit made against an older revision is refused, and the plan then finishes at rest."""

import os
import signal

import pytest
from action_msgs.msg import GoalStatus
from rclpy.action import ActionClient

from semgoal_bringup.graph import NODES, node_params
from semgoal_core.names import Assignee, PlanStatus
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import GoalRequest, OperatorEvent
from semgoal_ros import interfaces as topics
from semgoal_ros.client import GraphClient

TASK, SEED = "DC-4", 6
KILLS = 3


def plan_view(plan) -> tuple:
    return (plan.revision, plan.status, plan.current, plan.replans,
            [(step.action, step.status, step.assignee) for step in plan.steps])


@pytest.mark.timeout(600)
def test_a_killed_planner_resumes_its_plan_and_tells_the_action_client(nodes, probe, tmp_path) -> None:
    params = node_params(TASK, SEED, "lockstep", state_dir=str(tmp_path / "state"))
    started = {executable: nodes.start(package, executable, params[executable]) for package, executable in NODES}
    client = GraphClient("semgoal_test_operator", watch=False)
    events: dict[str, OperatorEvent] = {}
    probe.node.create_subscription(OperatorEvent, topics.OPERATOR_EVENTS,
                                   lambda event: events.__setitem__(event.request_id, event), topics.EVENTS)
    raw = ActionClient(probe.node, ExecuteGoal, topics.EXECUTE_GOAL)
    try:
        assert client.wait_ready(), nodes.logs()
        for kill in range(KILLS):
            client.must_reset(TASK, SEED + kill)
            handle = probe.send_goal(raw, ExecuteGoal.Goal(goal=GoalRequest(task=TASK), episode=client.episode))
            assert handle.accepted
            assert client.spin_until(lambda: client.get_plan().plan.current >= 1, 120), "no step done"
            plan = client.get_plan().plan
            assert client.edit("pause", revision=plan.revision).success
            last = len(plan.steps) - 1
            assigned = client.edit("assign", index=last, action="human")
            assert assigned.success, assigned.message
            before = plan_view(client.get_plan().plan)

            os.kill(started["planner_node"].pid, signal.SIGKILL)
            started["planner_node"].wait(10)
            started["planner_node"] = nodes.start("semgoal_planner", "planner_node", params["planner_node"])

            goal_id = bytes(handle.goal_id.uuid).hex()
            probe.spin_until(lambda h=handle, g=goal_id: h.status == GoalStatus.STATUS_ABORTED and g in events, 30,
                             "the raw action client to learn that its goal ended")
            assert "interrupted: planner_node stopped and started again; the plan resumed" in events[goal_id].answer
            assert client.spin_until(lambda r=before[0]: client.get_plan().plan.revision == r, 30), nodes.logs()
            after = plan_view(client.get_plan().plan)
            assert after == before, (before, after)
            assert after[4][last][2] == Assignee.HUMAN and after[1] == PlanStatus.PAUSED

            stale = client.edit("assign", index=last, action="robot", revision=before[0] - 1)
            assert not stale.success and f"revision {before[0] - 1}" in stale.message
            assert client.edit("assign", index=last, action="robot", revision=before[0]).success
            assert client.edit("resume").success
            assert client.spin_until(lambda: client.get_plan().plan.status == PlanStatus.SUCCEEDED, 180), nodes.logs()
            done = client.get_plan().plan
            assert done.replans == before[3], "the plan was carried on, not made again"
            assert [step.action for step in done.steps] == [action for action, _, _ in before[4]]
            assert all(step.status in ("done", "skipped") for step in done.steps)
        assert all(process.poll() is None for process in started.values())
    finally:
        client.close()
