"""The four nodes in one process (`graph_node`, one executor) are the same graph: the same node names and
parameters, and in lockstep the steps and re-plans of the in-process episode; `bench graph --composed` measures
it beside four processes."""

import json
import subprocess

import pytest

from conftest import ROOT, GraphProbe, NodeProcesses
from semgoal_bringup.experiments.episodes import make_agent
from semgoal_bringup.graph import NODES, Sight, composed_command, graph_commands, graph_nodes, node_params
from semgoal_core.tasks import TASK_STEP_BUDGET, get_task
from semgoal_msgs.msg import SemanticState, SubGoal
from semgoal_ros import interfaces as topics
from semgoal_ros.client import GraphClient

TASK, SEED = "MC-3", 3_000_002
"""A start that re-plans in process (the lockstep graph test's)."""
PIXELS = Sight(perception="camera", policy_input="camera")


def test_the_composed_graph_takes_the_in_process_steps(nodes: NodeProcesses, probe: GraphProbe) -> None:
    expected = make_agent("hierarchical", get_task(TASK).scene).run(TASK, SEED)
    params = node_params(TASK, SEED, "lockstep")
    nodes.run("graph_node", composed_command([(package, exe, params[exe]) for package, exe in NODES]))
    client = GraphClient("semgoal_test_operator", watch=False)
    try:
        assert client.wait_ready(), nodes.logs()
        probe.spin_until(lambda: {"sim", "predicates", "planner", "policy"} <= set(probe.node.get_node_names()), 20,
                         "the four node names from the one process")
        ok, message = client.reset(TASK, SEED)
        assert ok, message
        result = client.execute(TASK, max_steps=TASK_STEP_BUDGET)
    finally:
        client.close()
    assert (result.success, result.control_steps, result.replans) == (expected.success, expected.steps,
                                                                      expected.replans), result.message
    # the nodes handed their messages to each other over in the process; a late joiner outside, the graph now idle,
    # still gets the last semantic state and sub-goal (transient local), as from four processes
    states, subgoals = [], []
    probe.node.create_subscription(SemanticState, topics.SEMANTIC_STATE, states.append, topics.LATCHED)
    probe.node.create_subscription(SubGoal, topics.SUBGOAL, subgoals.append, topics.LATCHED)
    # the latched history comes over a few spins, older decisions first (the reset's empty one): wait for the plan's
    # last decision, that the goal succeeded
    probe.spin_until(lambda: bool(states) and bool(subgoals) and subgoals[-1].status == "succeeded", 30,
                     "the last semantic state and sub-goal")
    assert states[-1].step > 0 and subgoals[-1].step == states[-1].step  # the decision on the last state


def test_from_pixels_the_composed_graph_solves_dc3_with_perception_in_the_process(nodes: NodeProcesses) -> None:
    """The sim's RGB-D frames go to perception_node in the same process (handed over, not serialised), and the plan
    and the policy run on what it sees."""
    for name, command in graph_commands(graph_nodes("DC-3", 6, "lockstep", sight=PIXELS), composed=True).items():
        nodes.run(name.replace("/", "-"), command)
    client = GraphClient("semgoal_test_operator", watch=False)
    try:
        assert client.wait_ready(timeout=60.0), nodes.logs()
        ok, message = client.reset("DC-3", 6)
        assert ok, message
        result = client.execute("DC-3", max_steps=600)
    finally:
        client.close()
    assert result.success, result.message


@pytest.mark.timeout(600)
def test_bench_graph_runs_the_composed_graph_at_a_tiny_size() -> None:
    out = subprocess.run([str(ROOT / "semgoal"), "bench", "graph", "--task", "MC-2", "--episodes", "1", "--realtime-s", "2",
                          "--composed", "--pixels", "--json"], capture_output=True, text=True, timeout=560, check=True,
                         cwd=ROOT)
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result["lockstep_composed_steps_per_s"] > 0 and result["composed_over_processes"] > 0  # one warm-up episode
    assert result["composed_through_middleware_steps_per_s"] > 0 and result["pixels_composed_over_processes"] > 0
    assert result["graph_over_in_process"] > 0 and result["realtime"]["steps"] > 0
