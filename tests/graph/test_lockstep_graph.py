"""Lockstep through the four node processes is the in-process episode: the policy follows the planner's
decision on the step before (or, where that names no sub-goal, on the current step, once it has come),
so the graph takes exactly the steps and re-plans that :class:`HierarchicalAgent` takes with the same
cores, seeds and actor. Each case re-plans in process, so the re-plan timing (the planner's stall and
contradiction clocks) is compared too. The client watches no stream, as the Table 1 evaluation through
the graph runs."""

import pytest

from conftest import NodeProcesses
from semgoal_bringup.experiments.episodes import make_agent
from semgoal_bringup.graph import NODES, node_params
from semgoal_core.tasks import TASK_STEP_BUDGET, get_task
from semgoal_ros.client import GraphClient

CASES = [("Swap-2", 3_000_043), ("MC-3", 3_000_018), ("DC-4", 3_000_006)]
"""One start per scene where the shipped actors re-plan in process (once or twice; all solved at rest). Re-pick
them when an actor or the executive's rules change: the first seed from 3000000 that re-plans and succeeds."""


@pytest.mark.parametrize(("task", "seed"), CASES)
def test_the_graph_takes_the_in_process_steps(task: str, seed: int, nodes: NodeProcesses) -> None:
    expected = make_agent("hierarchical", get_task(task).scene).run(task, seed)
    assert expected.replans >= 1, "the case should exercise re-planning"
    params = node_params(task, seed, "lockstep")
    for package, exe in NODES:
        nodes.start(package, exe, params=params[exe])
    client = GraphClient("semgoal_test_operator", watch=False)
    try:
        assert client.wait_ready(), "the four nodes did not come up"
        ok, message = client.reset(task, seed)
        assert ok, message
        result = client.execute(task, max_steps=TASK_STEP_BUDGET)
    finally:
        client.close()
    graph = (result.success, result.control_steps, result.replans)
    assert graph == (expected.success, expected.steps, expected.replans), result.message
