"""The four nodes as processes, solving MC-2 through ExecuteGoal while an operator intervenes:
a block moved by hand mid-task is re-planned around, a policy node killed mid-task and started
again picks the task up where it stood (the lockstep world waits for it), and an early re-plan leaves the
result's step count true. The interventions happen
while the operator holds the world through plan edits, so they do not race the graph."""

from collections.abc import Callable

import numpy as np
import pytest

from conftest import NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_core.names import PlanStatus, StepStatus
from semgoal_msgs.msg import SubGoal
from semgoal_ros import interfaces as topics
from semgoal_ros.client import GraphClient
from semgoal_ros.messages import block_centres

TASK, SEED = "MC-2", 4


@pytest.fixture
def graph(nodes: NodeProcesses, request):
    """The four nodes on MC-2, reset; ``request.param`` (indirect parametrisation) adds planner parameters."""
    params = node_params(TASK, SEED, "lockstep")
    params["planner_node"].update(getattr(request, "param", {}))
    processes = {exe: nodes.start(package, exe, params=params[exe]) for package, exe in NODES}
    client = GraphClient("semgoal_test_operator")
    assert client.wait_ready(), "the four nodes did not come up"
    ok, message = client.reset(TASK, SEED)
    assert ok, message
    yield client, processes
    client.close()


def _free_spot(client: GraphClient, keep_away_from: str) -> tuple[float, float, float]:
    """Of a few table spots, the one farthest from ``keep_away_from`` (so put_near is not achieved by the move)."""
    block = block_centres(client.world)[keep_away_from]
    spots = [(x, y, 0.425) for x in (1.24, 1.36) for y in (0.60, 0.75)]
    return max(spots, key=lambda s: np.hypot(s[0] - block[0], s[1] - block[1]))


def _planner_sees(client: GraphClient, name: str, args: list[str], value: bool, timeout: float = 10.0) -> bool:
    """Whether the semantic state the planner last decided on comes to hold ``name(args)`` as ``value``."""
    def seen() -> bool:
        reply = client.get_plan()
        return any(p.name == name and list(p.args) == args and bool(p.value) == value
                                         for p in reply.state.predicates)
    return client.spin_until(seen, timeout)


def _with_the_block_held(client: GraphClient, while_paused: Callable[[str], None],
                         after_resume: Callable[[], None] = lambda: None) -> tuple[Callable[[], None], list[str]]:
    """A ``while_running`` hook for a planner that waits for approval: the operator hands the carry step
    (step 1) to a human before approving, so the lockstep world waits once the robot holds its block,
    however fast the graph runs. There the operator pauses, hands the step back to the robot (valid while
    it holds the block), calls ``while_paused(carry action)``, resumes and calls ``after_resume()``. A
    re-planned plan is approved too. Returns the hook and the list of interventions done."""
    done: list[str] = []

    def hook() -> None:
        status = client.subgoal.status if client.subgoal else ""
        if status == "awaiting_approval" and not done:
            for edit in (("assign", 1, "human"), ("approve",)):
                assert client.edit(*edit).success, edit
            done.append("approved")
        elif status == "awaiting_approval":
            client.edit("approve")  # refused harmlessly when a stale sub-goal message repeats the status
        elif status == "waiting_for_human" and done == ["approved"]:
            carry = client.get_plan().plan.steps[1].action
            for edit in (("pause",), ("assign", 1, "robot")):
                assert client.edit(*edit).success, edit
            while_paused(carry)
            assert client.edit("resume").success
            after_resume()
            done.append("intervened")

    return hook, done


@pytest.mark.parametrize("graph", [{"require_approval": True}], indirect=True)
def test_block_moved_mid_task_is_replanned_and_the_task_succeeds(graph) -> None:
    """While the robot holds its block, it is put back on the table through the sim's service; the planner
    finds by itself that the plan no longer fits and re-plans."""
    client, _ = graph

    def put_back(carry: str) -> None:
        held, reference = carry.removeprefix("put_near(").rstrip(")").split(",")[:2]
        moved, message = client.move_block(held, *_free_spot(client, reference))
        assert moved, message
        assert _planner_sees(client, "holding", [held], False), "the planner did not see the block put down"

    hook, done = _with_the_block_held(client, put_back)
    result = client.execute(TASK, while_running=hook, timeout=120)
    assert done == ["approved", "intervened"], done
    assert result.success, result.message
    assert result.replans >= 1


@pytest.mark.parametrize("graph", [{"require_approval": True}], indirect=True)
def test_policy_node_restarted_mid_task_and_the_task_resumes(graph, nodes: NodeProcesses) -> None:
    """While the robot holds its block, the policy node is stopped: with the plan resumed the lockstep world
    waits for it; started again, it carries the task on to success."""
    client, processes = graph
    frozen: list[int] = []

    def stop_policy(_: str) -> None:
        nodes.stop(processes["policy_node"])

    def check_frozen_and_restart() -> None:
        client.spin_until(lambda: False, 0.5)  # a command already in flight may still land
        step = client.world.step
        client.spin_until(lambda: False, 1.0)
        assert client.world.step == step  # lockstep: no policy, no steps
        params = node_params(TASK, SEED, "lockstep")["policy_node"]
        processes["policy_node"] = nodes.start("semgoal_policy", "policy_node", params=params)
        frozen.append(step)

    hook, done = _with_the_block_held(client, stop_policy, check_frozen_and_restart)
    result = client.execute(TASK, while_running=hook, timeout=120)
    assert done == ["approved", "intervened"], done
    assert result.success, result.message
    assert result.control_steps > frozen[0]


@pytest.mark.parametrize("graph", [{"require_approval": True}], indirect=True)
def test_control_steps_are_the_worlds_steps_from_the_goals_start_to_its_end_across_a_replan_and_a_reset(graph) -> None:
    """The result counts the world's control steps between the planner's first decision on the goal and the one
    that found it held at rest, read from the step stamps of every decision, with an operator's early re-plan and
    a world reset to step 0 in between (a reset under the goal used to make the count the new world's alone)."""
    client, _ = graph
    decisions = []
    client.node.create_subscription(SubGoal, topics.SUBGOAL, decisions.append, topics.RECORDING)
    interventions = []

    def replan_and_reset(_: str) -> None:
        interventions.append(client.edit("replan").success)
        client.reset(TASK, SEED + 1, attempts=1)  # the goal goes on in a new world of the same blocks
        interventions.append(client.episode)

    hook, done = _with_the_block_held(client, replan_and_reset)
    result = client.execute(TASK, while_running=hook, timeout=120)
    assert done == ["approved", "intervened"], done
    assert result.success, result.message
    assert interventions[0] is True and interventions[1] > 1
    client.spin_until(lambda: False, 0.5)  # the last decisions, still on their way
    first = next(i for i, d in enumerate(decisions) if d.status == StepStatus.ACTIVE)
    last = next(i for i, d in enumerate(decisions) if d.status == PlanStatus.SUCCEEDED)
    counted, previous = 0, decisions[first].step
    for decision in decisions[first + 1: last + 1]:  # a step before the last: the world was reset to step 0
        counted += decision.step - previous if decision.step >= previous else decision.step
        previous = decision.step
    assert len({d.episode for d in decisions[first: last + 1]}) == 2
    assert result.control_steps == counted > decisions[last].step, (result.control_steps, counted)
