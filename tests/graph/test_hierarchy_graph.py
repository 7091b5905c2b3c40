"""The four nodes as processes, solving MC-2 through ExecuteGoal while an operator intervenes:
a block moved by hand mid-task is re-planned around, and a policy node killed mid-task and started
again picks the task up where it stood (the lockstep world waits for it)."""

import numpy as np
import pytest

from conftest import NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_bringup.graph_client import GraphClient

TASK, SEED = "MC-2", 4


@pytest.fixture
def graph(nodes: NodeProcesses):
    params = node_params(TASK, SEED, "lockstep")
    processes = {exe: nodes.start(package, exe, params=params[exe]) for package, exe in NODES}
    client = GraphClient("semgoal_test_operator")
    assert client.wait_ready(), "the four nodes did not come up"
    ok, message = client.reset(TASK, SEED)
    assert ok, message
    yield client, processes
    client.close()


def _free_spot(client: GraphClient, keep_away_from: str) -> tuple[float, float, float]:
    """Of a few table spots, the one farthest from ``keep_away_from`` (so put_near is not achieved by the move)."""
    block = next(b for b in client.world.blocks if b.name == keep_away_from)
    spots = [(x, y, 0.425) for x in (1.24, 1.36) for y in (0.60, 0.75)]
    return max(spots, key=lambda s: np.hypot(s[0] - block.pose.position.x, s[1] - block.pose.position.y))


def test_block_moved_mid_task_is_replanned_and_the_task_succeeds(graph) -> None:
    client, _ = graph
    moved: list[tuple[bool, str]] = []

    def intervene() -> None:  # while the robot carries its block to the other, put it back on the table
        subgoal = client.subgoal
        if moved or subgoal is None or subgoal.status != "active" or not subgoal.action.startswith("put_near"):
            return
        held, reference = subgoal.action.removeprefix("put_near(").rstrip(")").split(",")[:2]
        moved.append(client.move_block(held, *_free_spot(client, reference)))

    result = client.execute(TASK, while_running=intervene)
    assert moved and moved[0][0], moved
    assert result.success, result.message
    assert result.replans >= 1


def test_policy_node_restarted_mid_task_and_the_task_resumes(graph, nodes: NodeProcesses) -> None:
    client, processes = graph
    restarted: list[int] = []

    def restart_policy() -> None:
        if restarted or client.world is None or client.world.step < 8:
            return
        nodes.stop(processes["policy_node"])
        client.spin_until(lambda: False, 0.5)  # a command already in flight may still land
        frozen = client.world.step
        client.spin_until(lambda: False, 1.0)
        assert client.world.step == frozen  # lockstep: no policy, no steps
        params = node_params(TASK, SEED, "lockstep")["policy_node"]
        processes["policy_node"] = nodes.start("semgoal_policy", "policy_node", params=params)
        restarted.append(frozen)

    result = client.execute(TASK, while_running=restart_policy)
    assert restarted
    assert result.success, result.message
    assert result.control_steps > restarted[0]
