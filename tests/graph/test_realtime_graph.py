"""The four node processes in realtime mode: the sim steps on its own 25 Hz clock and the policy acts at
its rate on the latest world state, so nothing waits for anyone. The operator resets the world and the
planner's GetPlan confirms it (the world goes on stepping meanwhile, the arm holding still), then MC-2
is solved within its step budget."""

from conftest import NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_core.layout import CONTROL_DT
from semgoal_core.tasks import TASK_STEP_BUDGET
from semgoal_ros.client import GraphClient

TASK, SEED = "MC-2", 3_000_000


def test_realtime_graph_resets_and_solves_mc2(nodes: NodeProcesses) -> None:
    params = node_params(TASK, SEED, "realtime")
    for package, exe in NODES:
        nodes.start(package, exe, params=params[exe])
    client = GraphClient("semgoal_test_operator", watch=False, lockstep=False)
    try:
        assert client.wait_ready(), "the four nodes did not come up"
        ok, message = client.reset(TASK, SEED)
        assert ok, message
        result = client.execute(TASK, max_steps=TASK_STEP_BUDGET, timeout=60)
    finally:
        client.close()
    assert result.success, result.message
    assert 0 < result.control_steps < TASK_STEP_BUDGET
    assert abs(result.sim_time - result.control_steps * CONTROL_DT) < 1e-6
